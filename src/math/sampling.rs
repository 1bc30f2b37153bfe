//! Sampling of the GGX half-vector distribution and low-discrepancy points. Mirror of
//! `shaders/common/sampling.wgsl` (same function names).
//!
//! The GGX half-vector density with respect to solid angle is
//! pdf(h) = D(h) (n·h), whose θ marginal has the CDF
//! u(θ) = sin²θ / (sin²θ + α² cos²θ) (Walter et al. 2007, eq. 35; Karis 2013).
//! The functions below work with q = 1 − u instead of u: for small α nearly all of the mass
//! sits at q ≪ 1 where u = 1 − q would round to 1 in f32, while q keeps full precision.

use crate::math::cubemap::normalize;

/// q(θ) = 1 − u(θ) = α² cos²θ / (sin²θ + α² cos²θ), from cos²θ and sin²θ.
/// It falls from 1 at θ = 0 to 0 at θ = π/2.
pub fn ggx_q_from_theta(cos2_theta: f32, sin2_theta: f32, alpha2: f32) -> f32 {
    let ac = alpha2 * cos2_theta;
    ac / (sin2_theta + ac)
}

/// Inverse of [`ggx_q_from_theta`]: (cos²θ, sin²θ) for a given q, both computed without
/// cancellation: cos²θ = q / (q + α² (1 − q)), sin²θ = α² (1 − q) / (q + α² (1 − q)).
pub fn ggx_theta_from_q(q: f32, alpha2: f32) -> (f32, f32) {
    let s = alpha2 * (1.0 - q);
    let den = q + s;
    (q / den, s / den)
}

/// ln(1 + x) to about 1e-7 relative, identical on every driver: for |x| < ½ the series
/// 2 atanh(s) = 2 (s + s³/3 + … + s¹⁵/15), s = x / (2 + x) (|s| ≤ ⅓, the first term left
/// out is below 2e-8), else ln(1 + x). Vulkan only bounds `log` to 2⁻²¹ absolute near 1,
/// which is no relative accuracy at all for the small arguments the Charlie mapping needs.
pub fn log1p_accurate(x: f32) -> f32 {
    if x.abs() >= 0.5 {
        return (1.0 + x).ln();
    }
    let s = x / (2.0 + x);
    let s2 = s * s;
    let mut p = 1.0 / 15.0;
    for k in [13.0f32, 11.0, 9.0, 7.0, 5.0, 3.0, 1.0] {
        p = p * s2 + 1.0 / k;
    }
    2.0 * s * p
}

/// eˣ − 1 to about 1e-7 relative, identical on every driver: for |x| < ½ the Taylor
/// series to x¹⁰/10! (the first term left out is below 3e-10 relative), else eˣ − 1.
pub fn expm1_accurate(x: f32) -> f32 {
    if x.abs() >= 0.5 {
        return x.exp() - 1.0;
    }
    // x (1 + x/2 (1 + x/3 (1 + … (1 + x/10)))) by Horner.
    let mut p = 1.0f32;
    for k in [10.0f32, 9.0, 8.0, 7.0, 6.0, 5.0, 4.0, 3.0, 2.0] {
        p = 1.0 + x / k * p;
    }
    x * p
}

/// The Charlie sheen distribution (Estevez & Kulla 2017, "Production Friendly Microfacet
/// Sheen BRDF"): D(h) = (2 + 1/α) sin^(1/α)θ / (2π), α = r². Its half-vector density
/// D(h)(n·h) has the θ marginal CDF u(θ) = sin^(2 + 1/α)θ = (1 − cos²θ)^e, e = 1 + 1/(2α);
/// q = 1 − u as for GGX, computed through log1p/expm1 so that θ near π/2 (where the
/// distribution puts its mass for small α) keeps its precision.
pub fn charlie_q_from_theta(cos2_theta: f32, alpha: f32) -> f32 {
    let e = 1.0 + 0.5 / alpha;
    -expm1_accurate(e * log1p_accurate(-cos2_theta))
}

/// Inverse of [`charlie_q_from_theta`]: (cos²θ, sin²θ) = (−expm1(ln(1 − q)/e), exp(ln(1 − q)/e)).
pub fn charlie_theta_from_q(q: f32, alpha: f32) -> (f32, f32) {
    let e = 1.0 + 0.5 / alpha;
    let l = log1p_accurate(-q) / e;
    (-expm1_accurate(l), l.exp())
}

/// Van der Corput radical inverse in base 2 (bit reversal), in [0, 1).
pub fn radical_inverse_vdc(bits: u32) -> f32 {
    bits.reverse_bits() as f32 * (1.0 / 4_294_967_296.0)
}

/// The i-th of n Hammersley points in [0, 1)²: (i/n, radical inverse of i).
pub fn hammersley(i: u32, n: u32) -> [f32; 2] {
    [i as f32 / n as f32, radical_inverse_vdc(i)]
}

/// GGX half-vector in tangent space (z = n) from a point of [0, 1)².
// pdf(h) = D(h) (n·h) with respect to solid angle (Walter et al. 2007, eq. 35-36).
pub fn importance_sample_ggx(xi: [f32; 2], alpha: f32) -> [f32; 3] {
    let phi = 2.0 * std::f32::consts::PI * xi[1];
    let (cos2, sin2) = ggx_theta_from_q(1.0 - xi[0], alpha * alpha);
    let (c, s) = (cos2.sqrt(), sin2.sqrt());
    [s * phi.cos(), s * phi.sin(), c]
}

/// An orthonormal tangent frame (t, b) around unit `n`: t = normalize(up × n) with up = +Z,
/// or +X where n is within 2.6° of ±Z; b = n × t.
pub fn tangent_frame(n: [f32; 3]) -> ([f32; 3], [f32; 3]) {
    let up = if n[2].abs() < 0.999 {
        [0.0, 0.0, 1.0]
    } else {
        [1.0, 0.0, 0.0]
    };
    let t = normalize(cross(up, n));
    (t, cross(n, t))
}

/// The cross product a × b.
pub fn cross(a: [f32; 3], b: [f32; 3]) -> [f32; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

#[cfg(any(test, feature = "internals"))]
/// A point of the unit disk from a point of [0, 1)²: (√u₁ cos 2πu₂, √u₁ sin 2πu₂), the
/// concentric-free polar map both sphere samplers below start from. The kernels read these
/// points from a table built here (GPU sin/cos are only accurate to ~1e-3 absolute).
pub fn unit_disk_point(xi: [f32; 2]) -> [f32; 2] {
    let r = xi[0].sqrt();
    let phi = 2.0 * std::f32::consts::PI * xi[1];
    [r * phi.cos(), r * phi.sin()]
}

/// Cosine-weighted direction in tangent space (z = n) from a unit-disk point: the disk
/// point lifted to the hemisphere (Malley's method).
// pdf(l) = (n·l) / π.
pub fn cosine_hemisphere_from_disk(p: [f32; 2]) -> [f32; 3] {
    [
        p[0],
        p[1],
        (1.0 - p[0] * p[0] - p[1] * p[1]).max(0.0).sqrt(),
    ]
}

/// A GGX visible normal for the view direction `v` (tangent space, z = n, v.z > 0) from a
/// unit-disk point `p` (Heitz 2018, "Sampling the GGX Distribution of Visible Normals",
/// listing 1, isotropic α): the disk is warped onto the projected hemisphere of the
/// stretched view, and the normal unstretched.
// pdf(h) = G1(v) max(0, v·h) D(h) / (n·v), G1 the exact Smith masking
// (`brdf::g1_smith_ggx`); for l = reflect(−v, h), pdf(l) = pdf(h) / (4 v·h).
pub fn sample_ggx_vndf(v: [f32; 3], alpha: f32, p: [f32; 2]) -> [f32; 3] {
    let vh = normalize([alpha * v[0], alpha * v[1], v[2]]);
    let lensq = vh[0] * vh[0] + vh[1] * vh[1];
    let t1 = if lensq > 0.0 {
        let inv = 1.0 / lensq.sqrt();
        [-vh[1] * inv, vh[0] * inv, 0.0]
    } else {
        [1.0, 0.0, 0.0]
    };
    let t2 = cross(vh, t1);
    let s = 0.5 * (1.0 + vh[2]);
    let d1 = p[0];
    let d2 = (1.0 - s) * (1.0 - d1 * d1).max(0.0).sqrt() + s * p[1];
    let dz = (1.0 - d1 * d1 - d2 * d2).max(0.0).sqrt();
    let nh = [0, 1, 2].map(|c| d1 * t1[c] + d2 * t2[c] + dz * vh[c]);
    normalize([alpha * nh[0], alpha * nh[1], nh[2].max(0.0)])
}

/// PCG hash of a 32-bit integer (Jarzynski & Olano 2020, "Hash Functions for GPU
/// Rendering"): decorrelates per-pixel sample sets with integer operations only, so both
/// backends draw the same points.
pub fn pcg_hash(x: u32) -> u32 {
    let state = x.wrapping_mul(747_796_405).wrapping_add(2_891_336_453);
    let word = ((state >> ((state >> 28) + 4)) ^ state).wrapping_mul(277_803_737);
    (word >> 22) ^ word
}

/// A 32-bit integer as a float in [0, 1) (its top 24 bits, exactly representable).
pub fn unit_float(bits: u32) -> f32 {
    (bits >> 8) as f32 * (1.0 / 16_777_216.0)
}

#[cfg(test)]
mod tests {
    #[test]
    fn log1p_and_expm1_are_accurate_across_the_switch() {
        for k in -2000..=2000 {
            let x = k as f64 / 2000.0 * 0.99; // (−0.99, 0.99)
            for x in [x, x * 1e-6] {
                let l = log1p_accurate(x as f32) as f64;
                let e = expm1_accurate(x as f32) as f64;
                let (tl, te) = ((x as f32 as f64).ln_1p(), (x as f32 as f64).exp_m1());
                assert!(
                    (l - tl).abs() <= 4e-7 * tl.abs().max(1e-30),
                    "log1p({x}) {l} vs {tl}"
                );
                assert!(
                    (e - te).abs() <= 4e-7 * te.abs().max(1e-30),
                    "expm1({x}) {e} vs {te}"
                );
            }
        }
    }
    use super::*;

    #[test]
    fn q_mapping_round_trips() {
        for &alpha in &[1e-3f32, 0.1, 0.5, 1.0] {
            let a2 = alpha * alpha;
            for &theta in &[0.01f32, 0.3, 0.8, 1.4] {
                let (c2, s2) = (theta.cos().powi(2), theta.sin().powi(2));
                let q = ggx_q_from_theta(c2, s2, a2);
                let (c2b, s2b) = ggx_theta_from_q(q, a2);
                assert!((c2 - c2b).abs() < 1e-5 && (s2 - s2b).abs() < 1e-5);
            }
        }
    }

    #[test]
    fn hammersley_is_stratified() {
        let n = 64;
        let mut seen = vec![false; n as usize];
        for i in 0..n {
            let p = hammersley(i, n);
            seen[(p[1] * n as f32) as usize] = true;
        }
        assert!(seen.iter().all(|&s| s));
    }
}
