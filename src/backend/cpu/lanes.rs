//! The CPU backend's exact sums: the texels of an exact level as a structure of arrays in
//! lanes, summed branch-free so that the loop vectorises (several times faster than the
//! texel-by-texel twins in [`crate::cpu::convolve_exact`], which the GPU mirrors).

use crate::environment::texels::SourceTexel;
use crate::math::brdf::alpha_from_roughness;

/// Lanes of [`ExactSource`]: eight f32, one AVX register or two SSE ones.
const LANES: usize = 8;

/// The texels of an exact sum as a structure of arrays in lanes of `LANES` (the last
/// lane group padded with texels of zero solid angle), so that the sum over them runs
/// branch-free and vectorises: [`ExactSource::prefilter`] computes
/// [`prefilter_exact_texel`](crate::cpu::convolve_exact::prefilter_exact_texel) several
/// times faster. The GPU kernel and the reference keep
/// the texel-by-texel loop.
pub struct ExactSource {
    /// Direction x, y, z and solid angle Ω, per lane group.
    dir_omega: Vec<[[f32; LANES]; 4]>,
    /// Radiance r, g, b and normaliser weight, per lane group.
    radiance: Vec<[[f32; LANES]; 4]>,
}

impl ExactSource {
    /// Packs `texels` into lanes.
    pub fn new(texels: &[SourceTexel]) -> Self {
        let groups = texels.len().div_ceil(LANES);
        let mut dir_omega = vec![[[0.0; LANES]; 4]; groups];
        let mut radiance = vec![[[0.0; LANES]; 4]; groups];
        for (k, t) in texels.iter().enumerate() {
            for c in 0..4 {
                dir_omega[k / LANES][c][k % LANES] = t.dir_omega[c];
                radiance[k / LANES][c][k % LANES] = t.radiance[c];
            }
        }
        ExactSource {
            dir_omega,
            radiance,
        }
    }

    /// [`prefilter_exact_texel`] over these texels. The same sum, with D(n·h) taken from
    /// (n·h)² = (1 + n·l)/2 directly and without its constant factor α²/π, which cancels
    /// in the ratio; texels below the horizon get weight 0 through max(n·l, 0) instead of
    /// a branch. Each lane keeps its own partial sums, added at the end.
    pub fn prefilter(&self, n: [f32; 3], roughness: f32) -> [f32; 4] {
        #[cfg(target_arch = "x86_64")]
        if std::is_x86_feature_detected!("avx") {
            // SAFETY: the CPU has AVX, checked just above.
            return unsafe { self.prefilter_avx(n, roughness) };
        }
        self.prefilter_lanes(n, roughness)
    }

    /// [`Self::prefilter_lanes`] compiled for AVX: one register per lane group instead of
    /// two SSE ones. Without FMA, so every lane does the same IEEE operations in the same
    /// order as the SSE build and the result is bit-identical on every x86-64 machine.
    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx")]
    fn prefilter_avx(&self, n: [f32; 3], roughness: f32) -> [f32; 4] {
        self.prefilter_lanes(n, roughness)
    }

    /// The lane sum itself (see [`Self::prefilter`]).
    #[inline(always)]
    fn prefilter_lanes(&self, n: [f32; 3], roughness: f32) -> [f32; 4] {
        let alpha = alpha_from_roughness(roughness);
        let k = alpha * alpha - 1.0;
        self.lobe_sum(n, |n_dot_l, omega| {
            // D(n·h) ∝ 1 / ((n·h)² (α² − 1) + 1)², (n·h)² = (1 + n·l) / 2
            let q = (0.5 + 0.5 * n_dot_l) * k + 1.0;
            n_dot_l * omega / (q * q)
        })
    }

    /// Σ L w / Σ w over these texels, `lobe(n·l, Ω)` giving a texel's weight w (the lobe
    /// times the solid angle) from its n·l, clamped at 0 (a texel below the horizon must
    /// get weight 0 from `lobe`), and its solid angle. Each lane keeps its own partial
    /// sums, added at the end; a `lobe` without calls or loops vectorises across lanes.
    #[inline(always)]
    pub fn lobe_sum(&self, n: [f32; 3], lobe: impl Fn(f32, f32) -> f32) -> [f32; 4] {
        let mut acc = [[0.0f32; LANES]; 4];
        for (d, rad) in self.dir_omega.iter().zip(&self.radiance) {
            for l in 0..LANES {
                let n_dot_l = (n[0] * d[0][l] + n[1] * d[1][l] + n[2] * d[2][l]).max(0.0);
                let w = lobe(n_dot_l, d[3][l]);
                for c in 0..4 {
                    acc[c][l] += w * rad[c][l];
                }
            }
        }
        let total = acc.map(|lanes| lanes.iter().sum::<f32>());
        [
            total[0] / total[3],
            total[1] / total[3],
            total[2] / total[3],
            1.0,
        ]
    }
}


/// How the power (1 − n·l)^(1/(2α)) of the Charlie weight is taken in the lane sum: by
/// repeated squaring where the exponent is 2, 4, 8 or 16 (the viewer's chain at r = 1/2
/// and 1/4: 2 and 8), by a square root where it is ½ (r = 1), all of which vectorise,
/// and by `powf` otherwise.
#[derive(Clone, Copy, Debug, PartialEq)]
enum LanePower {
    Squarings(u32),
    Sqrt,
    Powf(f32),
}

impl LanePower {
    fn new(exponent: f32) -> Self {
        match exponent {
            0.5 => LanePower::Sqrt,
            2.0 => LanePower::Squarings(1),
            4.0 => LanePower::Squarings(2),
            8.0 => LanePower::Squarings(3),
            16.0 => LanePower::Squarings(4),
            e => LanePower::Powf(e),
        }
    }
}

/// [`prefilter_charlie_texel`](crate::cpu::convolve_exact::prefilter_charlie_texel) over the lane-packed texels of `source`: the same sum in
/// [`ExactSource::lobe_sum`]'s branch-free form, the power taken as `LanePower` says
/// (the CPU backend's sum; the reference and the GPU kernel keep the texel-by-texel loop
/// and `pow`).
pub fn prefilter_charlie_lanes(source: &ExactSource, n: [f32; 3], roughness: f32) -> [f32; 4] {
    let power = LanePower::new(0.5 / alpha_from_roughness(roughness));
    #[cfg(target_arch = "x86_64")]
    if std::is_x86_feature_detected!("avx") {
        // SAFETY: the CPU has AVX, checked just above.
        return unsafe { charlie_sum_avx(source, n, power) };
    }
    charlie_sum(source, n, power)
}

/// [`charlie_sum`] compiled for AVX (without FMA, as [`ExactSource::prefilter`]).
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx")]
fn charlie_sum_avx(source: &ExactSource, n: [f32; 3], power: LanePower) -> [f32; 4] {
    charlie_sum(source, n, power)
}

/// x^(2^S) by S squarings.
#[inline(always)]
fn squared<const S: u32>(x: f32) -> f32 {
    (0..S).fold(x, |x, _| x * x)
}

#[inline(always)]
fn charlie_sum(source: &ExactSource, n: [f32; 3], power: LanePower) -> [f32; 4] {
    // The weight (1 − n·l)^e (n·l) Ω in the order charlie_prefilter_weight takes it; a
    // texel below the horizon has n·l clamped to 0 and so weight 0.
    let x = |n_dot_l: f32| (1.0 - n_dot_l).max(0.0);
    match power {
        LanePower::Squarings(1) => source.lobe_sum(n, |c, o| squared::<1>(x(c)) * c * o),
        LanePower::Squarings(2) => source.lobe_sum(n, |c, o| squared::<2>(x(c)) * c * o),
        LanePower::Squarings(3) => source.lobe_sum(n, |c, o| squared::<3>(x(c)) * c * o),
        LanePower::Squarings(_) => source.lobe_sum(n, |c, o| squared::<4>(x(c)) * c * o),
        LanePower::Sqrt => source.lobe_sum(n, |c, o| x(c).sqrt() * c * o),
        LanePower::Powf(e) => source.lobe_sum(n, |c, o| x(c).powf(e) * c * o),
    }
}


/// The lane sums' test source: 1533 texels (not a multiple of [`LANES`]) of a patterned
/// 16² cube with a bright spot.
#[cfg(test)]
fn lane_test_source() -> Vec<SourceTexel> {
    let mut cube = crate::environment::sample::patterned_chain(16, 5);
    cube.levels[0][1000][0] += 5000.0;
    let mut texels = crate::environment::texels::source_texels(&cube, 0);
    texels.truncate(texels.len() - 3);
    texels
}

/// The lane sums' test directions: 200 unit vectors spread over the sphere.
#[cfg(test)]
pub(crate) fn lane_test_normals() -> impl Iterator<Item = [f32; 3]> {
    (0..200).map(|k| {
        crate::math::cubemap::normalize([
            (k as f32 * 0.37).sin(),
            (k as f32 * 0.91).cos(),
            (k as f32 * 0.13).sin() - 0.2,
        ])
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::cpu::convolve_exact::{prefilter_charlie_texel, prefilter_exact_texel};

    /// The lane-packed sum gives the texel-by-texel reference's value at every roughness of
    /// a chain, within 1e-5 + 2e-7/α² relative: two sums of 1533 f32 terms taken in
    /// different orders (~√N·ε ≈ 5e-6), and D's denominator (n·h)²(α² − 1) + 1, which
    /// cancels to about α² near the lobe's peak, so the one rounding that separates
    /// (n·h)² = (1 + n·l)/2 from √ then squared is amplified by 1/α² (1.2e-4 at r = 0.2,
    /// 3e-6 at r = 0.5; the lane sum is the one with fewer roundings),
    /// on a source with a bright spot and a texel count that is not a multiple of the
    /// lane width.
    #[test]
    fn lane_sum_equals_the_reference() {
        let texels = lane_test_source();
        let lanes = ExactSource::new(&texels);
        for r in [0.2f32, 0.35, 0.5, 0.8, 1.0] {
            for n in lane_test_normals() {
                let want = prefilter_exact_texel(&texels, n, r);
                let got = lanes.prefilter(n, r);
                let alpha2 = alpha_from_roughness(r).powi(2);
                for c in 0..3 {
                    let rel = (got[c] - want[c]).abs() / want[c].abs().max(1e-6);
                    assert!(
                        rel <= 1e-5 + 2e-7 / alpha2,
                        "r {r} n {n:?} channel {c}: {} vs {}",
                        got[c],
                        want[c]
                    );
                }
            }
        }
    }

    /// The lane-packed sum gives the texel-by-texel reference's value at every roughness
    /// of the viewer's chain and between (each kind of power: squarings at r = 1/4 and 1/2,
    /// the square root at 1, powf at 0.3 and 3/4), within 2e-5 relative: two sums of 1533
    /// f32 terms in different orders (~√N·ε ≈ 5e-6), and x⁸ by three squarings against
    /// powf (≤ 7 roundings, 8e-7 per weight); on a source with a bright spot and a texel
    /// count that is not a multiple of the lane width.
    #[test]
    fn charlie_lane_sum_equals_the_reference() {
        let texels = lane_test_source();
        let lanes = ExactSource::new(&texels);
        for (r, power) in [
            (0.25f32, LanePower::Squarings(3)),
            (0.5, LanePower::Squarings(1)),
            (1.0, LanePower::Sqrt),
            (0.3, LanePower::Powf(0.5 / 0.09)),
            (0.75, LanePower::Powf(0.5 / 0.5625)),
        ] {
            let exponent = 0.5 / alpha_from_roughness(r);
            assert_eq!(LanePower::new(exponent), power, "r {r}");
            for n in lane_test_normals() {
                let want = prefilter_charlie_texel(&texels, n, r);
                let got = prefilter_charlie_lanes(&lanes, n, r);
                for c in 0..3 {
                    let rel = (got[c] - want[c]).abs() / want[c].abs().max(1e-6);
                    assert!(
                        rel <= 2e-5,
                        "r {r} n {n:?} channel {c}: {} vs {}",
                        got[c],
                        want[c]
                    );
                }
            }
        }
    }

}
