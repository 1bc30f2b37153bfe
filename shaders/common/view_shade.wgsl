// The viewer's split-sum radiance of what a pixel sees, for the deferred kernel
// (view_split_sum.wgsl) and the forward pass (view_forward.wgsl): the object shaded by
// `split_sum_shade` (common/split_sum.wgsl, the preview's function, with the recipe's taps
// at grazing views) plus the point lights on and the lights taken out of the environment
// (common/view_sun.wgsl); the floor from its table by view direction
// (common/view_floor.wgsl), each light through its visibility from the floor's grids
// (common/view_floor_shadow.wgsl), plus the point lights; the background the chain's level 0.
// Mirror of `shade_split_sum` in src/view/cpu.rs.
// The including shader declares what split_sum.wgsl, view_surface.wgsl and
// view_floor.wgsl need, and passes the two light counts: the deferred kernel the frame's,
// the forward pass its pipeline's constants (a loop whose count is a constant is
// unrolled, or gone when 0).

fn background_radiance(dir: vec3<f32>) -> vec3<f32> {
    return sample_cube_lod(specular, light.specular_size, light.specular_levels, dir, 0.0);
}

// `point_lights`: frame.light_count; `sun_lights`: frame.sun.x (the lights taken out).
fn object_radiance(px: PixelView, point_lights: u32, sun_lights: u32) -> vec3<f32> {
    return split_sum_shade(px.s.n, px.v, px.n_dot_v, px.m) + direct_lights(px, point_lights) + split_lights_shade(px, sun_lights);
}

fn floor_radiance(px: PixelView, point_lights: u32, sun_lights: u32) -> vec3<f32> {
    return floor_table_radiance(px.v, floor_lights_visibility(px, sun_lights), sun_lights) + direct_lights(px, point_lights);
}

// The object's or the floor's, by the surface's id.
fn surface_radiance(px: PixelView, point_lights: u32, sun_lights: u32) -> vec3<f32> {
    if (px.s.id == 2u) {
        return floor_radiance(px, point_lights, sun_lights);
    }
    return object_radiance(px, point_lights, sun_lights);
}
