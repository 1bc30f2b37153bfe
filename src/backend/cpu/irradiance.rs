//! The CPU backend's irradiance cube: the exact sum of `irradiance_texel` (`cpu::convolve_exact`) taken run by
//! run ([`MomentRuns`]), which skips or lumps the runs of texels wholly below or above a
//! normal's horizon.

use std::f32::consts::PI;

use crate::cpu::convolve_exact::add_moment_texel;
use crate::environment::texels::{irradiance_source_level, moment_texels, MomentTexel};
use crate::environment::walk::fill_cube_level;
use crate::environment::{Cubemap, IrradianceSource};
use crate::math::cubemap::{cube_face_direction, cube_texel_direction, FACES};

/// Texels per run of [`MomentRuns`].
pub const RUN_TEXELS: u32 = 8;

/// Slack of the run tests, far above the f32 rounding of n·l (≈ 1e-7).
const RUN_MARGIN: f32 = 1e-5;

/// The moment texels of an n²-per-face source cut into runs of [`RUN_TEXELS`] consecutive
/// texels of a face row, each with its face frame, its rectangle in face coordinates and
/// the sum of its moments. For a normal n, a run wholly below the horizon (every texel
/// more than its cap radius below it) adds nothing and is skipped, and a run wholly above
/// it (every texel more than its cap radius above it, so each adds n · moment, and
/// n · moment ≥ 0) adds n · (its moment sum): one dot product instead of eight. Only runs
/// near the horizon go texel by texel. Same terms as `irradiance_texel` (`cpu::convolve_exact`), summed in
/// another order (differences of f32 rounding, ~1e-6 relative).
///
/// Bounds: a point of the face plane is p = c + s·eᵤ + t·eᵥ (|p| ≤ √3) and texel
/// centroids lie inside their texels, so over a run's rectangle
/// n·p ∈ [Bmin, Bmax] with Bmin/Bmax = n·c + min/max(s₀ n·eᵤ, s₁ n·eᵤ) + min/max(t₀ n·eᵥ,
/// t₁ n·eᵥ); n·l = n·p/|p| is then ≤ Bmax/√3 when Bmax < 0 and ≥ Bmin/√3 when Bmin > 0.
#[derive(Clone, Debug)]
pub struct MomentRuns {
    runs: Vec<MomentRun>,
}

#[derive(Clone, Debug)]
struct MomentRun {
    range: std::ops::Range<usize>,
    centre: [f32; 3],
    eu: [f32; 3],
    ev: [f32; 3],
    s: [f32; 2],
    t: [f32; 2],
    /// The largest cap radius sin σ of the run's texels.
    reach: f32,
    /// Σ moments of the run, per channel.
    moments: [[f32; 3]; 3],
}

fn dot3(a: [f32; 3], b: [f32; 3]) -> f32 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

impl MomentRuns {
    /// Runs of `source`, the moment texels of an n²-per-face mip (face-major, row-major,
    /// as [`moment_texels`] lists them).
    pub fn new(source: &[MomentTexel], n: u32) -> Self {
        let run = RUN_TEXELS.min(n);
        let coord = |i: u32| 2.0 * i as f32 / n as f32 - 1.0;
        let mut runs = Vec::new();
        for face in 0..FACES as u32 {
            let centre = cube_face_direction(face, 0.0, 0.0);
            let eu = [0, 1, 2].map(|k| cube_face_direction(face, 1.0, 0.0)[k] - centre[k]);
            let ev = [0, 1, 2].map(|k| cube_face_direction(face, 0.0, 1.0)[k] - centre[k]);
            for j in 0..n {
                for i0 in (0..n).step_by(run as usize) {
                    let i1 = (i0 + run).min(n);
                    let first = ((face * n + j) * n + i0) as usize;
                    let range = first..first + (i1 - i0) as usize;
                    let texels = &source[range.clone()];
                    let reach = texels
                        .iter()
                        .map(|t| t.dir_sin2[3].max(0.0).sqrt())
                        .fold(0.0f32, f32::max);
                    let mut sum = [[0.0f64; 3]; 3];
                    for t in texels {
                        for (sc, mc) in sum.iter_mut().zip(&t.moments) {
                            for (s, m) in sc.iter_mut().zip(mc) {
                                *s += *m as f64;
                            }
                        }
                    }
                    runs.push(MomentRun {
                        range,
                        centre,
                        eu,
                        ev,
                        s: [coord(i0), coord(i1)],
                        t: [coord(j), coord(j + 1)],
                        reach,
                        moments: sum.map(|m| m.map(|v| v as f32)),
                    });
                }
            }
        }
        MomentRuns { runs }
    }
}

/// E(n)/π for unit `n`, as `irradiance_texel` (`cpu::convolve_exact`) but the cold texels run by run (see
/// [`MomentRuns`]).
pub fn irradiance_texel_runs(
    source: &[MomentTexel],
    runs: &MomentRuns,
    hot: &[MomentTexel],
    n: [f32; 3],
) -> [f32; 4] {
    let sqrt3 = 3f32.sqrt();
    let mut e = [0.0f32; 3];
    for r in &runs.runs {
        let (du, dv) = (dot3(n, r.eu), dot3(n, r.ev));
        let (su, sv) = ([r.s[0] * du, r.s[1] * du], [r.t[0] * dv, r.t[1] * dv]);
        let c = dot3(n, r.centre);
        let b_max = c + su[0].max(su[1]) + sv[0].max(sv[1]);
        let b_min = c + su[0].min(su[1]) + sv[0].min(sv[1]);
        let limit = r.reach + RUN_MARGIN;
        if b_max < 0.0 && b_max / sqrt3 < -limit {
            continue;
        }
        if b_min > 0.0 && b_min / sqrt3 > limit {
            for (ec, m) in e.iter_mut().zip(&r.moments) {
                *ec += dot3(n, *m);
            }
            continue;
        }
        for t in &source[r.range.clone()] {
            add_moment_texel(&mut e, t, n);
        }
    }
    for t in hot {
        add_moment_texel(&mut e, t, n);
    }
    [e[0] / PI, e[1] / PI, e[2] / PI, 1.0]
}

/// The irradiance cube of edge `size` (one level).
pub fn irradiance(src: &IrradianceSource, size: u32) -> Cubemap {
    let cold = &src.cold;
    let m = irradiance_source_level(cold);
    let source = moment_texels(cold, m);
    let runs = MomentRuns::new(&source, cold.level_size(m));
    let level = fill_cube_level(size, |face, i, j| {
        irradiance_texel_runs(
            &source,
            &runs,
            &src.hot,
            cube_texel_direction(face, i as i32, j as i32, size),
        )
    });
    Cubemap {
        size,
        levels: vec![level],
    }
}
