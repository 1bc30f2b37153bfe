//! What an environment holds, for `splitsum inspect`: its size, mean and peak radiance,
//! dynamic range (peak over a low percentile by solid angle), how much of the sphere is
//! black, and bad texels (the sun is [`crate::environment::sun`]'s).

use serde::Serialize;

use crate::environment::sun::grid::{luminance, Grid};
use crate::environment::Environment;

/// The share of the sphere's solid angle under [`Inventory::low_luminance`]: the darkest
/// 1 %. Weighting by solid angle makes the figure the sphere's, not the texel grid's (an
/// equirect's pole rows hold many texels and little solid angle); leaving the darkest 1 %
/// out keeps a few dead or clamped texels from setting the range, while a region that
/// lights a lobe (a window, a patch of sky) is larger than that.
pub const LOW_SHARE: f64 = 0.01;

/// What an environment holds, for `splitsum inspect`. Every figure is finite: the texels
/// that are not (`non_finite`) are left out of all the others.
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
    /// The percentile [`Inventory::low_luminance`] is taken at, in percent of the sphere's
    /// solid angle (1: `LOW_SHARE`).
    pub low_percentile: f32,
    /// The luminance under which the darkest `low_percentile` % of the sphere lies: the
    /// smallest texel luminance whose texels, with every darker one, cover that share of
    /// the solid angle. 0 when that share of the sphere is black.
    pub low_luminance: f32,
    /// `peak_luminance / low_luminance`: the range of the sphere without its darkest
    /// `low_percentile` %. 0 when `low_luminance` is 0 (at least that share of the sphere
    /// is black, or all of it: the ratio has no finite value; `black_fraction` says how
    /// much is black), so the figure is always a finite number.
    pub dynamic_range: f32,
    /// The share of the sphere's solid angle whose texels are exactly black (luminance 0,
    /// negative channels counted as 0), from 0 to 1.
    pub black_fraction: f32,
    /// Texels that are NaN or infinite in any channel.
    pub non_finite: usize,
    /// Texels with a negative channel.
    pub negative: usize,
}

/// The luminance at `share` of the total solid angle of `texels` (luminance, solid angle),
/// counted from the darkest: the smallest luminance whose texels and every darker one
/// cover at least that share; 0 when `texels` is empty.
fn low_percentile(texels: &mut [(f32, f32)], share: f64) -> f64 {
    let total: f64 = texels.iter().map(|&(_, omega)| f64::from(omega)).sum();
    texels.sort_unstable_by(|a, b| a.0.total_cmp(&b.0));
    let wanted = share * total;
    let mut covered = 0.0;
    for &(y, omega) in texels.iter() {
        covered += f64::from(omega);
        if covered >= wanted {
            return f64::from(y);
        }
    }
    texels.last().map_or(0.0, |&(y, _)| f64::from(y))
}

/// Size, mean and peak radiance, dynamic range, black share and bad texels of `env`.
pub fn inventory(env: &Environment) -> Inventory {
    let grid = Grid::of(env);
    let (mut sum, mut peak) = ([0.0f64; 3], 0.0f64);
    let (mut sphere, mut black) = (0.0f64, 0.0f64);
    let mut lit: Vec<(f32, f32)> = Vec::new();
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
        sphere += omega;
        if y > 0.0 {
            lit.push((y as f32, omega as f32));
        } else {
            black += omega;
        }
    }
    let mean = sum.map(|s| s / (4.0 * std::f64::consts::PI));
    // The black texels are the darkest; the lit ones are sorted only when they reach
    // below the percentile.
    let low = if sphere == 0.0 || black >= LOW_SHARE * sphere {
        0.0
    } else {
        low_percentile(&mut lit, (LOW_SHARE * sphere - black) / (sphere - black))
    };
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
        low_percentile: (100.0 * LOW_SHARE) as f32,
        low_luminance: low as f32,
        dynamic_range: if low > 0.0 { (peak / low) as f32 } else { 0.0 },
        black_fraction: if sphere > 0.0 {
            (black / sphere) as f32
        } else {
            0.0
        },
        non_finite,
        negative,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::environment::Equirect;

    /// A `W`×`H` equirect of `l` everywhere.
    fn uniform(l: f32) -> Equirect {
        const W: u32 = 64;
        const H: u32 = 32;
        Equirect {
            width: W,
            height: H,
            data: vec![[l; 3]; (W * H) as usize],
        }
    }

    fn of(e: Equirect) -> Inventory {
        inventory(&Environment::Equirect(e))
    }

    fn assert_finite(i: &Inventory) {
        for x in [
            i.peak_luminance,
            i.low_luminance,
            i.dynamic_range,
            i.black_fraction,
            i.mean_luminance,
        ] {
            assert!(x.is_finite(), "{i:?}");
        }
    }

    /// An all-black map: no range (0, not NaN), the whole sphere black.
    #[test]
    fn all_black() {
        let i = of(uniform(0.0));
        assert_finite(&i);
        assert_eq!(
            (i.peak_luminance, i.low_luminance, i.dynamic_range),
            (0.0, 0.0, 0.0)
        );
        assert!((i.black_fraction - 1.0).abs() < 1e-6, "{i:?}");
    }

    /// One lit texel on black: the peak is the lamp's, the low percentile is black, so the
    /// range is 0 and the black share is the sphere less that texel's solid angle.
    #[test]
    fn one_lit_texel_on_black() {
        const LAMP: f32 = 26432.0;
        let mut e = uniform(0.0);
        let (x, y) = (e.width / 2, e.height / 2);
        e.data[(y * e.width + x) as usize] = [LAMP; 3];
        let omega = e.row_solid_angle(y);
        let i = of(e);
        assert_finite(&i);
        assert!((i.peak_luminance - LAMP).abs() < 1e-2 * LAMP, "{i:?}");
        assert_eq!((i.low_luminance, i.dynamic_range), (0.0, 0.0));
        let want = 1.0 - omega / (4.0 * std::f64::consts::PI);
        assert!((f64::from(i.black_fraction) - want).abs() < 1e-6, "{i:?}");
    }

    /// A uniform map: the low percentile is the peak, range 1, nothing black.
    #[test]
    fn uniform_map_has_range_one() {
        let i = of(uniform(0.5));
        assert_finite(&i);
        assert!((i.dynamic_range - 1.0).abs() < 1e-6, "{i:?}");
        assert_eq!(i.black_fraction, 0.0);
        assert_eq!(i.low_percentile, 1.0);
    }

    /// The percentile weighs texels by solid angle: a dark pole row (little solid angle
    /// for its texels) does not set it, a dark band of more than 1 % of the sphere does.
    #[test]
    fn the_low_percentile_is_by_solid_angle() {
        const DARK: f32 = 0.01;
        let mut e = uniform(1.0);
        let w = e.width as usize;
        e.data[..w].fill([DARK; 3]);
        let pole = e.row_solid_angle(0) * e.width as f64 / (4.0 * std::f64::consts::PI);
        assert!(pole < LOW_SHARE, "the pole row is {pole} of the sphere");
        assert!((of(e.clone()).dynamic_range - 1.0).abs() < 1e-6);
        let equator = e.height as usize / 2;
        e.data[equator * w..(equator + 1) * w].fill([DARK; 3]);
        let band =
            e.row_solid_angle(equator as u32) * e.width as f64 / (4.0 * std::f64::consts::PI);
        assert!(
            pole + band > LOW_SHARE,
            "the rows are {} of the sphere",
            pole + band
        );
        let i = of(e);
        assert!((i.dynamic_range - 1.0 / DARK).abs() < 1e-2 / DARK, "{i:?}");
    }
}
