//! DDS cubemaps with the DX10 extension header (Microsoft, "DDS programming guide"). The
//! writer: DXGI formats, optional cubemap flag and full mip chain; DDS stores data face by
//! face, each face with all its mips. The reader (through the `ddsfile` crate): level 0 of
//! a cube in one of splitsum's formats.

use std::path::Path;

use super::format::{EncodedTexture, PixelFormat};
use super::limits::check_dimensions;
use super::read_file;
use crate::environment::Cubemap;
use crate::math::cubemap::FACES;
use crate::{Error, Result};

const DDSD_CAPS: u32 = 0x1;
const DDSD_HEIGHT: u32 = 0x2;
const DDSD_WIDTH: u32 = 0x4;
const DDSD_PITCH: u32 = 0x8;
const DDSD_PIXELFORMAT: u32 = 0x1000;
const DDSD_MIPMAPCOUNT: u32 = 0x20000;
const DDSD_LINEARSIZE: u32 = 0x80000;
const DDPF_FOURCC: u32 = 0x4;
const DDSCAPS_COMPLEX: u32 = 0x8;
const DDSCAPS_TEXTURE: u32 = 0x1000;
const DDSCAPS_MIPMAP: u32 = 0x40_0000;
const DDSCAPS2_CUBEMAP_ALL_FACES: u32 = 0x200 | 0xFC00;
const D3D10_RESOURCE_DIMENSION_TEXTURE2D: u32 = 3;
const DDS_RESOURCE_MISC_TEXTURECUBE: u32 = 0x4;

/// Serialises `tex` as a DDS file with a DX10 header; a format with no `DXGI_FORMAT`
/// (ASTC) is an error naming it.
pub fn encode(tex: &EncodedTexture) -> std::result::Result<Vec<u8>, String> {
    let dxgi = tex.format.dxgi_format().ok_or_else(|| {
        format!(
            "DDS holds DXGI formats, and {} has none (Direct3D does not sample ASTC); write it as KTX2",
            tex.format.name()
        )
    })?;
    let levels = tex.levels.len() as u32;
    let cube = tex.faces == 6;
    // Uncompressed formats give a row's pitch; block formats the size of level 0's face
    // ("linear size").
    let (size_flag, pitch_or_linear) = if tex.format.is_block() {
        (
            DDSD_LINEARSIZE,
            tex.format.image_bytes(tex.width, tex.height) as u32,
        )
    } else {
        (DDSD_PITCH, tex.width * tex.format.texel_bytes())
    };
    let mut flags = DDSD_CAPS | DDSD_HEIGHT | DDSD_WIDTH | DDSD_PIXELFORMAT | size_flag;
    let mut caps = DDSCAPS_TEXTURE;
    if levels > 1 {
        flags |= DDSD_MIPMAPCOUNT;
        caps |= DDSCAPS_COMPLEX | DDSCAPS_MIPMAP;
    }
    if cube {
        caps |= DDSCAPS_COMPLEX;
    }
    let mut words: Vec<u32> = vec![
        124, // dwSize
        flags,
        tex.height,
        tex.width,
        pitch_or_linear,
        0, // depth
        levels,
    ];
    words.extend([0u32; 11]); // dwReserved1
                              // DDS_PIXELFORMAT: size, flags, fourCC "DX10", rgb bit count and masks unused.
    words.extend([32, DDPF_FOURCC, u32::from_le_bytes(*b"DX10"), 0, 0, 0, 0, 0]);
    words.extend([
        caps,
        if cube { DDSCAPS2_CUBEMAP_ALL_FACES } else { 0 },
        0,
        0,
        0,
    ]);
    // DDS_HEADER_DXT10
    words.extend([
        dxgi,
        D3D10_RESOURCE_DIMENSION_TEXTURE2D,
        if cube {
            DDS_RESOURCE_MISC_TEXTURECUBE
        } else {
            0
        },
        1, // arraySize (number of cubes for a cubemap)
        0, // miscFlags2: alpha mode unknown
    ]);
    let mut out = b"DDS ".to_vec();
    out.extend(words.into_iter().flat_map(u32::to_le_bytes));
    for face in 0..tex.faces as usize {
        for level in &tex.levels {
            let face_len = level.len() / tex.faces as usize;
            out.extend_from_slice(&level[face * face_len..(face + 1) * face_len]);
        }
    }
    Ok(out)
}

/// Reads level 0 of a DX10 DDS cubemap in one of splitsum's formats.
pub fn read_cube(path: &Path) -> Result<Cubemap> {
    decode_cube(path, &read_file(path)?)
}

/// Decodes level 0 of a DX10 DDS cubemap from `bytes` (`path` names it in errors).
pub fn decode_cube(path: &Path, bytes: &[u8]) -> Result<Cubemap> {
    const F: &str = "DDS";
    let bad = |message: String| Error::Decode {
        path: path.to_path_buf(),
        format: F,
        message,
    };
    let dds = ddsfile::Dds::read(bytes).map_err(|e| bad(e.to_string()))?;
    let unsupported = |message: String| Error::UnsupportedInput {
        path: path.to_path_buf(),
        message,
    };
    let is_cube = dds
        .header10
        .as_ref()
        .is_some_and(|h| h.misc_flag.contains(ddsfile::MiscFlag::TEXTURECUBE));
    let n = dds.get_width();
    if !is_cube || dds.get_height() != n {
        return Err(unsupported(
            "DDS file is not a cubemap with a DX10 header".into(),
        ));
    }
    let pf = dds
        .header10
        .as_ref()
        .and_then(|h| PixelFormat::from_dxgi_format(h.dxgi_format as u32))
        .filter(|f| !matches!(f, PixelFormat::Rg16f | PixelFormat::Rg32f))
        .ok_or_else(|| {
            unsupported(
                "DDS format is not one splitsum reads (rgba16f, rgba32f, rgb9e5, rg11b10f, bc6h)"
                    .into(),
            )
        })?;
    check_dimensions(path, n, n)?;
    // Faces are stored one after the other, each with all its mips. The mip count comes
    // from the header, so it is bounded before the face stride is computed from it.
    let mips = dds.get_num_mipmap_levels().max(1);
    let full = Cubemap::full_mip_count(n);
    if mips > full {
        return Err(bad(format!(
            "header claims {mips} mip levels; a {n}×{n} face has at most {full}"
        )));
    }
    let size = |m: u32| (n >> m).max(1);
    let face_bytes = pf.image_bytes(n, n);
    let stride: usize = (0..mips).map(|m| pf.image_bytes(size(m), size(m))).sum();
    let data = &dds.data;
    if data.len() < stride * (FACES - 1) + face_bytes {
        return Err(bad(format!(
            "holds {} bytes of texels, {} expected (truncated?)",
            data.len(),
            stride * FACES
        )));
    }
    let mut level = Vec::with_capacity(Cubemap::level_len(n));
    for face in 0..FACES {
        level.extend(pf.decode_faces(&data[face * stride..face * stride + face_bytes], n, 1));
    }
    Ok(Cubemap {
        size: n,
        levels: vec![level],
    })
}
