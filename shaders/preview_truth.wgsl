// The preview's ground truth: each sphere pixel's full reflectance integral
// (`truth_shade_parts`, common/truth.wgsl) with its row's material and its column's
// roughness, the specular scaled by the LUT's compensation where the BRDF is compensated,
// the quadrature rotated by a hash of the pixel index; background pixels read the
// environment. CPU mirror: src/cpu/preview_truth.rs.

@group(0) @binding(0) var<uniform> scene: SceneParams;
@group(0) @binding(1) var<uniform> truth: TruthParams;
@group(0) @binding(2) var env: texture_2d_array<f32>;
@group(0) @binding(3) var cold: texture_2d_array<f32>;
@group(0) @binding(4) var<storage, read> hot: array<vec4<f32>>;
// Per sphere, row by row: (roughness, lod, bend, stretch).
@group(0) @binding(5) var<storage, read> spheres: array<vec4<f32>>;
// Per material: (F0, metallic), (albedo, 0).
@group(0) @binding(6) var<storage, read> materials: array<vec4<f32>>;
@group(0) @binding(7) var<storage, read> points: array<vec4<f32>>;
@group(0) @binding(8) var lut: texture_2d<f32>;
@group(0) @binding(9) var output: texture_storage_2d<rgba32float, write>;

@compute @workgroup_size(WORKGROUP_X, WORKGROUP_Y, WORKGROUP_Z)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    if (id.x >= scene.width || id.y >= scene.height) {
        return;
    }
    let g = pixel_geometry(scene, id.x, id.y);
    var c: vec3<f32>;
    if (g.sphere) {
        let n_dot_v = max(dot(g.dir, g.v), scene.min_n_dot_v);
        let shift = pixel_shift(id.y * scene.width + id.x);
        let m = preview_material(g.material, g.column);
        let parts = truth_shade_parts(g.dir, g.v, n_dot_v, m, shift);
        var spec = parts.spec;
        if (truth.compensated != 0u) {
            spec *= specular_compensation(lut_bilinear(truth.lut_width, truth.lut_height, n_dot_v, m.roughness), m.f0);
        }
        c = spec + parts.diff;
    } else {
        c = sample_cube_lod(env, truth.env_size, 1u, g.dir, 0.0);
    }
    textureStore(output, vec2<i32>(id.xy), vec4<f32>(c, 1.0));
}
