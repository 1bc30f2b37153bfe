//! Inverse trigonometry that is accurate to a few ULP and identical on CPU and GPU.
//! Mirror of `shaders/common/trig.wgsl` (same function names).
//!
//! Vulkan lets a driver's atan, acos and atan2 be off by up to 4096 ULP (lavapipe's are
//! off by ~1e-4 relative), enough to move an equirect lookup by a fraction of a texel or a
//! LUT integral past its 1e-4 budget, so the kernels use these polynomial versions.

use std::f32::consts::PI;

/// Minimax coefficients of atan(x) ≈ x + x·z·(c₀ + z(c₁ + z(c₂ + z c₃))), z = x², on
/// |x| ≤ tan(π/8) (Cephes `atanf`, S. Moshier). The WGSL twin `ATAN_C0..3` in
/// `shaders/common/trig.wgsl` must equal these (checked by tests/shaders.rs).
pub const ATAN_COEFFS: [f32; 4] = [
    -3.333_295e-1,
    1.997_771_1e-1,
    -1.387_768_6e-1,
    8.053_744_5e-2,
];

/// atan(x) to within a few ULP in f32, the same on CPU and GPU. Vulkan lets a driver's
/// atan be off by 4096 ULP, enough to shift an equirect lookup by a fraction of a texel,
/// so the kernels use this instead (Cephes `atanf` range reduction: x > tan(3π/8) uses
/// π/2 − atan(1/x), x > tan(π/8) uses π/4 + atan((x−1)/(x+1))).
pub fn atan_precise(x: f32) -> f32 {
    let a = x.abs();
    let (base, t) = if a > 2.414_213_6 {
        (0.5 * PI, -1.0 / a)
    } else if a > 0.414_213_57 {
        (0.25 * PI, (a - 1.0) / (a + 1.0))
    } else {
        (0.0, a)
    };
    let z = t * t;
    let [c0, c1, c2, c3] = ATAN_COEFFS;
    let r = base + t + t * z * (c0 + z * (c1 + z * (c2 + z * c3)));
    if x < 0.0 {
        -r
    } else {
        r
    }
}

/// atan2(y, x) in (−π, π] built on [`atan_precise`].
pub fn atan2_precise(y: f32, x: f32) -> f32 {
    if x > 0.0 {
        atan_precise(y / x)
    } else if x < 0.0 {
        let a = atan_precise(y / x);
        if y >= 0.0 {
            a + PI
        } else {
            a - PI
        }
    } else if y > 0.0 {
        0.5 * PI
    } else if y < 0.0 {
        -0.5 * PI
    } else {
        0.0
    }
}

/// acos(x) = atan2(√(1 − x²), x), x clamped to [−1, 1].
pub fn acos_precise(x: f32) -> f32 {
    let x = x.clamp(-1.0, 1.0);
    atan2_precise((1.0 - x * x).max(0.0).sqrt(), x)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn precise_atan_is_accurate() {
        let mut worst = 0.0f64;
        for i in -2000..=2000 {
            let x = i as f32 * 0.01;
            for y in [-3.0f32, -0.5, 0.0, 0.7, 5.0] {
                let e = (atan2_precise(y, x) as f64 - (y as f64).atan2(x as f64)).abs();
                worst = worst.max(e);
            }
        }
        assert!(worst < 5e-7, "{worst}");
    }

    #[test]
    fn precise_acos_is_accurate() {
        for i in -1000..=1000 {
            let x = i as f32 / 1000.0;
            assert!(
                (acos_precise(x) as f64 - (x as f64).acos()).abs() < 1e-6,
                "{x}"
            );
        }
    }
}
