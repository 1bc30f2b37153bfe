//! Where a shader looks the prefiltered specular chain up: the direction each engine's
//! shader derives from the normal n, the view v (toward the eye) and the perceptual
//! roughness r. The chain's level for r is prefiltered with v = n, so its lobe is centred
//! on R = reflect(−v, n) only at normal incidence; at high roughness the true lobe leans
//! toward n (the "off-specular peak", Lagarde & de Rousiers 2014, §4.9.3). Every lookup
//! here is R bent toward n, normalize(mix(R, n, t)), by a bend t ∈ [0, 1] that depends on
//! r alone ([`SpecularLookup::bend`]), so the shading functions take t as part of the
//! material, beside the chain's lod for r (`plan::material::ShadeMaterial::bend`; WGSL
//! `bent_reflection` in `shaders/common/split_sum.wgsl`).
//!
//! [`SpecularLookup::Frostbite`] is the one the README's WGSL recipe, the preview and the
//! viewer use ([`SpecularLookup::GENERIC`]), chosen by the lookup study
//! (`examples/lookup_study.rs`, docs/accuracy.md) against the preview's ground truth.

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
}

impl SpecularLookup {
    /// Every lookup, in the study's order.
    pub const ALL: [SpecularLookup; 4] = [
        SpecularLookup::Reflect,
        SpecularLookup::RSquared,
        SpecularLookup::AlphaSquared,
        SpecularLookup::Frostbite,
    ];

    /// The lookup of the README's WGSL recipe, the preview and the viewer: the best or
    /// within 0.6 % of the best of these at every roughness with the sun split, on every
    /// bundled HDRI (docs/accuracy.md, "Where to look the chain up").
    pub const GENERIC: SpecularLookup = SpecularLookup::Frostbite;

    /// The name `preview --lookup` takes and its JSON writes.
    pub fn id(self) -> &'static str {
        match self {
            SpecularLookup::Reflect => "reflect",
            SpecularLookup::RSquared => "r2",
            SpecularLookup::AlphaSquared => "alpha2",
            SpecularLookup::Frostbite => "frostbite",
        }
    }

    /// The lookup called `id` ([`SpecularLookup::id`]).
    pub fn by_id(id: &str) -> Option<SpecularLookup> {
        SpecularLookup::ALL.into_iter().find(|l| l.id() == id)
    }

    /// What it is, in a line (`preview --help`).
    pub fn description(self) -> &'static str {
        match self {
            SpecularLookup::Reflect => "R = reflect(-v, n) (Babylon.js, the glTF Sample Viewer)",
            SpecularLookup::RSquared => "mix(R, n, r^2) (no engine's; the lookup study's)",
            SpecularLookup::AlphaSquared => "mix(R, n, alpha^2), alpha = r^2 (three.js, Filament)",
            SpecularLookup::Frostbite => {
                "Frostbite's dominant direction, R bent toward n as the GGX lobe leans (the README's recipe; Bevy)"
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
        }
    }

    /// The bend t of normalize(mix(R, n, t)) at perceptual roughness `roughness`: 0 reads
    /// along R, 1 along n.
    pub fn bend(self, roughness: f32) -> f32 {
        let alpha = crate::math::brdf::alpha_from_roughness(roughness);
        match self {
            SpecularLookup::Reflect => 0.0,
            SpecularLookup::RSquared => roughness * roughness,
            SpecularLookup::AlphaSquared => alpha * alpha,
            SpecularLookup::Frostbite => {
                // mix(n, R, w) = mix(R, n, 1 − w).
                let s = (1.0 - alpha).clamp(0.0, 1.0);
                1.0 - s * (s.sqrt() + alpha)
            }
        }
    }

    /// The unit direction to look the chain up along, for unit `n` and `v` with n·v > 0.
    pub fn direction(self, n: Vec3, v: Vec3, roughness: f32) -> Vec3 {
        bent_reflection(n, v, self.bend(roughness))
    }
}

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
            assert!(lookup.direction(n, v, 0.0).distance(r) < 1e-6, "{lookup:?}");
            let half = lookup.direction(n, v, 0.5);
            assert!(half.z.abs() < 1e-6 && half.x <= 0.0 && half.y >= r.y, "{lookup:?}");
        }
        for lookup in &SpecularLookup::ALL[1..] {
            assert!(lookup.direction(n, v, 1.0).distance(n) < 1e-6, "{lookup:?}");
        }
        assert!(SpecularLookup::Reflect.direction(n, v, 1.0).distance(r) < 1e-6);
        assert!(FITTED.direction(n, v, 0.0).distance(r) < 1e-6);
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
            let got = SpecularLookup::Frostbite.direction(n, v, r);
            assert!(got.distance(listing) < 1e-6, "r {r}: {got} vs {listing}");
        }
    }
}
