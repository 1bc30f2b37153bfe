//! DDS writer with the DX10 extension header (Microsoft, "DDS programming guide"):
//! uncompressed DXGI formats, optional cubemap flag and full mip chain. DDS stores data
//! face by face, each face with all its mips.

use super::format::EncodedTexture;

const DDSD_CAPS: u32 = 0x1;
const DDSD_HEIGHT: u32 = 0x2;
const DDSD_WIDTH: u32 = 0x4;
const DDSD_PITCH: u32 = 0x8;
const DDSD_PIXELFORMAT: u32 = 0x1000;
const DDSD_MIPMAPCOUNT: u32 = 0x20000;
const DDPF_FOURCC: u32 = 0x4;
const DDSCAPS_COMPLEX: u32 = 0x8;
const DDSCAPS_TEXTURE: u32 = 0x1000;
const DDSCAPS_MIPMAP: u32 = 0x40_0000;
const DDSCAPS2_CUBEMAP_ALL_FACES: u32 = 0x200 | 0xFC00;
const D3D10_RESOURCE_DIMENSION_TEXTURE2D: u32 = 3;
const DDS_RESOURCE_MISC_TEXTURECUBE: u32 = 0x4;

/// Serialises `tex` as a DDS file with a DX10 header.
pub fn encode(tex: &EncodedTexture) -> Vec<u8> {
    let levels = tex.levels.len() as u32;
    let cube = tex.faces == 6;
    let mut flags = DDSD_CAPS | DDSD_HEIGHT | DDSD_WIDTH | DDSD_PIXELFORMAT | DDSD_PITCH;
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
        tex.width * tex.format.texel_bytes(), // pitch
        0,                                    // depth
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
        tex.format.dxgi_format(),
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
    out
}
