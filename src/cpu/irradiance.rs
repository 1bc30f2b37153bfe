//! CPU reference for the irradiance mode of `shaders/convolve_exact.wgsl`: the irradiance
//! cube E(n)/π without noise, as a sum of max(0, n · Mₖ), Mₖ = ∫ L l dω, over every texel
//! of the cold ≤ 64² cube and every cell of the hot texels split off at the source's
//! resolution ([`crate::environment::hot`]). The clamped cosine is linear in l above the
//! horizon, so this equals the full-resolution integral except for the texels and cells
//! straddling n's horizon, which are modelled as caps (clipped in closed form); a sun keeps
//! its exact direction and its terminator is resolved to a quarter of a source texel.

use std::f32::consts::PI;

use crate::cpu::equirect_to_cube::fill_cube_level;
use crate::environment::{Cubemap, IrradianceSource};
use crate::math::cubemap::{
    cube_face_direction, cube_texel_direction, cube_texel_solid_angle, FACES,
};
use crate::math::trig::{acos_precise, atan_precise};

/// Largest source mip edge the irradiance sum reads.
pub const IRRADIANCE_SOURCE_SIZE: u32 = 64;

/// One texel of a source mip for the exact kernels, summarising the level-0 texels it
/// covers. Shared by CPU and GPU (uploaded as an array of vec4).
#[derive(Clone, Copy, Debug, bytemuck::Pod, bytemuck::Zeroable)]
#[repr(C)]
pub struct SourceTexel {
    /// Luminance-weighted centroid direction of the texel's radiance (its centre when it
    /// is black), and its exact solid angle Ω.
    pub dir_omega: [f32; 4],
    /// Mean radiance (rgb) and the texel's weight in the exact sum's normaliser (a: 1, or 0
    /// for a hot cell, whose solid angle the cold texels already count).
    pub radiance: [f32; 4],
}

/// One source texel for the irradiance sum. Its first moments ∫ L_c l dω (one vec4 per
/// channel, xyz): the cosine kernel is linear in l, so ∫_texel L (n·l) dω = n · moment
/// exactly whenever the texel lies wholly above n's horizon, and a sun inside a coarse
/// texel keeps its true direction. For texels that straddle the horizon, the texel's
/// radiance is modelled as a uniform cap around its centroid whose spread matches the
/// moment's length, and the clipped cosine integral is evaluated in closed form
/// ([`clipped_cap_cosine`]).
#[derive(Clone, Copy, Debug, bytemuck::Pod, bytemuck::Zeroable)]
#[repr(C)]
pub struct MomentTexel {
    /// Moments of R, G and B (xyz; w unused).
    pub moments: [[f32; 4]; 3],
    /// Unit radiance centroid (xyz) and sin²σ of the effective cap (w).
    pub dir_sin2: [f32; 4],
    /// Total radiance × solid angle (rgb) and, for hot cells, the solid angle (a).
    pub radiance_omega: [f32; 4],
}

/// Below this sin²σ (σ ≈ 1.8°) [`clipped_cap_cosine`] treats the cap as a flat disk: the
/// closed form's terms cancel to O(σ³) there, which f32 cannot resolve (at sin²σ = 1e-6
/// it is ~10 % off), while the disk's error is O(σ²) relative (< 1e-3).
pub const SMALL_CAP_SIN2: f32 = 1e-3;

/// ∫ max(0, n·l) dω over a spherical cap of half-angle σ whose centre makes cos θ with n
/// (the horizon-clipped sphere-light illuminance of Snyder 1996, in the form of Lagarde &
/// de Rousiers, "Moving Frostbite to PBR", 2014), divided by the cap's solid angle
/// 2π(1 − cos σ): the mean clamped cosine over the cap. For a small cap
/// (sin²σ < [`SMALL_CAP_SIN2`]) n·l is linear across it, x₀ + g·w·σ with x₀ = cos θ,
/// g = sin θ and w distributed as a disk's chord, (2/π)√(1 − w²) on [−1, 1]; with
/// t = x₀/(gσ) the mean of its positive part is gσ (t A(t) + B(t)), A(t) =
/// (π/2 + t√(1 − t²) + asin t)/π, B(t) = 2(1 − t²)^{3/2}/(3π).
pub fn clipped_cap_cosine(cos_theta: f32, sin2_sigma: f32) -> f32 {
    if sin2_sigma < 1e-12 {
        return cos_theta.max(0.0);
    }
    if sin2_sigma < SMALL_CAP_SIN2 {
        let sigma = sin2_sigma.sqrt(); // sin σ ≈ σ to O(σ³)
        let g = (1.0 - cos_theta * cos_theta).max(0.0).sqrt();
        let reach = g * sigma;
        if cos_theta >= reach {
            return cos_theta;
        }
        if cos_theta <= -reach {
            return 0.0;
        }
        let t = cos_theta / reach;
        let r = (1.0 - t * t).max(0.0).sqrt();
        let asin_t = atan_precise(t / r.max(1e-9));
        let a = (0.5 * PI + t * r + asin_t) / PI;
        let b = 2.0 * r * r * r / (3.0 * PI);
        return reach * (t * a + b);
    }
    let cap = 2.0 * PI * (1.0 - (1.0 - sin2_sigma).max(0.0).sqrt());
    let e = if cos_theta * cos_theta > sin2_sigma {
        PI * sin2_sigma * cos_theta.max(0.0)
    } else {
        let sin_theta = (1.0 - cos_theta * cos_theta).max(0.0).sqrt();
        let x = (1.0 / sin2_sigma - 1.0).max(0.0).sqrt();
        let y = (-x * cos_theta / sin_theta.max(1e-9)).clamp(-1.0, 1.0);
        let st_y = sin_theta * (1.0 - y * y).max(0.0).sqrt();
        (cos_theta * acos_precise(y) - x * st_y) * sin2_sigma + atan_precise(st_y / x.max(1e-9))
    };
    e.max(0.0) / cap
}

fn luminance(c: [f32; 4]) -> f32 {
    0.2126 * c[0] + 0.7152 * c[1] + 0.0722 * c[2]
}

/// Visits every texel of mip `m` of `env` with the level-0 texels it covers:
/// (face, i, j, [(direction, Ω, radiance)]).
fn for_each_source_texel(
    env: &Cubemap,
    m: usize,
    mut visit: impl FnMut(u32, u32, u32, &[([f32; 3], f32, [f32; 4])]),
) {
    let n = env.level_size(m);
    let n0 = env.size;
    let k = n0 / n;
    let mut children = Vec::with_capacity((k * k) as usize);
    for face in 0..FACES as u32 {
        for j in 0..n {
            for i in 0..n {
                children.clear();
                for cj in j * k..(j + 1) * k {
                    for ci in i * k..(i + 1) * k {
                        let d = cube_texel_direction(face, ci as i32, cj as i32, n0);
                        children.push((
                            d,
                            cube_texel_solid_angle(ci, cj, n0),
                            env.texel(0, face, ci, cj),
                        ));
                    }
                }
                visit(face, i, j, &children);
            }
        }
    }
}

/// A source texel's exact solid angle and luminance-weighted radiance centroid (its centre
/// direction when it is black), from the level-0 texels it covers.
fn texel_centroid(
    face: u32,
    i: u32,
    j: u32,
    n: u32,
    children: &[([f32; 3], f32, [f32; 4])],
) -> ([f32; 3], f32) {
    let mut moment = [0.0f64; 3];
    for (d, w, l) in children {
        let y = (luminance(*l) * w) as f64;
        for c in 0..3 {
            moment[c] += y * d[c] as f64;
        }
    }
    let len = (moment[0] * moment[0] + moment[1] * moment[1] + moment[2] * moment[2]).sqrt();
    let dir = if len > 0.0 {
        moment.map(|v| (v / len) as f32)
    } else {
        cube_texel_direction(face, i as i32, j as i32, n)
    };
    (dir, cube_texel_solid_angle(i, j, n))
}

/// Σ L Ω over a source texel's level-0 texels, per channel.
fn texel_radiance_sum(children: &[([f32; 3], f32, [f32; 4])]) -> [f64; 3] {
    let mut lw = [0.0f64; 3];
    for (_, w, l) in children {
        for c in 0..3 {
            lw[c] += (l[c] * w) as f64;
        }
    }
    lw
}

/// Every texel of mip `m` of `env`, summarised for the exact specular sum.
pub fn source_texels(env: &Cubemap, m: usize) -> Vec<SourceTexel> {
    let n = env.level_size(m);
    let mut out = Vec::with_capacity(FACES * (n * n) as usize);
    for_each_source_texel(env, m, |face, i, j, children| {
        let (dir, omega) = texel_centroid(face, i, j, n, children);
        let lw = texel_radiance_sum(children);
        let total: f64 = children.iter().map(|c| c.1 as f64).sum();
        out.push(SourceTexel {
            dir_omega: [dir[0], dir[1], dir[2], omega],
            radiance: [
                (lw[0] / total) as f32,
                (lw[1] / total) as f32,
                (lw[2] / total) as f32,
                1.0,
            ],
        });
    });
    out
}

/// Every texel of mip `m` of `env` as radiance moments, for the irradiance sum.
pub fn moment_texels(env: &Cubemap, m: usize) -> Vec<MomentTexel> {
    let n = env.level_size(m);
    let mut out = Vec::with_capacity(FACES * (n * n) as usize);
    for_each_source_texel(env, m, |face, i, j, children| {
        let (dir, omega) = texel_centroid(face, i, j, n, children);
        let lw = texel_radiance_sum(children);
        let mut moments = [[0.0f64; 3]; 3];
        for (d, w, l) in children {
            for c in 0..3 {
                for a in 0..3 {
                    moments[c][a] += (l[c] * w * d[a]) as f64;
                }
            }
        }
        // Effective cap: a uniform cap of half-angle σ has a mean direction of length
        // (1 + cos σ)/2, so the luminance moment's length sets σ: a texel holding a sun
        // acts as a point, a uniform texel as a cap of its own solid angle.
        let lum = |v: [f64; 3]| 0.2126 * v[0] + 0.7152 * v[1] + 0.0722 * v[2];
        let m_lum = [0, 1, 2].map(|a| lum([moments[0][a], moments[1][a], moments[2][a]]));
        let l_lum = lum(lw);
        let cos_sigma = if l_lum > 0.0 {
            let ratio =
                (m_lum[0] * m_lum[0] + m_lum[1] * m_lum[1] + m_lum[2] * m_lum[2]).sqrt() / l_lum;
            (2.0 * ratio - 1.0).clamp(-1.0, 1.0) as f32
        } else {
            1.0 - omega / (2.0 * PI)
        };
        out.push(MomentTexel {
            moments: moments.map(|m| [m[0] as f32, m[1] as f32, m[2] as f32, 0.0]),
            dir_sin2: [dir[0], dir[1], dir[2], 1.0 - cos_sigma * cos_sigma],
            radiance_omega: [lw[0] as f32, lw[1] as f32, lw[2] as f32, 0.0],
        });
    });
    out
}

/// The mip of `env` the irradiance sum reads: the largest no bigger than
/// [`IRRADIANCE_SOURCE_SIZE`].
pub fn irradiance_source_level(env: &Cubemap) -> usize {
    (0..env.levels.len())
        .find(|&m| env.level_size(m) <= IRRADIANCE_SOURCE_SIZE)
        .unwrap_or(env.levels.len() - 1)
}

/// E(n)/π for unit `n` over every cold source texel and then every hot cell (see
/// [`crate::environment::hot`]): (1/π) Σ n · moment for texels above the horizon, the
/// clipped-cap estimate for texels straddling it. The mirror of the irradiance mode of
/// `convolve_exact.wgsl`; [`irradiance`] computes the same sum faster with [`MomentRuns`].
pub fn irradiance_texel(source: &[MomentTexel], hot: &[MomentTexel], n: [f32; 3]) -> [f32; 4] {
    let mut e = [0.0f32; 3];
    for t in source.iter().chain(hot) {
        add_moment_texel(&mut e, t, n);
    }
    [e[0] / PI, e[1] / PI, e[2] / PI, 1.0]
}

/// Adds one texel's share of E(n) to `e` (see [`irradiance_texel`]).
fn add_moment_texel(e: &mut [f32; 3], t: &MomentTexel, n: [f32; 3]) {
    let d = t.dir_sin2;
    let cos_theta = n[0] * d[0] + n[1] * d[1] + n[2] * d[2];
    if cos_theta * cos_theta > d[3] {
        if cos_theta > 0.0 {
            for (c, m) in t.moments.iter().enumerate() {
                e[c] += (n[0] * m[0] + n[1] * m[1] + n[2] * m[2]).max(0.0);
            }
        }
    } else {
        let k = clipped_cap_cosine(cos_theta, d[3]);
        for (ec, lc) in e.iter_mut().zip(&t.radiance_omega) {
            *ec += k * lc;
        }
    }
}

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
/// near the horizon go texel by texel. Same terms as [`irradiance_texel`], summed in
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

/// E(n)/π for unit `n`, as [`irradiance_texel`] but the cold texels run by run (see
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
