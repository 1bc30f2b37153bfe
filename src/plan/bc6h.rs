//! BC6H (BPTC unsigned float) encoding, as both backends do it: the encoder is the
//! `block_compression` crate's port of Intel's ISPC Texture Compressor kernel, run as its
//! WGSL compute shader on the GPU backend and as its CPU port on the CPU backend. Both read
//! the same input, prepared here: each face of each level as half floats (clamped to the
//! half range, as rgba16f stores them), padded to whole 4×4 blocks by repeating the last
//! row and column, since a block holds 4×4 texels whatever the face's size (a 2² or 1²
//! level is one block, of which a sampler reads the top-left texels).

use block_compression::BC6HSettings;
use half::f16;

use crate::environment::Cubemap;

/// Edge of a BC6H block in texels.
pub const BLOCK_EDGE: u32 = 4;
/// Bytes of a BC6H block.
pub const BLOCK_BYTES: usize = 16;
/// The encoder, as manifests record it.
pub const ENCODER: &str = "block_compression (Intel ISPC Texture Compressor's BC6H kernel)";
/// Its version (the one Cargo.lock pins).
pub const ENCODER_VERSION: &str = "0.11";

/// Levels of at most this edge are encoded with at least the `Basic` preset.
pub const THOROUGH_MAX_EDGE: u32 = 64;

/// How hard the encoder searches (which modes, partitions and refinements it tries): the
/// crate's presets of ISPC's. `Fast` is the default: on a default bake its texel error is
/// within 6 % of `Basic`'s (log RMSE 0.0028 against 0.0027 at 256², 0.0105 against 0.0099
/// at 4²) at less than half the time; see `docs/accuracy.md`, "BC6H".
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, PartialOrd, Ord)]
pub enum Bc6hQuality {
    /// ISPC's "fast": one-region modes first, the two-region ones skipped when the first
    /// is good enough, one refinement.
    #[default]
    Fast,
    /// ISPC's "basic": every mode, two refinements.
    Basic,
    /// ISPC's "slow": every mode and more partitions.
    Slow,
}

impl Bc6hQuality {
    /// Every preset, fastest first.
    pub const ALL: [Bc6hQuality; 3] = [Bc6hQuality::Fast, Bc6hQuality::Basic, Bc6hQuality::Slow];

    /// The name on the command line and in manifests.
    pub fn name(self) -> &'static str {
        match self {
            Bc6hQuality::Fast => "fast",
            Bc6hQuality::Basic => "basic",
            Bc6hQuality::Slow => "slow",
        }
    }

    /// The preset called `name`.
    pub fn by_name(name: &str) -> Option<Bc6hQuality> {
        Self::ALL.into_iter().find(|q| q.name() == name)
    }

    /// The encoder's settings for a level of edge `n`: the preset's, but never below
    /// `Basic` for levels of `THOROUGH_MAX_EDGE`² (64²) and less. Those hold the rough lobes
    /// a shader reads at r ≥ 0.5 and are 6 % of a default chain's blocks, so searching
    /// every mode there costs little: on a default bake of studio_small_03, `Fast` on
    /// every level puts the lookup error at r = 0.5 0.52 points above rgb9e5's, this 0.44.
    pub fn settings(self, n: u32) -> BC6HSettings {
        let preset = if n <= THOROUGH_MAX_EDGE {
            self.max(Bc6hQuality::Basic)
        } else {
            self
        };
        match preset {
            Bc6hQuality::Fast => BC6HSettings::fast(),
            Bc6hQuality::Basic => BC6HSettings::basic(),
            Bc6hQuality::Slow => BC6HSettings::slow(),
        }
    }
}

/// Blocks along each axis of an n² face.
pub fn blocks_per_row(n: u32) -> u32 {
    n.div_ceil(BLOCK_EDGE)
}

/// Bytes of one n² face.
pub fn face_bytes(n: u32) -> usize {
    (blocks_per_row(n) * blocks_per_row(n)) as usize * BLOCK_BYTES
}

/// The edge of an n² face padded to whole blocks.
pub fn padded_edge(n: u32) -> u32 {
    blocks_per_row(n) * BLOCK_EDGE
}

/// Face `face` of level `m` of `cube` as the encoder reads it: RGBA half floats, row-major,
/// [`padded_edge`]² texels, values clamped to [0, 65504] (BC6H unsigned float holds no
/// negative value; larger ones clip as in rgba16f), the padding repeating the last row
/// and column.
pub fn encoder_input(cube: &Cubemap, m: usize, face: u32) -> Vec<f16> {
    let n = cube.level_size(m);
    let p = padded_edge(n);
    let half = |v: f32| f16::from_f32(v.clamp(0.0, f16::MAX.to_f32()));
    let mut out = Vec::with_capacity((p * p * 4) as usize);
    for y in 0..p {
        for x in 0..p {
            let t = cube.texel(m, face, x.min(n - 1), y.min(n - 1));
            out.extend([half(t[0]), half(t[1]), half(t[2]), f16::ONE]);
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn small_faces_are_padded_to_one_block_by_repetition() {
        let cube = Cubemap {
            size: 2,
            levels: vec![(0..24).map(|k| [k as f32, 0.5, 70000.0, 1.0]).collect()],
        };
        let input = encoder_input(&cube, 0, 1);
        assert_eq!(input.len(), 4 * 4 * 4);
        // Face 1 holds texels 4..8; (3, 3) repeats (1, 1), texel 7.
        assert_eq!(input[(3 * 4 + 3) * 4].to_f32(), 7.0);
        assert_eq!(input[(3 * 4) * 4].to_f32(), 6.0);
        // Above the half range: clipped to 65504, as rgba16f stores it.
        assert_eq!(input[2].to_f32(), 65504.0);
        assert_eq!(face_bytes(2), 16);
        assert_eq!(face_bytes(8), 4 * 16);
        assert_eq!(face_bytes(6), 4 * 16);
    }
}
