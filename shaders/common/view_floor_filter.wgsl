// The forward pass's floor (view_forward.wgsl): the floor's table and its shadow grid
// (common/view_floor.wgsl, common/view_floor_shadow.wgsl say what they hold) read through
// the sampler's bilinear filter, one `textureSampleLevel` a layer and one for the grid,
// where the deferred kernels fetch four entries of each from storage. The same entries at
// the same positions; the weights up to the hardware's sub-texel precision, as the chains
// are read there (common/cube_filter_bordered.wgsl). The including shader declares
// `floor_table_texels` (texture_2d_array<f32>: layer l, row j, column i the table's
// entry), `floor_shadow_texels` (texture_2d<f32>: row j, column i the grid's node),
// `floor_repeat` (bilinear, repeating across columns, clamped across rows) and
// `cube_linear` (bilinear, clamped).

// As `floor_radiance` (common/view_shade.wgsl) reads the floor's caches from storage.
fn floor_radiance_filtered(px: PixelView, point_lights: u32, sun_lights: u32) -> vec3<f32> {
    let nodes = vec2<f32>(textureDimensions(floor_shadow_texels));
    let node = (floor_shadow_position(px.s.p) + 0.5) / nodes;
    let visibility = floor_lit(textureSampleLevel(floor_shadow_texels, cube_linear, node, 0.0), sun_lights);
    let size = vec2<f32>(textureDimensions(floor_table_texels));
    let uv = (floor_table_position(px.v, size) + 0.5) / size;
    var sum = textureSampleLevel(floor_table_texels, floor_repeat, uv, 0, 0.0).rgb;
    for (var k = 0u; k < min(sun_lights, MAX_SHADOW_MAPS); k++) {
        sum += visibility[k] * textureSampleLevel(floor_table_texels, floor_repeat, uv, 1u + k, 0.0).rgb;
    }
    return sum + direct_lights(px, point_lights);
}
