//! Sampling of the GGX half-vector distribution and low-discrepancy points. Mirror of
//! `shaders/common/sampling.wgsl` (same function names).
//!
//! The GGX half-vector density with respect to solid angle is
//! pdf(h) = D(h) (n·h), whose θ marginal has the CDF
//! u(θ) = sin²θ / (sin²θ + α² cos²θ) (Walter et al. 2007, eq. 35; Karis 2013).
//! The functions below work with q = 1 − u instead of u: for small α nearly all of the mass
//! sits at q ≪ 1 where u = 1 − q would round to 1 in f32, while q keeps full precision.

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

#[cfg(test)]
mod tests {
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
