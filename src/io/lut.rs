//! Writes a BRDF LUT in the format its path's extension names, and reads back the PNG
//! one a bake writes.

use std::path::Path;

use super::format::{EncodedTexture, PixelFormat};
use super::{atomic::write_atomic, dds, exr, extension_of, ktx2, png};
use crate::plan::lut::BrdfLut;
use crate::{Error, Result};

/// Extensions a LUT can be written as.
pub const LUT_EXTENSIONS: &[&str] = &["png", "exr", "ktx2", "dds"];

/// Options for LUT outputs.
#[derive(Clone, Copy, Debug, Default)]
pub struct LutWriteOptions {
    /// KTX2/DDS: store 32-bit floats instead of 16-bit.
    pub f32: bool,
}

/// Checks that `path` names a LUT format, before any work is done.
pub fn check_lut_path(path: &Path) -> Result<()> {
    super::check_output_extension(path, "a BRDF LUT", LUT_EXTENSIONS)
}

/// Encodes `lut` for `path`'s extension: `.png` 16-bit RGB (R = A, G = B, B = 0 or the
/// third channel), `.exr` float32 R and G (and B for a third channel), `.ktx2` and `.dds`
/// R16G16 float (R32G32 with `f32`; RGBA16F or RGBA32F with A = 1 for a third channel).
/// Row 0 (roughness ≈ 0) is the first row in every format.
pub fn encode_lut(path: &Path, lut: &BrdfLut, opts: LutWriteOptions) -> Result<Vec<u8>> {
    let ext = extension_of(path);
    let encode_err = |format: &'static str| {
        move |message: String| Error::Encode {
            path: path.to_path_buf(),
            format,
            message,
        }
    };
    let rgb: Vec<[f32; 3]> = match &lut.third {
        Some(b) => lut
            .data
            .iter()
            .zip(b)
            .map(|(t, &b)| [t[0], t[1], b])
            .collect(),
        None => lut.data.iter().map(|t| [t[0], t[1], 0.0]).collect(),
    };
    let texture = || {
        let format = match (lut.third.is_some(), opts.f32) {
            (false, false) => PixelFormat::Rg16f,
            (false, true) => PixelFormat::Rg32f,
            (true, false) => PixelFormat::Rgba16f,
            (true, true) => PixelFormat::Rgba32f,
        };
        let texels: Vec<[f32; 4]> = rgb.iter().map(|&[r, g, b]| [r, g, b, 1.0]).collect();
        EncodedTexture {
            format,
            width: lut.width,
            height: lut.height,
            faces: 1,
            levels: vec![format.encode(&texels)],
        }
    };
    match ext.as_str() {
        "png" => {
            let flat: Vec<f32> = rgb.iter().flatten().copied().collect();
            png::encode_rgb16(lut.width, lut.height, &flat).map_err(encode_err("PNG"))
        }
        "exr" if lut.third.is_some() => {
            exr::encode_rgb32(lut.width, lut.height, &rgb).map_err(encode_err("OpenEXR"))
        }
        "exr" => exr::encode_rg32(lut.width, lut.height, &lut.data).map_err(encode_err("OpenEXR")),
        "ktx2" => ktx2::encode(&texture(), None).map_err(|e| encode_err("KTX2")(e.to_string())),
        "dds" => dds::encode(&texture()).map_err(encode_err("DDS")),
        _ => check_lut_path(path).map(|_| Vec::new()),
    }
}

/// The warning for writing `lut` as the 16-bit PNG `path`, when the PNG cannot hold some
/// of its values: those above 1 by more than half a step of the format (1/131070) are
/// stored as 1. (A default-model table reaches 1 only by rounding, and is not clipped.)
pub fn png_clip_warning(path: &Path, lut: &BrdfLut) -> Option<String> {
    if extension_of(path) != "png" {
        return None;
    }
    let limit = 1.0 + 0.5 / 65535.0;
    let (clipped, largest) = lut
        .values()
        .filter(|&v| v > limit)
        .fold((0usize, 0.0f32), |(n, m), v| (n + 1, m.max(v)));
    (clipped > 0).then(|| {
        format!(
            "{}: {clipped} values of the {} model are above 1 (the largest {largest:.3}) and are stored as 1 in a 16-bit PNG",
            path.display(),
            lut.model.name()
        )
    })
}

/// Encodes and writes `lut` to `path` atomically.
pub fn write_lut(path: &Path, lut: &BrdfLut, opts: LutWriteOptions) -> Result<()> {
    let bytes = encode_lut(path, lut, opts)?;
    write_atomic(path, &bytes)
}

/// Reads a LUT PNG as `encode_lut` writes it (R = A, G = B, 16 bits: within 1/131070).
pub fn read_lut_png(path: &Path) -> Result<BrdfLut> {
    let bytes = std::fs::read(path).map_err(|e| Error::io(path, e))?;
    let (width, height, rgb) = png::decode_rgb(&bytes).map_err(|message| Error::Decode {
        path: path.to_path_buf(),
        format: "PNG",
        message,
    })?;
    crate::plan::lut::validate_lut_size(width, height)?;
    Ok(BrdfLut::new(
        width,
        height,
        rgb.iter().map(|t| [t[0], t[1]]).collect(),
    ))
}
