//! Size limits every reader checks from the header, before allocating anything.

use std::path::Path;

use super::format::PixelFormat;
use crate::math::cubemap::FACES;
use crate::{Error, Result};

/// Smallest accepted width and height.
pub const MIN_DIMENSION: u32 = 8;
/// Largest accepted width or height.
pub const MAX_DIMENSION: u32 = 32768;
/// Largest accepted texel count (16384 × 16384; a 32768 × 16384 equirect is accepted).
pub const MAX_TEXELS: u64 = 1 << 29;

/// Refuses dimensions outside [`MIN_DIMENSION`]..=[`MAX_DIMENSION`] or above
/// [`MAX_TEXELS`], naming the file.
pub fn check_dimensions(path: &Path, width: u32, height: u32) -> Result<()> {
    let refuse = |message: String| {
        Err(Error::UnsupportedInput {
            path: path.to_path_buf(),
            message,
        })
    };
    if width < MIN_DIMENSION || height < MIN_DIMENSION {
        return refuse(format!(
            "image is {width}×{height}; at least {MIN_DIMENSION}×{MIN_DIMENSION} is needed"
        ));
    }
    if width > MAX_DIMENSION || height > MAX_DIMENSION || width as u64 * height as u64 > MAX_TEXELS
    {
        return refuse(format!(
            "image is {width}×{height}; splitsum accepts at most {MAX_DIMENSION} texels per side and {MAX_TEXELS} texels"
        ));
    }
    Ok(())
}

/// Checks that level 0 of an n² cube in `pf` (`bytes` long) is complete and within the limits.
pub fn check_cube_level0(
    path: &Path,
    format: &'static str,
    n: u32,
    bytes: usize,
    pf: PixelFormat,
) -> Result<()> {
    check_dimensions(path, n, n)?;
    let expected = FACES * pf.image_bytes(n, n);
    if bytes < expected {
        return Err(Error::Decode {
            path: path.to_path_buf(),
            format,
            message: format!("level 0 holds {bytes} bytes, {expected} expected (truncated?)"),
        });
    }
    Ok(())
}
