//! The recipe's taps at grazing views ([`crate::math::lookup::SpecularLookup::Filtered`]), the
//! plan of `filtered_prefiltered` in `cpu::preview_split_sum` and shaders/common/filtered.wgsl:
//! filtered importance sampling of the prefiltered chain (Křivánek and Colbert, "Real-time
//! Shading with Filtered Importance Sampling", EGSR 2008; Colbert and Křivánek, GPU Gems 3
//! ch. 20, 2007) with [`FILTERED_TAPS`] samples of GGX's visible normals (Heitz, "Sampling
//! the GGX Distribution of Visible Normals", JCGT 2018) in the plane of incidence, where the
//! chain's own lookup is furthest off: at grazing views, where the true lobe reaches past R
//! toward the horizon, is masked there, and a level prefiltered with v = n cannot follow it.
//!
//! Per shaded point of normal n, view v, α = r²: for the fixed set of [`FILTERED_TAPS`]
//! points of Heitz's disc on its axis in the plane of incidence, at the midpoints of the
//! four quarters of the disc's area ([`filtered_point`], the same in every pixel: no
//! noise), h drawn from the visible normals, l = reflect(−v, h); each l with n·l > 0 reads
//! the chain at the level whose lobe covers the share of the sphere
//! Ω_s = 1 / ([`FILTERED_LEVEL_TAPS`] pdf(l)), pdf(l) = G1(v) D(h) / (4 n·v)
//! ([`sample_lod`]), and is weighted by the BRDF over its pdf, F(v·h) G(l) G(v) / G1(v)
//! (Schlick-GGX G of the recipe's BRDF, the exact Smith G1 of the sampler). The taps lie
//! along the lobe's long axis, which a grazing view stretches along the plane of incidence
//! and narrows across it; each level, round, covers the lobe across. The normalised sum
//! Σ w L / Σ w (per channel) stands for the prefiltered radiance: the LUT's F0 A + B scales
//! it as it scales the chain's lookup, so a uniform environment is exact whatever the taps.
//!
//! The recipe blends to it by [`filtered_share`]: fully below n·v = 0.4 and between
//! r = 0.2 and 0.6, not at all above n·v = 0.6, above r = 0.9 or at a mirror, where the chain's lookup with its blend toward E/π
//! is the better one (a few taps of a wide lobe are worse than the chain at r = 1). A
//! study of 50 estimators on four HDRIs, then of the taps' layout in the preview itself,
//! chose these (docs/accuracy.md, "The residual's lookup"): four taps in the plane of
//! incidence, each at the level of twice a quarter's share, less half a level; the fixed
//! set; the normalised sum.

use crate::plan::chain::MipRoughness;

/// Samples of the lobe at a point where they are used in full.
pub const FILTERED_TAPS: u32 = 4;

/// The sample count a tap's share of the sphere counts ([`sample_lod`]): each of the
/// [`FILTERED_TAPS`] taps in a line stands for a strip across the lobe, wider than a
/// quarter of it, so its level is that of half the lobe (measured best of 1, 2 and 4: 4
/// reads too sharp a level across the lobe, 1 blurs the taps into one).
pub const FILTERED_LEVEL_TAPS: u32 = 2;

/// The positions of the taps on the disc's axis in the plane of incidence, ±these: where
/// the disc's area ([`disc_marginal_cdf`]) reaches 1/8 and 3/8 from either end, the
/// midpoints of its quarters (`plan::filtered` tests check it).
pub const FILTERED_PLANE_POINTS: [f32; 2] = [0.197_643_95, 0.634_704_6];

/// n·v below which the taps are used in full, and above which not at
/// all (linear between).
pub const FILTERED_N_DOT_V: [f32; 2] = [0.4, 0.6];

/// Roughness below which the taps are used in full, and above which not at all.
pub const FILTERED_ROUGHNESS: [f32; 2] = [0.6, 0.9];

/// Roughness from which the taps are used in full, fading in from none at a mirror (r = 0),
/// whose lobe is the chain's level 0 along R, which the chain's read gives exactly (taps
/// of a lobe a texel wide would only blur it): under the first r the study measured, 0.25.
pub const FILTERED_FADE_IN_ROUGHNESS: f32 = 0.2;

/// Levels added to each sample's level ([`sample_lod`]): the sharpest of −3 … +2 in the
/// study (+0 costs 0.5–1.5 points).
pub const FILTERED_LOD_BIAS: f32 = -0.5;

/// The smallest α the taps sample at: a mirror's lobe is the chain's level 0
/// along R, which the recipe's lookup already reads exactly.
pub const MIN_FILTERED_ALPHA: f32 = 1e-3;

/// How much of the taps' radiance a point of `n_dot_v` and roughness `r` takes, in [0, 1].
pub fn filtered_share(n_dot_v: f32, r: f32) -> f32 {
    let ramp = |x: f32, [lo, hi]: [f32; 2]| ((hi - x) / (hi - lo)).clamp(0.0, 1.0);
    ramp(n_dot_v, FILTERED_N_DOT_V)
        * ramp(r, FILTERED_ROUGHNESS)
        * (r / FILTERED_FADE_IN_ROUGHNESS).clamp(0.0, 1.0)
}

/// The chain's level for a sample of density `pdf` (per steradian) among `taps`: the level
/// whose GGX lobe's solid angle 4π α² is the sample's share Ω_s = 1 / (taps pdf), at
/// α_eq = √(Ω_s / 4π), read as the chain maps roughness √α_eq (`mapping` over `levels`),
/// plus [`FILTERED_LOD_BIAS`], within the chain.
pub fn sample_lod(mapping: MipRoughness, levels: u32, pdf: f32, taps: u32) -> f32 {
    let omega = 1.0 / (taps as f32 * pdf);
    let alpha = (omega / (4.0 * std::f32::consts::PI)).sqrt().min(1.0);
    let lod = mapping.lod(alpha.sqrt(), levels) + FILTERED_LOD_BIAS;
    lod.clamp(0.0, levels.saturating_sub(1) as f32)
}

/// The `i`-th of [`FILTERED_TAPS`] points of the fixed set on Heitz's unit disc
/// (`math::sampling::sample_ggx_vndf`'s p): on its second axis, the one in the plane of
/// incidence, at −outer, −inner, inner, outer ([`FILTERED_PLANE_POINTS`]).
pub fn filtered_point(i: u32) -> [f32; 2] {
    let y = if i == 0 || i + 1 == FILTERED_TAPS {
        FILTERED_PLANE_POINTS[1]
    } else {
        FILTERED_PLANE_POINTS[0]
    };
    [0.0, if i < FILTERED_TAPS / 2 { -y } else { y }]
}

/// The share of the unit disc's area at second coordinate below `y` ∈ [−1, 1]:
/// ½ + (y √(1 − y²) + asin y) / π.
pub fn disc_marginal_cdf(y: f64) -> f64 {
    0.5 + (y * (1.0 - y * y).max(0.0).sqrt() + y.clamp(-1.0, 1.0).asin()) / std::f64::consts::PI
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The share is whole at grazing views of glossy points and nothing elsewhere.
    #[test]
    fn the_share_ramps() {
        assert_eq!(filtered_share(0.2, 0.5), 1.0);
        assert_eq!(filtered_share(0.7, 0.5), 0.0);
        assert_eq!(filtered_share(0.2, 1.0), 0.0);
        assert!((filtered_share(0.5, 0.5) - 0.5).abs() < 1e-6);
        assert!((filtered_share(0.2, 0.75) - 0.5).abs() < 1e-6);
        assert_eq!(filtered_share(0.2, 0.0), 0.0);
        assert!((filtered_share(0.2, 0.1) - 0.5).abs() < 1e-6);
    }

    /// The taps sit at the midpoints of the disc's four quarters, two each side of its
    /// centre, in the order of the axis (f32 rounding of the f64 quantiles: 1e-6).
    #[test]
    fn the_taps_halve_the_quarters_of_the_disc() {
        let ys: Vec<f32> = (0..FILTERED_TAPS).map(|i| filtered_point(i)[1]).collect();
        for (i, y) in ys.iter().enumerate() {
            assert_eq!(filtered_point(i as u32)[0], 0.0);
            let want = (i as f64 + 0.5) / FILTERED_TAPS as f64;
            let got = disc_marginal_cdf(*y as f64);
            assert!((got - want).abs() < 1e-6, "tap {i}: {got} vs {want}");
        }
        assert!(ys.windows(2).all(|w| w[0] < w[1]), "{ys:?}");
        assert_eq!(disc_marginal_cdf(-1.0), 0.0);
        assert!((disc_marginal_cdf(1.0) - 1.0).abs() < 1e-12);
    }

    /// A sample as dense as a level's lobe reads that level (less the bias).
    #[test]
    fn a_sample_reads_the_level_of_its_share() {
        let levels = 9;
        let r = 0.5f32;
        let alpha = r * r;
        let omega = 4.0 * std::f32::consts::PI * alpha * alpha;
        let lod = sample_lod(MipRoughness::Linear, levels, 1.0 / omega, 1);
        let want = r * (levels - 1) as f32 + FILTERED_LOD_BIAS;
        assert!((lod - want).abs() < 1e-4, "{lod} vs {want}");
    }
}
