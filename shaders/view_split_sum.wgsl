// The viewer's deferred split-sum shading: each pixel of the G-buffer shaded as
// common/view_shade.wgsl says (the object by the preview's split-sum function, the floor
// from its table, each plus the point lights on, the background by the chain's level 0), for the heat map and the HDR
// readback; the window's split-sum view draws the same in one pass (view_forward.wgsl).
// Writes (radiance, surface id) per pixel. CPU mirror: src/view/cpu.rs.

@group(0) @binding(0) var<uniform> frame: FrameParams;
@group(0) @binding(1) var<uniform> light: SplitSumParams;
@group(0) @binding(2) var specular: texture_2d_array<f32>;
@group(0) @binding(3) var irradiance: texture_2d_array<f32>;
@group(0) @binding(4) var lut: texture_2d<f32>;
@group(0) @binding(5) var<storage, read> lights: array<vec4<f32>>;
@group(0) @binding(6) var gbuffer_position: texture_2d<f32>;
@group(0) @binding(7) var gbuffer_normal: texture_2d<f32>;
@group(0) @binding(8) var<storage, read_write> shaded: array<vec4<f32>>;
@group(0) @binding(9) var<storage, read> sun_texels: array<vec4<f32>>;
@group(0) @binding(10) var shadow_map: texture_2d_array<f32>;
@group(0) @binding(11) var<storage, read> floor_table: array<vec4<f32>>;
@group(0) @binding(12) var<storage, read> floor_shadow: array<vec4<f32>>;

@compute @workgroup_size(WORKGROUP_X, WORKGROUP_Y, WORKGROUP_Z)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    if (id.x >= frame.width || id.y >= frame.height) {
        return;
    }
    let px = pixel_view(id.xy);
    var c: vec3<f32>;
    if (px.s.id == 0u) {
        c = background_radiance(px.dir);
    } else {
        c = surface_radiance(px, frame.light_count, frame.sun.x);
    }
    shaded[id.y * frame.width + id.x] = vec4<f32>(c, f32(px.s.id));
}
