//! The specular chain's layout, which both backends follow: how many levels, the roughness
//! of each mip and the lod a shader reads a roughness at ([`MipRoughness`], per target),
//! and how each level is computed ([`level_method`]: an exact sum over a small source mip
//! where the lobe is wide enough, filtered importance sampling elsewhere).

use std::f32::consts::PI;

use crate::environment::Cubemap;
use crate::math::brdf::alpha_from_roughness;

/// Default GGX samples per texel and level. Measured by `prefilter_accuracy_scan`
/// (tests/specular.rs) on the sampled r = 1/7 level of a 128² chain, energy-weighted error
/// against brute force: 32 samples 0.51 % (quarry), 64: 0.39 % (quarry) and 0.99 %
/// (studio_small_03), 128: 0.30 % and 0.90 %. 64 halves the time of the sampled levels
/// (the bulk of a default bake) for about 0.1 point.
pub const DEFAULT_SAMPLES: u32 = 64;

/// How a chain's mips map to perceptual roughness, and back: a shader reads roughness r at
/// `lod(r)`, and mip m is prefiltered at `roughness(m)`, its inverse.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum MipRoughness {
    /// r = m/(M − 1), lod = r·(M − 1) (docs/conventions.md, "Specular mip chain"; Bevy's `environment_map.wgsl`,
    /// glTF-IBL-Sampler).
    Linear,
    /// r = 1 − √(1 − m/(M − 1)), lod = (M − 1)·r·(2 − r): three.js r187's PMREM
    /// (`PMREMGenerator` `lodToRoughness`, `roughnessToMip` in
    /// envmap_common_pars_fragment) and Filament's `perceptualRoughnessToLod`.
    Quadratic,
    /// Babylon.js (and the generic target), for a chain of M levels, N = 2^(M − 1) (the
    /// level-0 edge of a whole chain down to 1×1): mip m > 0 holds GGX at
    /// α = 2^(m/s) / N (`HDRFiltering`, s = 0.8, Babylon's `lodGenerationScale`; m = 0 the environment),
    /// r = √min(α, 1), and the shader reads lod = s·log2(N·(r² + ε)), ε = 0.0005,
    /// Babylon's `MINIMUMVARIANCE` (`getLodFromAlphaG`, `convertRoughnessToAverageSlope`).
    Babylon,
}

/// Babylon's `lodGenerationScale`, the default of its own prefiltering and what splitsum
/// writes into a `.env`.
pub const BABYLON_LOD_SCALE: f32 = 0.8;
/// Babylon's `MINIMUMVARIANCE`, added to r² to make the shader's α.
pub const BABYLON_MINIMUM_VARIANCE: f32 = 0.0005;

impl MipRoughness {
    /// Roughness of mip `m` of a chain of `levels`.
    pub fn roughness(self, m: u32, levels: u32) -> f32 {
        if levels <= 1 {
            return 0.0;
        }
        let t = m as f32 / (levels - 1) as f32;
        match self {
            MipRoughness::Linear => t,
            MipRoughness::Quadratic => 1.0 - (1.0 - t).max(0.0).sqrt(),
            MipRoughness::Babylon if m == 0 => 0.0,
            MipRoughness::Babylon => {
                let alpha = (m as f32 / BABYLON_LOD_SCALE - (levels - 1) as f32).exp2();
                alpha.min(1.0).sqrt()
            }
        }
    }

    /// The lod a shader reads roughness `r` at, in a chain of `levels`.
    pub fn lod(self, r: f32, levels: u32) -> f32 {
        let r = r.clamp(0.0, 1.0);
        let max_lod = levels.saturating_sub(1) as f32;
        match self {
            MipRoughness::Linear => r * max_lod,
            MipRoughness::Quadratic => r * (2.0 - r) * max_lod,
            MipRoughness::Babylon => (BABYLON_LOD_SCALE
                * (max_lod + (r * r + BABYLON_MINIMUM_VARIANCE).log2()))
            .clamp(0.0, max_lod),
        }
    }

    /// The mapping as the kernels take it (`MIP_ROUGHNESS_*` in common/filtered.wgsl).
    pub fn code(self) -> u32 {
        match self {
            MipRoughness::Linear => 0,
            MipRoughness::Quadratic => 1,
            MipRoughness::Babylon => 2,
        }
    }

    /// The mapping as written in manifests.
    pub fn formula(self) -> &'static str {
        match self {
            MipRoughness::Linear => "m / (levels - 1)",
            MipRoughness::Quadratic => "1 - sqrt(1 - m / (levels - 1))",
            MipRoughness::Babylon => {
                "sqrt(min(1, 2^(m / 0.8 - (levels - 1)))) for m > 0 (Babylon's lodGenerationScale 0.8), 0 for m = 0"
            }
        }
    }
}

/// The layout of a prefiltered chain: how many levels and the roughness of each.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct SpecularChain {
    /// Number of levels M (level 0 is the environment itself, r = 0).
    pub levels: u32,
    /// Roughness of each level.
    pub roughness: MipRoughness,
}

impl SpecularChain {
    /// `levels` levels at r = m/(M − 1).
    pub fn linear(levels: u32) -> Self {
        SpecularChain {
            levels,
            roughness: MipRoughness::Linear,
        }
    }

    /// Roughness of mip `m`.
    pub fn mip_roughness(&self, m: u32) -> f32 {
        self.roughness.roughness(m, self.levels)
    }
}

#[cfg(any(test, feature = "internals"))]
/// Roughness of mip `m` of a linear chain of `levels` (docs/conventions.md: r = m / (M − 1)).
pub fn mip_roughness(m: u32, levels: u32) -> f32 {
    MipRoughness::Linear.roughness(m, levels)
}

/// How one prefiltered level is computed.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum LevelMethod {
    /// Exact sum over every texel of source mip `source_mip`.
    Exact {
        /// The source mip read.
        source_mip: u32,
    },
    /// Filtered importance sampling with this many samples per texel.
    Sampled {
        /// GGX samples per texel.
        samples: u32,
    },
}

/// Largest exact-sum cost (output texels × source texels) per level before importance
/// sampling is used instead (~2e8 weighted sums, about 0.6 CPU-s on the CPU backend;
/// docs/accuracy.md has the timings).
pub const EXACT_BUDGET: u64 = 200_000_000;

/// Source texels per GGX α in the exact sum: the source mip's texel angle (π/2)/n is at
/// most α / `EXACT_TEXELS_PER_ALPHA`, so D varies little across a texel.
pub const EXACT_TEXELS_PER_ALPHA: f32 = 16.0;

/// Largest source mip edge of an exact sum. 6·64² texels × 32 bytes = 768 KiB of storage
/// buffer: Mesa's lavapipe (22.3) silently reads zeros past the first 2 MiB of a storage
/// binding, whatever limit it reports (`tests/specular.rs` fails otherwise).
pub const EXACT_MAX_SOURCE: u32 = 64;

/// Picks the method for output mip `m` (at roughness `r`) of an `env_size` chain: the exact sum over the
/// smallest source mip fine enough for the lobe (texel angle ≤ α/16) when it fits
/// [`EXACT_BUDGET`], else filtered importance sampling.
pub fn level_method(env_size: u32, m: u32, r: f32, samples: u32) -> LevelMethod {
    let alpha = alpha_from_roughness(r);
    let out = (env_size >> m).max(1) as u64;
    // Smallest power of two n with (π/2)/n ≤ α/K, at most the environment's size.
    // (Clamped before the integer conversion: α = 0 asks for an infinitely fine mip.)
    let needed = (EXACT_TEXELS_PER_ALPHA * PI / (2.0 * alpha))
        .clamp(1.0, env_size as f32)
        .ceil() as u32;
    let n = needed
        .next_power_of_two()
        .min(env_size)
        .min(EXACT_MAX_SOURCE) as u64;
    let cost = 6 * out * out * 6 * n * n;
    if cost <= EXACT_BUDGET {
        LevelMethod::Exact {
            source_mip: (env_size as u64 / n).trailing_zeros(),
        }
    } else {
        LevelMethod::Sampled { samples }
    }
}

/// Default edge of the smallest mip of a [`MipRoughness::Linear`] chain (Bevy's): the chain
/// stops there instead of at 1×1 (see [`chain_levels`]). A 256 chain then has 7 levels,
/// r = m/6. Chosen by the lookup
/// error a shader sees (seamless trilinear at lod = r·(M − 1), `tests/lookup.rs`
/// `layout_scan`): a 1×1 or 2×2 level cannot hold the r = 1 lobe (quarry_01: 30 % and
/// 11 % at r = 1), while fewer levels blend lobes farther apart (16² and 32² minima:
/// 16 % and 4 % at r = 0.35); 4² keeps every r ≥ 0.3 within 3.2 % on quarry_01 and
/// 4.2 % on royal_esplanade.
pub const DEFAULT_MIN_MIP_SIZE: u32 = 4;

/// Number of levels M of a specular chain from `size` down to `min_mip_size` (both powers
/// of two; a minimum above the size gives one level): log2(size / min) + 1.
pub fn chain_levels(size: u32, min_mip_size: u32) -> u32 {
    let min = min_mip_size.clamp(1, size.max(1));
    Cubemap::full_mip_count(size) - Cubemap::full_mip_count(min) + 1
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Each mapping's lod is the inverse of its roughness per mip: a shader asking for a
    /// level's roughness reads that level (Babylon's only below α = 1, and up to its ε:
    /// 0.8 log2(1 + ε/α), 0.06 at the first level's α = 0.0093).
    #[test]
    fn lod_inverts_the_roughness_of_each_mip() {
        for (mapping, levels) in [
            (MipRoughness::Linear, 7),
            (MipRoughness::Quadratic, 5),
            (MipRoughness::Babylon, 9),
        ] {
            for m in 0..levels {
                let r = mapping.roughness(m, levels);
                if mapping == MipRoughness::Babylon && (m == 0 || r >= 1.0) {
                    continue;
                }
                let lod = mapping.lod(r, levels);
                let tol = match mapping {
                    MipRoughness::Babylon => {
                        0.02 + BABYLON_LOD_SCALE * (1.0 + BABYLON_MINIMUM_VARIANCE / (r * r)).log2()
                    }
                    _ => 0.02,
                };
                assert!(
                    (lod - m as f32).abs() < tol,
                    "{mapping:?} m {m}: r {r}, lod {lod}"
                );
            }
        }
        // Babylon's 256² chain: α = 2^(m / 0.8) / 256 reaches 1 at m = 6.4.
        assert_eq!(MipRoughness::Babylon.roughness(0, 9), 0.0);
        assert!((MipRoughness::Babylon.roughness(4, 9) - (32.0f32 / 256.0).sqrt()).abs() < 1e-6);
        assert_eq!(MipRoughness::Babylon.roughness(7, 9), 1.0);
        assert!((MipRoughness::Babylon.lod(1.0, 9) - 6.4006).abs() < 1e-3);
    }

}
