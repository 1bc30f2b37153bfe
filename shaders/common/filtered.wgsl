// The recipe's taps at grazing views: filtered importance sampling of the prefiltered chain with
// samples of GGX's visible normals in the plane of incidence at grazing views (src/plan/filtered.rs says what and
// why). Mirror of cpu::preview_split_sum::{filtered_lookup, filtered_prefiltered} and
// plan::filtered::{filtered_share, sample_lod, filtered_point}, plan::chain::MipRoughness::lod.
// The including kernel includes brdf.wgsl, sampling.wgsl, cube_sample.wgsl, material.wgsl
// and split_sum.wgsl, and declares `light` (SplitSumParams) and `specular`.

// plan::filtered's constants.
const FILTERED_TAPS: u32 = 4u;
const FILTERED_LEVEL_TAPS: u32 = 2u;
const FILTERED_PLANE_INNER: f32 = 0.19764395;
const FILTERED_PLANE_OUTER: f32 = 0.6347046;
const FILTERED_N_DOT_V_LO: f32 = 0.4;
const FILTERED_N_DOT_V_HI: f32 = 0.6;
const FILTERED_ROUGHNESS_LO: f32 = 0.6;
const FILTERED_ROUGHNESS_HI: f32 = 0.9;
const FILTERED_FADE_IN_ROUGHNESS: f32 = 0.2;
const FILTERED_LOD_BIAS: f32 = -0.5;
const MIN_FILTERED_ALPHA: f32 = 1e-3;
// plan::chain::MipRoughness as u32, and Babylon's mapping's constants.
const MIP_ROUGHNESS_LINEAR: u32 = 0u;
const MIP_ROUGHNESS_QUADRATIC: u32 = 1u;
const BABYLON_LOD_SCALE: f32 = 0.8;
const BABYLON_MINIMUM_VARIANCE: f32 = 0.0005;

// The lod a shader reads roughness r at in the chain (light.mip_roughness over levels).
fn chain_lod(r_in: f32, levels: u32) -> f32 {
    let r = clamp(r_in, 0.0, 1.0);
    let max_lod = f32(max(levels, 1u) - 1u);
    if (light.mip_roughness == MIP_ROUGHNESS_LINEAR) {
        return r * max_lod;
    }
    if (light.mip_roughness == MIP_ROUGHNESS_QUADRATIC) {
        return r * (2.0 - r) * max_lod;
    }
    return clamp(BABYLON_LOD_SCALE * (max_lod + log2(r * r + BABYLON_MINIMUM_VARIANCE)), 0.0, max_lod);
}

// How much of the taps' radiance a point of n_dot_v and roughness r takes.
fn filtered_share(n_dot_v: f32, r: f32) -> f32 {
    let a = clamp((FILTERED_N_DOT_V_HI - n_dot_v) / (FILTERED_N_DOT_V_HI - FILTERED_N_DOT_V_LO), 0.0, 1.0);
    let b = clamp((FILTERED_ROUGHNESS_HI - r) / (FILTERED_ROUGHNESS_HI - FILTERED_ROUGHNESS_LO), 0.0, 1.0);
    return a * b * clamp(r / FILTERED_FADE_IN_ROUGHNESS, 0.0, 1.0);
}

// The chain's level for a sample of density pdf among `taps`.
fn sample_lod(levels: u32, pdf: f32, taps: u32) -> f32 {
    let omega = 1.0 / (f32(taps) * pdf);
    let alpha = min(sqrt(omega / (4.0 * PI)), 1.0);
    let lod = chain_lod(sqrt(alpha), levels) + FILTERED_LOD_BIAS;
    return clamp(lod, 0.0, f32(max(levels, 1u) - 1u));
}

// The i-th point of the fixed set on the disc of sample_ggx_vndf: on its axis in the plane
// of incidence at -outer, -inner, inner, outer.
fn filtered_point(i: u32) -> vec2<f32> {
    let y = select(FILTERED_PLANE_INNER, FILTERED_PLANE_OUTER, i == 0u || i + 1u == FILTERED_TAPS);
    return vec2<f32>(0.0, select(y, -y, i < FILTERED_TAPS / 2u));
}

// The taps' normalised radiance at a point (rgb) and whether a sample was above
// the horizon (w = 1) or not (w = 0).
fn filtered_prefiltered(n: vec3<f32>, v: vec3<f32>, n_dot_v: f32, m: ShadeMaterial) -> vec4<f32> {
    let alpha = max(alpha_from_roughness(m.roughness), MIN_FILTERED_ALPHA);
    let frame = tangent_frame(n);
    let t1 = frame[0];
    let t2 = frame[1];
    let v_local = vec3<f32>(dot(v, t1), dot(v, t2), n_dot_v);
    let k = k_ibl(m.roughness);
    // The sampler's exact masking of v, which every sample's pdf and weight divide by.
    let g1_v = g1_smith_ggx(n_dot_v, alpha * alpha);
    let masking_v = g1_schlick_ggx(n_dot_v, k) / g1_v;
    var sum = vec3<f32>(0.0);
    var weight = vec3<f32>(0.0);
    for (var i = 0u; i < FILTERED_TAPS; i++) {
        let hl = sample_ggx_vndf(v_local, alpha, filtered_point(i));
        let h = t1 * hl.x + t2 * hl.y + n * hl.z;
        let v_dot_h = dot(v, h);
        let l = 2.0 * v_dot_h * h - v;
        let n_dot_l = dot(n, l);
        if (n_dot_l <= 0.0 || v_dot_h <= 0.0) {
            continue;
        }
        let pdf = g1_v * d_ggx(max(dot(n, h), 0.0), alpha) / (4.0 * n_dot_v);
        let lod = sample_lod(light.specular_levels, pdf, FILTERED_LEVEL_TAPS);
        let w = fresnel3(m.f0, v_dot_h) * (g1_schlick_ggx(n_dot_l, k) * masking_v);
        sum += w * sample_cube_lod(specular, light.specular_size, light.specular_levels, l, lod);
        weight += w;
    }
    if (min(weight.x, min(weight.y, weight.z)) > 0.0) {
        return vec4<f32>(sum / weight, 1.0);
    }
    return vec4<f32>(0.0);
}

// The taps at a point as split_sum_shade_with takes it: (radiance, share), or 0
// where the light has none (light.filtered = 0) or the point takes none.
fn filtered_lookup(n: vec3<f32>, v: vec3<f32>, n_dot_v: f32, m: ShadeMaterial) -> vec4<f32> {
    let share = filtered_share(n_dot_v, m.roughness);
    if (light.filtered == 0u || share <= 0.0) {
        return vec4<f32>(0.0);
    }
    let f = filtered_prefiltered(n, v, n_dot_v, m);
    return vec4<f32>(f.rgb, share * f.w);
}
