//! 8/16-bit PNG and JPEG inputs, decoded from sRGB to linear radiance with the sRGB EOTF
//! (IEC 61966-2-1).

use std::io::Cursor;
use std::path::Path;

use crate::environment::Equirect;
use crate::{Error, Result};

/// sRGB-encoded value in [0, 1] to linear.
pub fn srgb_to_linear(c: f32) -> f32 {
    if c <= 0.04045 {
        c / 12.92
    } else {
        ((c + 0.055) / 1.055).powf(2.4)
    }
}

/// The sRGB transfer function (IEC 61966-2-1) of a linear value in [0, 1] (clamped), as
/// 8 bits.
pub fn srgb8(v: f32) -> u8 {
    let v = v.clamp(0.0, 1.0);
    let e = if v <= 0.003_130_8 {
        12.92 * v
    } else {
        1.055 * v.powf(1.0 / 2.4) - 0.055
    };
    (e * 255.0).round() as u8
}

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
