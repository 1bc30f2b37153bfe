//! A surface's material as both renderers' shading functions take it (the preview's
//! spheres, the viewer's object and floor). CPU twin of `shaders/common/material.wgsl`.
//!
//! The BRDF: Cook-Torrance with GGX D (α = r²), Smith / Schlick-GGX G and Fresnel-Schlick,
//! plus Lambert diffuse c/π weighted by kD = (1 − F)(1 − metallic)
//! (docs/conventions.md, "Roughness, BRDF").

use glam::Vec3;

use crate::math::brdf::{
    alpha_from_roughness, burley_weight, d_ggx, fresnel_schlick_weight, g1_over_n_dot_v, g1_schlick_ggx, k_direct,
    smith_correlated_4v_n_dot_l, smith_correlated_lambda,
};
use crate::plan::shading::{DiffuseLobe, LightBrdf, Masking};

/// One surface's material and where the split-sum reads the chain for its roughness: the
/// lod, the lookup direction's bend and its stretch (`math::lookup`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ShadeMaterial {
    /// Linear-RGB reflectance at normal incidence.
    pub f0: Vec3,
    /// 1 for a metal (no diffuse), 0 for a dielectric.
    pub metallic: f32,
    /// Linear-RGB diffuse albedo c (Lambert c/π).
    pub albedo: Vec3,
    /// Perceptual roughness r.
    pub roughness: f32,
    /// The specular chain's lod for `roughness` (`RoughnessMapping::lod`).
    pub lod: f32,
    /// How far the chain's lookup direction leans from R toward n for `roughness` and
    /// `f0` (`math::lookup::SpecularLookup::bend`: 0 along R, 1 along n).
    pub bend: f32,
    /// How strongly the lookup reads two taps stretched toward grazing views
    /// (`math::lookup::stretched_taps`; `SpecularLookup::stretch`: 0 reads one tap).
    pub stretch: f32,
}

/// Fresnel-Schlick per channel: F0 + (1 − F0)(1 − v·h)⁵ (Schlick 1994).
pub fn fresnel3(f0: Vec3, v_dot_h: f32) -> Vec3 {
    let w = fresnel_schlick_weight(v_dot_h);
    f0 * (1.0 - w) + Vec3::splat(w)
}

/// 4 (n·l) times `brdf`'s specular masking over 4 (n·l)(n·v), for n·l > 0: the
/// Schlick-GGX G1(n·l) G1(n·v)/(n·v) with k = α/2, or the height-correlated 4 V (n·l).
/// Mirror of `light_masking` in `shaders/common/material.wgsl`.
pub fn light_masking(brdf: LightBrdf, n_dot_l: f32, n_dot_v: f32, alpha: f32) -> f32 {
    match brdf.masking {
        Masking::SmithCorrelated => {
            let a2 = alpha * alpha;
            smith_correlated_4v_n_dot_l(n_dot_v, n_dot_l, a2, smith_correlated_lambda(n_dot_v, a2))
        }
        Masking::SchlickGgx => {
            let k = 0.5 * alpha;
            g1_schlick_ggx(n_dot_l, k) * g1_over_n_dot_v(n_dot_v, k)
        }
    }
}

/// What `brdf`'s diffuse lobe weights Lambert by besides (1 − metallic), for n·l, n·v and
/// v·h (= l·h): 1 − F(v·h), 1, Burley's ([`burley_weight`]), or 1 − F0. Mirror of `diffuse_weight`
/// in `shaders/common/material.wgsl`.
pub fn diffuse_weight(
    brdf: LightBrdf,
    f0: Vec3,
    n_dot_l: f32,
    n_dot_v: f32,
    v_dot_h: f32,
    alpha: f32,
) -> Vec3 {
    match brdf.diffuse {
        DiffuseLobe::FresnelWeighted => Vec3::ONE - fresnel3(f0, v_dot_h),
        DiffuseLobe::Lambert => Vec3::ONE,
        DiffuseLobe::Burley => Vec3::splat(burley_weight(n_dot_l, n_dot_v, v_dot_h, alpha)),
        DiffuseLobe::DielectricLambert => Vec3::ONE - f0,
    }
}

/// What a light of irradiance `e` (L times its solid angle) from unit direction `l` sends
/// towards `v` off a point with normal `n`, e f(l, v) (n·l) with `brdf`, as (specular,
/// diffuse per unit albedo): GGX D, its masking ([`light_masking`]), Fresnel-Schlick at
/// v·h, plus Lambert weighted by (1 − F)(1 − metallic) or by (1 − metallic) alone, as its
/// diffuse says; at α = 0 no specular (a mirror shows a direction's light as a point: the
/// mirror lookup's). The truth's hot texels and the lights taken out of the environment are
/// shaded by it ([`LightBrdf::GENERIC`]: Schlick-GGX, Fresnel-weighted, for the recipe).
/// Mirror of `directional_light` in `shaders/common/material.wgsl`.
#[allow(clippy::too_many_arguments)]
pub fn directional_light(
    n: Vec3,
    v: Vec3,
    n_dot_v: f32,
    alpha: f32,
    f0: Vec3,
    metallic: f32,
    l: Vec3,
    e: Vec3,
    brdf: LightBrdf,
) -> (Vec3, Vec3) {
    let n_dot_l = n.dot(l);
    if n_dot_l <= 0.0 {
        return (Vec3::ZERO, Vec3::ZERO);
    }
    let h = (l + v).normalize();
    let f = fresnel3(f0, v.dot(h).max(0.0));
    let mut spec = Vec3::ZERO;
    if alpha > 0.0 {
        // f (n·l) = D F (4 (n·l) masking) / 4
        let w = d_ggx(n.dot(h).max(0.0), alpha) * light_masking(brdf, n_dot_l, n_dot_v, alpha) * 0.25;
        spec = e * f * w;
    }
    let mut diff = Vec3::ZERO;
    if metallic < 1.0 {
        let weight = diffuse_weight(brdf, f0, n_dot_l, n_dot_v, v.dot(h).max(0.0), alpha);
        diff = e * weight * ((1.0 - metallic) * n_dot_l / std::f32::consts::PI);
    }
    (spec, diff)
}

/// The radiance towards `v` that a point light at `light_position` of intensity
/// `light_colour` sends off a surface point `p` with normal `n`: Cook-Torrance with GGX D
/// (α = r²), Schlick-GGX G1 with k = (r + 1)²/8 ([`k_direct`]) for l and v, Fresnel-Schlick
/// at v·h, plus Lambert c/π weighted by (1 − F)(1 − metallic), times n·l and colour/d²;
/// α is at least `min_alpha` ([`MIN_DIRECT_ALPHA`]).
/// `n_dot_v` is n·v clamped away from 0 by the caller. Mirror of `point_light` in
/// `shaders/common/material.wgsl`, argument for argument.
#[allow(clippy::too_many_arguments)]
#[cfg_attr(not(feature = "view"), allow(dead_code))]
pub fn point_light(
    p: Vec3,
    n: Vec3,
    v: Vec3,
    n_dot_v: f32,
    m: &ShadeMaterial,
    light_position: Vec3,
    light_colour: Vec3,
    min_alpha: f32,
) -> Vec3 {
    let to_light = light_position - p;
    let d2 = to_light.length_squared();
    let l = to_light / d2.sqrt();
    let n_dot_l = n.dot(l);
    if n_dot_l <= 0.0 || d2 <= 0.0 {
        return Vec3::ZERO;
    }
    let h = (l + v).normalize();
    let f = fresnel3(m.f0, v.dot(h).max(0.0));
    let k = k_direct(m.roughness);
    let alpha = alpha_from_roughness(m.roughness).max(min_alpha);
    let d = d_ggx(n.dot(h).max(0.0), alpha);
    let g = g1_schlick_ggx(n_dot_l, k) * g1_schlick_ggx(n_dot_v, k);
    let specular = f * (d * g / (4.0 * n_dot_l * n_dot_v));
    let diffuse = (Vec3::ONE - f) * (1.0 - m.metallic) * m.albedo / std::f32::consts::PI;
    (specular + diffuse) * light_colour * (n_dot_l / d2)
}

/// The smallest α the point lights use: a point light on a mirror is a single pixel of
/// infinite radiance, so r = 0 is lit as α = 1e-3 (r ≈ 0.03), a highlight a few pixels
/// wide.
#[cfg_attr(not(feature = "view"), allow(dead_code))]
pub const MIN_DIRECT_ALPHA: f32 = 1e-3;
