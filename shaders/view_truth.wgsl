// The viewer's ground truth, one more estimate per call: each object or floor pixel's full
// reflectance integral (`truth_shade`, common/truth.wgsl, the preview's function) with
// truth.point_count points rotated by a hash of the pixel and frame.truth_frame, plus the
// point lights on and the discs of the lights taken out of the environment (the sun's
// through the same shadow map as the split-sum's, common/view_sun.wgsl); background pixels
// read the environment. Accumulates (radiance x
// points, points) per pixel, restarting at truth_frame 0. CPU mirror: src/view/cpu.rs.

@group(0) @binding(0) var<uniform> frame: FrameParams;
@group(0) @binding(1) var<uniform> truth: TruthParams;
@group(0) @binding(2) var env: texture_2d_array<f32>;
@group(0) @binding(3) var cold: texture_2d_array<f32>;
@group(0) @binding(4) var<storage, read> hot: array<vec4<f32>>;
@group(0) @binding(5) var<storage, read> points: array<vec4<f32>>;
@group(0) @binding(6) var<storage, read> lights: array<vec4<f32>>;
@group(0) @binding(7) var gbuffer_position: texture_2d<f32>;
@group(0) @binding(8) var gbuffer_normal: texture_2d<f32>;
@group(0) @binding(9) var<storage, read_write> accum: array<vec4<f32>>;
@group(0) @binding(10) var<storage, read> sun_texels: array<vec4<f32>>;
@group(0) @binding(11) var shadow_map: texture_2d_array<f32>;
@group(0) @binding(12) var<storage, read> floor_shadow: array<vec4<f32>>;

@compute @workgroup_size(WORKGROUP_X, WORKGROUP_Y, WORKGROUP_Z)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    if (id.x >= frame.width || id.y >= frame.height) {
        return;
    }
    let px = pixel_view(id.xy);
    let pixel = id.y * frame.width + id.x;
    var c: vec3<f32>;
    if (px.s.id == 0u) {
        c = sample_cube_lod(env, truth.env_size, 1u, px.dir, 0.0);
    } else {
        let shift = pixel_shift(pixel + frame.truth_frame * frame.width * frame.height);
        c = truth_shade(px.s.n, px.v, px.n_dot_v, px.m, shift) + direct_lights(px, frame.light_count)
            + truth_texels_shade(px, SPLIT_RECORD * frame.sun.x, frame.sun.y);
    }
    let w = f32(truth.point_count);
    let estimate = vec4<f32>(c * w, w);
    if (frame.truth_frame == 0u) {
        accum[pixel] = estimate;
    } else {
        accum[pixel] = accum[pixel] + estimate;
    }
}
