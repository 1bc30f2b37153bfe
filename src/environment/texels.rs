//! The source texels the exact kernels read: a mip's texels summarised from the level-0
//! texels they cover, as the specular and sheen sums take them ([`SourceTexel`]: centroid
//! direction, solid angle, mean radiance) and as the irradiance sum takes them
//! ([`MomentTexel`]: first radiance moments and an equivalent cap). Shared by both
//! backends (the GPU uploads them as arrays of vec4).

use std::f32::consts::PI;

use crate::environment::Cubemap;
use crate::math::cubemap::{cube_texel_direction, cube_texel_solid_angle, FACES};

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
/// ([`clipped_cap_cosine`](crate::cpu::convolve_exact::clipped_cap_cosine)).
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

fn luminance(c: [f32; 4]) -> f32 {
    crate::math::color::luminance([c[0], c[1], c[2]])
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
        let lum = crate::math::color::luminance_f64;
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
