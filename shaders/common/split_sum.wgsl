// Split-sum shading of one surface point, exactly as the README tells an engine to (or as
// an engine's own shader does, plan::shading, with the params' ibl_terms):
// L = mix(prefiltered(d, lod(r)), E/pi(n), w(r)) (F0 A + B) + E/pi(n) albedo kD,
// w(r) = r^4 the blend toward the irradiance (params' radiance_blend: RADIANCE_BLEND_*),
// kD = (1 - F0)(1 - W(n.v))(1 - metallic), the BRDF's diffuse weight averaged over the light
// directions (diffuse_fresnel_weight in common/brdf.wgsl), and
// d = normalize(mix(R, n, bend)) the lookup direction, R = reflect(-v, n) bent toward
// the normal by the material's bend (of r and F0), read as two taps stretched toward grazing views by the material's stretch
// (math::lookup: Frostbite's dominant direction, stretched, for the generic target), leaning
// toward the recipe's taps of the lobe at grazing views where the light asks for them
// (common/filtered.wgsl, which every kernel including this one includes too).
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
    ibl_terms: u32,          // IBL_TERMS_* (plan::shading::IblTerms)
    roughness_fresnel: u32,  // 1: kS is the roughness-aware Fresnel
    radiance_blend: u32,     // RADIANCE_BLEND_* (plan::shading::RadianceBlend)
    filtered: u32,           // 1: the grazing taps (common/filtered.wgsl)
    mip_roughness: u32,      // MIP_ROUGHNESS_*: how the chain's levels map to roughness
    pad: vec2<u32>,
}

// plan::shading::IblTerms: how the prefiltered radiance, (A, B) and E/pi combine.
const IBL_TERMS_SPLITSUM: u32 = 0u;
const IBL_TERMS_ENERGY_COMPENSATED: u32 = 1u;
const IBL_TERMS_MULTISCATTER_IRRADIANCE: u32 = 2u;
const IBL_TERMS_MULTISCATTER_RADIANCE: u32 = 3u;
const IBL_TERMS_LEGACY_DIFFUSE: u32 = 4u;
// plan::shading::RadianceBlend: how far S leans toward E/pi, w = 0, alpha or alpha^2.
const RADIANCE_BLEND_NONE: u32 = 0u;
const RADIANCE_BLEND_ALPHA: u32 = 1u;
const RADIANCE_BLEND_ALPHA_SQUARED: u32 = 2u;
// The cosine-weighted mean of (1 - cos)^5, 1/21 (plan::shading::FRESNEL_MEAN_WEIGHT).
const FRESNEL_MEAN_WEIGHT: f32 = 0.04761904761904762;

// The LUT at uv = (n.v, r) (lut_bilinear, common/lut.wgsl).
fn sample_lut(n_dot_v: f32, roughness: f32) -> vec2<f32> {
    return lut_bilinear(light.lut_width, light.lut_height, n_dot_v, roughness);
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

// The light towards v from the prefiltered radiance s, the LUT's ab = (A, B) and the
// irradiance e = E/pi at n, combined as the params' ibl_terms say (plan::shading: the
// recipe's S (F0 A + B) + E c kD, or an engine's FssEss / FmsEms terms).
// Mirror of cpu::preview_split_sum::ibl_terms.
fn ibl_terms(s: vec3<f32>, e: vec3<f32>, ab: vec2<f32>, n_dot_v: f32, m: ShadeMaterial) -> vec3<f32> {
    if (light.ibl_terms == IBL_TERMS_SPLITSUM) {
        let kd = (vec3<f32>(1.0) - m.f0) * ((1.0 - diffuse_fresnel_weight(n_dot_v)) * (1.0 - m.metallic));
        return s * (m.f0 * ab.x + vec3<f32>(ab.y)) + e * m.albedo * kd;
    }
    var ks = m.f0;
    if (light.roughness_fresnel != 0u) {
        ks = m.f0 + (max(vec3<f32>(1.0 - m.roughness), m.f0) - m.f0) * fresnel_schlick_weight(n_dot_v);
    }
    let fss_ess = ks * ab.x + vec3<f32>(ab.y);
    let ess = ab.x + ab.y;
    if (light.ibl_terms == IBL_TERMS_ENERGY_COMPENSATED || light.ibl_terms == IBL_TERMS_LEGACY_DIFFUSE) {
        // Filament's diffuse takes what the specular leaves, Babylon's legacy one 1 - F0.
        var kd = vec3<f32>(1.0) - fss_ess;
        if (light.ibl_terms == IBL_TERMS_LEGACY_DIFFUSE) {
            kd = vec3<f32>(1.0) - m.f0;
        }
        return s * fss_ess * specular_compensation(ab, m.f0) + e * m.albedo * kd * (1.0 - m.metallic);
    }
    let ems = 1.0 - ess;
    let f_avg = m.f0 + (vec3<f32>(1.0) - m.f0) * FRESNEL_MEAN_WEIGHT;
    let fms_ems = ems * fss_ess * f_avg / (vec3<f32>(1.0) - ems * f_avg);
    let diffuse = e * m.albedo * (vec3<f32>(1.0) - fss_ess - fms_ems) * (1.0 - m.metallic);
    if (light.ibl_terms == IBL_TERMS_MULTISCATTER_RADIANCE) {
        return s * (fss_ess + fms_ems) + diffuse;
    }
    return s * fss_ess + e * fms_ems + diffuse;
}

// The weight w of E/pi in the blended radiance mix(S, E, w) for roughness r, as the params'
// radiance_blend says. Mirror of plan::shading::RadianceBlend::weight.
fn radiance_blend_weight(r: f32) -> f32 {
    let alpha = alpha_from_roughness(r);
    if (light.radiance_blend == RADIANCE_BLEND_ALPHA) {
        return alpha;
    }
    if (light.radiance_blend == RADIANCE_BLEND_ALPHA_SQUARED) {
        return alpha * alpha;
    }
    return 0.0;
}

// The split-sum radiance towards v of a point with normal n; n_dot_v is n.v clamped
// away from 0 by the caller (silhouette normals are perpendicular to v). With the recipe's
// taps at grazing views (light.filtered) the prefiltered radiance leans toward
// `filtered_lookup`'s (common/filtered.wgsl).
fn split_sum_shade(n: vec3<f32>, v: vec3<f32>, n_dot_v: f32, m: ShadeMaterial) -> vec3<f32> {
    let filtered = filtered_lookup(n, v, n_dot_v, m);
    return split_sum_shade_with(n, bent_reflection(n, v, m.bend), n_dot_v, m, filtered);
}

// The split-sum radiance with the chain read along dir, its prefiltered radiance leaning
// toward `filtered`'s rgb by its w (the recipe's grazing taps, common/filtered.wgsl; w = 0 reads
// the chain alone). Mirror of cpu::preview_split_sum::split_sum_shade_with.
fn split_sum_shade_with(n: vec3<f32>, dir: vec3<f32>, n_dot_v: f32, m: ShadeMaterial, filtered: vec4<f32>) -> vec3<f32> {
    let prefiltered = stretched_prefiltered(n, dir, n_dot_v, m);
    let ab = sample_lut(n_dot_v, m.roughness);
    let e = sample_cube_lod(irradiance, light.irradiance_size, 1u, n, 0.0);
    let s = mix(mix(prefiltered, e, radiance_blend_weight(m.roughness)), filtered.rgb, filtered.w);
    return ibl_terms(s, e, ab, n_dot_v, m);
}
