//! ASTC HDR encoding: Arm's astc-encoder (the reference encoder, vendored in
//! `vendor/astcenc`, see `docs/astc.md`) compresses each face of each level with the HDR
//! RGBA profile at a 4×4 (8 bits a texel) or 6×6 (3.56 bits a texel) footprint. What it
//! reads is prepared here: RGBA `f32` texels clamped to [0, 65504] (ASTC HDR decodes to
//! half floats and holds no negative value; larger values clip as in rgba16f), A = 1. A
//! face smaller than a block (a 2² level at 4×4, a 4² or 2² one at 6×6) is one block that
//! astcenc pads by repeating its edge texels, as BC6H's input does, and of which a sampler
//! reads the top-left texels.
//!
//! The encoder weighs each channel's error by its share of luminance
//! ([`CHANNEL_WEIGHTS`]): what a shader's lookup gets wrong is seen as luminance, and on a
//! default bake these weights bring ASTC 4×4's lookup error below BC6H's at every
//! roughness of every bundled HDRI (venice_sunset's EXR at r = 0.8: 0.91 % with equal
//! weights, 0.60 % with these, rgb9e5 0.31 %), at the cost of a colour error per channel a
//! fifth larger (log RMSE 0.0088 against 0.0074 on a 32² level); `docs/astc.md`.

use half::f16;

use crate::environment::Cubemap;
use crate::math::color::LUMINANCE;

/// The encoder, as manifests record it.
pub const ENCODER: &str = "astc-encoder (Arm's reference ASTC encoder, vendored)";
/// Its version (vendor/astcenc/astc-encoder).
pub const ENCODER_VERSION: &str = "5.3.0";

/// astc-encoder's per-channel error weights (RGBA): the Rec. 709 luminance weights scaled
/// to sum to 3, as equal weights do; alpha (always 1) keeps astcenc's default.
pub const CHANNEL_WEIGHTS: [f32; 4] = [
    3.0 * LUMINANCE[0],
    3.0 * LUMINANCE[1],
    3.0 * LUMINANCE[2],
    1.0,
];

/// How hard astc-encoder searches: its presets of the same names (`ASTCENC_PRE_FAST`,
/// `_MEDIUM`, `_THOROUGH`). `Medium` is the default; `docs/astc.md` gives each preset's
/// texel error and CPU seconds on a default bake.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, PartialOrd, Ord)]
pub enum AstcQuality {
    /// `ASTCENC_PRE_FAST`.
    Fast,
    /// `ASTCENC_PRE_MEDIUM`.
    #[default]
    Medium,
    /// `ASTCENC_PRE_THOROUGH`.
    Thorough,
}

impl AstcQuality {
    /// Every preset, fastest first.
    pub const ALL: [AstcQuality; 3] = [AstcQuality::Fast, AstcQuality::Medium, AstcQuality::Thorough];

    /// The name on the command line and in manifests.
    pub fn name(self) -> &'static str {
        match self {
            AstcQuality::Fast => "fast",
            AstcQuality::Medium => "medium",
            AstcQuality::Thorough => "thorough",
        }
    }

    /// The preset called `name`.
    pub fn by_name(name: &str) -> Option<AstcQuality> {
        Self::ALL.into_iter().find(|q| q.name() == name)
    }

    /// astc-encoder's preset.
    pub(crate) fn preset(self) -> splitsum_astcenc::Preset {
        match self {
            AstcQuality::Fast => splitsum_astcenc::Preset::Fast,
            AstcQuality::Medium => splitsum_astcenc::Preset::Medium,
            AstcQuality::Thorough => splitsum_astcenc::Preset::Thorough,
        }
    }
}

/// Face `face` of level `m` of `cube` as the encoder reads it: RGBA, row-major, each
/// channel clamped to [0, 65504] (NaN to 0), A = 1.
pub fn encoder_input(cube: &Cubemap, m: usize, face: u32) -> Vec<[f32; 4]> {
    let n = cube.level_size(m);
    let max = f16::MAX.to_f32();
    let clamp = |v: f32| if v.is_nan() { 0.0 } else { v.clamp(0.0, max) };
    (0..n * n)
        .map(|k| {
            let t = cube.texel(m, face, k % n, k / n);
            [clamp(t[0]), clamp(t[1]), clamp(t[2]), 1.0]
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn input_is_clamped_to_the_half_range_with_opaque_alpha() {
        let cube = Cubemap {
            size: 2,
            levels: vec![(0..24)
                .map(|k| [k as f32, -0.5, if k == 5 { f32::NAN } else { 70000.0 }, 0.25])
                .collect()],
        };
        let face1 = encoder_input(&cube, 0, 1);
        assert_eq!(face1.len(), 4);
        assert_eq!(face1[0], [4.0, 0.0, 65504.0, 1.0]);
        assert_eq!(face1[1], [5.0, 0.0, 0.0, 1.0]);
        assert_eq!(AstcQuality::by_name("thorough"), Some(AstcQuality::Thorough));
        assert_eq!(AstcQuality::by_name("slow"), None);
    }
}
