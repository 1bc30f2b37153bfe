//! Cook-Torrance microfacet terms used by the split-sum integrals. Mirror of
//! `shaders/common/brdf.wgsl` (same function names).
//!
//! Conventions (DESIGN.md "Roughness, BRDF"): perceptual roughness r in [0, 1], α = r²,
//! Smith/Schlick-GGX geometry with the IBL remapping k = r²/2 (Karis 2013), Fresnel-Schlick.

use std::f32::consts::PI;

/// GGX α from perceptual roughness: α = r² (Burley 2012, Karis 2013).
pub fn alpha_from_roughness(roughness: f32) -> f32 {
    roughness * roughness
}

/// Schlick-GGX k for image-based lighting: k = α/2 = r²/2 (Karis 2013, "Specular G").
pub fn k_ibl(roughness: f32) -> f32 {
    0.5 * alpha_from_roughness(roughness)
}

/// GGX / Trowbridge-Reitz normal distribution (Walter et al. 2007, eq. 33):
/// D(h) = α² / (π ((n·h)² (α² − 1) + 1)²).
pub fn d_ggx(n_dot_h: f32, alpha: f32) -> f32 {
    let a2 = alpha * alpha;
    let d = n_dot_h * n_dot_h * (a2 - 1.0) + 1.0;
    a2 / (PI * d * d)
}

/// Schlick-GGX single-direction masking term G1(x) = x / (x (1 − k) + k) (Schlick 1994,
/// Karis 2013).
pub fn g1_schlick_ggx(n_dot_x: f32, k: f32) -> f32 {
    n_dot_x / (n_dot_x * (1.0 - k) + k)
}

/// G1(n·v) / (n·v) = 1 / (n·v (1 − k) + k): the view-side masking with the 1/(n·v) of the
/// microfacet BRDF divided out analytically, so the integrand stays finite at grazing n·v.
pub fn g1_over_n_dot_v(n_dot_v: f32, k: f32) -> f32 {
    1.0 / (n_dot_v * (1.0 - k) + k)
}

/// Λ'(x) = √((n·x)² (1 − α²) + α²), the per-direction term of the height-correlated
/// Smith-GGX visibility (Heitz 2014, "Understanding the Masking-Shadowing Function",
/// eq. 99; Filament's `V_SmithGGXCorrelated`).
pub fn smith_correlated_lambda(n_dot_x: f32, alpha2: f32) -> f32 {
    (n_dot_x * n_dot_x * (1.0 - alpha2) + alpha2).sqrt()
}

/// 4 V (n·l) for the height-correlated Smith-GGX visibility
/// V = 0.5 / (n·l Λ'(v) + n·v Λ'(l)) (Heitz 2014): 2 n·l / (n·l Λ'(v) + n·v Λ'(l)),
/// with `lambda_v` = Λ'(v) precomputed. Finite at grazing n·v (→ 2/α), like
/// [`g1_over_n_dot_v`] for the uncorrelated form.
pub fn smith_correlated_4v_n_dot_l(n_dot_v: f32, n_dot_l: f32, alpha2: f32, lambda_v: f32) -> f32 {
    2.0 * n_dot_l / (n_dot_l * lambda_v + n_dot_v * smith_correlated_lambda(n_dot_l, alpha2))
}

/// 4 V (n·l) for the Ashikhmin / Neubelt visibility V = 1 / (4 (n·l + n·v − n·l n·v))
/// (Neubelt & Pettineo 2013), the sheen visibility of Filament's cloth model and of
/// glTF-IBL-Sampler's Charlie LUT: n·l / (n·l + n·v − n·l n·v).
pub fn ashikhmin_4v_n_dot_l(n_dot_v: f32, n_dot_l: f32) -> f32 {
    n_dot_l / (n_dot_l + n_dot_v - n_dot_l * n_dot_v)
}

/// The Fresnel-Schlick weight (1 − v·h)⁵: F = F0 + (1 − F0)·w = F0 (1 − w) + w (Schlick 1994).
pub fn fresnel_schlick_weight(v_dot_h: f32) -> f32 {
    let m = (1.0 - v_dot_h).clamp(0.0, 1.0);
    let m2 = m * m;
    m2 * m2 * m
}

/// Full Fresnel-Schlick for a given F0: F0 + (1 − F0)(1 − v·h)⁵.
pub fn fresnel_schlick(f0: f32, v_dot_h: f32) -> f32 {
    let w = fresnel_schlick_weight(v_dot_h);
    f0 * (1.0 - w) + w
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ggx_d_is_normalised_over_projected_hemisphere() {
        // ∫ D(h) (n·h) dω = 1 for any α; midpoint rule in cos θ.
        for &alpha in &[0.1f32, 0.5, 1.0] {
            let n = 200_000;
            let mut sum = 0.0f64;
            for i in 0..n {
                let c = (i as f64 + 0.5) / n as f64;
                sum += d_ggx(c as f32, alpha) as f64 * c * 2.0 * std::f64::consts::PI / n as f64;
            }
            assert!((sum - 1.0).abs() < 1e-3, "alpha {alpha}: {sum}");
        }
    }

    #[test]
    fn fresnel_limits() {
        assert_eq!(fresnel_schlick(0.04, 1.0), 0.04);
        assert!((fresnel_schlick(0.04, 0.0) - 1.0).abs() < 1e-6);
        assert!((g1_over_n_dot_v(0.5, 0.25) * 0.5 - g1_schlick_ggx(0.5, 0.25)).abs() < 1e-7);
    }
}
