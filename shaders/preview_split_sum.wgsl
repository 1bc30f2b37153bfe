// The preview's split-sum render: each sphere pixel shaded as the README tells engines to,
// L = prefiltered(reflect(-v, n), lod(r)) (F0 A + B) + E/pi(n) albedo kD,
// kD = (1 - F_r(n.v))(1 - metallic); background pixels read the chain's level 0.
// CPU mirror: src/cpu/preview_split_sum.rs (same function names).

struct SplitSumParams {
    specular_size: u32,
    specular_levels: u32,
    irradiance_size: u32,
    lut_width: u32,
    lut_height: u32,
    _pad0: u32,
    _pad1: u32,
    _pad2: u32,
}

@group(0) @binding(0) var<uniform> scene: SceneParams;
@group(0) @binding(1) var<uniform> params: SplitSumParams;
@group(0) @binding(2) var specular: texture_2d_array<f32>;
@group(0) @binding(3) var irradiance: texture_2d_array<f32>;
@group(0) @binding(4) var lut: texture_2d<f32>;
// Per column: (roughness, lod, 0, 0).
@group(0) @binding(5) var<storage, read> columns: array<vec4<f32>>;
// Per material: (F0, metallic), (albedo, 0).
@group(0) @binding(6) var<storage, read> materials: array<vec4<f32>>;
@group(0) @binding(7) var output: texture_storage_2d<rgba32float, write>;

// Bilinear LUT lookup at uv = (n.v, r), clamp-to-edge, texel centres at (i + 0.5) / W.
fn sample_lut(n_dot_v: f32, roughness: f32) -> vec2<f32> {
    let w = params.lut_width;
    let h = params.lut_height;
    let x = clamp(n_dot_v * f32(w) - 0.5, 0.0, f32(w - 1u));
    let y = clamp(roughness * f32(h) - 0.5, 0.0, f32(h - 1u));
    let x0 = floor(x);
    let y0 = floor(y);
    let fx = x - x0;
    let fy = y - y0;
    let i0 = u32(x0);
    let j0 = u32(y0);
    let i1 = min(i0 + 1u, w - 1u);
    let j1 = min(j0 + 1u, h - 1u);
    let a = textureLoad(lut, vec2<u32>(i0, j0), 0).xy;
    let b = textureLoad(lut, vec2<u32>(i1, j0), 0).xy;
    let c = textureLoad(lut, vec2<u32>(i0, j1), 0).xy;
    let d = textureLoad(lut, vec2<u32>(i1, j1), 0).xy;
    return (a * (1.0 - fx) + b * fx) * (1.0 - fy) + (c * (1.0 - fx) + d * fx) * fy;
}

fn split_sum_shade(n: vec3<f32>, v: vec3<f32>, material: u32, column: u32) -> vec3<f32> {
    let col = columns[column];
    let r = col.x;
    let fm = materials[2u * material];
    let albedo = materials[2u * material + 1u].rgb;
    let f0 = fm.rgb;
    let metallic = fm.w;
    let n_dot_v = max(dot(n, v), scene.min_n_dot_v);
    let refl = 2.0 * dot(n, v) * n - v;
    let prefiltered = sample_cube_lod(specular, params.specular_size, params.specular_levels, refl, col.y);
    let ab = sample_lut(n_dot_v, r);
    let spec = prefiltered * (f0 * ab.x + vec3<f32>(ab.y));
    let f_r = vec3<f32>(
        fresnel_schlick_roughness(f0.x, n_dot_v, r),
        fresnel_schlick_roughness(f0.y, n_dot_v, r),
        fresnel_schlick_roughness(f0.z, n_dot_v, r),
    );
    let kd = (vec3<f32>(1.0) - f_r) * (1.0 - metallic);
    let e = sample_cube_lod(irradiance, params.irradiance_size, 1u, n, 0.0);
    return spec + e * albedo * kd;
}

@compute @workgroup_size(WORKGROUP_X, WORKGROUP_Y, WORKGROUP_Z)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    if (id.x >= scene.width || id.y >= scene.height) {
        return;
    }
    let g = pixel_geometry(scene, id.x, id.y);
    var c: vec3<f32>;
    if (g.sphere) {
        c = split_sum_shade(g.dir, g.v, g.material, g.column);
    } else {
        c = sample_cube_lod(specular, params.specular_size, params.specular_levels, g.dir, 0.0);
    }
    textureStore(output, vec2<i32>(id.xy), vec4<f32>(c, 1.0));
}
