//! Real spherical harmonics, bands 0–2 (9 coefficients), in the order (l, m) = (0,0),
//! (1,−1), (1,0), (1,1), (2,−2), (2,−1), (2,0), (2,1), (2,2), evaluated on world-space
//! direction components (DESIGN.md): Y00 = ½√(1/π), Y1m = √(3/(4π)) {y, z, x},
//! Y2,−2 = ½√(15/π) xy, Y2,−1 = ½√(15/π) yz, Y20 = ¼√(5/π)(3z² − 1), Y21 = ½√(15/π) xz,
//! Y22 = ¼√(15/π)(x² − y²) (Sloan, "Stupid Spherical Harmonics Tricks", 2008).
//! The clamped cosine's band factors Â = (π, 2π/3, π/4) (Ramamoorthi & Hanrahan 2001).

use std::f32::consts::PI;

/// The coefficient order, as written in `sh.json`.
pub const SH_ORDER: &str = "l0m0,l1m-1,l1m0,l1m1,l2m-2,l2m-1,l2m0,l2m1,l2m2";

/// The 9 basis functions at unit direction `d`.
pub fn sh_basis(d: [f32; 3]) -> [f32; 9] {
    let [x, y, z] = d;
    let c0 = 0.5 * (1.0 / PI).sqrt();
    let c1 = (3.0 / (4.0 * PI)).sqrt();
    let c2 = 0.5 * (15.0 / PI).sqrt();
    let c20 = 0.25 * (5.0 / PI).sqrt();
    let c22 = 0.25 * (15.0 / PI).sqrt();
    [
        c0,
        c1 * y,
        c1 * z,
        c1 * x,
        c2 * x * y,
        c2 * y * z,
        c20 * (3.0 * z * z - 1.0),
        c2 * x * z,
        c22 * (x * x - y * y),
    ]
}

/// Band of coefficient k.
pub fn sh_band(k: usize) -> usize {
    match k {
        0 => 0,
        1..=3 => 1,
        _ => 2,
    }
}

/// Â_l / π: the factor that turns radiance coefficients into E/π coefficients
/// (1, 2/3, 1/4 for bands 0, 1, 2).
pub fn irradiance_band_factor(band: usize) -> f32 {
    [PI, 2.0 * PI / 3.0, PI / 4.0][band] / PI
}

/// Evaluates 9 RGB coefficients at `d`.
pub fn sh_eval(coeffs: &[[f32; 3]; 9], d: [f32; 3]) -> [f32; 3] {
    let y = sh_basis(d);
    let mut out = [0.0f32; 3];
    for (k, c) in coeffs.iter().enumerate() {
        for ch in 0..3 {
            out[ch] += y[k] * c[ch];
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn constants_match_the_design() {
        let y = sh_basis([0.0, 1.0, 0.0]);
        assert!((y[0] - 0.282095).abs() < 1e-6);
        assert!((y[1] - 0.488603).abs() < 1e-6);
        let y = sh_basis([1.0, 0.0, 0.0]);
        assert!((y[8] - 0.546274).abs() < 1e-6);
        assert!((sh_basis([0.0, 0.0, 1.0])[6] - 0.630783).abs() < 1e-6);
    }
}
