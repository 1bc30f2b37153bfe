//! The recipe's quality lookup ([`crate::math::lookup::SpecularLookup::Filtered`]), the
//! plan of `filtered_prefiltered` in `cpu::preview_split_sum` and shaders/common/filtered.wgsl:
//! filtered importance sampling of the prefiltered chain (Křivánek and Colbert, "Real-time
//! Shading with Filtered Importance Sampling", EGSR 2008; Colbert and Křivánek, GPU Gems 3
//! ch. 20, 2007) with [`FILTERED_TAPS`] samples of GGX's visible normals (Heitz, "Sampling
//! the GGX Distribution of Visible Normals", JCGT 2018), where the chain's own lookup is
//! furthest off: at grazing views, where the true lobe reaches past R toward the horizon and
//! a level prefiltered with v = n cannot follow it.
//!
//! Per shaded point of normal n, view v, α = r²: for the fixed set of [`FILTERED_TAPS`]
//! points (i + ½)/N, radical inverse of i (the same in every pixel: no noise), h drawn from
//! the visible normals, l = reflect(−v, h); each l with n·l > 0 reads the chain at the level
//! whose lobe covers the sample's share of the sphere, Ω_s = 1 / (N pdf(l)),
//! pdf(l) = G1(v) D(h) / (4 n·v) ([`sample_lod`]), and is weighted by the BRDF over its
//! pdf, F(v·h) G(l) G(v) / G1(v) (Schlick-GGX G of the recipe's BRDF, the exact Smith G1 of
//! the sampler). The normalised sum Σ w L / Σ w (per channel) stands for the prefiltered
//! radiance: the LUT's F0 A + B scales it as it scales the chain's lookup, so a uniform
//! environment is exact whatever the taps.
//!
//! The recipe blends to it by [`filtered_share`]: fully below n·v = 0.4 and r = 0.8, not
//! at all above n·v = 0.6 or r = 0.9, where the chain's lookup with its blend toward E/π
//! is the better one (a few taps of a wide lobe are worse than the chain at r = 1). A
//! numpy study of 50 estimators on four HDRIs chose these (docs/accuracy.md, "The
//! residual's lookup"): 16 taps, the level from Ω_s less half a level, the fixed set, the
//! normalised sum.

use crate::plan::chain::MipRoughness;

/// Samples of the quality lookup at a point where it is used in full.
pub const FILTERED_TAPS: u32 = 16;

/// n·v below which the quality lookup is used in full, and above which not at
/// all (linear between).
pub const FILTERED_N_DOT_V: [f32; 2] = [0.4, 0.6];

/// Roughness below which the quality lookup is used in full, and above which not at all.
pub const FILTERED_ROUGHNESS: [f32; 2] = [0.8, 0.9];

/// Levels added to each sample's level ([`sample_lod`]): the sharpest of −3 … +2 in the
/// study (+0 costs 0.5–1.5 points).
pub const FILTERED_LOD_BIAS: f32 = -0.5;

/// The smallest α the quality lookup samples at: a mirror's lobe is the chain's level 0
/// along R, which the recipe's lookup already reads exactly.
pub const MIN_FILTERED_ALPHA: f32 = 1e-3;

/// How much of the quality lookup a point of `n_dot_v` and roughness `r` takes, in [0, 1].
pub fn filtered_share(n_dot_v: f32, r: f32) -> f32 {
    let ramp = |x: f32, [lo, hi]: [f32; 2]| ((hi - x) / (hi - lo)).clamp(0.0, 1.0);
    ramp(n_dot_v, FILTERED_N_DOT_V) * ramp(r, FILTERED_ROUGHNESS)
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

/// The `i`-th of [`FILTERED_TAPS`] points of the fixed set, in [0, 1)²: ((i + ½)/N,
/// radical inverse of i).
pub fn filtered_point(i: u32) -> [f32; 2] {
    [
        (i as f32 + 0.5) / FILTERED_TAPS as f32,
        crate::math::sampling::radical_inverse_vdc(i),
    ]
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
