// The viewer's split-sum frame in one render pass (vertex and fragment stages) after the
// object's G-buffer, what the window draws while the split-sum view is shown: each object
// pixel and floor fragment shaded as the deferred kernel shades a G-buffer pixel
// (`object_radiance`, common/view_shade.wgsl, and `floor_radiance_filtered`,
// common/view_floor_filter.wgsl, its `floor_radiance`), the background where nothing
// nearer was drawn (`background_radiance`), then displayed with the HUD over it as the present pass shows
// a split-sum pixel (common/view_display.wgsl). The same functions of the same surface as
// the deferred path (view_gbuffer, view_split_sum, view_present), which the truth and
// heat views and the HDR readback use; both give the same picture (tests/view.rs). CPU
// mirror: src/view/cpu.rs through the deferred path.

// Bindings 0 to 5 are what the background reads; the object's and the floor's bind
// groups name the bindings each reads (src/view/gpu/passes.rs). The chains and the floor's
// caches are read through the sampler's bilinear filter (common/cube_filter_bordered.wgsl,
// common/view_floor_filter.wgsl), where the deferred kernels fetch four texels or entries
// (common/cube_bilinear.wgsl, common/view_floor.wgsl, common/view_floor_shadow.wgsl).
@group(0) @binding(0) var<uniform> frame: FrameParams;
@group(0) @binding(1) var<uniform> light: SplitSumParams;
@group(0) @binding(2) var specular: texture_2d_array<f32>;
@group(0) @binding(3) var<uniform> present: PresentParams;
@group(0) @binding(4) var hud: texture_2d<f32>;
@group(0) @binding(5) var cube_linear: sampler;
@group(0) @binding(6) var irradiance: texture_2d_array<f32>;
@group(0) @binding(7) var lut: texture_2d<f32>;
@group(0) @binding(8) var<storage, read> lights: array<vec4<f32>>;
@group(0) @binding(9) var<storage, read> sun_texels: array<vec4<f32>>;
@group(0) @binding(10) var shadow_map: texture_2d_array<f32>;
@group(0) @binding(11) var<storage, read> floor_table: array<vec4<f32>>;
@group(0) @binding(12) var<storage, read> floor_shadow: array<vec4<f32>>;
@group(0) @binding(13) var gbuffer_position: texture_2d<f32>;
@group(0) @binding(14) var gbuffer_normal: texture_2d<f32>;
@group(0) @binding(15) var floor_table_texels: texture_2d_array<f32>;
@group(0) @binding(16) var floor_shadow_texels: texture_2d<f32>;
@group(0) @binding(17) var floor_repeat: sampler;

// The frame's light counts (frame.light_count, frame.sun.x), constants of the pipeline
// (src/view/gpu/mod.rs, `ForwardKey`): with them constant, the compiler unrolls the
// lights' loops or removes them, which a software rasteriser's fragment stage otherwise
// pays for even when they run zero times (docs/accuracy.md, "The viewer").
override POINT_LIGHTS: u32 = 0u;
override SUN_LIGHTS: u32 = 0u;

// The object's pixels, each shaded once from the G-buffer the pass before this one wrote
// of the object alone (view_gbuffer.wgsl's stages): one triangle over the frame, drawn
// where that pass left a depth (src/view/gpu/pipelines.rs, `Depth::Covered`).
@fragment
fn fs_object(@builtin(position) position: vec4<f32>) -> @location(0) vec4<f32> {
    let pixel = vec2<u32>(position.xy);
    return with_hud(display(object_radiance(pixel_view(pixel), POINT_LIGHTS, SUN_LIGHTS)), pixel);
}

// The floor's fragments, drawn after the object (whose depth hides what it covers), its
// caches read through the sampler (common/view_floor_filter.wgsl).
@fragment
fn fs_floor(v: VertexOut) -> @location(0) vec4<f32> {
    var s: Surface;
    s.id = u32(round(v.id));
    s.p = v.world;
    s.n = normalize(v.normal);
    let px = surface_view(v.clip.xy, s);
    return with_hud(display(floor_radiance_filtered(px, POINT_LIGHTS, SUN_LIGHTS)), vec2<u32>(v.clip.xy));
}

// The background: one triangle on the far plane, drawn last where the depth is still the
// cleared 1.
@vertex
fn vs_background(@builtin(vertex_index) i: u32) -> @builtin(position) vec4<f32> {
    return fullscreen_triangle(i, 1.0);
}

@fragment
fn fs_background(@builtin(position) position: vec4<f32>) -> @location(0) vec4<f32> {
    let dir = pixel_ray(frame, position.xy).dir;
    return with_hud(display(background_radiance(dir)), vec2<u32>(position.xy));
}
