//! SH projection (a CPU pass on both backends: 9 × 6 × 64² multiply-adds): the radiance
//! coefficients cₖ = Σ L(dᵢ) Yₖ(dᵢ) Ωᵢ over the texels of the cold ≤ 64² cube (exact solid
//! angles, which sum to 4π, so a constant environment projects exactly) plus the hot cells
//! at their mean directions (a lamp keeps its energy and direction), and the irradiance
//! coefficients Â_l/π · cₖ that evaluate to E/π directly.

use crate::environment::IrradianceSource;
use crate::environment::walk::texel_centres;
use crate::math::cubemap::cube_texel_solid_angle;
use crate::math::sh::{irradiance_band_factor, sh_band, sh_basis};

/// Largest mip edge projected.
pub const SH_SOURCE_SIZE: u32 = 64;

/// Radiance and E/π coefficients.
#[derive(Clone, Debug, PartialEq)]
pub struct ShCoefficients {
    /// Projection of the radiance.
    pub radiance: [[f32; 3]; 9],
    /// Irradiance / π (clamped-cosine convolution).
    pub irradiance: [[f32; 3]; 9],
}

/// Projects the irradiance source (the cold cube's texels and the hot cells at their exact
/// mean directions) onto bands 0–2.
pub fn sh_project(src: &IrradianceSource) -> ShCoefficients {
    let env = &src.cold;
    let m = (0..env.levels.len())
        .find(|&m| env.level_size(m) <= SH_SOURCE_SIZE)
        .unwrap_or(env.levels.len() - 1);
    let n = env.level_size(m);
    let mut acc = [[0.0f64; 3]; 9];
    for (face, i, j, d) in texel_centres(n) {
        let y = sh_basis(d);
        let w = cube_texel_solid_angle(i, j, n) as f64;
        let l = env.texel(m, face, i, j);
        for k in 0..9 {
            for c in 0..3 {
                acc[k][c] += l[c] as f64 * y[k] as f64 * w;
            }
        }
    }
    for cell in &src.hot {
        let d = cell.dir_sin2;
        let y = sh_basis([d[0], d[1], d[2]]);
        for (a, yk) in acc.iter_mut().zip(y) {
            for (v, lo) in a.iter_mut().zip(&cell.radiance_omega) {
                *v += *lo as f64 * yk as f64;
            }
        }
    }
    let radiance = acc.map(|c| c.map(|v| v as f32));
    let mut irradiance = radiance;
    for (k, c) in irradiance.iter_mut().enumerate() {
        let f = irradiance_band_factor(sh_band(k));
        c.iter_mut().for_each(|v| *v *= f);
    }
    ShCoefficients {
        radiance,
        irradiance,
    }
}
