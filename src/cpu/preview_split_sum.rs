//! Split-sum shading ([`split_sum_shade`], also the viewer's) and the preview's split-sum
//! render: every sphere pixel shaded exactly as the README tells an engine to, from the
//! baked files' contents. CPU mirror of `shaders/common/split_sum.wgsl` and
//! `shaders/preview_split_sum.wgsl` (same function names).
//!
//! For normal n, view v, roughness r and a material (F0, albedo c, metallic m):
//!
//! L = mix(prefiltered(d, lod(r)), E/π(n), w(r)) · (F0·A + B) + E/π(n) · c · kD,
//! kD = (1 − F0)(1 − W(n·v))(1 − m), w(r) = r⁴ the blend toward the irradiance
//! (`plan::shading::RadianceBlend`),
//!
//! (an engine's mode combines the same reads as that engine's shader does: [`ibl_terms`],
//! `plan::shading`),
//!
//! with d = normalize(mix(R, n, t)) the lookup direction, R = reflect(−v, n) bent toward
//! n by the material's bend t (`math::lookup`: for the generic target Frostbite's dominant
//! direction, faded in below r = 0.5 and scaled down for a low F0; the engines' own in
//! their modes), read as the mean of two taps
//! stretched along the plane of incidence toward grazing views, from a sharper level, by
//! the material's stretch (`math::lookup::stretched_taps`; one tap with stretch 0), and
//! for the recipe's lookup leaning at grazing views of glossy points toward four taps of
//! the lobe itself ([`filtered_prefiltered`], `plan::filtered`),
//! (A, B) the LUT at uv = (n·v, r) sampled bilinearly with clamp-to-edge,
//! prefiltered a seamless trilinear lookup at the chain's lod for r, E/π a seamless
//! bilinear lookup of the irradiance cube, and W the cosine-weighted mean of the
//! Fresnel-Schlick weight (1 − v·h)⁵ over the light directions
//! (`brdf::diffuse_fresnel_weight`), so that kD is the BRDF's diffuse weight
//! (1 − F(v·h))(1 − m) under uniform light. Background pixels read level 0 of the chain (the
//! environment itself).

use glam::Vec3;
use rayon::prelude::*;

use crate::environment::sample::sample_cube_lod;
use crate::environment::Cubemap;
use crate::math::brdf::{
    alpha_from_roughness, d_ggx, diffuse_fresnel_weight, fresnel_schlick_weight, g1_schlick_ggx,
    g1_smith_ggx, k_ibl,
};
use crate::math::sampling::{sample_ggx_vndf, tangent_frame};
use crate::plan::chain::MipRoughness;
use crate::plan::filtered::{
    filtered_point, filtered_share, sample_lod, FILTERED_LEVEL_TAPS, FILTERED_TAPS, MIN_FILTERED_ALPHA,
};
use crate::plan::material::fresnel3;
use crate::math::lookup::{bent_reflection, stretched_taps};
use crate::plan::lut::BrdfLut;
use crate::plan::material::ShadeMaterial;
use crate::plan::shading::{IblTerms, ShadingTerms, FRESNEL_MEAN_WEIGHT};
use crate::plan::scene::{
    pixel_geometry, preview_material, PixelGeometry, SceneUniform, SplitSumInputs, SplitSumLight,
    MIN_N_DOT_V,
};

/// Bilinear lookup of the LUT at uv = (n·v, r) with clamp-to-edge addressing and texel
/// centres at ((i + ½)/W, (j + ½)/H), as a GPU sampler reads it. The WGSL reads the same
/// four taps with two loads of a texture holding each texel beside its right neighbour
/// (`gpu::texture::upload_lut_pairs`).
pub fn sample_lut(lut: &BrdfLut, n_dot_v: f32, roughness: f32) -> [f32; 2] {
    let (w, h) = (lut.width, lut.height);
    let x = (n_dot_v * w as f32 - 0.5).clamp(0.0, (w - 1) as f32);
    let y = (roughness * h as f32 - 0.5).clamp(0.0, (h - 1) as f32);
    let (x0, y0) = (x.floor(), y.floor());
    let (fx, fy) = (x - x0, y - y0);
    let (i0, j0) = (x0 as u32, y0 as u32);
    let (i1, j1) = ((i0 + 1).min(w - 1), (j0 + 1).min(h - 1));
    let (a, b, c, d) = (
        lut.get(i0, j0),
        lut.get(i1, j0),
        lut.get(i0, j1),
        lut.get(i1, j1),
    );
    [0, 1].map(|k| {
        (a[k] * (1.0 - fx) + b[k] * fx) * (1.0 - fy) + (c[k] * (1.0 - fx) + d[k] * fx) * fy
    })
}

/// The split-sum radiance towards `v` of a point with normal `n`; `n_dot_v` is n·v clamped
/// away from 0 by the caller (silhouette normals are perpendicular to v). With the quality
/// lookup (`light.filtered`) the prefiltered radiance leans toward [`filtered_prefiltered`]
/// by `plan::filtered::filtered_share`.
pub fn split_sum_shade(light: &SplitSumLight, n: Vec3, v: Vec3, n_dot_v: f32, m: &ShadeMaterial) -> Vec3 {
    let filtered = filtered_lookup(light, n, v, n_dot_v, m);
    split_sum_shade_with(light, n, bent_reflection(n, v, m.bend), n_dot_v, m, filtered)
}

/// The recipe's grazing taps' radiance at a point and its share there (`plan::filtered`), where
/// `light` has it and the share is above 0.
pub fn filtered_lookup(
    light: &SplitSumLight,
    n: Vec3,
    v: Vec3,
    n_dot_v: f32,
    m: &ShadeMaterial,
) -> Option<(Vec3, f32)> {
    let mapping = light.filtered?;
    let share = filtered_share(n_dot_v, m.roughness);
    if share <= 0.0 {
        return None;
    }
    filtered_prefiltered(light.specular, mapping, n, v, n_dot_v, m).map(|f| (f, share))
}

/// The split-sum radiance with the chain read along `dir` (the material's bent reflection
/// for [`split_sum_shade`]; a lookup that depends on more than r in the lookup study), as
/// the material's stretch says.
#[cfg_attr(not(feature = "internals"), allow(dead_code))]
pub fn split_sum_shade_along(
    light: &SplitSumLight,
    n: Vec3,
    dir: Vec3,
    n_dot_v: f32,
    m: &ShadeMaterial,
) -> Vec3 {
    split_sum_shade_with(light, n, dir, n_dot_v, m, None)
}

/// [`split_sum_shade_along`], its prefiltered radiance leaning toward `filtered`'s
/// radiance by its share where there is one.
pub fn split_sum_shade_with(
    light: &SplitSumLight,
    n: Vec3,
    dir: Vec3,
    n_dot_v: f32,
    m: &ShadeMaterial,
    filtered: Option<(Vec3, f32)>,
) -> Vec3 {
    let (a, b, lod) = stretched_taps(n, dir, n_dot_v, m.roughness, m.lod, m.stretch);
    let prefiltered = 0.5
        * (Vec3::from(sample_cube_lod(light.specular, a.into(), lod))
            + Vec3::from(sample_cube_lod(light.specular, b.into(), lod)));
    let ab = sample_lut(light.lut, n_dot_v, m.roughness);
    let irradiance = Vec3::from(sample_cube_lod(light.irradiance, n.into(), 0.0));
    let mut s = prefiltered.lerp(irradiance, light.terms.radiance_blend.weight(m.roughness));
    if let Some((f, share)) = filtered {
        s = s.lerp(f, share);
    }
    ibl_terms(light.terms, s, irradiance, ab, n_dot_v, m)
}

/// The recipe's grazing taps' prefiltered radiance at a point of normal `n` seen from `v`
/// (`plan::filtered`): [`FILTERED_TAPS`] samples of the GGX lobe's visible normals in the
/// plane of incidence, each l = reflect(−v, h) above the horizon read from `chain` at the
/// level of its share of the sphere (`mapping` its levels' roughness), their sum weighted
/// by F G(l) G(v) / G1(v), normalised per channel; None where no sample is above the
/// horizon. Mirror of `filtered_prefiltered` in shaders/common/filtered.wgsl.
pub fn filtered_prefiltered(
    chain: &Cubemap,
    mapping: MipRoughness,
    n: Vec3,
    v: Vec3,
    n_dot_v: f32,
    m: &ShadeMaterial,
) -> Option<Vec3> {
    let alpha = alpha_from_roughness(m.roughness).max(MIN_FILTERED_ALPHA);
    let (t1, t2) = tangent_frame(n.into());
    let (t1, t2) = (Vec3::from(t1), Vec3::from(t2));
    let v_local = [v.dot(t1), v.dot(t2), n_dot_v];
    let k = k_ibl(m.roughness);
    // The sampler's exact masking of v, which every sample's pdf and weight divide by.
    let g1_v = g1_smith_ggx(n_dot_v, alpha * alpha);
    let masking_v = g1_schlick_ggx(n_dot_v, k) / g1_v;
    let levels = chain.levels.len() as u32;
    let (mut sum, mut weight) = (Vec3::ZERO, Vec3::ZERO);
    for i in 0..FILTERED_TAPS {
        let h = sample_ggx_vndf(v_local, alpha, filtered_point(i));
        let h = t1 * h[0] + t2 * h[1] + n * h[2];
        let v_dot_h = v.dot(h);
        let l = 2.0 * v_dot_h * h - v;
        let n_dot_l = n.dot(l);
        if n_dot_l <= 0.0 || v_dot_h <= 0.0 {
            continue;
        }
        let pdf = g1_v * d_ggx(n.dot(h).max(0.0), alpha) / (4.0 * n_dot_v);
        let lod = sample_lod(mapping, levels, pdf, FILTERED_LEVEL_TAPS);
        let w = fresnel3(m.f0, v_dot_h) * (g1_schlick_ggx(n_dot_l, k) * masking_v);
        sum += w * Vec3::from(sample_cube_lod(chain, l.into(), lod));
        weight += w;
    }
    (weight.min_element() > 0.0).then(|| sum / weight)
}

/// The light towards v from the prefiltered radiance `s`, the LUT's `ab` = (A, B) and the
/// irradiance `e` = E/π at n, combined as `terms` says ([`crate::plan::shading`]'s
/// notation): the recipe's S (F0 A + B) + E c (1 − F0)(1 − W(n·v))(1 − m), or an engine's
/// FssEss and FmsEms terms. Mirror of `ibl_terms` in `shaders/common/split_sum.wgsl`.
pub fn ibl_terms(terms: ShadingTerms, s: Vec3, e: Vec3, ab: [f32; 2], n_dot_v: f32, m: &ShadeMaterial) -> Vec3 {
    let [a, b] = ab;
    if terms.ibl == IblTerms::Splitsum {
        let kd = (Vec3::ONE - m.f0) * ((1.0 - diffuse_fresnel_weight(n_dot_v)) * (1.0 - m.metallic));
        return s * (m.f0 * a + Vec3::splat(b)) + e * m.albedo * kd;
    }
    let ks = if terms.roughness_fresnel {
        m.f0 + (Vec3::splat(1.0 - m.roughness).max(m.f0) - m.f0) * fresnel_schlick_weight(n_dot_v)
    } else {
        m.f0
    };
    let fss_ess = ks * a + Vec3::splat(b);
    let ess = a + b;
    if matches!(terms.ibl, IblTerms::EnergyCompensated | IblTerms::LegacyDiffuse) {
        // Filament's diffuse takes what the specular leaves, Babylon's legacy one 1 − F0.
        let kd = match terms.ibl {
            IblTerms::LegacyDiffuse => Vec3::ONE - m.f0,
            _ => Vec3::ONE - fss_ess,
        };
        return s * fss_ess * specular_compensation(ab, m.f0) + e * m.albedo * kd * (1.0 - m.metallic);
    }
    let ems = 1.0 - ess;
    let f_avg = m.f0 + (Vec3::ONE - m.f0) * FRESNEL_MEAN_WEIGHT;
    let fms_ems = ems * fss_ess * f_avg / (Vec3::ONE - ems * f_avg);
    let diffuse = e * m.albedo * (Vec3::ONE - fss_ess - fms_ems) * (1.0 - m.metallic);
    if terms.ibl == IblTerms::MultiscatterRadiance {
        return s * (fss_ess + fms_ems) + diffuse;
    }
    s * fss_ess + e * fms_ems + diffuse
}

/// The factor 1 + F0 (1/Ess − 1), Ess = A + B of the LUT's `ab`, by which a compensated
/// light BRDF scales its specular ([`crate::plan::shading::LightBrdf::compensated`];
/// Turquin 2019). Mirror of `specular_compensation` in `shaders/common/lut.wgsl`.
pub fn specular_compensation(ab: [f32; 2], f0: Vec3) -> Vec3 {
    Vec3::ONE + f0 * (1.0 / (ab[0] + ab[1]) - 1.0)
}

/// The split-sum panel, row-major linear RGB.
pub fn render_split_sum(scene: &SceneUniform, inputs: &SplitSumInputs) -> Vec<[f32; 3]> {
    render_with(scene, inputs, |n, v, n_dot_v, m| {
        split_sum_shade(&inputs.light, n, v, n_dot_v, m)
    })
}

/// The panel with each sphere pixel shaded by `shade(n, v, n·v clamped, material)` (a
/// lookup study's variant of [`split_sum_shade`], such as [`split_sum_shade_along`] a
/// direction that depends on n·v: `math::lookup::FITTED`) and the background reading
/// level 0 of the chain.
#[cfg(any(test, feature = "internals"))]
pub fn render_split_sum_shaded(
    scene: &SceneUniform,
    inputs: &SplitSumInputs,
    shade: impl Fn(Vec3, Vec3, f32, &ShadeMaterial) -> Vec3 + Sync,
) -> Vec<[f32; 3]> {
    render_with(scene, inputs, shade)
}

/// The panel with each sphere pixel shaded by `shade(n, v, n·v clamped, material)` and the
/// background reading level 0 of the chain.
fn render_with(
    scene: &SceneUniform,
    inputs: &SplitSumInputs,
    shade: impl Fn(Vec3, Vec3, f32, &ShadeMaterial) -> Vec3 + Sync,
) -> Vec<[f32; 3]> {
    (0..scene.height)
        .into_par_iter()
        .flat_map_iter(|y| {
            let shade = &shade;
            (0..scene.width).map(move |x| match pixel_geometry(scene, x, y) {
                PixelGeometry::Background { dir } => {
                    sample_cube_lod(inputs.light.specular, dir.into(), 0.0)
                }
                PixelGeometry::Sphere {
                    n,
                    v,
                    material,
                    column,
                } => {
                    let m = preview_material(inputs.spheres, inputs.materials, scene.columns as usize, material, column);
                    shade(n, v, n.dot(v).max(MIN_N_DOT_V), &m).into()
                }
            })
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::plan::shading::RadianceBlend;

    fn material(f0: f32, metallic: f32, roughness: f32) -> ShadeMaterial {
        ShadeMaterial {
            f0: Vec3::splat(f0),
            metallic,
            albedo: Vec3::splat(0.5),
            roughness,
            lod: 0.0,
            bend: 0.0,
            stretch: 0.0,
        }
    }

    /// Babylon.js's terms: the specular scaled by FssEss and the compensation; the diffuse
    /// c (1 − F0)(1 − m), whatever FssEss.
    #[test]
    fn legacy_diffuse_terms() {
        let terms = ShadingTerms {
            ibl: IblTerms::LegacyDiffuse,
            roughness_fresnel: false,
            radiance_blend: RadianceBlend::None,
        };
        let (ab, n_dot_v) = ([0.3, 0.2], 0.7);
        // A metal: FssEss = 0.9 · 0.3 + 0.2 = 0.47, the compensation 1 + 0.9 (1/0.5 − 1).
        let metal = material(0.9, 1.0, 0.5);
        let got = ibl_terms(terms, Vec3::splat(2.0), Vec3::ONE, ab, n_dot_v, &metal);
        assert!((got.x - 2.0 * 0.47 * 1.9).abs() < 1e-6, "{got}");
        // A dielectric lit by E alone: E c (1 − 0.04).
        let dielectric = material(0.04, 0.0, 0.0);
        let got = ibl_terms(terms, Vec3::ZERO, Vec3::ONE, ab, n_dot_v, &dielectric);
        assert!((got.x - 0.5 * 0.96).abs() < 1e-6, "{got}");
    }

    /// The blend's weight of E/π: none, α or α² (a white furnace has S = E and cannot
    /// tell them apart).
    #[test]
    fn radiance_blend_weights() {
        for (blend, want) in [
            (RadianceBlend::None, 0.0),
            (RadianceBlend::Alpha, 0.25),
            (RadianceBlend::AlphaSquared, 0.0625),
        ] {
            assert_eq!(blend.weight(0.5), want, "{blend:?}");
            assert_eq!(blend.weight(1.0), if blend == RadianceBlend::None { 0.0 } else { 1.0 });
        }
    }
}
