//! Gauss-Legendre quadrature rules, computed once in f64 and shared by the CPU reference
//! and the GPU kernels (uploaded as a storage buffer), so the node tables exist in one place.
//!
//! Nodes are the roots of the Legendre polynomial P_n found by Newton's method from the
//! Tricomi initial guess; weights w_i = 2 / ((1 − x_i²) P_n'(x_i)²) (Abramowitz & Stegun
//! 25.4.29). Returned rules are mapped to [0, 1] with weights summing to 1.

use std::f64::consts::PI;

/// One quadrature node on [0, 1]: position and weight.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Node {
    /// Abscissa in (0, 1).
    pub x: f64,
    /// Weight; the weights of a rule sum to 1.
    pub w: f64,
}

/// Evaluates P_n(x) and P_{n−1}(x) by the three-term recurrence.
fn legendre_pair(n: usize, x: f64) -> (f64, f64) {
    let (mut p_prev, mut p) = (1.0, x);
    for k in 2..=n {
        let p_next = ((2 * k - 1) as f64 * x * p - (k - 1) as f64 * p_prev) / k as f64;
        p_prev = p;
        p = p_next;
    }
    (p, p_prev)
}

/// The n-point Gauss-Legendre rule on [0, 1], nodes in increasing order. Exact for
/// polynomials of degree ≤ 2n − 1.
pub fn gauss_legendre_unit(n: usize) -> Vec<Node> {
    assert!(n >= 1, "a quadrature rule needs at least one node");
    if n == 1 {
        return vec![Node { x: 0.5, w: 1.0 }];
    }
    let mut nodes = Vec::with_capacity(n);
    for i in 0..n {
        // Tricomi's approximation of the i-th root (descending in [-1, 1]).
        let mut z = (PI * (i as f64 + 0.75) / (n as f64 + 0.5)).cos();
        let mut dp = 1.0;
        for _ in 0..100 {
            let (p, p_prev) = legendre_pair(n, z);
            dp = n as f64 * (z * p - p_prev) / (z * z - 1.0);
            let dz = p / dp;
            z -= dz;
            if dz.abs() < 1e-16 {
                let (p, p_prev) = legendre_pair(n, z);
                dp = n as f64 * (z * p - p_prev) / (z * z - 1.0);
                break;
            }
        }
        let w = 2.0 / ((1.0 - z * z) * dp * dp);
        nodes.push(Node {
            x: 0.5 * (1.0 - z),
            w: 0.5 * w,
        });
    }
    nodes
}

/// An n-node rule on [0, 1] for integrands that are even about 0, f(x) = f(−x): the
/// non-negative half of the 2n-point Gauss-Legendre rule on [−1, 1]. Its nodes cluster only
/// at x = 1, and it is exact for even polynomials of degree ≤ 4n − 2.
pub fn gauss_legendre_even_half(n: usize) -> Vec<Node> {
    let full = gauss_legendre_unit(2 * n);
    // Nodes of the [0, 1] rule above 0.5 are (1 + z)/2 for z > 0; weights double.
    full.into_iter()
        .filter(|q| q.x > 0.5)
        .map(|q| Node {
            x: 2.0 * q.x - 1.0,
            w: 2.0 * q.w,
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn integrates_polynomials_exactly() {
        for n in [1usize, 2, 5, 8, 16, 32] {
            let rule = gauss_legendre_unit(n);
            assert!((rule.iter().map(|q| q.w).sum::<f64>() - 1.0).abs() < 1e-14);
            for degree in 0..(2 * n) {
                let approx: f64 = rule.iter().map(|q| q.w * q.x.powi(degree as i32)).sum();
                let exact = 1.0 / (degree as f64 + 1.0);
                assert!((approx - exact).abs() < 1e-13, "n={n} degree={degree}");
            }
            assert!(rule.windows(2).all(|p| p[0].x < p[1].x));
        }
    }

    #[test]
    fn even_half_rule_integrates_even_polynomials() {
        for n in [1usize, 4, 8] {
            let rule = gauss_legendre_even_half(n);
            assert_eq!(rule.len(), n);
            for k in 0..(2 * n) {
                let approx: f64 = rule.iter().map(|q| q.w * q.x.powi(2 * k as i32)).sum();
                assert!(
                    (approx - 1.0 / (2 * k + 1) as f64).abs() < 1e-13,
                    "n={n} k={k}"
                );
            }
        }
    }
}
