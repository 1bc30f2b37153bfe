//! 8/16-bit PNG and JPEG inputs, decoded from sRGB to linear radiance with the sRGB EOTF
//! (IEC 61966-2-1).

use std::io::Cursor;
use std::path::Path;

use crate::environment::Equirect;
use crate::math::color::srgb_to_linear;
use crate::{Error, Result};

/// Decodes a PNG or JPEG; the size is checked from the header before decoding.
pub fn decode(path: &Path, bytes: &[u8], format: &'static str) -> Result<Equirect> {
    let bad = |message: String| Error::Decode {
        path: path.to_path_buf(),
        format,
        message,
    };
    let reader = image::ImageReader::new(Cursor::new(bytes))
        .with_guessed_format()
        .map_err(|e| bad(e.to_string()))?;
    let (w, h) = reader.into_dimensions().map_err(|e| bad(e.to_string()))?;
    super::limits::check_dimensions(path, w, h)?;
    let img = image::ImageReader::new(Cursor::new(bytes))
        .with_guessed_format()
        .map_err(|e| bad(e.to_string()))?
        .decode()
        .map_err(|e| bad(e.to_string()))?;
    let rgb = img.to_rgb32f();
    let data = rgb.pixels().map(|p| p.0.map(srgb_to_linear)).collect();
    Ok(Equirect {
        width: w,
        height: h,
        data,
    })
}
