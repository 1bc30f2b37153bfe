// The viewer's split-sum shading: each object or floor pixel of the G-buffer shaded by
// `split_sum_shade` (common/split_sum.wgsl, the preview's function) plus the point lights
// on; background pixels read the chain's level 0. Writes (radiance, surface id) per pixel.
// CPU mirror: src/view/cpu.rs.

@group(0) @binding(0) var<uniform> frame: FrameParams;
@group(0) @binding(1) var<uniform> light: SplitSumParams;
@group(0) @binding(2) var specular: texture_2d_array<f32>;
@group(0) @binding(3) var irradiance: texture_2d_array<f32>;
@group(0) @binding(4) var lut: texture_2d<f32>;
@group(0) @binding(5) var<storage, read> lights: array<vec4<f32>>;
@group(0) @binding(6) var gbuffer_position: texture_2d<f32>;
@group(0) @binding(7) var gbuffer_normal: texture_2d<f32>;
@group(0) @binding(8) var<storage, read_write> shaded: array<vec4<f32>>;

@compute @workgroup_size(WORKGROUP_X, WORKGROUP_Y, WORKGROUP_Z)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    if (id.x >= frame.width || id.y >= frame.height) {
        return;
    }
    let px = pixel_view(id.xy);
    var c: vec3<f32>;
    if (px.s.id == 0u) {
        c = sample_cube_lod(specular, light.specular_size, light.specular_levels, px.dir, 0.0);
    } else {
        c = split_sum_shade(px.s.n, px.v, px.n_dot_v, px.m) + direct_lights(px);
    }
    shaded[id.y * frame.width + id.x] = vec4<f32>(c, f32(px.s.id));
}
