//! 16-bit PNG writer (RGB, values clamped to [0, 1] and rounded to 1/65535) and its reader.

use std::io::Cursor;

/// Encodes width×height texels of 3 floats as a 16-bit RGB PNG.
pub fn encode_rgb16(width: u32, height: u32, rgb: &[f32]) -> Result<Vec<u8>, String> {
    let data: Vec<u16> = rgb
        .iter()
        .map(|&v| (v.clamp(0.0, 1.0) * 65535.0).round() as u16)
        .collect();
    let img = image::ImageBuffer::<image::Rgb<u16>, Vec<u16>>::from_raw(width, height, data)
        .ok_or_else(|| "pixel buffer does not match the image size".to_string())?;
    let mut out = Cursor::new(Vec::new());
    img.write_to(&mut out, image::ImageFormat::Png)
        .map_err(|e| e.to_string())?;
    Ok(out.into_inner())
}

/// Decodes a PNG as RGB values in [0, 1] (8- or 16-bit, any colour type the `image` crate
/// reads; alpha dropped): width, height, row-major texels.
pub fn decode_rgb(bytes: &[u8]) -> Result<(u32, u32, Vec<[f32; 3]>), String> {
    let img = image::load_from_memory_with_format(bytes, image::ImageFormat::Png)
        .map_err(|e| e.to_string())?;
    let rgb = img.to_rgb32f();
    let (w, h) = rgb.dimensions();
    Ok((w, h, rgb.pixels().map(|p| p.0).collect()))
}
