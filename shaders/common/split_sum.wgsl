// Split-sum shading of one surface point, exactly as the README tells an engine to:
// L = prefiltered(d, lod(r)) (F0 A + B) + E/pi(n) albedo kD,
// kD = (1 - F0)(1 - W(n.v))(1 - metallic), the BRDF's diffuse weight averaged over the light
// directions (diffuse_fresnel_weight in common/brdf.wgsl), and
// d = normalize(mix(R, n, bend(r))) the lookup direction, R = reflect(-v, n) bent toward
// the normal, read as two taps stretched toward grazing views by the material's stretch
// (math::lookup: Frostbite's dominant direction, stretched, for the generic target).
// CPU mirror: src/cpu/preview_split_sum.rs (same function names).
//
// The including kernel declares the baked light as module globals:
//   light: SplitSumParams (uniform), specular, irradiance: texture_2d_array<f32>,
//   lut: texture_2d<f32>.

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

// Bilinear LUT lookup at uv = (n.v, r), clamp-to-edge, texel centres at (i + 0.5) / W.
// The LUT texture holds each texel's (A, B) in .xy and its right neighbour's (clamped to
// the last column) in .zw (gpu::texture::upload_lut_pairs), so the four taps a, b, c, d of
// the CPU twin are two loads.
fn sample_lut(n_dot_v: f32, roughness: f32) -> vec2<f32> {
    let w = light.lut_width;
    let h = light.lut_height;
    let x = clamp(n_dot_v * f32(w) - 0.5, 0.0, f32(w - 1u));
    let y = clamp(roughness * f32(h) - 0.5, 0.0, f32(h - 1u));
    let x0 = floor(x);
    let y0 = floor(y);
    let fx = x - x0;
    let fy = y - y0;
    let i0 = u32(x0);
    let j0 = u32(y0);
    let j1 = min(j0 + 1u, h - 1u);
    let row0 = textureLoad(lut, vec2<u32>(i0, j0), 0);
    let row1 = textureLoad(lut, vec2<u32>(i0, j1), 0);
    let a = row0.xy;
    let b = row0.zw;
    let c = row1.xy;
    let d = row1.zw;
    return (a * (1.0 - fx) + b * fx) * (1.0 - fy) + (c * (1.0 - fx) + d * fx) * fy;
}

// normalize(mix(R, n, bend)) with R = reflect(-v, n); with n.v > 0, R.n = n.v > 0, so the
// blend never vanishes. Mirror of math::lookup::bent_reflection.
fn bent_reflection(n: vec3<f32>, v: vec3<f32>, bend: f32) -> vec3<f32> {
    let refl = 2.0 * dot(n, v) * n - v;
    return normalize(mix(refl, n, bend));
}

// The smallest |n - d (n.d)| stretched_prefiltered divides by (math::lookup::STRETCH_EPSILON).
const STRETCH_EPSILON: f32 = 1e-4;
// Where the taps' spread starts to fade to 0 at r = 1 (math::lookup::STRETCH_FADE_ROUGHNESS).
const STRETCH_FADE_ROUGHNESS: f32 = 0.9;

// The chain read along unit d for normal n as the material's stretch says: the mean of
// two taps normalize(d +- t) at lod', g = 1 - n.v,
// lod' = lod (1 - stretch g^2 (1 - r)), c = n - d (n.d),
// t = stretch alpha g fade c / max(|c|, eps), fade = min(1, (1 - r) / (1 - r_fade));
// with stretch 0 both are d at the chain's lod. Mirror of math::lookup::stretched_taps.
fn stretched_prefiltered(n: vec3<f32>, d: vec3<f32>, n_dot_v: f32, m: ShadeMaterial) -> vec3<f32> {
    let g = 1.0 - n_dot_v;
    let lod = m.lod * (1.0 - m.stretch * g * g * (1.0 - m.roughness));
    let c = n - d * dot(n, d);
    let fade = min(1.0, (1.0 - m.roughness) / (1.0 - STRETCH_FADE_ROUGHNESS));
    let t = (m.stretch * m.roughness * m.roughness * g * fade / max(length(c), STRETCH_EPSILON)) * c;
    let a = sample_cube_lod(specular, light.specular_size, light.specular_levels, normalize(d + t), lod);
    let b = sample_cube_lod(specular, light.specular_size, light.specular_levels, normalize(d - t), lod);
    return 0.5 * (a + b);
}

// The split-sum radiance towards v of a point with normal n; n_dot_v is n.v clamped
// away from 0 by the caller (silhouette normals are perpendicular to v).
fn split_sum_shade(n: vec3<f32>, v: vec3<f32>, n_dot_v: f32, m: ShadeMaterial) -> vec3<f32> {
    let dir = bent_reflection(n, v, m.bend);
    let prefiltered = stretched_prefiltered(n, dir, n_dot_v, m);
    let ab = sample_lut(n_dot_v, m.roughness);
    let spec = prefiltered * (m.f0 * ab.x + vec3<f32>(ab.y));
    let kd = (vec3<f32>(1.0) - m.f0) * ((1.0 - diffuse_fresnel_weight(n_dot_v)) * (1.0 - m.metallic));
    let e = sample_cube_lod(irradiance, light.irradiance_size, 1u, n, 0.0);
    return spec + e * m.albedo * kd;
}
