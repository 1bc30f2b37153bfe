//! SH projection (a CPU pass on both backends: 9 × 6 × 64² multiply-adds): the radiance
//! coefficients cₖ = Σ L(dᵢ) Yₖ(dᵢ) Ωᵢ over the texels of the cold ≤ 64² cube (exact solid
//! angles, which sum to 4π, so a constant environment projects exactly) plus the hot cells
//! at their mean directions (a lamp keeps its energy and direction), and the irradiance
//! coefficients Â_l/π · cₖ that evaluate to E/π directly.
//!
//! An environment with a small bright source (a sun kept in the IBL, a one-texel lamp)
//! rings: the nine coefficients of its irradiance go negative opposite the source, and a
//! diffuse surface facing away would be lit negatively. The coefficients a target uses are
//! therefore windowed ([`crate::math::sh::sinc_window`]) with the weakest window, found by
//! bisection of its cutoff, that leaves E/π non-negative at [`RING_CHECK_DIRECTIONS`]
//! directions in every channel; the exact projection is kept beside them. Band 0 (the
//! mean) is never changed. ZH3 ([`crate::math::sh::Zh3`]) of the exact projection is
//! kept too, for renderers that store linear SH probes.

use crate::environment::IrradianceSource;
use crate::environment::walk::texel_centres;
use crate::math::cubemap::cube_texel_solid_angle;
use crate::math::sh::{
    irradiance_band_factor, sh_band, sh_basis, sh_eval, sh_windowed, zh3_from_sh9, Zh3,
};

/// Largest mip edge projected.
pub const SH_SOURCE_SIZE: u32 = 64;

/// Directions (a Fibonacci sphere) at which the windowed irradiance must be non-negative:
/// 0.025 rad apart, where a band-2 function's value moves by under 1e-3 of its range.
pub const RING_CHECK_DIRECTIONS: usize = 20_000;

/// The window's cutoff bisection: this many halvings of [1, [`MAX_CUTOFF`]].
const CUTOFF_STEPS: usize = 40;
/// The weakest window tried (band 2 × 0.994): no window at all is tried first.
const MAX_CUTOFF: f32 = 64.0;

/// Radiance and E/π coefficients, as a target uses them (deringed), and the exact
/// projection.
#[derive(Clone, Debug, PartialEq)]
pub struct ShCoefficients {
    /// Projection of the radiance, deringed (the window of `window_cutoff` applied).
    pub radiance: [[f32; 3]; 9],
    /// Irradiance / π (clamped-cosine convolution), deringed: non-negative everywhere.
    pub irradiance: [[f32; 3]; 9],
    /// The exact projection of the radiance.
    pub exact_radiance: [[f32; 3]; 9],
    /// Its irradiance / π, which may ring below 0.
    pub exact_irradiance: [[f32; 3]; 9],
    /// The cutoff, in bands, of the sinc⁴ deringing window applied to `irradiance`;
    /// `None` when the exact irradiance is non-negative already.
    pub window_cutoff: Option<f32>,
    /// ZH3 of the exact irradiance / π.
    pub zh3_irradiance: Zh3,
}

/// The irradiance / π coefficients of radiance coefficients.
fn irradiance_of(radiance: &[[f32; 3]; 9]) -> [[f32; 3]; 9] {
    let mut irradiance = *radiance;
    for (k, c) in irradiance.iter_mut().enumerate() {
        let f = irradiance_band_factor(sh_band(k));
        c.iter_mut().for_each(|v| *v *= f);
    }
    irradiance
}

/// `count` directions spread evenly over the sphere (a Fibonacci lattice).
pub fn fibonacci_directions(count: usize) -> Vec<[f32; 3]> {
    let golden = std::f64::consts::PI * (3.0 - 5f64.sqrt());
    (0..count)
        .map(|i| {
            let y = 1.0 - 2.0 * (i as f64 + 0.5) / count as f64;
            let r = (1.0 - y * y).max(0.0).sqrt();
            let phi = golden * i as f64;
            [(r * phi.cos()) as f32, y as f32, (r * phi.sin()) as f32]
        })
        .collect()
}

/// Whether E/π of `irradiance` is non-negative at every one of `directions`.
fn non_negative(irradiance: &[[f32; 3]; 9], directions: &[[f32; 3]]) -> bool {
    directions
        .iter()
        .all(|&d| sh_eval(irradiance, d).iter().all(|&e| e >= 0.0))
}

/// The cutoff of the weakest window that leaves `radiance`'s irradiance non-negative, or
/// `None` when it is already.
pub fn dering_cutoff(radiance: &[[f32; 3]; 9]) -> Option<f32> {
    let directions = fibonacci_directions(RING_CHECK_DIRECTIONS);
    let ok = |cutoff: f32| non_negative(&irradiance_of(&sh_windowed(radiance, cutoff)), &directions);
    if non_negative(&irradiance_of(radiance), &directions) {
        return None;
    }
    // At a cutoff of 1 only band 0 is left, a non-negative constant for any non-negative
    // radiance.
    let (mut good, mut bad) = (1.0f32, MAX_CUTOFF);
    if ok(bad) {
        return Some(bad);
    }
    for _ in 0..CUTOFF_STEPS {
        let mid = 0.5 * (good + bad);
        if ok(mid) {
            good = mid;
        } else {
            bad = mid;
        }
    }
    Some(good)
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
    let exact_radiance = acc.map(|c| c.map(|v| v as f32));
    let exact_irradiance = irradiance_of(&exact_radiance);
    let window_cutoff = dering_cutoff(&exact_radiance);
    let radiance = match window_cutoff {
        Some(cutoff) => sh_windowed(&exact_radiance, cutoff),
        None => exact_radiance,
    };
    ShCoefficients {
        radiance,
        irradiance: irradiance_of(&radiance),
        exact_radiance,
        exact_irradiance,
        window_cutoff,
        zh3_irradiance: zh3_from_sh9(&exact_irradiance),
    }
}
