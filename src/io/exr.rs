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

/// Encodes a width×height RGB float32 image (channels R, G, B), rows top to bottom.
pub fn encode_rgb32(
    width: u32,
    height: u32,
    rgb: &[[f32; 3]],
) -> std::result::Result<Vec<u8>, String> {
    let w = width as usize;
    let channels = SpecificChannels::rgb(|pos: Vec2<usize>| {
        let t = rgb[pos.y() * w + pos.x()];
        (t[0], t[1], t[2])
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

/// Reads the first layer's R, G and B channels (half, float or uint) at full resolution.
/// The header is read first, so the size is checked before any pixel is allocated and an
/// unsupported compression is named in the error.
pub fn decode(path: &std::path::Path, bytes: &[u8]) -> crate::Result<crate::environment::Equirect> {
    use crate::Error;
    let bad = |message: String| Error::Decode {
        path: path.to_path_buf(),
        format: "OpenEXR",
        message,
    };
    let meta = exr::meta::MetaData::read_from_buffered(Cursor::new(bytes), false)
        .map_err(|e| bad(e.to_string()))?;
    let header = meta
        .headers
        .first()
        .ok_or_else(|| bad("no layers".into()))?;
    let size = header.layer_size;
    super::limits::check_dimensions(path, size.0 as u32, size.1 as u32)?;
    let names: Vec<String> = header
        .channels
        .list
        .iter()
        .map(|c| c.name.to_string())
        .collect();
    for needed in ["R", "G", "B"] {
        if !names.iter().any(|n| n == needed) {
            return Err(Error::UnsupportedInput {
                path: path.to_path_buf(),
                message: format!(
                    "OpenEXR first layer has channels [{}]; splitsum needs R, G and B",
                    names.join(", ")
                ),
            });
        }
    }
    let compression = header.compression;
    let (w, h) = (size.0, size.1);
    let image = read()
        .no_deep_data()
        .largest_resolution_level()
        .rgb_channels(
            |_, _| vec![[0.0f32; 3]; w * h],
            move |data: &mut Vec<[f32; 3]>, pos: Vec2<usize>, (r, g, b): (f32, f32, f32)| {
                data[pos.y() * w + pos.x()] = [r, g, b];
            },
        )
        .first_valid_layer()
        .all_attributes()
        .non_parallel()
        .from_buffered(Cursor::new(bytes))
        .map_err(|e| match e {
            exr::error::Error::NotSupported(what) => Error::UnsupportedInput {
                path: path.to_path_buf(),
                message: format!(
                    "OpenEXR {compression} compression or feature not supported: {what}"
                ),
            },
            other => bad(other.to_string()),
        })?;
    Ok(crate::environment::Equirect {
        width: w as u32,
        height: h as u32,
        data: image.layer_data.channel_data.pixels,
    })
}
