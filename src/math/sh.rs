//! Real spherical harmonics, bands 0–2 (9 coefficients), in the order (l, m) = (0,0),
//! (1,−1), (1,0), (1,1), (2,−2), (2,−1), (2,0), (2,1), (2,2), evaluated on world-space
//! direction components (docs/conventions.md, "Spherical harmonics"): Y00 = ½√(1/π), Y1m = √(3/(4π)) {y, z, x},
//! Y2,−2 = ½√(15/π) xy, Y2,−1 = ½√(15/π) yz, Y20 = ¼√(5/π)(3z² − 1), Y21 = ½√(15/π) xz,
//! Y22 = ¼√(15/π)(x² − y²) (Sloan, "Stupid Spherical Harmonics Tricks", 2008).
//! The clamped cosine's band factors Â = (π, 2π/3, π/4) (Ramamoorthi & Hanrahan 2001).

use std::f32::consts::PI;

/// The coefficient order, as written in `sh.json`.
pub const SH_ORDER: &str = "l0m0,l1m-1,l1m0,l1m1,l2m-2,l2m-1,l2m0,l2m1,l2m2";

/// The constant factor of each basis function: Y_k(d) = K_k · P_k(d) with the monomials
/// P = (1, y, z, x, xy, yz, 3z² − 1, xz, x² − y²).
pub fn sh_constants() -> [f32; 9] {
    let c0 = 0.5 * (1.0 / PI).sqrt();
    let c1 = (3.0 / (4.0 * PI)).sqrt();
    let c2 = 0.5 * (15.0 / PI).sqrt();
    let c20 = 0.25 * (5.0 / PI).sqrt();
    let c22 = 0.25 * (15.0 / PI).sqrt();
    [c0, c1, c1, c1, c2, c2, c20, c2, c22]
}

/// The 9 basis functions at unit direction `d`.
pub fn sh_basis(d: [f32; 3]) -> [f32; 9] {
    let [x, y, z] = d;
    let k = sh_constants();
    [
        k[0],
        k[1] * y,
        k[2] * z,
        k[3] * x,
        k[4] * x * y,
        k[5] * y * z,
        k[6] * (3.0 * z * z - 1.0),
        k[7] * x * z,
        k[8] * (x * x - y * y),
    ]
}

/// Coefficients with the basis constants folded in (c_k · K_k), so that the expansion is
/// the plain polynomial Σ c'_k P_k(d): Filament's "pre-scaled" SH (cmgen `--sh-shader`,
/// the `iblSH` its `Irradiance_SphericalHarmonics` evaluates).
pub fn sh_prescaled(coeffs: &[[f32; 3]; 9]) -> [[f32; 3]; 9] {
    let k = sh_constants();
    std::array::from_fn(|i| coeffs[i].map(|c| c * k[i]))
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

/// The coefficients of f ∘ R⁻¹ from those of f, for an orthogonal `r` (rows: R·d): the
/// same function seen in a frame whose directions are R·d, so that
/// `sh_eval(&sh_rotated(c, r), R·d) = sh_eval(c, d)`. Band 1 is a linear form aᵀd and
/// band 2 a traceless quadratic form dᵀQd; they become (Ra)ᵀd and dᵀ(RQRᵀ)d, band 0 is
/// unchanged. Exact (up to rounding) for any rotation or mirror.
pub fn sh_rotated(coeffs: &[[f32; 3]; 9], r: [[f32; 3]; 3]) -> [[f32; 3]; 9] {
    let constants = sh_constants().map(f64::from);
    let (c1, c2, c20, c22) = (constants[1], constants[4], constants[6], constants[8]);
    let r = r.map(|row| row.map(f64::from));
    let mut out = [[0.0f32; 3]; 9];
    for ch in 0..3 {
        let k = |i: usize| f64::from(coeffs[i][ch]);
        out[0][ch] = coeffs[0][ch];
        // Band 1: c1 (k11 x + k1-1 y + k10 z).
        let a = [c1 * k(3), c1 * k(1), c1 * k(2)];
        let ra: [f64; 3] = std::array::from_fn(|i| (0..3).map(|j| r[i][j] * a[j]).sum());
        out[3][ch] = (ra[0] / c1) as f32;
        out[1][ch] = (ra[1] / c1) as f32;
        out[2][ch] = (ra[2] / c1) as f32;
        // Band 2 on the unit sphere: c20 (3z² − 1) = c20 (2z² − x² − y²).
        let q = [
            [-c20 * k(6) + c22 * k(8), 0.5 * c2 * k(4), 0.5 * c2 * k(7)],
            [0.5 * c2 * k(4), -c20 * k(6) - c22 * k(8), 0.5 * c2 * k(5)],
            [0.5 * c2 * k(7), 0.5 * c2 * k(5), 2.0 * c20 * k(6)],
        ];
        let rq: [[f64; 3]; 3] = std::array::from_fn(|i| {
            std::array::from_fn(|j| (0..3).map(|l| r[i][l] * q[l][j]).sum())
        });
        let p: [[f64; 3]; 3] = std::array::from_fn(|i| {
            std::array::from_fn(|j| (0..3).map(|l| rq[i][l] * r[j][l]).sum())
        });
        out[4][ch] = (2.0 * p[0][1] / c2) as f32;
        out[5][ch] = (2.0 * p[1][2] / c2) as f32;
        out[6][ch] = (p[2][2] / (2.0 * c20)) as f32;
        out[7][ch] = (2.0 * p[0][2] / c2) as f32;
        out[8][ch] = ((p[0][0] - p[1][1]) / (2.0 * c22)) as f32;
    }
    out
}

/// The deringing window of band `band` at `cutoff` (in bands): sinc(π l / w)⁴ below the
/// cutoff, 0 from it on, 1 for band 0 (Sloan, "Deringing Spherical Harmonics", 2017;
/// the window Filament's `CubemapSH::windowSH` applies). The smaller the cutoff, the
/// stronger the window; band 0, and with it the mean, is never changed.
pub fn sinc_window(band: usize, cutoff: f32) -> f32 {
    if band == 0 {
        return 1.0;
    }
    if band as f32 >= cutoff {
        return 0.0;
    }
    let x = PI * band as f32 / cutoff;
    (x.sin() / x).powi(4)
}

/// `coeffs` with [`sinc_window`] at `cutoff` applied band by band.
pub fn sh_windowed(coeffs: &[[f32; 3]; 9], cutoff: f32) -> [[f32; 3]; 9] {
    std::array::from_fn(|k| coeffs[k].map(|c| c * sinc_window(sh_band(k), cutoff)))
}

/// ZH3 (Roughton, Bastard, Salvi & Ahmed, "ZH3: Quadratic Zonal Harmonics", i3D 2024):
/// linear SH (bands 0 and 1, per channel) plus one zonal harmonic of band 2 per channel,
/// all about one axis: the direction of the luminance's band-1 vector. 15 numbers where
/// SH9 has 27; for irradiance it recovers most of what band 2 adds over linear SH.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub struct Zh3 {
    /// The zonal axis (unit; +Y when the luminance has no band 1).
    pub axis: [f32; 3],
    /// Bands 0 and 1 as in SH9's order (l0m0, l1m-1, l1m0, l1m1), per channel.
    pub linear: [[f32; 3]; 4],
    /// The zonal coefficient z per channel: the band-2 part is z · Y20 about the axis,
    /// ¼√(5/π) (3 (axis·d)² − 1) z.
    pub zonal: [f32; 3],
}

/// The ZH3 of 9 SH coefficients: the linear bands kept, band 2 projected onto the zonal
/// harmonic about the luminance axis, z = √(4π/5) Σₘ f₂ₘ Y₂ₘ(axis) (the addition theorem:
/// the rotated zonal harmonic's coefficients are √(4π/5) Y₂ₘ(axis)).
pub fn zh3_from_sh9(coeffs: &[[f32; 3]; 9]) -> Zh3 {
    let lum = crate::math::color::luminance;
    // Band 1 is c1 (k11 x + k1-1 y + k10 z): the luminance's vector is (k11, k1-1, k10).
    let v = [lum(coeffs[3]), lum(coeffs[1]), lum(coeffs[2])];
    let len = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
    let axis = if len > 0.0 {
        v.map(|c| c / len)
    } else {
        [0.0, 1.0, 0.0]
    };
    let y = sh_basis(axis);
    let scale = (4.0 * PI / 5.0).sqrt();
    let zonal = std::array::from_fn(|ch| scale * (4..9).map(|k| coeffs[k][ch] * y[k]).sum::<f32>());
    Zh3 {
        axis,
        linear: [coeffs[0], coeffs[1], coeffs[2], coeffs[3]],
        zonal,
    }
}

#[cfg(any(test, feature = "internals"))]
/// Evaluates a [`Zh3`] at unit direction `d`.
pub fn zh3_eval(zh3: &Zh3, d: [f32; 3]) -> [f32; 3] {
    let y = sh_basis(d);
    let k20 = sh_constants()[6];
    let c = zh3.axis[0] * d[0] + zh3.axis[1] * d[1] + zh3.axis[2] * d[2];
    let zonal = k20 * (3.0 * c * c - 1.0);
    std::array::from_fn(|ch| {
        (0..4).map(|k| zh3.linear[k][ch] * y[k]).sum::<f32>() + zh3.zonal[ch] * zonal
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn zh3_of_a_zonal_function_about_the_luminance_axis_is_exact() {
        // A grey function 1 + 0.5 (a·d) + 0.3 Y20 about a = (0.48, 0.6, -0.64): its SH9
        // projection, then ZH3, evaluates to the same values.
        let a = [0.48f32, 0.6, -0.64];
        let y = sh_basis(a);
        let scale = (4.0 * PI / 5.0).sqrt();
        let grey = |k: usize| match k {
            0 => 1.0,
            1 => 0.5 * a[1],
            2 => 0.5 * a[2],
            3 => 0.5 * a[0],
            _ => 0.3 * scale * y[k],
        };
        let c: [[f32; 3]; 9] = std::array::from_fn(|k| [grey(k); 3]);
        let z = zh3_from_sh9(&c);
        for (i, v) in a.iter().enumerate() {
            assert!((z.axis[i] - v).abs() < 1e-5);
        }
        for d in [[0.0f32, 1.0, 0.0], [0.6, 0.0, 0.8], [-0.36, -0.48, 0.8], a] {
            let (e, g) = (sh_eval(&c, d), zh3_eval(&z, d));
            assert!((e[0] - g[0]).abs() < 1e-5, "{d:?}: {e:?} vs {g:?}");
        }
    }

    #[test]
    fn the_window_keeps_band_0_and_goes_to_zero_at_its_cutoff() {
        assert_eq!(sinc_window(0, 1.5), 1.0);
        assert_eq!(sinc_window(2, 2.0), 0.0);
        assert!(sinc_window(1, 1e6) > 0.999999);
        assert!(sinc_window(2, 3.0) < sinc_window(1, 3.0));
    }

    #[test]
    fn constants_match_the_real_sh_basis() {
        let y = sh_basis([0.0, 1.0, 0.0]);
        assert!((y[0] - 0.282095).abs() < 1e-6);
        assert!((y[1] - 0.488603).abs() < 1e-6);
        let y = sh_basis([1.0, 0.0, 0.0]);
        assert!((y[8] - 0.546274).abs() < 1e-6);
        assert!((sh_basis([0.0, 0.0, 1.0])[6] - 0.630783).abs() < 1e-6);
    }

    #[test]
    fn a_rotated_expansion_takes_the_same_values_at_the_rotated_directions() {
        // Arbitrary coefficients; a quarter turn about +Y, a mirror and a general rotation.
        let c: [[f32; 3]; 9] =
            std::array::from_fn(|i| [i as f32 * 0.3 - 1.0, (i * i) as f32 * 0.1, 0.7 - i as f32]);
        let (ca, sa) = (0.6f32, 0.8f32);
        let general = [[ca, 0.0, sa], [0.0, 1.0, 0.0], [-sa, 0.0, ca]];
        let turns = [
            crate::math::cubemap::AxisMap {
                axis: [2, 1, 0],
                sign: [-1, 1, 1],
            }
            .matrix(),
            crate::math::cubemap::AxisMap::mirror(0).matrix(),
            general,
        ];
        for r in turns {
            let rc = sh_rotated(&c, r);
            for d in [
                [0.6f32, 0.0, 0.8],
                [0.0, 1.0, 0.0],
                [0.48, 0.6, -0.64],
                [-0.36, -0.48, 0.8],
            ] {
                let rd: [f32; 3] = std::array::from_fn(|i| (0..3).map(|j| r[i][j] * d[j]).sum());
                let (a, b) = (sh_eval(&c, d), sh_eval(&rc, rd));
                for ch in 0..3 {
                    assert!((a[ch] - b[ch]).abs() < 1e-5, "{r:?} {d:?}: {a:?} vs {b:?}");
                }
            }
        }
    }
}
