//! SH projection (a CPU pass on both backends: 9 × 6 × 64² multiply-adds): the radiance
//! coefficients cₖ = Σ L(dᵢ) Yₖ(dᵢ) Ωᵢ over the texels of a ≤ 64² mip (exact solid angles,
//! which sum to 4π, so a constant environment projects exactly), and the irradiance
//! coefficients Â_l/π · cₖ that evaluate to E/π directly.

use crate::environment::Cubemap;
use crate::math::cubemap::{cube_texel_direction, cube_texel_solid_angle, FACES};
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

/// Projects `env` onto bands 0–2.
pub fn sh_project(env: &Cubemap) -> ShCoefficients {
    let m = (0..env.levels.len())
        .find(|&m| env.level_size(m) <= SH_SOURCE_SIZE)
        .unwrap_or(env.levels.len() - 1);
    let n = env.level_size(m);
    let mut acc = [[0.0f64; 3]; 9];
    for face in 0..FACES as u32 {
        for j in 0..n {
            for i in 0..n {
                let y = sh_basis(cube_texel_direction(face, i as i32, j as i32, n));
                let w = cube_texel_solid_angle(i, j, n) as f64;
                let l = env.texel(m, face, i, j);
                for k in 0..9 {
                    for c in 0..3 {
                        acc[k][c] += l[c] as f64 * y[k] as f64 * w;
                    }
                }
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
