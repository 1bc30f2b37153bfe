//! The roughest specular level chosen for the lookup a shader makes (a CPU pass on both
//! backends, like the SH: a 96-unknown least-squares problem).
//!
//! At r = 1 (α = 1) the GGX distribution is constant, so the split-sum prefiltered
//! radiance with n = v is ∫ L (n·l)⁺ dω / ∫ (n·l)⁺ dω = E(n)/π: the irradiance. A chain's
//! last level is small (4² by default), and a shader reads it with bilinear filtering
//! between texel centres, which for a sun-lit sky is ~4 % off between them even when every
//! texel holds the exact value at its centre. The texels are therefore solved for instead:
//! the values whose seamless bilinear lookup (the lookup `cpu::cube_sample` makes, which is
//! linear in the texels) best matches, in least squares, the finer irradiance cube at its
//! texel centres. Normal equations WᵀW v = Wᵀ y in f64 (Cholesky), one right-hand side per
//! channel; negative solutions are clamped to 0.

use crate::environment::sample::sample_cube_lod;
use crate::environment::Cubemap;
use crate::math::cubemap::cube_texel_direction;

/// Refits the last level of `chain` (roughness 1) to `irradiance` (E/π) when the
/// irradiance cube is at least twice as fine; otherwise leaves it as it is. Returns whether
/// it refitted.
pub fn fit_roughest_level(chain: &mut Cubemap, irradiance: &Cubemap) -> bool {
    let last = chain.levels.len() - 1;
    let n = chain.level_size(last);
    if last == 0 || irradiance.size < 2 * n {
        return false;
    }
    match fit_level_for_lookup(n, irradiance) {
        Some(level) => {
            chain.levels[last] = level;
            true
        }
        None => false,
    }
}

/// The texels of an `n`² level whose seamless bilinear lookup best matches, in least
/// squares, level 0 of the finer `target` at its texel centres (see the module
/// documentation); None when the normal equations are singular.
pub fn fit_level_for_lookup(n: u32, target: &Cubemap) -> Option<Vec<[f32; 4]>> {
    let unknowns = Cubemap::level_len(n);
    let fine = target.size;
    let dirs: Vec<[f32; 3]> = (0..6 * fine * fine)
        .map(|k| {
            let (face, j, i) = (k / (fine * fine), (k % (fine * fine)) / fine, k % fine);
            cube_texel_direction(face, i as i32, j as i32, fine)
        })
        .collect();
    // W: the lookup's weight of texel t at each fine direction, found by probing (the
    // lookup is linear in the texel values).
    let mut probe = Cubemap {
        size: n,
        levels: vec![vec![[0.0f32; 4]; unknowns]],
    };
    let mut weights: Vec<Vec<(usize, f64)>> = vec![Vec::new(); dirs.len()];
    for t in 0..unknowns {
        probe.levels[0][t] = [1.0, 0.0, 0.0, 1.0];
        for (f, d) in dirs.iter().enumerate() {
            let w = sample_cube_lod(&probe, *d, 0.0)[0];
            if w != 0.0 {
                weights[f].push((t, w as f64));
            }
        }
        probe.levels[0][t] = [0.0, 0.0, 0.0, 1.0];
    }
    let mut a = vec![0.0f64; unknowns * unknowns];
    let mut b = vec![[0.0f64; 3]; unknowns];
    for (f, row) in weights.iter().enumerate() {
        let y = target.levels[0][f];
        for &(p, wp) in row {
            for &(q, wq) in row {
                a[p * unknowns + q] += wp * wq;
            }
            for c in 0..3 {
                b[p][c] += wp * y[c] as f64;
            }
        }
    }
    let l = cholesky(&a, unknowns)?;
    let mut level = vec![[0.0f32, 0.0, 0.0, 1.0]; unknowns];
    for c in 0..3 {
        let rhs: Vec<f64> = b.iter().map(|v| v[c]).collect();
        let v = cholesky_solve(&l, unknowns, &rhs);
        for (t, value) in v.into_iter().enumerate() {
            level[t][c] = value.max(0.0) as f32;
        }
    }
    Some(level)
}

/// Lower-triangular L with L Lᵀ = `a` (n×n, row-major); None if `a` is not positive
/// definite.
fn cholesky(a: &[f64], n: usize) -> Option<Vec<f64>> {
    let mut l = vec![0.0f64; n * n];
    for i in 0..n {
        for j in 0..=i {
            let mut s = a[i * n + j];
            for k in 0..j {
                s -= l[i * n + k] * l[j * n + k];
            }
            if i == j {
                if s <= 0.0 {
                    return None;
                }
                l[i * n + i] = s.sqrt();
            } else {
                l[i * n + j] = s / l[j * n + j];
            }
        }
    }
    Some(l)
}

fn cholesky_solve(l: &[f64], n: usize, b: &[f64]) -> Vec<f64> {
    let mut y = vec![0.0f64; n];
    for i in 0..n {
        let s: f64 = (0..i).map(|k| l[i * n + k] * y[k]).sum();
        y[i] = (b[i] - s) / l[i * n + i];
    }
    let mut x = vec![0.0f64; n];
    for i in (0..n).rev() {
        let s: f64 = (i + 1..n).map(|k| l[k * n + i] * x[k]).sum();
        x[i] = (y[i] - s) / l[i * n + i];
    }
    x
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_constant_is_fitted_as_the_constant() {
        let mut chain = Cubemap {
            size: 8,
            levels: vec![vec![[0.0; 4]; Cubemap::level_len(8)]],
        };
        crate::environment::mips::build_mips(&mut chain, 2);
        let irradiance = Cubemap {
            size: 16,
            levels: vec![vec![[2.0, 3.0, 4.0, 1.0]; Cubemap::level_len(16)]],
        };
        assert!(fit_roughest_level(&mut chain, &irradiance));
        for t in &chain.levels[1] {
            for (c, want) in [2.0, 3.0, 4.0].iter().enumerate() {
                assert!((t[c] - want).abs() < 1e-4, "{t:?}");
            }
        }
    }
}
