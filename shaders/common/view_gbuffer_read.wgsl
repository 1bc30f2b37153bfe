// A pixel's surface read from the viewer's G-buffer (written by view_gbuffer.wgsl), for
// the deferred kernels. Mirror of src/view/cpu.rs (`pixel_view`). The including kernel
// declares `gbuffer_position` and `gbuffer_normal` (texture_2d<f32>).

fn load_surface(pixel: vec2<u32>) -> Surface {
    let g = textureLoad(gbuffer_position, pixel, 0);
    var s: Surface;
    s.id = u32(round(g.w));
    s.p = g.xyz;
    s.n = textureLoad(gbuffer_normal, pixel, 0).xyz;
    return s;
}

fn pixel_view(pixel: vec2<u32>) -> PixelView {
    return surface_view(vec2<f32>(f32(pixel.x) + 0.5, f32(pixel.y) + 0.5), load_surface(pixel));
}
