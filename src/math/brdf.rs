//! Cook-Torrance microfacet terms used by the split-sum integrals. Mirror of
//! `shaders/common/brdf.wgsl` (same function names).
//!
//! Conventions (docs/conventions.md, "Roughness, BRDF"): perceptual roughness r in [0, 1], α = r²,
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

/// Schlick-GGX k for analytic lights: k = (r + 1)²/8 (Karis 2013, "Specular G": the
/// remapping that keeps point-lit rough surfaces from going too bright; the viewer's point
/// lights).
#[cfg_attr(not(feature = "view"), allow(dead_code))]
pub fn k_direct(roughness: f32) -> f32 {
    (roughness + 1.0) * (roughness + 1.0) / 8.0
}

/// GGX / Trowbridge-Reitz normal distribution (Walter et al. 2007, eq. 33):
/// D(h) = α² / (π ((n·h)² (α² − 1) + 1)²).
pub fn d_ggx(n_dot_h: f32, alpha: f32) -> f32 {
    let a2 = alpha * alpha;
    let d = n_dot_h * n_dot_h * (a2 - 1.0) + 1.0;
    a2 / (PI * d * d)
}

#[cfg(any(test, feature = "internals"))]
/// GGX D(h) times n·l in a prefiltered sum with n = v, for n·l > 0: |n + l|² = 2 + 2 n·l, so
/// n·h = (1 + n·l) / |n + l| = √((1 + n·l) / 2).
pub fn ggx_prefilter_weight(n_dot_l: f32, alpha: f32) -> f32 {
    d_ggx((0.5 * (1.0 + n_dot_l)).sqrt(), alpha) * n_dot_l
}

#[cfg(any(test, feature = "internals"))]
/// The Charlie sheen distribution (Estevez & Kulla 2017), D(h) = (2 + 1/α) sin^(1/α)θh /
/// (2π), times n·l, in a prefiltered sum with n = v, up to a constant factor: there
/// sin²θh = (1 − n·l)/2, so D ∝ (1 − n·l)^(1/(2α)). The dropped factor
/// (2 + 1/α) 2^(−1/(2α)) / (2π) cancels in the sum's ratio, and would underflow f32 for
/// small α.
pub fn charlie_prefilter_weight(n_dot_l: f32, alpha: f32) -> f32 {
    (1.0 - n_dot_l).max(0.0).powf(0.5 / alpha) * n_dot_l
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

/// The KHR_materials_sheen fit of the Charlie Λ (Estevez & Kulla 2017, their table of
/// a..e interpolated in (1 − α)²; the glTF Sample Viewer's `lambdaSheenNumericHelper`).
pub fn lambda_sheen_numeric_helper(x: f32, alpha: f32) -> f32 {
    let t = (1.0 - alpha) * (1.0 - alpha);
    let mix = |p: f32, q: f32| p + (q - p) * t;
    let a = mix(21.5473, 25.3245);
    let b = mix(3.82987, 3.32435);
    let c = mix(0.19823, 0.16801);
    let d = mix(-1.97760, -1.27393);
    let e = mix(-4.32054, -4.85967);
    a / (1.0 + b * x.powf(c)) + d * x + e
}

/// Λ(cos θ) of the Charlie sheen (KHR_materials_sheen, `lambdaSheen`): exp(L(cos θ)) below
/// cos θ = ½, exp(2 L(½) − L(1 − cos θ)) above.
pub fn lambda_sheen(cos_theta: f32, alpha: f32) -> f32 {
    if cos_theta.abs() < 0.5 {
        lambda_sheen_numeric_helper(cos_theta, alpha).exp()
    } else {
        (2.0 * lambda_sheen_numeric_helper(0.5, alpha)
            - lambda_sheen_numeric_helper(1.0 - cos_theta, alpha))
        .exp()
    }
}

/// 4 V (n·l) for the sheen visibility of KHR_materials_sheen,
/// V = clamp(1 / ((1 + Λ(v) + Λ(l)) 4 n·v n·l), 0, 1) (`V_Sheen`), with `lambda_v` = Λ(v):
/// min(4 n·l, 1 / ((1 + Λ(v) + Λ(l)) n·v)).
pub fn sheen_4v_n_dot_l(n_dot_v: f32, n_dot_l: f32, alpha: f32, lambda_v: f32) -> f32 {
    let unclamped = 1.0 / ((1.0 + lambda_v + lambda_sheen(n_dot_l, alpha)) * n_dot_v);
    unclamped.min(4.0 * n_dot_l)
}

/// The Fresnel-Schlick weight (1 − v·h)⁵: F = F0 + (1 − F0)·w = F0 (1 − w) + w (Schlick 1994).
pub fn fresnel_schlick_weight(v_dot_h: f32) -> f32 {
    let m = (1.0 - v_dot_h).clamp(0.0, 1.0);
    let m2 = m * m;
    m2 * m2 * m
}

#[cfg(any(test, feature = "internals"))]
/// Full Fresnel-Schlick for a given F0: F0 + (1 − F0)(1 − v·h)⁵.
pub fn fresnel_schlick(f0: f32, v_dot_h: f32) -> f32 {
    let w = fresnel_schlick_weight(v_dot_h);
    f0 * (1.0 - w) + w
}

/// Scale of [`diffuse_fresnel_weight`]'s fit: W(0), the mean of (1 − v·h)⁵ at a grazing
/// view.
pub const DIFFUSE_FRESNEL_SCALE: f32 = 0.028;
/// Power of [`diffuse_fresnel_weight`]'s fit.
pub const DIFFUSE_FRESNEL_POWER: f32 = 2.55;

/// W(n·v) = (1/π) ∫ (1 − v·h)⁵ (n·l) dl over the hemisphere, h = normalize(l + v): the
/// cosine-weighted mean of the Fresnel-Schlick weight of the BRDF's diffuse term
/// kD(h) = (1 − F(v·h))(1 − metallic), so that the split-sum's diffuse weight
/// (1 − F0)(1 − W(n·v))(1 − metallic) is the BRDF's own under uniform light. W depends on
/// n·v alone (h is the half vector of l and v, not a microfacet normal) and stays small
/// (0.028 at a grazing view: most light directions meet v at a wide angle), where the
/// Fresnel at n·v would darken the diffuse to nothing at the silhouette. Fitted as
/// W ≈ 0.028 (1 − n·v)^2.55 to a 200 × 400 quadrature of the integral at 41 values of n·v
/// (largest error 5.4e-4; `tests` below checks it against the integral). WGSL:
/// `diffuse_fresnel_weight` in `shaders/common/brdf.wgsl`, its constants held equal by
/// `tests/shaders.rs`.
pub fn diffuse_fresnel_weight(n_dot_v: f32) -> f32 {
    DIFFUSE_FRESNEL_SCALE * (1.0 - n_dot_v).clamp(0.0, 1.0).powf(DIFFUSE_FRESNEL_POWER)
}

/// Burley's diffuse over Lambert's, (1 + (f90 − 1)(1 − n·l)⁵)(1 + (f90 − 1)(1 − n·v)⁵) with
/// f90 = 1/2 + 2 α (l·h)² (Burley 2012, "Physically-Based Shading at Disney", as
/// Filament's and bevy_pbr's `Fd_Burley` write it with α = r²).
pub fn burley_weight(n_dot_l: f32, n_dot_v: f32, l_dot_h: f32, alpha: f32) -> f32 {
    let f90 = 0.5 + 2.0 * alpha * l_dot_h * l_dot_h;
    (1.0 + (f90 - 1.0) * fresnel_schlick_weight(n_dot_l))
        * (1.0 + (f90 - 1.0) * fresnel_schlick_weight(n_dot_v))
}

/// The coefficients of [`env_brdf_approx`]: r·C0 + C1 (Karis 2014).
const ENV_BRDF_APPROX_C0: [f32; 4] = [-1.0, -0.0275, -0.572, 0.022];
/// See [`ENV_BRDF_APPROX_C0`].
const ENV_BRDF_APPROX_C1: [f32; 4] = [1.0, 0.0425, 1.04, -0.04];
/// The floor Bevy puts under both terms, so that 1/(A + B) stays finite.
const ENV_BRDF_APPROX_FLOOR: f32 = 5e-5;

/// Karis's analytic fit of the split-sum (A, B) for mobile ("Physically Based Shading on
/// Mobile", 2014, `EnvBRDFApprox`): with c = r·C0 + C1,
/// a = min(c₀², 2^(−9.28 n·v)) c₀ + c₁, (A, B) = (−1.04 a + c₂, 1.04 a + c₃); each term
/// at least 5e-5 as bevy_pbr 0.19's `F_AB` keeps it (without its `dfg_lut` feature, off by
/// default).
pub fn env_brdf_approx(roughness: f32, n_dot_v: f32) -> [f32; 2] {
    let c: [f32; 4] =
        std::array::from_fn(|k| roughness * ENV_BRDF_APPROX_C0[k] + ENV_BRDF_APPROX_C1[k]);
    let a004 = (c[0] * c[0]).min((-9.28 * n_dot_v).exp2()) * c[0] + c[1];
    [
        (-1.04 * a004 + c[2]).max(ENV_BRDF_APPROX_FLOOR),
        (1.04 * a004 + c[3]).max(ENV_BRDF_APPROX_FLOOR),
    ]
}

/// The exact Smith masking of GGX for one direction, G1(x) = 2 n·x / (n·x + Λ'(x))
/// (Walter et al. 2007, eq. 34; Λ' as [`smith_correlated_lambda`]): the normalisation of
/// the distribution of visible normals that `math::sampling::sample_ggx_vndf` draws from.
pub fn g1_smith_ggx(n_dot_x: f32, alpha2: f32) -> f32 {
    2.0 * n_dot_x / (n_dot_x + smith_correlated_lambda(n_dot_x, alpha2))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The fit of W against the integral by a midpoint rule over cosine-distributed
    /// directions (n·l = √u, 400 × 800 cells: far below the fit's 5.4e-4): within 6e-4.
    #[test]
    fn diffuse_fresnel_weight_fits_its_integral() {
        for k in 0..=10 {
            let n_dot_v = k as f64 / 10.0;
            let sv = (1.0 - n_dot_v * n_dot_v).sqrt();
            let (rows, cols) = (400, 800);
            let mut sum = 0.0;
            for i in 0..rows {
                let u = (i as f64 + 0.5) / rows as f64;
                let (ct, st) = (u.sqrt(), (1.0 - u).sqrt());
                for j in 0..cols {
                    let phi = (j as f64 + 0.5) / cols as f64 * std::f64::consts::TAU;
                    let v_dot_l = st * phi.cos() * sv + ct * n_dot_v;
                    let v_dot_h = (0.5 * (1.0 + v_dot_l)).max(0.0).sqrt();
                    sum += (1.0 - v_dot_h).powi(5);
                }
            }
            let exact = sum / (rows * cols) as f64;
            let fit = diffuse_fresnel_weight(n_dot_v as f32) as f64;
            assert!((fit - exact).abs() < 6e-4, "n·v {n_dot_v}: fit {fit}, integral {exact}");
        }
    }

    /// Karis's fit at two points, worked by hand from the published coefficients: at
    /// r = 0.5, n·v = 0.5, c = (0.5, 0.02875, 0.754, −0.029), a = min(0.25, 2^−4.64)·0.5 +
    /// 0.02875 = 0.048804, (A, B) = (0.70324, 0.02176); at r = 1, n·v = 0 the floor holds B.
    #[test]
    fn env_brdf_approx_at_worked_points() {
        let [a, b] = env_brdf_approx(0.5, 0.5);
        assert!((a - 0.70324).abs() < 1e-5, "{a}");
        assert!((b - 0.02176).abs() < 1e-5, "{b}");
        let [a, b] = env_brdf_approx(1.0, 0.0);
        // c = (0, 0.015, 0.468, −0.018): a = 0.015, A = 0.4524, B = −0.0024 → the floor.
        assert!((a - 0.4524).abs() < 1e-5, "{a}");
        assert_eq!(b, ENV_BRDF_APPROX_FLOOR);
    }

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
        // The diffuse weight's fit: its scale at a grazing view, nothing at normal incidence.
        assert_eq!(diffuse_fresnel_weight(0.0), DIFFUSE_FRESNEL_SCALE);
        assert_eq!(diffuse_fresnel_weight(1.0), 0.0);
        assert!((g1_smith_ggx(1.0, 0.3) - 1.0).abs() < 1e-6);
    }
}
