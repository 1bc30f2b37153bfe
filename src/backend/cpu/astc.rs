//! ASTC HDR on the CPU: astc-encoder compresses each face of each level of a cube
//! ([`crate::plan::astc`]), one context for the whole cube, every call on all of rayon's
//! threads (astcenc runs them itself: each thread calls `astcenc_compress_image` with its
//! own index). Both backends encode ASTC here; the encoder has no GPU kernel.

use splitsum_astcenc::Context;

use crate::environment::Cubemap;
use crate::plan::astc::{encoder_input, AstcQuality, CHANNEL_WEIGHTS};
use crate::{Error, Result};

/// The ASTC blocks of every level of `cube` at `footprint` (texels wide, high), each level
/// its six faces one after the other, each face's blocks row-major.
pub fn encode_astc(cube: &Cubemap, footprint: (u32, u32), quality: AstcQuality) -> Result<Vec<Vec<u8>>> {
    let failed = |e: splitsum_astcenc::Error| Error::Encoder {
        encoder: "astc-encoder",
        message: e.to_string(),
    };
    let threads = rayon::current_num_threads() as u32;
    let mut context = Context::hdr_weighted(footprint.0, footprint.1, quality.preset(), threads, CHANNEL_WEIGHTS).map_err(failed)?;
    (0..cube.levels.len())
        .map(|m| {
            let n = cube.level_size(m);
            let mut level = Vec::with_capacity(6 * context.compressed_len(n, n));
            for face in 0..6 {
                let texels = encoder_input(cube, m, face);
                level.extend(context.compress(n, n, &texels).map_err(failed)?);
            }
            Ok(level)
        })
        .collect()
}
