//! CPU reference for `shaders/brdf_lut.wgsl`: the split-sum BRDF LUT by deterministic
//! panel Gauss-Legendre quadrature in the GGX-sampled domain. The method and its derivation
//! are in [`crate::plan::lut`]; the functions here have the same names as the WGSL ones.

use std::f32::consts::{FRAC_PI_2, FRAC_PI_4, PI};

use rayon::prelude::*;

use crate::plan::lut::{lut_texel_coords, BrdfLut, LutDistribution, LutModel, LutQuadrature, Visibility};
use crate::math::brdf::{
    alpha_from_roughness, ashikhmin_4v_n_dot_l, fresnel_schlick_weight, g1_over_n_dot_v,
    g1_schlick_ggx, k_ibl, lambda_sheen, sheen_4v_n_dot_l, smith_correlated_4v_n_dot_l,
    smith_correlated_lambda,
};
use crate::math::sampling::{
    charlie_q_from_theta, charlie_theta_from_q, ggx_q_from_theta, ggx_theta_from_q,
};
use crate::math::trig::acos_precise;

/// Per-texel constants of the integrand. `g_vis` is the view-side factor of the
/// visibility: G1(n·v)/(n·v) for Schlick-GGX, Λ'(v) for the correlated form, the sheen
/// Λ(v) for the KHR_materials_sheen visibility.
struct LutTexel {
    cos_v: f32,
    sin_v: f32,
    alpha2: f32,
    k: f32,
    g_vis: f32,
    visibility: Visibility,
    alpha: f32,
    distribution: LutDistribution,
}

/// q at polar angle θ of the half vector, in the texel's distribution.
fn lut_q_at_theta(tx: &LutTexel, theta: f32) -> f32 {
    match tx.distribution {
        LutDistribution::Ggx => ggx_q_at_theta(theta, tx.alpha2),
        LutDistribution::Charlie => {
            let c = theta.cos();
            charlie_q_from_theta(c * c, tx.alpha)
        }
    }
}

/// (cos²θ, sin²θ) of the half vector at q, in the texel's distribution.
fn lut_theta_from_q(tx: &LutTexel, q: f32) -> (f32, f32) {
    match tx.distribution {
        LutDistribution::Ggx => ggx_theta_from_q(q, tx.alpha2),
        LutDistribution::Charlie => charlie_theta_from_q(q, tx.alpha),
    }
}

/// 4 V (n·l): f (n·l) / pdf(l) = 4 V (n·l) · F · (v·h)/(n·h) for pdf(l) = D (n·h) / (4 v·h).
fn lut_visibility(tx: &LutTexel, n_dot_l: f32) -> f32 {
    match tx.visibility {
        Visibility::SchlickGgx => g1_schlick_ggx(n_dot_l, tx.k) * tx.g_vis,
        Visibility::SmithCorrelated => {
            smith_correlated_4v_n_dot_l(tx.cos_v, n_dot_l, tx.alpha2, tx.g_vis)
        }
        Visibility::Ashikhmin => ashikhmin_4v_n_dot_l(tx.cos_v, n_dot_l),
        Visibility::Sheen => sheen_4v_n_dot_l(tx.cos_v, n_dot_l, tx.alpha, tx.g_vis),
    }
}

/// Maps a Gauss-Legendre abscissa t ∈ [0, 1] to the panel variable x ∈ [0, 1] and returns
/// (x, dx/dt). Ends flagged singular get a quadratic change of variable (x ≈ t² there),
/// which turns the panel's √ end behaviour into a smooth one.
pub fn panel_map(t: f32, lower_singular: bool, upper_singular: bool) -> (f32, f32) {
    if lower_singular && upper_singular {
        (t * t * (3.0 - 2.0 * t), 6.0 * t * (1.0 - t))
    } else if lower_singular {
        (t * t, 2.0 * t)
    } else if upper_singular {
        let s = 1.0 - t;
        (1.0 - s * s, 2.0 * s)
    } else {
        (t, 1.0)
    }
}

/// End of the partial panel that starts at θh = `t0`. The φ range changes on the scale of
/// θh's distance to 0 near the first breakpoint and of its distance to π/2 near the second
/// (the two breakpoints are mirror images about π/4), so panels grow geometrically by
/// `growth` away from both: t0·growth below π/4, π/2 − (π/2 − t0)/growth above.
pub fn next_panel_end(t0: f32, growth: f32) -> f32 {
    if t0 < FRAC_PI_4 {
        (t0 * growth).min(FRAC_PI_4)
    } else {
        FRAC_PI_2 - (FRAC_PI_2 - t0) / growth
    }
}

/// q at polar angle θ of the half vector.
pub fn ggx_q_at_theta(theta: f32, alpha2: f32) -> f32 {
    let c = theta.cos();
    let s = theta.sin();
    ggx_q_from_theta(c * c, s * s, alpha2)
}

/// ∫ over one θh panel [q_a, q_b] (q falls as θh grows) and over φ of the split-sum
/// integrand, returning (A, B) contributions. `full` panels cover φ ∈ [0, π]; partial ones
/// stop where n·l = 0.
#[allow(clippy::too_many_arguments)]
fn integrate_panel(
    tx: &LutTexel,
    q_a: f32,
    q_b: f32,
    full: bool,
    lower_singular: bool,
    upper_singular: bool,
    theta_rule: &[[f32; 2]],
    phi_rule: &[[f32; 2]],
) -> [f32; 2] {
    let mut sum = [0.0f32; 2];
    let width = q_a - q_b;
    for &[t, w] in theta_rule {
        let (x, dx) = panel_map(t, lower_singular, upper_singular);
        let q = q_a - width * x;
        let weight_q = width * w * dx;
        let (cos2_h, sin2_h) = lut_theta_from_q(tx, q);
        let cos_h = cos2_h.sqrt();
        let sin_h = sin2_h.sqrt();
        let phi_max = if full {
            PI
        } else {
            let c0 = tx.cos_v * (1.0 - 2.0 * cos2_h) / (2.0 * tx.sin_v * sin_h * cos_h);
            acos_precise(c0)
        };
        // dφ/π over [0, φmax] (the integrand is even in φ).
        let weight_panel = weight_q * phi_max / PI;
        for &[tp, wp] in phi_rule {
            let phi = phi_max * tp;
            let v_dot_h = tx.sin_v * sin_h * phi.cos() + tx.cos_v * cos_h;
            let n_dot_l = 2.0 * v_dot_h * cos_h - tx.cos_v;
            if n_dot_l > 0.0 {
                // f (n·l) / pdf(l) without F = 4 V (n·l) · (v·h)/(n·h)
                let g = lut_visibility(tx, n_dot_l) * v_dot_h / cos_h;
                let fc = fresnel_schlick_weight(v_dot_h);
                let wgt = weight_panel * wp * g;
                sum[0] += wgt * (1.0 - fc);
                sum[1] += wgt * fc;
            }
        }
    }
    sum
}

/// The model's two channels for one (n·v, roughness) pair (see [`LutModel`]).
pub fn brdf_lut_texel(
    n_dot_v: f32,
    roughness: f32,
    quad: &LutQuadrature,
    model: LutModel,
) -> [f32; 2] {
    let alpha = alpha_from_roughness(roughness);
    let alpha2 = alpha * alpha;
    let k = k_ibl(roughness);
    let visibility = model.visibility();
    let tx = LutTexel {
        cos_v: n_dot_v,
        sin_v: (1.0 - n_dot_v * n_dot_v).max(0.0).sqrt(),
        alpha2,
        k,
        g_vis: match visibility {
            Visibility::SchlickGgx => g1_over_n_dot_v(n_dot_v, k),
            Visibility::SmithCorrelated => smith_correlated_lambda(n_dot_v, alpha2),
            Visibility::Ashikhmin => 0.0,
            Visibility::Sheen => lambda_sheen(n_dot_v, alpha),
        },
        visibility,
        alpha,
        distribution: model.distribution(),
    };
    let theta_v = acos_precise(n_dot_v);
    // Horizon breakpoints in θh (see crate::lut).
    let theta_full = 0.5 * (FRAC_PI_2 - theta_v);
    let theta_end = 0.5 * (FRAC_PI_2 + theta_v);

    let full_rule = quad.rule(quad.full);
    let partial_rule = quad.rule(quad.partial);
    let phi_rule = quad.rule(quad.phi);

    let q_full = lut_q_at_theta(&tx, theta_full);
    let q_mid = lut_q_at_theta(&tx, theta_full / quad.panel_growth);
    let mut ab = integrate_panel(&tx, 1.0, q_mid, true, false, false, full_rule, phi_rule);
    let ab2 = integrate_panel(&tx, q_mid, q_full, true, false, false, full_rule, phi_rule);
    ab[0] += ab2[0];
    ab[1] += ab2[1];
    let mut t0 = theta_full;
    let mut q0 = q_full;
    for panel in 0..quad.max_panels {
        if t0 >= theta_end {
            break;
        }
        let next = next_panel_end(t0, quad.panel_growth);
        let last = panel + 1 == quad.max_panels || next >= theta_end;
        let t1 = if last { theta_end } else { next };
        let q1 = lut_q_at_theta(&tx, t1);
        let part = integrate_panel(&tx, q0, q1, false, panel == 0, last, partial_rule, phi_rule);
        ab[0] += part[0];
        ab[1] += part[1];
        t0 = t1;
        q0 = q1;
    }
    model.layout().arrange(ab)
}

/// The whole LUT of `model` on the CPU with every texel integrated (rayon over rows), as
/// the GPU kernel computes it; the CPU backend interpolates most texels instead
/// ([`crate::backend::cpu::lut_interpolation`]).
pub fn brdf_lut_exact(width: u32, height: u32, quad: &LutQuadrature, model: LutModel) -> BrdfLut {
    let mut data = vec![[0.0f32; 2]; (width * height) as usize];
    data.par_chunks_mut(width as usize)
        .enumerate()
        .for_each(|(j, row)| {
            for (i, texel) in row.iter_mut().enumerate() {
                let (n_dot_v, roughness) = lut_texel_coords(i as u32, j as u32, width, height);
                *texel = brdf_lut_texel(n_dot_v, roughness, quad, model);
            }
        });
    BrdfLut::new(width, height, data)
}
