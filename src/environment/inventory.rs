//! What an environment holds, for `splitsum inspect`: its size, mean and peak radiance,
//! dynamic range and bad texels (the sun is [`crate::environment::sun`]'s).

use serde::Serialize;

use crate::environment::sun::grid::{luminance, Grid};
use crate::environment::Environment;

/// What an environment holds, for `splitsum inspect`.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Inventory {
    /// "equirect" or "cube".
    pub layout: &'static str,
    /// Width in texels (a cube's face edge).
    pub width: u32,
    /// Height in texels (a cube's face edge).
    pub height: u32,
    /// Texel count.
    pub texels: usize,
    /// Mean radiance over the sphere, per channel (Σ L Ω / 4π).
    pub mean: [f32; 3],
    /// Mean luminance over the sphere.
    pub mean_luminance: f32,
    /// The largest texel luminance.
    pub peak_luminance: f32,
    /// Peak luminance over the smallest positive texel luminance.
    pub dynamic_range: f32,
    /// Texels that are NaN or infinite in any channel.
    pub non_finite: usize,
    /// Texels with a negative channel.
    pub negative: usize,
}

/// Size, mean and peak radiance, dynamic range and bad texels of `env`.
pub fn inventory(env: &Environment) -> Inventory {
    let grid = Grid::of(env);
    let (mut sum, mut peak, mut low) = ([0.0f64; 3], 0.0f64, f64::INFINITY);
    let (mut non_finite, mut negative) = (0, 0);
    for k in 0..grid.len() {
        let l = grid.raw(k);
        if l.iter().any(|c| !c.is_finite()) {
            non_finite += 1;
            continue;
        }
        if l.iter().any(|&c| c < 0.0) {
            negative += 1;
        }
        let l = l.map(|c| f64::from(c.max(0.0)));
        let omega = grid.solid_angle(k);
        for c in 0..3 {
            sum[c] += l[c] * omega;
        }
        let y = luminance(l);
        peak = peak.max(y);
        if y > 0.0 {
            low = low.min(y);
        }
    }
    let mean = sum.map(|s| s / (4.0 * std::f64::consts::PI));
    let (layout, width, height) = match env {
        Environment::Equirect(e) => ("equirect", e.width, e.height),
        Environment::Cube(c) => ("cube", c.size, c.size),
    };
    Inventory {
        layout,
        width,
        height,
        texels: grid.len(),
        mean: mean.map(|m| m as f32),
        mean_luminance: luminance(mean) as f32,
        peak_luminance: peak as f32,
        dynamic_range: if low.is_finite() { (peak / low) as f32 } else { 0.0 },
        non_finite,
        negative,
    }
}

