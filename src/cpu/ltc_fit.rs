//! The LTC table's fit on the CPU, twin of `shaders/ltc_fit.wgsl` (Heitz, Dupuy, Hill,
//! Neubelt 2016, their `fitLTC.cpp`, step for step; [`crate::plan::ltc`] says what a cell
//! holds and how it is fitted): the BRDF's lobe by GGX sampling (`lobe_terms`), the
//! fit's error by multiple importance sampling of the lobe and the LTC (`fit_error`),
//! Nelder-Mead over (m11, m22, m13) (`nelder_mead`), in the kernel's order
//! ([`LtcTable::fit`]).

use glam::Vec3;
use rayon::prelude::*;

use crate::math::brdf::d_ggx;
use crate::math::ltc::Ltc;
use crate::plan::ltc::{
    ltc_brdf, LtcCell, LtcTable, FIT_SAMPLES, MIN_ALPHA, MIN_FIT_N_DOT_V, MIN_SCALE, SIMPLEX_ITERATIONS,
    SIMPLEX_STEP, SIMPLEX_TOLERANCE,
};
use crate::plan::lut::LutModel;
use crate::plan::material::light_masking;
use crate::plan::shading::LightBrdf;
use crate::Result;

/// The `size`² LTC table that goes with the split-sum LUT `model`, fitted on the CPU to
/// the GGX lobe with the LUT's masking (`Baker::ltc` fits it on a baker's backend): a sheen
/// model, or a size outside 2 to 256, is an [`crate::Error::InvalidOption`].
pub fn fit_ltc(model: LutModel, size: u32) -> Result<LtcTable> {
    Ok(LtcTable::fit(ltc_brdf(model, size)?, size))
}

/// The BRDF's f (n·l) with F = 1 at unit l for view v (n = +Z) and the pdf of
/// [`sample_brdf`] for l: GGX D, `brdf`'s masking, D (n·h) / (4 v·h).
fn eval_brdf(brdf: LightBrdf, v: Vec3, l: Vec3, alpha: f32) -> (f32, f32) {
    let h = (v + l).normalize();
    let d = d_ggx(h.z.max(0.0), alpha);
    let pdf = (d * h.z / (4.0 * v.dot(h))).abs();
    if l.z <= 0.0 || v.z <= 0.0 {
        return (0.0, pdf);
    }
    (d * light_masking(brdf, l.z, v.z, alpha) * 0.25, pdf)
}

/// l reflected about a GGX normal sampled by (u1, u2) (Walter et al. 2007, eq. 35-36).
fn sample_brdf(v: Vec3, alpha: f32, u1: f32, u2: f32) -> Vec3 {
    let phi = 2.0 * std::f32::consts::PI * u1;
    let r = alpha * (u2 / (1.0 - u2)).sqrt();
    let h = Vec3::new(r * phi.cos(), r * phi.sin(), 1.0).normalize();
    2.0 * h.dot(v) * h - v
}

/// The quadrature's points (u1, u2), cell centres of a [`FIT_SAMPLES`]² grid.
fn fit_points() -> impl Iterator<Item = (f32, f32)> {
    let n = FIT_SAMPLES;
    (0..n * n).map(move |k| {
        (
            ((k % n) as f32 + 0.5) / n as f32,
            ((k / n) as f32 + 0.5) / n as f32,
        )
    })
}

/// The lobe's magnitude (F = 1), Fresnel part and mean direction (in the plane of
/// incidence) by GGX sampling.
fn lobe_terms(brdf: LightBrdf, v: Vec3, alpha: f32) -> (f32, f32, Vec3) {
    let (mut norm, mut fresnel, mut mean) = (0.0f64, 0.0f64, Vec3::ZERO);
    for (u1, u2) in fit_points() {
        let l = sample_brdf(v, alpha, u1, u2);
        let (value, pdf) = eval_brdf(brdf, v, l, alpha);
        if pdf > 0.0 {
            let w = value / pdf;
            let h = (v + l).normalize();
            norm += f64::from(w);
            fresnel += f64::from(w * (1.0 - v.dot(h).max(0.0)).powi(5));
            mean += w * l;
        }
    }
    let count = f64::from(FIT_SAMPLES * FIT_SAMPLES);
    mean.y = 0.0;
    let mean = mean.try_normalize().unwrap_or(Vec3::Z);
    ((norm / count) as f32, (fresnel / count) as f32, mean)
}

/// The fit's error of `ltc` (scaled by `norm`) against the lobe: the mean of
/// |f (n·l) − norm D|³ / (pdf_LTC + pdf_BRDF) over samples of both.
fn fit_error(brdf: LightBrdf, ltc: &Ltc, norm: f32, v: Vec3, alpha: f32) -> f64 {
    let mut error = 0.0f64;
    let mut add = |l: Vec3| {
        let (value, pdf_brdf) = eval_brdf(brdf, v, l, alpha);
        let d = ltc.density(l);
        let e = f64::from((value - norm * d).abs()).powi(3);
        error += e / f64::from(d + pdf_brdf).max(f64::from(f32::MIN_POSITIVE));
    };
    for (u1, u2) in fit_points() {
        add(ltc.sample(u1, u2));
        add(sample_brdf(v, alpha, u1, u2));
    }
    error / f64::from(FIT_SAMPLES * FIT_SAMPLES)
}

/// Nelder-Mead over three parameters from `start` (Heitz's `NelderMead.h`: reflection 1,
/// expansion 2, contraction and shrink 1/2): the best point found.
fn nelder_mead(start: [f32; 3], f: &dyn Fn([f32; 3]) -> f64) -> [f32; 3] {
    let mut s = [start; 4];
    for (i, p) in s.iter_mut().enumerate().skip(1) {
        p[i - 1] += SIMPLEX_STEP;
    }
    let mut fs = s.map(f);
    let along = |o: [f32; 3], p: [f32; 3], t: f32| std::array::from_fn(|i| o[i] + t * (o[i] - p[i]));
    for _ in 0..SIMPLEX_ITERATIONS {
        let (mut lo, mut hi, mut nh) = (0, 0, 0);
        for i in 1..4 {
            if fs[i] < fs[lo] {
                lo = i;
            }
            if fs[i] > fs[hi] {
                nh = hi;
                hi = i;
            } else if fs[i] > fs[nh] {
                nh = i;
            }
        }
        let (a, b) = (fs[lo].abs(), fs[hi].abs());
        if 2.0 * (a - b).abs() < (a + b) * f64::from(SIMPLEX_TOLERANCE) {
            break;
        }
        let mut o = [0.0f32; 3];
        for (k, p) in s.iter().enumerate() {
            if k != hi {
                for i in 0..3 {
                    o[i] += p[i] / 3.0;
                }
            }
        }
        let r = along(o, s[hi], 1.0);
        let fr = f(r);
        if fr < fs[nh] {
            if fr < fs[lo] {
                let e = along(o, s[hi], 2.0);
                let fe = f(e);
                if fe < fr {
                    (s[hi], fs[hi]) = (e, fe);
                    continue;
                }
            }
            (s[hi], fs[hi]) = (r, fr);
            continue;
        }
        let c = along(o, s[hi], -0.5);
        let fc = f(c);
        if fc < fs[hi] {
            (s[hi], fs[hi]) = (c, fc);
            continue;
        }
        for k in 0..4 {
            if k != lo {
                s[k] = std::array::from_fn(|i| s[lo][i] + 0.5 * (s[k][i] - s[lo][i]));
                fs[k] = f(s[k]);
            }
        }
    }
    let lo = (0..4).min_by(|&a, &b| fs[a].total_cmp(&fs[b])).unwrap_or(0);
    s[lo]
}

/// The fitted parameters (m11, m22, m13) of one cell from `start`, and the cell.
fn fit_cell(brdf: LightBrdf, size: u32, i: u32, j: u32, start: [f32; 3]) -> ([f32; 3], LtcCell) {
    let x = j as f32 / (size - 1) as f32;
    let n_dot_v = (1.0 - x * x).max(MIN_FIT_N_DOT_V);
    let v = Vec3::new((1.0 - n_dot_v * n_dot_v).sqrt(), 0.0, n_dot_v);
    let r = i as f32 / (size - 1) as f32;
    let alpha = (r * r).max(MIN_ALPHA);
    let (norm, fresnel, mean) = lobe_terms(brdf, v, alpha);
    let isotropic = j == 0;
    let frame = match isotropic {
        true => [Vec3::X, Vec3::Y, Vec3::Z],
        false => [Vec3::new(mean.z, 0.0, -mean.x), Vec3::Y, mean],
    };
    let ltc_of = |p: [f32; 3]| {
        let (m11, m22) = (p[0].max(MIN_SCALE), p[1].max(MIN_SCALE));
        match isotropic {
            true => ([m11, m11, 0.0], Ltc::new(m11, m11, 0.0, frame)),
            false => ([m11, m22, p[2]], Ltc::new(m11, m22, p[2], frame)),
        }
    };
    let best = nelder_mead(start, &|p| fit_error(brdf, &ltc_of(p).1, norm, v, alpha));
    let (params, ltc) = ltc_of(best);
    let inverse = ltc.inverse;
    let scale = inverse.y_axis.y;
    let cell = LtcCell {
        inverse: [
            inverse.x_axis.x / scale,
            inverse.x_axis.z / scale,
            inverse.z_axis.x / scale,
            inverse.z_axis.z / scale,
        ],
        norm,
        fresnel,
    };
    (params, cell)
}

impl LtcTable {
    /// Fits the `size`² table of `brdf` (at least 2) on the CPU: the normal-incidence column
    /// from the roughest cell down, then each roughness's row along θ in parallel (the
    /// GPU's twin: `gpu::ltc_fit`, shaders/ltc_fit.wgsl).
    pub fn fit(brdf: LightBrdf, size: u32) -> LtcTable {
        let size = size.max(2);
        // Normal incidence, r = 1 first: a cosine (m11 = m22 = 1).
        let mut first = vec![([1.0f32, 1.0, 0.0], None); size as usize];
        let mut start = [1.0f32, 1.0, 0.0];
        for i in (0..size).rev() {
            let (params, cell) = fit_cell(brdf, size, i, 0, start);
            first[i as usize] = (params, Some(cell));
            start = params;
        }
        let rows: Vec<Vec<LtcCell>> = (0..size)
            .into_par_iter()
            .map(|i| {
                let (mut params, cell) = first[i as usize];
                let mut column = vec![cell.expect("fitted above")];
                for j in 1..size {
                    let (p, cell) = fit_cell(brdf, size, i, j, params);
                    params = p;
                    column.push(cell);
                }
                column
            })
            .collect();
        let cells = (0..size as usize)
            .flat_map(|j| rows.iter().map(move |column| column[j]))
            .collect();
        LtcTable { size, brdf, cells }
    }
}
