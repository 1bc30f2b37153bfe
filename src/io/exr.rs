//! OpenEXR writer for float32 images with named channels.

use std::io::Cursor;

use exr::prelude::*;

/// Encodes a width×height image with two float32 channels "R" and "G".
pub fn encode_rg32(
    width: u32,
    height: u32,
    rg: &[[f32; 2]],
) -> std::result::Result<Vec<u8>, String> {
    let w = width as usize;
    let channels = SpecificChannels::build()
        .with_channel("R")
        .with_channel("G")
        .with_pixel_fn(|pos: Vec2<usize>| {
            let t = rg[pos.y() * w + pos.x()];
            (t[0], t[1])
        });
    let image = Image::from_channels((width as usize, height as usize), channels);
    let mut out = Cursor::new(Vec::new());
    image
        .write()
        .non_parallel()
        .to_buffered(&mut out)
        .map_err(|e| e.to_string())?;
    Ok(out.into_inner())
}
