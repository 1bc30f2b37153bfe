//! Irradiance and SH against ground truth at full source resolution: real HDRIs with a sun
//! and a one-texel lamp, every irradiance size 8 … 64 and specular size 32 … 512 of a bake.
//!
//! The truth is computed here, in f64, independently of the library: E(n)/π =
//! (1/π) Σ over every source texel of L ∫_texel max(0, n·l) dω. A texel wholly above n's
//! horizon adds L n·∫ l dω (its exact first moment, in closed form over the
//! latitude-longitude cell); one wholly below adds nothing; one that straddles the horizon
//! adds L Ω times the mean of max(0, ·) of n·l linearised over the cell (a closed form in
//! the ramp's third antiderivative), exact up to the curvature of n·l across a cell. Blocks
//! of 16×16 texels wholly above or below the horizon are summed at once.
//!
//! Metric: the worst texel of |E − truth| / max(truth, 1 % of the mean truth),
//! on luminance.
mod common;

use std::f64::consts::PI;

use splitsum::environment::{Environment, Equirect};
use splitsum::math::cubemap::cube_texel_direction;
use splitsum::stages::convert::environment_into_cube_with_irradiance;
use splitsum::stages::sh::sh_project;

fn luminance(c: [f64; 3]) -> f64 {
    0.2126 * c[0] + 0.7152 * c[1] + 0.0722 * c[2]
}

const BLOCK: usize = 16;

/// The full-resolution source, prepared for the truth.
struct Truth {
    w: usize,
    h: usize,
    /// Per texel: luminance and exact first moment ∫ l dω.
    lum: Vec<f64>,
    moment: Vec<[f64; 3]>,
    blocks: Vec<Block>,
}

/// Σ luminance × moment of a block of texels, its centre direction, the sine of its
/// angular radius, and its rows and columns.
type Block = (
    [f64; 3],
    [f64; 3],
    f64,
    std::ops::Range<usize>,
    std::ops::Range<usize>,
);

fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

fn direction(phi: f64, theta: f64) -> [f64; 3] {
    [
        theta.sin() * phi.cos(),
        theta.cos(),
        theta.sin() * phi.sin(),
    ]
}

impl Truth {
    fn new(e: &Equirect) -> Self {
        let (w, h) = (e.width as usize, e.height as usize);
        let (dphi, dtheta) = (2.0 * PI / w as f64, PI / h as f64);
        let mut lum = Vec::with_capacity(w * h);
        let mut moment = Vec::with_capacity(w * h);
        for y in 0..h {
            let (t0, t1) = (y as f64 * dtheta, (y + 1) as f64 * dtheta);
            let s2 = 0.5 * (t1 - t0) - 0.25 * ((2.0 * t1).sin() - (2.0 * t0).sin());
            let cs = 0.5 * (t1.sin().powi(2) - t0.sin().powi(2));
            for x in 0..w {
                let (p0, p1) = (x as f64 * dphi - PI, (x + 1) as f64 * dphi - PI);
                let l = e.get(x as u32, y as u32);
                lum.push(luminance(l.map(|v| v as f64)));
                moment.push([
                    s2 * (p1.sin() - p0.sin()),
                    cs * dphi,
                    s2 * (p0.cos() - p1.cos()),
                ]);
            }
        }
        let mut blocks = Vec::new();
        for by in (0..h).step_by(BLOCK) {
            for bx in (0..w).step_by(BLOCK) {
                let (ys, xs) = (by..(by + BLOCK).min(h), bx..(bx + BLOCK).min(w));
                let mut m = [0.0; 3];
                for y in ys.clone() {
                    for x in xs.clone() {
                        let k = y * w + x;
                        (0..3).for_each(|c| m[c] += lum[k] * moment[k][c]);
                    }
                }
                // Bounding cap: the block's boundary sampled finely, plus a texel's margin.
                let (p0, p1) = (bx as f64 * dphi - PI, xs.end as f64 * dphi - PI);
                let (t0, t1) = (by as f64 * dtheta, ys.end as f64 * dtheta);
                let centre = direction(0.5 * (p0 + p1), 0.5 * (t0 + t1));
                let mut radius = 0.0f64;
                for k in 0..=32 {
                    let f = k as f64 / 32.0;
                    for d in [
                        direction(p0 + f * (p1 - p0), t0),
                        direction(p0 + f * (p1 - p0), t1),
                        direction(p0, t0 + f * (t1 - t0)),
                        direction(p1, t0 + f * (t1 - t0)),
                    ] {
                        radius = radius.max(dot(centre, d).clamp(-1.0, 1.0).acos());
                    }
                }
                let radius = radius + 2.0 * dphi.max(dtheta);
                blocks.push((m, centre, radius.min(PI / 2.0).sin(), ys, xs));
            }
        }
        Truth {
            w,
            h,
            lum,
            moment,
            blocks,
        }
    }

    /// E(n)/π of the luminance.
    fn irradiance(&self, n: [f64; 3]) -> f64 {
        let (dphi, dtheta) = (2.0 * PI / self.w as f64, PI / self.h as f64);
        let mut e = 0.0;
        for (m, centre, sin_r, ys, xs) in &self.blocks {
            let c = dot(n, *centre);
            if c >= *sin_r {
                e += dot(n, *m);
                continue;
            }
            if c <= -*sin_r {
                continue;
            }
            for y in ys.clone() {
                let theta = (y as f64 + 0.5) * dtheta;
                let omega = dphi * ((y as f64 * dtheta).cos() - ((y + 1) as f64 * dtheta).cos());
                for x in xs.clone() {
                    let k = y * self.w + x;
                    if self.lum[k] == 0.0 {
                        continue;
                    }
                    let phi = (x as f64 + 0.5) * dphi - PI;
                    let d = direction(phi, theta);
                    // n·l over the cell ≈ x_c + a u + b v, u ∈ [−Δθ/2, Δθ/2], v ∈ [−Δφ/2, Δφ/2].
                    let xc = dot(n, d);
                    let a = dot(n, direction(phi, theta + 0.5 * PI)) * 0.5 * dtheta;
                    let b = (n[2] * phi.cos() - n[0] * phi.sin()) * theta.sin() * 0.5 * dphi;
                    let (a, b) = (a.abs(), b.abs());
                    if xc - a - b >= 0.0 {
                        e += self.lum[k] * dot(n, self.moment[k]);
                    } else if xc + a + b > 0.0 {
                        e += self.lum[k] * omega * mean_ramp(xc, a, b);
                    }
                }
            }
        }
        e / PI
    }
}

/// Mean of max(0, x + a u + b v) over u, v ∈ [−1, 1] (a, b ≥ 0), from the third
/// antiderivative of the ramp, R(t) = max(0, t)³/6.
fn mean_ramp(x: f64, a: f64, b: f64) -> f64 {
    let r = |t: f64| t.max(0.0).powi(3) / 6.0;
    let r2 = |t: f64| t.max(0.0).powi(2) / 2.0;
    const TINY: f64 = 1e-12;
    if a < TINY && b < TINY {
        x.max(0.0)
    } else if a < TINY || b < TINY {
        let s = a.max(b);
        (r2(x + s) - r2(x - s)) / (2.0 * s)
    } else {
        (r(x + a + b) - r(x + a - b) - r(x - a + b) + r(x - a - b)) / (4.0 * a * b)
    }
}

/// A one-texel lamp of radiance 1000 in a black 1024×512.
fn lamp() -> Equirect {
    let (w, h) = (1024u32, 512u32);
    let mut data = vec![[0.0f32; 3]; (w * h) as usize];
    data[(170 * w + 301) as usize] = [1000.0; 3];
    Equirect {
        width: w,
        height: h,
        data,
    }
}

/// Irradiance worst texel ≤ 0.5 % on quarry_01, royal_esplanade and a one-texel lamp, at
/// every irradiance size 8 … 64 (the texels of `common::truth_texel_stride`) and specular
/// size 32 … 512 (the GPU: one pair).
#[test]
fn irradiance_matches_the_full_resolution_truth() {
    let backends = common::backends();
    for (name, e) in [
        (
            "quarry_01_1k.hdr",
            common::test_equirect("quarry_01_1k.hdr"),
        ),
        (
            "royal_esplanade_1k.hdr",
            common::test_equirect("royal_esplanade_1k.hdr"),
        ),
        ("one-texel lamp", lamp()),
    ] {
        let truth = Truth::new(&e);
        let sizes = [8u32, 16, 32, 64];
        // The truth at the checked texels of each size (common::truth_texel_stride).
        let truths: Vec<Vec<f64>> = sizes
            .iter()
            .map(|&n| {
                use rayon::prelude::*;
                (0..6 * n * n)
                    .into_par_iter()
                    .step_by(common::truth_texel_stride(n))
                    .map(|k| {
                        let (face, j, i) = (k / (n * n), (k % (n * n)) / n, k % n);
                        truth.irradiance(
                            cube_texel_direction(face, i as i32, j as i32, n).map(|v| v as f64),
                        )
                    })
                    .collect()
            })
            .collect();
        for backend in &backends {
            // lavapipe takes ~10 s for each 32² irradiance cube; the GPU kernel is checked
            // against the CPU one in tests/specular.rs, so here one size pair suffices.
            let cpu = backend.identity() == "cpu";
            let (specs, irradiance_sizes): (&[u32], &[u32]) = if cpu {
                (&[32, 64, 128, 256, 512], &sizes)
            } else {
                (&[256], &[8])
            };
            let mut worst = 0.0f64;
            for &spec in specs {
                let (_, source) = environment_into_cube_with_irradiance(
                    backend.as_ref(),
                    Environment::Equirect(e.clone()),
                    spec,
                    true,
                    0.0,
                )
                .unwrap();
                for (&n, t) in sizes.iter().zip(&truths) {
                    if !irradiance_sizes.contains(&n) {
                        continue;
                    }
                    let irr = backend.irradiance(&source, n).unwrap();
                    let mean = t.iter().sum::<f64>() / t.len() as f64;
                    let checked = irr.levels[0]
                        .iter()
                        .enumerate()
                        .step_by(common::truth_texel_stride(n));
                    for ((k, got), &truth_k) in checked.zip(t) {
                        let got = luminance([got[0] as f64, got[1] as f64, got[2] as f64]);
                        let rel = (got - truth_k).abs() / truth_k.max(0.01 * mean);
                        worst = worst.max(rel);
                        assert!(
                            rel <= 5e-3,
                            "{name}, specular {spec}, irradiance {n} ({}): texel {k} {got} vs {} ({:.2} %)",
                            backend.description(),
                            truth_k,
                            rel * 100.0
                        );
                    }
                }
            }
            println!(
                "{name}: worst irradiance texel {:.3} % ({})",
                worst * 100.0,
                backend.description()
            );
        }
    }
}

/// The SH of a one-texel lamp evaluate (as E/π) within 0.5 % of the lamp's exact SH-9
/// projection (the texel split into 64×64 equal-area cells) at 600 random directions,
/// relative to max(|exact|, 1 % of the mean |exact|).
#[test]
fn sh_of_a_lamp_is_exact() {
    use splitsum::math::sh::{irradiance_band_factor, sh_band, sh_basis};
    let e = lamp();
    let (w, h) = (e.width as f64, e.height as f64);
    let (x, y) = (301.0, 170.0);
    let mut exact = [0.0f64; 9];
    const SUB: usize = 64;
    let (ya, yb) = ((PI * y / h).cos(), (PI * (y + 1.0) / h).cos());
    let cell = 1000.0 * 2.0 * PI / w * (ya - yb) / (SUB * SUB) as f64;
    for a in 0..SUB {
        let phi = 2.0 * PI * ((x + (a as f64 + 0.5) / SUB as f64) / w - 0.5);
        for b in 0..SUB {
            let yy = ya + (yb - ya) * (b as f64 + 0.5) / SUB as f64;
            let r = (1.0 - yy * yy).sqrt();
            let d = [(r * phi.cos()) as f32, yy as f32, (r * phi.sin()) as f32];
            let basis = sh_basis(d);
            for k in 0..9 {
                exact[k] += cell * basis[k] as f64;
            }
        }
    }
    for (k, c) in exact.iter_mut().enumerate() {
        *c *= irradiance_band_factor(sh_band(k)) as f64;
    }
    for spec in [32u32, 256] {
        let (_, source) = environment_into_cube_with_irradiance(
            &splitsum::backend::CpuBackend,
            Environment::Equirect(e.clone()),
            spec,
            true,
            0.0,
        )
        .unwrap();
        let sh = sh_project(&source);
        let dirs: Vec<[f32; 3]> = common::uniform_directions(600, 99)
            .into_iter()
            .map(|d| d.map(|v| v as f32))
            .collect();
        let eval = |c: &dyn Fn(usize) -> f64, d: [f32; 3]| -> f64 {
            let b = sh_basis(d);
            (0..9).map(|k| c(k) * b[k] as f64).sum()
        };
        let values: Vec<(f64, f64)> = dirs
            .iter()
            .map(|&d| {
                (
                    eval(&|k| exact[k], d),
                    eval(&|k| sh.exact_irradiance[k][0] as f64, d),
                )
            })
            .collect();
        let mean = values.iter().map(|v| v.0.abs()).sum::<f64>() / values.len() as f64;
        let worst = values
            .iter()
            .map(|(t, g)| (g - t).abs() / t.abs().max(0.01 * mean))
            .fold(0.0, f64::max);
        println!(
            "specular {spec}: SH of the lamp, worst {:.4} %",
            worst * 100.0
        );
        assert!(worst <= 5e-3, "specular {spec}: {:.3} %", worst * 100.0);
    }
}
