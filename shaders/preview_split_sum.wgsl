// The preview's split-sum render: each sphere pixel shaded by `split_sum_shade`
// (common/split_sum.wgsl, with the grazing taps of common/filtered.wgsl where the light
// asks for it) with its row's material and its column's roughness; background
// pixels read the chain's level 0. CPU mirror: src/cpu/preview_split_sum.rs.

@group(0) @binding(0) var<uniform> scene: SceneParams;
@group(0) @binding(1) var<uniform> light: SplitSumParams;
@group(0) @binding(2) var specular: texture_2d_array<f32>;
@group(0) @binding(3) var irradiance: texture_2d_array<f32>;
@group(0) @binding(4) var lut: texture_2d<f32>;
// Per sphere, row by row: (roughness, lod, bend, stretch).
@group(0) @binding(5) var<storage, read> spheres: array<vec4<f32>>;
// Per material: (F0, metallic), (albedo, 0).
@group(0) @binding(6) var<storage, read> materials: array<vec4<f32>>;
@group(0) @binding(7) var output: texture_storage_2d<rgba32float, write>;

@compute @workgroup_size(WORKGROUP_X, WORKGROUP_Y, WORKGROUP_Z)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    if (id.x >= scene.width || id.y >= scene.height) {
        return;
    }
    let g = pixel_geometry(scene, id.x, id.y);
    var c: vec3<f32>;
    if (g.sphere) {
        let n_dot_v = max(dot(g.dir, g.v), scene.min_n_dot_v);
        let m = preview_material(g.material, g.column);
        c = split_sum_shade(g.dir, g.v, n_dot_v, m);
    } else {
        c = sample_cube_lod(specular, light.specular_size, light.specular_levels, g.dir, 0.0);
    }
    textureStore(output, vec2<i32>(id.xy), vec4<f32>(c, 1.0));
}
