//! The source of the irradiance cube and the SH: the environment split into its hot texels
//! (a sun, lamps), summed exactly at the source's own resolution with their true
//! directions, and the cold rest, converted to a small cube.
//!
//! A converted cube places a lamp's energy on its texel grid: a one-texel lamp of a 1k
//! equirect becomes a 2.8°-wide texel of a 32² cube, which moves its first moment and
//! blurs its terminator, and irradiance next to the terminator (normals nearly
//! perpendicular to the lamp) is then tens of percent off. So every source texel brighter
//! than [`HOT_FACTOR`] × the mean (at most [`MAX_HOT_TEXELS`], the most energetic) is taken
//! out of the source and kept as [`HOT_SUBCELLS`]² cells of equal solid angle, each with its
//! exact first moment ∫ L l dω (closed form over a latitude-longitude cell) and an
//! equivalent cap for the horizon-clipped case (see `cpu::irradiance`); the rest is
//! converted exactly to an [`IRRADIANCE_SOURCE_SIZE`]² cube.

use crate::environment::texels::{MomentTexel, IRRADIANCE_SOURCE_SIZE};
use crate::environment::{Cubemap, Equirect};
use crate::math::color::luminance;
use crate::math::cubemap::{cube_texel_direction, cube_texel_solid_angle, rotate_y};

/// A texel is "hot" when its radiance exceeds this multiple of the environment's mean.
pub const HOT_FACTOR: f32 = 16.0;
/// At most this many hot texels (the most energetic) are split off.
pub const MAX_HOT_TEXELS: usize = 512;

/// Indices of the texels whose luminance exceeds [`HOT_FACTOR`] × `mean`, at most
/// [`MAX_HOT_TEXELS`], most energetic first; `texels` yields (index, luminance, energy =
/// luminance × Ω). Equal energies keep index order, so the choice is deterministic. Shared
/// by the sampled levels' split ([`split_hot_texels`](crate::plan::sources::split_hot_texels)) and the irradiance source's
/// ([`crate::environment::hot`]).
pub fn hottest_texels(texels: impl Iterator<Item = (usize, f64, f64)>, mean: f64) -> Vec<usize> {
    let mut hot: Vec<(usize, f64)> = texels
        .filter(|&(_, y, _)| y > HOT_FACTOR as f64 * mean)
        .map(|(k, _, e)| (k, e))
        .collect();
    hot.sort_by(|a, b| b.1.total_cmp(&a.1).then(a.0.cmp(&b.0)));
    hot.truncate(MAX_HOT_TEXELS);
    hot.into_iter().map(|h| h.0).collect()
}

/// Cells per axis a hot equirect texel is split into (equal solid angle: uniform in φ and
/// in cos θ), so a cell straddling a normal's horizon is 1/4 of a source texel wide.
pub const HOT_SUBCELLS: u32 = 4;

/// What the irradiance and SH kernels read.
#[derive(Clone, Debug)]
pub struct IrradianceSource {
    /// The environment without its hot texels, at most [`IRRADIANCE_SOURCE_SIZE`]², with
    /// its solid-angle mip chain (the exact specular levels read its mips).
    pub cold: Cubemap,
    /// The hot texels' cells, in the output frame (rotation applied).
    pub hot: Vec<MomentTexel>,
}

impl IrradianceSource {
    /// The source for a cube environment (a cube input, or a test's cube): its level-0
    /// texels above the hot threshold, each one cell at its centre, and the rest reduced
    /// to at most [`IRRADIANCE_SOURCE_SIZE`]².
    pub fn from_cube(env: &Cubemap) -> Self {
        let n = env.size;
        let mut level0 = env.levels[0].clone();
        let lum = |t: &[f32; 4]| luminance([t[0], t[1], t[2]]);
        // Texel k is (face, j, i) = (k / n², k % n² / n, k % n); solid angles repeat per face.
        let face_omega: Vec<f32> = (0..n * n)
            .map(|k| cube_texel_solid_angle(k % n, k / n, n))
            .collect();
        let omega = |k: usize| face_omega[k % (n * n) as usize];
        let mean = (0..level0.len())
            .map(|k| lum(&level0[k]) as f64 * omega(k) as f64)
            .sum::<f64>()
            / (4.0 * std::f64::consts::PI);
        let hot = hottest_texels(
            (0..level0.len()).map(|k| {
                let y = lum(&level0[k]) as f64;
                (k, y, y * omega(k) as f64)
            }),
            mean,
        );
        let mut cells = Vec::with_capacity(hot.len());
        for k in hot {
            let (face, j, i) = (k as u32 / (n * n), (k as u32 % (n * n)) / n, k as u32 % n);
            let d = cube_texel_direction(face, i as i32, j as i32, n);
            let l = level0[k];
            cells.push(moment_cell(
                [l[0], l[1], l[2]],
                d.map(|v| v * omega(k)),
                omega(k),
            ));
            level0[k] = [0.0, 0.0, 0.0, 1.0];
        }
        IrradianceSource {
            cold: reduced_cold(Cubemap {
                size: n,
                levels: vec![level0],
            }),
            hot: cells,
        }
    }
}

/// The cold cube from its largest mip no bigger than [`IRRADIANCE_SOURCE_SIZE`]² down.
fn reduced_cold(mut cube: Cubemap) -> Cubemap {
    let full = Cubemap::full_mip_count(cube.size);
    crate::environment::mips::build_mips(&mut cube, full);
    let m = (0..cube.levels.len())
        .find(|&m| cube.level_size(m) <= IRRADIANCE_SOURCE_SIZE)
        .unwrap_or(cube.levels.len() - 1);
    Cubemap {
        size: cube.level_size(m),
        levels: cube.levels.split_off(m),
    }
}

/// A cell of radiance `l` with first moment ∫ l dω = `moment` and solid angle `omega`;
/// for the horizon-clipped cosine it acts as a uniform cap of the same solid angle,
/// 1 − cos σ = Ω/(2π), so sin²σ = u(2 − u) with u = Ω/(2π) (no cancellation for a tiny cell).
fn moment_cell(l: [f32; 3], moment: [f32; 3], omega: f32) -> MomentTexel {
    let len = (moment[0] * moment[0] + moment[1] * moment[1] + moment[2] * moment[2]).sqrt();
    let dir = moment.map(|v| v / len);
    let u = omega / (2.0 * std::f32::consts::PI);
    MomentTexel {
        moments: l.map(|c| [c * moment[0], c * moment[1], c * moment[2], 0.0]),
        dir_sin2: [dir[0], dir[1], dir[2], u * (2.0 - u)],
        radiance_omega: [l[0] * omega, l[1] * omega, l[2] * omega, omega],
    }
}

/// Takes the hot texels out of `level` (an equirect, set to 0 there) and returns their
/// cells, each direction rotated by `rotation` (cos, sin of the environment's rotation
/// about +Y, as the conversion applies it).
pub fn split_equirect(level: &mut Equirect, rotation: [f32; 2]) -> Vec<MomentTexel> {
    use std::f64::consts::PI;
    let (w, h) = (level.width as usize, level.height as usize);
    let row_omega: Vec<f64> = (0..h as u32).map(|y| level.row_solid_angle(y)).collect();
    let mut mean = 0.0f64;
    for (y, row) in level.data.chunks(w).enumerate() {
        let s: f64 = row.iter().map(|t| luminance(*t) as f64).sum();
        mean += s * row_omega[y];
    }
    mean /= 4.0 * PI;
    let hot = hottest_texels(
        (0..level.data.len()).map(|k| {
            let y = luminance(level.data[k]) as f64;
            (k, y, y * row_omega[k / w])
        }),
        mean,
    );
    let s = HOT_SUBCELLS as usize;
    let mut cells = Vec::with_capacity(hot.len() * s * s);
    for k in hot {
        let (x, y) = (k % w, k / w);
        let l = level.data[k];
        level.data[k] = [0.0; 3];
        let (ya, yb) = (
            (PI * y as f64 / h as f64).cos(),
            (PI * (y + 1) as f64 / h as f64).cos(),
        );
        for b in 0..s {
            // Equal solid angle: uniform in cos θ.
            let y0 = ya + (yb - ya) * b as f64 / s as f64;
            let y1 = ya + (yb - ya) * (b + 1) as f64 / s as f64;
            let (t0, t1) = (y0.clamp(-1.0, 1.0).acos(), y1.clamp(-1.0, 1.0).acos());
            // ∫ sin²θ dθ and ∫ cos θ sin θ dθ over [t0, t1].
            let s2 = 0.5 * (t1 - t0) - 0.25 * ((2.0 * t1).sin() - (2.0 * t0).sin());
            let cs = 0.5 * (t1.sin().powi(2) - t0.sin().powi(2));
            for a in 0..s {
                let p0 = 2.0 * PI * ((x as f64 + a as f64 / s as f64) / w as f64 - 0.5);
                let p1 = 2.0 * PI * ((x as f64 + (a + 1) as f64 / s as f64) / w as f64 - 0.5);
                let m = [
                    s2 * (p1.sin() - p0.sin()),
                    cs * (p1 - p0),
                    s2 * (p0.cos() - p1.cos()),
                ];
                let omega = (p1 - p0) * (y0 - y1);
                let m = rotate_y(m.map(|v| v as f32), rotation[0], rotation[1]);
                cells.push(moment_cell(l, m, omega as f32));
            }
        }
    }
    cells
}
