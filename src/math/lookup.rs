//! Where a shader looks the prefiltered specular chain up: the direction each engine's
//! shader derives from the normal n, the view v (toward the eye) and the perceptual
//! roughness r. The chain's level for r is prefiltered with v = n, so its lobe is centred
//! on R = reflect(−v, n) only at normal incidence; at high roughness the true lobe leans
//! toward n (the "off-specular peak", Lagarde & de Rousiers 2014, §4.9.3). Every lookup
//! here is R bent toward n, normalize(mix(R, n, t)), by a bend t ∈ [0, 1] that depends on
//! r and, for the recipe's lookup, on the material's F0, whose Fresnel pulls the lobe back
//! toward R ([`SpecularLookup::bend`], [`fresnel_bend_scale`]); neither varies over a
//! surface of one material, so the shading functions take t as part of the material,
//! beside the chain's lod for r (`plan::material::ShadeMaterial::bend`; WGSL
//! `bent_reflection` in `shaders/common/split_sum.wgsl`).
//!
//! [`SpecularLookup::Stretched`] also reads the chain as the true lobe is shaped toward
//! grazing views, where it narrows across the plane of incidence and stretches along it
//! (the GGX lobe of the reflected directions, seen from v: Heitz 2018's visible normals
//! reflected about them): two taps either side of the bent direction d, along the plane
//! of incidence, from a sharper level ([`stretched_taps`]; its strength is the material's
//! `stretch`, 0 for every other lookup, where both taps are d at the chain's lod), chosen
//! by the lookup study (`examples/lookup_study.rs`, docs/accuracy.md) against the
//! preview's ground truth. [`SpecularLookup::Filtered`] adds four taps of the lobe itself
//! at grazing views of glossy points (`plan::filtered`): it is the one the README's WGSL
//! recipe, the preview and the viewer use ([`SpecularLookup::GENERIC`]).

use glam::Vec3;

/// A lookup direction for the prefiltered chain.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum SpecularLookup {
    /// R = reflect(−v, n): the glTF Sample Viewer 1.1 (`getIBLRadianceGGX` in
    /// `ibl.glsl`) and Babylon.js 9 (`computeReflectionCoords` of the world normal).
    Reflect,
    /// mix(R, n, α²) with α = r²: three.js r187 (`getIBLRadiance` in
    /// `envmap_physical_pars_fragment`: normalize(mix(R, n, pow4(roughness))) with the
    /// perceptual roughness) and Filament 1.53 (`getSpecularDominantDirection(n, r,
    /// pixel.roughness)` in `light_indirect.fs`, where `pixel.roughness` is α).
    AlphaSquared,
    /// normalize(mix(R, n, r²)): a steeper blend no engine makes, in the study for
    /// comparison.
    RSquared,
    /// mix(n, R, s (√s + α)) with s = 1 − α: Frostbite's dominant direction (Lagarde &
    /// de Rousiers 2014, Listing 22, fitted to the GGX lobe's peak); also bevy_pbr 0.19
    /// (`radiance_sample_direction` in `environment_map.wgsl`, with its α).
    Frostbite,
    /// Frostbite's direction d, its bend faded in below r = 0.5
    /// (`math::lookup::BEND_FADE_ROUGHNESS`) and scaled down for a low F0
    /// (`math::lookup::fresnel_bend_scale`), read as two taps stretched along the plane of
    /// incidence toward grazing views, from a sharper level (`math::lookup::stretched_taps`):
    /// the README's recipe without its taps at grazing views.
    Stretched,
    /// [`SpecularLookup::Stretched`] blended at grazing views of glossy points into
    /// filtered importance sampling of the chain (`plan::filtered`: 4 samples of the GGX
    /// lobe in the plane of incidence, each read at the level of its share of the sphere):
    /// the README's recipe.
    Filtered,
}

impl SpecularLookup {
    /// Every lookup, in the study's order.
    pub const ALL: [SpecularLookup; 5] = [
        SpecularLookup::Reflect,
        SpecularLookup::RSquared,
        SpecularLookup::AlphaSquared,
        SpecularLookup::Frostbite,
        SpecularLookup::Stretched,
    ];

    /// The lookup of the README's WGSL recipe, the preview and the viewer: the stretched
    /// lookup (read with the recipe's blend toward E/π, the lowest lookup, or within 0.1
    /// point of it, in all but three of the lookup study's 48 cells at r ≥ 0.25: six HDRIs,
    /// the sun kept and split; docs/accuracy.md, "Where to look the chain up") with four
    /// taps of the lobe at grazing views, which put every bundled HDRI's spheres at
    /// r ≥ 0.25 within 3.7 % of the truth, lights split (docs/accuracy.md, "The residual's
    /// lookup").
    pub const GENERIC: SpecularLookup = SpecularLookup::Filtered;

    /// The name `preview --lookup` takes and its JSON writes.
    pub fn id(self) -> &'static str {
        match self {
            SpecularLookup::Reflect => "reflect",
            SpecularLookup::RSquared => "r2",
            SpecularLookup::AlphaSquared => "alpha2",
            SpecularLookup::Frostbite => "frostbite",
            SpecularLookup::Stretched => "stretched",
            SpecularLookup::Filtered => "filtered",
        }
    }

    /// The lookup called `id` ([`SpecularLookup::id`]): one of [`SpecularLookup::ALL`] or
    /// the recipe's.
    pub fn by_id(id: &str) -> Option<SpecularLookup> {
        SpecularLookup::ALL
            .into_iter()
            .chain([SpecularLookup::Filtered])
            .find(|l| l.id() == id)
    }

    /// Whether it samples the chain's lobe at grazing views (`plan::filtered`).
    pub fn filtered(self) -> bool {
        self == SpecularLookup::Filtered
    }

    /// What it is, in a line (`preview --help`).
    pub fn description(self) -> &'static str {
        match self {
            SpecularLookup::Reflect => "R = reflect(-v, n) (Babylon.js, the glTF Sample Viewer)",
            SpecularLookup::RSquared => "mix(R, n, r^2) (no engine's; the lookup study's)",
            SpecularLookup::AlphaSquared => "mix(R, n, alpha^2), alpha = r^2 (three.js, Filament)",
            SpecularLookup::Frostbite => {
                "Frostbite's dominant direction, R bent toward n as the GGX lobe leans (Bevy)"
            }
            SpecularLookup::Stretched => {
                "Frostbite's direction (its bend faded in below r = 0.5, less for a low F0) as two taps stretched along the plane of incidence toward grazing views (the README's recipe without its grazing taps)"
            }
            SpecularLookup::Filtered => {
                "stretched, blended at grazing views (n.v < 0.6, r < 0.9) into 4 samples of the GGX lobe in the plane of incidence, each read from the chain at its own level (the README's recipe)"
            }
        }
    }

    /// The name a table prints.
    pub fn name(self) -> &'static str {
        match self {
            SpecularLookup::Reflect => "R",
            SpecularLookup::RSquared => "mix(R, n, r²)",
            SpecularLookup::AlphaSquared => "mix(R, n, α²) (three.js, Filament)",
            SpecularLookup::Frostbite => "Frostbite's dominant direction",
            SpecularLookup::Stretched => "Frostbite's, stretched (two taps)",
            SpecularLookup::Filtered => "stretched, 4 filtered taps at grazing views",
        }
    }

    /// The bend t of normalize(mix(R, n, t)) at perceptual roughness `roughness` for a
    /// material of reflectance `f0` at normal incidence: 0 reads along R, 1 along n. Only
    /// the recipe's lookup ([`SpecularLookup::Stretched`]) reads `f0`
    /// (`math::lookup::fresnel_bend_scale`); the engines' bend by roughness alone.
    pub fn bend(self, roughness: f32, f0: Vec3) -> f32 {
        let alpha = crate::math::brdf::alpha_from_roughness(roughness);
        match self {
            SpecularLookup::Reflect => 0.0,
            SpecularLookup::RSquared => roughness * roughness,
            SpecularLookup::AlphaSquared => alpha * alpha,
            SpecularLookup::Frostbite => frostbite_bend(alpha),
            SpecularLookup::Stretched | SpecularLookup::Filtered => {
                frostbite_bend(alpha)
                    * (roughness / BEND_FADE_ROUGHNESS).powi(2).min(1.0)
                    * fresnel_bend_scale(roughness, f0)
            }
        }
    }

    /// How strongly the lookup stretches toward grazing views (`math::lookup::stretched_taps`): 1 for
    /// [`SpecularLookup::Stretched`], 0 (one tap at the chain's lod) for the others.
    pub fn stretch(self) -> f32 {
        match self {
            SpecularLookup::Stretched | SpecularLookup::Filtered => 1.0,
            _ => 0.0,
        }
    }

    /// The unit direction to look the chain up along (for [`SpecularLookup::Stretched`],
    /// the centre of its two taps), for unit `n` and `v` with n·v > 0, at `roughness`, for
    /// reflectance `f0`.
    pub fn direction(self, n: Vec3, v: Vec3, roughness: f32, f0: Vec3) -> Vec3 {
        bent_reflection(n, v, self.bend(roughness, f0))
    }
}

/// Frostbite's bend of R toward n at α: mix(n, R, w) = mix(R, n, 1 − w), w = s (√s + α),
/// s = 1 − α (Lagarde & de Rousiers 2014, Listing 22).
fn frostbite_bend(alpha: f32) -> f32 {
    let s = (1.0 - alpha).clamp(0.0, 1.0);
    1.0 - s * (s.sqrt() + alpha)
}

/// Below this roughness the recipe's bend ([`SpecularLookup::Stretched`]) is Frostbite's
/// times (r / 0.5)²: fitted for one tap, Frostbite's bend overshoots where the two
/// sharper taps already spread the read along the plane of incidence. Measured in the
/// default preview (64-pixel cells, 2048 points), the worst metal at r = 0.25 with the
/// fade against without: studio_small_03 15.1 against 20.8 % (plain R 20.1 %),
/// royal_esplanade split 2.5 against 3.5 %, quarry_01 split 2.7 against 2.8 %,
/// pedestrian_overpass 0.9 against 1.0 %, venice_sunset 1.35 against 1.34 %, and on
/// blender_studiolight_interior (lamps split; not one it was chosen on) 5.2 against 6.4 %; at
/// r ≥ 0.5 the bend is Frostbite's, unchanged (docs/accuracy.md, "Where to look the chain
/// up").
pub const BEND_FADE_ROUGHNESS: f32 = 0.5;

/// How much of Frostbite's bend a material of reflectance `f0` at normal incidence takes
/// at perceptual roughness r, with f the mean of F0's channels:
///
/// s(f, r) = f r^2.5 / max(f r^2.5 + b (1 − f), ε),  b = [`FRESNEL_BEND_WEIGHT`],
///
/// 1 for F0 = 1, for which Frostbite's bend was fitted (the lobe D G (n·l) alone, Lagarde
/// & de Rousiers 2014, §4.9.3), and less the lower F0 is: Fresnel-Schlick's
/// (1 − F0)(1 − v·h)⁵ weights the reflected directions whose half vector leans away from
/// v, those on R's far side from n, and pulls the lobe's mean back toward R. Fitted to
/// the lobe itself, not to an HDRI: the bend of the mean reflected direction of
/// D F V (n·l) for F0 against F0 = 1, averaged over a sphere's views (n·v with density
/// 2 n·v, weighted by the directional albedo), for F0 from 0.02 to 0.8 and r from 0.5 to
/// 0.9, lies within 0.021 of s (`lookup_study fresnel`, docs/accuracy.md). A dielectric
/// (F0 = 0.04) takes 0.51 of the bend at r = 0.5, 0.74 at 0.75; gold (mean F0 0.67) 0.98
/// at r = 0.5.
/// ε ([`FRESNEL_BEND_FLOOR`]) reads F0 = 1 at r = 0, where the bend is 0, as 0 instead of
/// 0/0.
pub fn fresnel_bend_scale(roughness: f32, f0: Vec3) -> f32 {
    fresnel_bend_share(roughness, f0.element_sum() / 3.0, FRESNEL_BEND_WEIGHT)
}

/// s(f, r) of [`fresnel_bend_scale`] for mean reflectance `f` and any weight b, the model
/// `lookup_study fresnel` fits b of ([`FRESNEL_BEND_WEIGHT`]) against the lobe.
pub fn fresnel_bend_share(roughness: f32, f: f32, weight: f32) -> f32 {
    let fr = f * roughness * roughness * roughness.sqrt();
    fr / (fr + weight * (1.0 - f)).max(FRESNEL_BEND_FLOOR)
}

/// The weight b of the Fresnel term against F0 in [`fresnel_bend_scale`]: the lobe's bend
/// relative to F0 = 1's is f / (f + b (1 − f) r^−2.5), b the least-squares fit to the
/// lobe's mean direction ([`lobe_bend_ratio`]) over r = 0.5, 0.6, …, 0.9 and F0 = 0.02,
/// 0.04, 0.1, 0.2, 0.5, 0.8 (`lookup_study fresnel`).
pub const FRESNEL_BEND_WEIGHT: f32 = 0.0071;

/// The smallest denominator of [`fresnel_bend_scale`]: only F0 = 1 at r = 0 (or r below
/// 0.004 for F0 near 1, where the bend faded in below r = 0.5 is under 1e-4) reaches it.
pub const FRESNEL_BEND_FLOOR: f32 = 1e-6;

/// The two taps of a stretched lookup and the lod both read at: for unit n, the unit
/// lookup direction d, n·v, roughness r (α = r²), the chain's lod for r and the stretch
/// k ∈ [0, 1], with g = 1 − n·v,
///
/// lod' = lod (1 − k g² (1 − r)),  c = n − d (n·d),  t = k α g φ(r) c / max(|c|, ε),
/// taps normalize(d ± t),  φ(r) = min(1, (1 − r) / (1 − r_f)).
///
/// Toward grazing views the lobe of reflected directions narrows across the plane of
/// incidence (a sharper level) and stretches along it (two taps in that plane, t ⊥ d, its
/// length k α g); at normal incidence (g = 0), at r = 0 (α = 0), where d is n (c = 0: r = 1
/// with Frostbite's bend, which also keeps the lod there, the roughest level being E/π)
/// and with k = 0 both taps are d at the chain's lod. ε ([`STRETCH_EPSILON`]) keeps c = 0
/// from dividing by zero; φ fades the spread out from r_f ([`STRETCH_FADE_ROUGHNESS`]) to
/// r = 1, so that the lookup is continuous in r where d reaches n. The form and its two unit strengths were fitted by the lookup study
/// (`examples/lookup_study.rs grazing`) on quarry_01, royal_esplanade and venice_sunset
/// with the sun split, and checked on the other bundled HDRIs; r_f = 0.9 by the spheres
/// between r = 0.8 and 0.99 (`lookup_study high`, docs/accuracy.md).
/// Mirror of `stretched_taps` in `shaders/common/split_sum.wgsl`.
pub fn stretched_taps(
    n: Vec3,
    d: Vec3,
    n_dot_v: f32,
    roughness: f32,
    lod: f32,
    stretch: f32,
) -> (Vec3, Vec3, f32) {
    let g = 1.0 - n_dot_v;
    let lod = lod * (1.0 - stretch * g * g * (1.0 - roughness));
    let fade = ((1.0 - roughness) / (1.0 - STRETCH_FADE_ROUGHNESS)).min(1.0);
    let c = n - d * n.dot(d);
    let t = (stretch * roughness * roughness * g * fade / c.length().max(STRETCH_EPSILON)) * c;
    ((d + t).normalize(), (d - t).normalize(), lod)
}

/// The smallest |n − d (n·d)| [`stretched_taps`] divides by: where d is within 1e-4 rad of
/// n, the taps' spread shrinks with that angle instead of dividing by it (WGSL:
/// `STRETCH_EPSILON` in `shaders/common/split_sum.wgsl`, held equal by `tests/shaders.rs`).
pub const STRETCH_EPSILON: f32 = 1e-4;

/// Where the taps' spread starts to fade: it falls linearly from this roughness to 0 at
/// r = 1, where Frostbite's direction reaches n and the spread's direction c/|c| is lost
/// (without the fade the lookup would jump there). The full spread gains on the spheres at
/// r = 0.8–0.9 and loses at 0.95–0.99 (`lookup_study high`, docs/accuracy.md). WGSL:
/// `STRETCH_FADE_ROUGHNESS` in `shaders/common/split_sum.wgsl`, held equal by
/// `tests/shaders.rs`.
pub const STRETCH_FADE_ROUGHNESS: f32 = 0.9;

/// normalize(mix(R, n, `bend`)) with R = reflect(−v, n). With n·v > 0, R·n = n·v > 0,
/// so the blend never vanishes. Mirror of `bent_reflection` in
/// `shaders/common/split_sum.wgsl`.
pub fn bent_reflection(n: Vec3, v: Vec3, bend: f32) -> Vec3 {
    let r = 2.0 * n.dot(v) * n - v;
    r.lerp(n, bend).normalize_or(n)
}

/// A blend of R toward n by t = min(1, a α^p (1 + b (1 − n·v))): α^p how it grows with
/// roughness, a its strength, b how much more it bends at grazing views (where the true
/// lobe leans furthest). The family the lookup study fits ([`FITTED`]); it depends on
/// n·v, so no shading function reads it.
#[cfg(any(test, feature = "internals"))]
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BlendFit {
    /// Strength.
    pub a: f32,
    /// Power of α.
    pub p: f32,
    /// Extra bend at grazing views.
    pub b: f32,
}

#[cfg(any(test, feature = "internals"))]
impl BlendFit {
    /// The lookup direction for unit `n`, `v` (n·v > 0) and roughness `roughness`.
    pub fn direction(self, n: Vec3, v: Vec3, roughness: f32) -> Vec3 {
        let alpha = crate::math::brdf::alpha_from_roughness(roughness);
        let t = (self.a * alpha.powf(self.p) * (1.0 + self.b * (1.0 - n.dot(v)))).min(1.0);
        bent_reflection(n, v, t)
    }
}

/// The blend fitted by `examples/lookup_study.rs fit` against the preview's ground truth
/// on quarry_01 and venice_sunset with the sun split (four views each): the mean
/// energy-weighted error of the spheres with r ≥ 0.25 minimised over a grid of a ∈ 0.8 …
/// 1.5, p ∈ 1 … 2.5, b ∈ 0 … 1 (2.84 %; the optimum lies inside the grid), that is
/// t = α^1.25 (1 + (1 − n·v)/2). It does not generalise better than
/// [`SpecularLookup::Frostbite`] (docs/accuracy.md).
#[cfg(any(test, feature = "internals"))]
pub const FITTED: BlendFit = BlendFit {
    a: 1.0,
    p: 1.25,
    b: 0.5,
};

/// The bend t (as in normalize(mix(R, n, t))) of the mean reflected direction of the
/// GGX lobe D F V (n·l) seen from n·v = `n_dot_v`, and the lobe's integral (the
/// directional albedo, F0 A + B), with α, Fresnel-Schlick of scalar
/// reflectance `f0` and the height-correlated Smith visibility (the preview's truth's
/// BRDF, `LightBrdf::GENERIC`): the lobe integrated over the hemisphere on a
/// `steps` × 2 `steps` grid in (θ, φ) (midpoints, weight sin θ), its mean direction's angle
/// from n in the plane of incidence turned into the bend that reaches it. The quantity
/// [`fresnel_bend_scale`] is fitted to, relative to F0 = 1 ([`lobe_bend_ratio`]).
#[cfg(any(test, feature = "internals"))]
pub fn lobe_mean_bend(alpha: f32, n_dot_v: f32, f0: f32, steps: u32) -> (f32, f32) {
    use crate::math::brdf::{d_ggx, fresnel_schlick, smith_correlated_4v_n_dot_l, smith_correlated_lambda};
    let (nv, a2) = (n_dot_v as f64, alpha * alpha);
    let sin_v = (1.0 - nv * nv).max(0.0).sqrt();
    let v = glam::DVec3::new(sin_v, 0.0, nv);
    let lambda_v = smith_correlated_lambda(n_dot_v, a2);
    let (dt, dp) = (std::f64::consts::FRAC_PI_2 / steps as f64, std::f64::consts::PI / steps as f64);
    let (mut mean, mut weight) = (glam::DVec3::ZERO, 0.0f64);
    for i in 0..steps {
        let theta = (i as f64 + 0.5) * dt;
        let (st, ct) = theta.sin_cos();
        for j in 0..2 * steps {
            let (sp, cp) = ((j as f64 + 0.5) * dp).sin_cos();
            let l = glam::DVec3::new(st * cp, st * sp, ct);
            let h = (l + v).normalize();
            // D F V (n·l), the helper giving 4 V (n·l).
            let f = 0.25
                * d_ggx(h.z as f32, alpha)
                * fresnel_schlick(f0, v.dot(h) as f32)
                * smith_correlated_4v_n_dot_l(n_dot_v, ct as f32, a2, lambda_v);
            mean += l * (f as f64 * st);
            weight += f as f64 * st;
        }
    }
    // The mean's angle β from n toward R (R = (−sin, 0, cos)), and the t with
    // normalize(mix(R, n, t)) at β: tan β = (1 − t) sin / ((1 − t) n·v + t).
    let tan_b = -mean.x / mean.z;
    let bend = (sin_v - tan_b * nv) / (tan_b * (1.0 - nv) + sin_v);
    // Σ f sin θ dθ dφ, f = D F V (n·l) holding the cosine: the directional albedo.
    let albedo = weight * dt * dp;
    (bend as f32, albedo as f32)
}

/// The bend of the lobe's mean direction for scalar reflectance `f0` relative to F0 = 1's
/// ([`lobe_mean_bend`]), averaged over the views of a sphere: `views` values of n·v at the
/// midpoints of (0, 1), each weighted by its share of a sphere's pixels (2 n·v) times the
/// lobe's directional albedo for `f0` (what that view sends to the camera).
#[cfg(any(test, feature = "internals"))]
pub fn lobe_bend_ratio(roughness: f32, f0: f32, views: u32, steps: u32) -> f32 {
    let alpha = crate::math::brdf::alpha_from_roughness(roughness);
    let (mut num, mut den) = (0.0f64, 0.0f64);
    for k in 0..views {
        let nv = (k as f32 + 0.5) / views as f32;
        let (bend, albedo) = lobe_mean_bend(alpha, nv, f0, steps);
        let w = (2.0 * nv * albedo) as f64;
        num += w * bend as f64;
        den += w * lobe_mean_bend(alpha, nv, 1.0, steps).0 as f64;
    }
    (num / den) as f32
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A mirror (r = 0) reads R with every lookup; at r = 1 the blends reach n (r², 
    /// α²: the weight is 1; Frostbite: s = 0); in between each lies in the plane of n
    /// and R, between them.
    #[test]
    fn lookups_run_from_r_to_n() {
        let n = Vec3::Y;
        let v = Vec3::new(0.6, 0.8, 0.0);
        let r = Vec3::new(-0.6, 0.8, 0.0);
        for lookup in SpecularLookup::ALL {
            // 1e-6: single-precision rounding.
            assert!(lookup.direction(n, v, 0.0, Vec3::ONE).distance(r) < 1e-6, "{lookup:?}");
            let half = lookup.direction(n, v, 0.5, Vec3::ONE);
            assert!(half.z.abs() < 1e-6 && half.x <= 0.0 && half.y >= r.y, "{lookup:?}");
        }
        for lookup in &SpecularLookup::ALL[1..] {
            assert!(lookup.direction(n, v, 1.0, Vec3::ONE).distance(n) < 1e-6, "{lookup:?}");
        }
        assert!(SpecularLookup::Reflect.direction(n, v, 1.0, Vec3::ONE).distance(r) < 1e-6);
        assert!(FITTED.direction(n, v, 0.0).distance(r) < 1e-6);
    }

    /// The lobe integral's sanity: a mirror-like lobe's mean direction is R (bend 0) and
    /// keeps all its energy; the roughest lobe's mean lies along n, where Frostbite's
    /// bend puts it.
    #[test]
    fn lobe_mean_bend_integrates_the_lobe() {
        let (bend, albedo) = lobe_mean_bend(0.02, 0.7, 1.0, 512);
        // 0.01: the grid's error on a lobe a few cells wide, far below a bend worth reading.
        assert!(bend.abs() < 0.01, "{bend}");
        // 0.02: single scattering at α = 0.02 keeps all but the grid's error.
        assert!((albedo - 1.0).abs() < 0.02, "{albedo}");
        // Frostbite's fit reaches n at α = 1; the lobe's mean is there within 0.05.
        for nv in [0.2, 0.5, 0.9] {
            let (bend, _) = lobe_mean_bend(1.0, nv, 1.0, 128);
            assert!((bend - 1.0).abs() < 0.05, "n·v {nv}: {bend}");
        }
    }

    /// [`fresnel_bend_scale`] against what it is fitted to, the Fresnel-weighted lobe's mean
    /// direction over a sphere's views ([`lobe_bend_ratio`]): within 0.03 for F0 from 0.02
    /// to 0.8 at r from 0.5 to 0.9 (the fit's residual is at most 0.021 on a finer grid;
    /// the rest is this grid's error), 1 at F0 = 1, and 0 where F0 = 1 meets r = 0.
    #[test]
    fn fresnel_bend_scale_follows_the_lobe() {
        for r in [0.5f32, 0.7, 0.9] {
            for f0 in [0.02f32, 0.04, 0.2, 0.8] {
                let lobe = lobe_bend_ratio(r, f0, 8, 96);
                let model = fresnel_bend_scale(r, Vec3::splat(f0));
                assert!((lobe - model).abs() < 0.03, "r {r} F0 {f0}: lobe {lobe} model {model}");
            }
            assert_eq!(fresnel_bend_scale(r, Vec3::ONE), 1.0);
        }
        assert_eq!(fresnel_bend_scale(0.0, Vec3::ONE), 0.0);
        assert_eq!(fresnel_bend_scale(0.0, Vec3::ZERO), 0.0);
        // Only the recipe's lookup reads F0.
        let (dielectric, metal) = (Vec3::splat(0.04), Vec3::ONE);
        assert!(SpecularLookup::Stretched.bend(0.5, dielectric) < 0.6 * SpecularLookup::Stretched.bend(0.5, metal));
        assert_eq!(SpecularLookup::Frostbite.bend(0.5, dielectric), SpecularLookup::Frostbite.bend(0.5, metal));
    }

    /// Frostbite's bend written as a blend of R toward n is Listing 22's mix(n, R, w):
    /// the same direction at every roughness.
    #[test]
    fn frostbite_bend_is_listing_22() {
        let n = Vec3::new(0.0, 0.6, 0.8);
        let v = Vec3::new(0.48, 0.8, -0.36).normalize();
        for r in [0.1f32, 0.3, 0.5, 0.7, 0.9] {
            let alpha = r * r;
            let s = 1.0 - alpha;
            let refl = 2.0 * n.dot(v) * n - v;
            let listing = n.lerp(refl, s * (s.sqrt() + alpha)).normalize();
            // 1e-6: single-precision rounding.
            let got = SpecularLookup::Frostbite.direction(n, v, r, Vec3::splat(0.04));
            assert!(got.distance(listing) < 1e-6, "r {r}: {got} vs {listing}");
        }
    }

    /// The stretched taps: d itself at the chain's lod with no stretch, at normal
    /// incidence and on a mirror; otherwise two directions symmetric about d in the plane
    /// of n and d, read from a sharper level.
    #[test]
    fn stretched_taps_lie_in_the_plane_of_incidence() {
        let n = Vec3::Y;
        let v = Vec3::new(0.8, 0.6, 0.0);
        let d = SpecularLookup::Stretched.direction(n, v, 0.5, Vec3::ONE);
        let n_dot_v = n.dot(v);
        // (n·v, r, stretch, the chain's lod for r: 0 for a mirror).
        for (n_dot_v, r, k, lod) in [
            (n_dot_v, 0.5, 0.0, 3.0),
            (1.0, 0.5, 1.0, 3.0),
            (n_dot_v, 0.0, 1.0, 0.0),
        ] {
            let (a, b, got) = stretched_taps(n, d, n_dot_v, r, lod, k);
            // 1e-6: single-precision rounding.
            assert!(a.distance(d) < 1e-6 && b.distance(d) < 1e-6, "{n_dot_v} {r} {k}");
            assert_eq!(got, lod);
        }
        // Where d is n (r = 1 with Frostbite's bend), no division by zero.
        let (a, b, _) = stretched_taps(n, n, n_dot_v, 1.0, 3.0, 1.0);
        assert!(a.distance(n) < 1e-6 && b.distance(n) < 1e-6, "{a} {b}");
        // Continuous where d reaches n: just below r = 1 the taps are within the fade of d.
        let rough = SpecularLookup::Stretched.direction(n, v, 0.999, Vec3::ONE);
        let (a, b, _) = stretched_taps(n, rough, n_dot_v, 0.999, 3.0, 1.0);
        assert!(a.distance(rough) < 0.01 && b.distance(rough) < 0.01, "{a} {b} {rough}");
        let (a, b, lod) = stretched_taps(n, d, n_dot_v, 0.5, 3.0, 1.0);
        assert!(lod < 3.0);
        assert!(a.z.abs() < 1e-6 && b.z.abs() < 1e-6, "{a} {b}");
        assert!((a.dot(d) - b.dot(d)).abs() < 1e-6 && a.dot(d) < 1.0 - 1e-4);
        // One tap leans toward n, the other away from it.
        assert!(a.dot(n) > d.dot(n) && b.dot(n) < d.dot(n));
    }
}
