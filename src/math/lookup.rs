//! Where a shader looks the prefiltered specular chain up: the direction each engine's
//! shader derives from the normal n, the view v (toward the eye) and the perceptual
//! roughness r. The chain's level for r is prefiltered with v = n, so its lobe is centred
//! on R = reflect(−v, n) only at normal incidence; at high roughness the true lobe leans
//! toward n (the "off-specular peak", Lagarde & de Rousiers 2014, §4.9.3), and the lookups
//! below bend R toward n by a blend that grows with r. CPU only (no WGSL twin yet): the
//! lookup study (`examples/lookup_study.rs`, docs/accuracy.md) compares them against the
//! preview's ground truth.

use glam::Vec3;

/// A blend of R toward n by t = min(1, a α^p (1 + b (1 − n·v))): α^p how it grows with
/// roughness, a its strength, b how much more it bends at grazing views (where the true
/// lobe leans furthest). The family the study fits ([`FITTED`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BlendFit {
    /// Strength.
    pub a: f32,
    /// Power of α.
    pub p: f32,
    /// Extra bend at grazing views.
    pub b: f32,
}

impl BlendFit {
    /// The lookup direction for unit `n`, `v` (n·v > 0) and roughness `roughness`.
    pub fn direction(self, n: Vec3, v: Vec3, roughness: f32) -> Vec3 {
        let r = 2.0 * n.dot(v) * n - v;
        let alpha = crate::math::brdf::alpha_from_roughness(roughness);
        let t = (self.a * alpha.powf(self.p) * (1.0 + self.b * (1.0 - n.dot(v)))).min(1.0);
        r.lerp(n, t).normalize_or(n)
    }
}

/// The blend fitted by `examples/lookup_study.rs fit` against the preview's ground truth
/// on quarry_01 and venice_sunset with the sun split (four views each): the mean
/// energy-weighted error of the spheres with r ≥ 0.25 minimised over a grid of a ∈ 0.8 …
/// 1.5, p ∈ 1 … 2.5, b ∈ 0 … 1 (2.84 %; the optimum lies inside the grid), that is
/// t = α^1.25 (1 + (1 − n·v)/2).
pub const FITTED: BlendFit = BlendFit {
    a: 1.0,
    p: 1.25,
    b: 0.5,
};

/// A lookup direction for the prefiltered chain.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SpecularLookup {
    /// R = reflect(−v, n): what the README's WGSL recipe, the preview and the viewer read.
    Reflect,
    /// normalize(mix(R, n, r²)): three.js r187 (`getIBLRadiance` in
    /// `envmap_physical_pars_fragment`, with the material's perceptual roughness).
    ThreeJs,
    /// mix(R, n, α²) with α = r²: Filament 1.53 (`getSpecularDominantDirection(n, r,
    /// pixel.roughness)` in `light_indirect.fs`, where `pixel.roughness` is α).
    Filament,
    /// mix(n, R, s (√s + α)) with s = 1 − α: Frostbite's dominant direction (Lagarde &
    /// de Rousiers 2014, Listing 22, fitted to the GGX lobe's peak).
    Frostbite,
    /// [`FITTED`]: splitsum's own blend.
    Fitted,
}

impl SpecularLookup {
    /// Every lookup, in the study's order.
    pub const ALL: [SpecularLookup; 5] = [
        SpecularLookup::Reflect,
        SpecularLookup::ThreeJs,
        SpecularLookup::Filament,
        SpecularLookup::Frostbite,
        SpecularLookup::Fitted,
    ];

    /// The name the study's table prints.
    pub fn name(self) -> &'static str {
        match self {
            SpecularLookup::Reflect => "R",
            SpecularLookup::ThreeJs => "mix(R, n, r²) (three.js)",
            SpecularLookup::Filament => "mix(R, n, α²) (Filament)",
            SpecularLookup::Frostbite => "Frostbite's dominant direction",
            SpecularLookup::Fitted => "fitted blend",
        }
    }

    /// The unit direction to look the chain up along, for unit `n` and `v` with n·v > 0.
    pub fn direction(self, n: Vec3, v: Vec3, roughness: f32) -> Vec3 {
        let r = 2.0 * n.dot(v) * n - v;
        let alpha = crate::math::brdf::alpha_from_roughness(roughness);
        let d = match self {
            SpecularLookup::Reflect => r,
            SpecularLookup::ThreeJs => r.lerp(n, roughness * roughness),
            SpecularLookup::Filament => r.lerp(n, alpha * alpha),
            SpecularLookup::Frostbite => {
                let s = (1.0 - alpha).clamp(0.0, 1.0);
                n.lerp(r, s * (s.sqrt() + alpha))
            }
            SpecularLookup::Fitted => return FITTED.direction(n, v, roughness),
        };
        d.normalize_or(n)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A mirror (r = 0) reads R with every lookup; at r = 1 the blends reach n (three.js,
    /// Filament: the weight is 1; Frostbite: s = 0); in between each lies in the plane of n
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
        for lookup in &SpecularLookup::ALL[1..4] {
            assert!(lookup.direction(n, v, 1.0).distance(n) < 1e-6, "{lookup:?}");
        }
        assert!(SpecularLookup::Reflect.direction(n, v, 1.0).distance(r) < 1e-6);
    }
}
