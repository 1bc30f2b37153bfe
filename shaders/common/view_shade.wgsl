// The viewer's split-sum radiance of what a pixel sees, for the deferred kernel
// (view_split_sum.wgsl) and the forward pass (view_forward.wgsl): a surface shaded by
// `split_sum_shade` (common/split_sum.wgsl, the preview's function) plus the point lights
// on and the lights taken out of the environment (common/view_sun.wgsl), the background
// the chain's level 0. Mirror of `shade_split_sum` in src/view/cpu.rs.
// The including shader declares what split_sum.wgsl and view_surface.wgsl need.

fn background_radiance(dir: vec3<f32>) -> vec3<f32> {
    return sample_cube_lod(specular, light.specular_size, light.specular_levels, dir, 0.0);
}

fn surface_radiance(px: PixelView) -> vec3<f32> {
    return split_sum_shade(px.s.n, px.v, px.n_dot_v, px.m) + direct_lights(px) + sun_texels_shade(px, 0u, frame.sun.x);
}
