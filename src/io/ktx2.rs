//! KTX 2.0 writer (Khronos KTX File Format Specification 2.0): header, level index, a
//! Khronos Basic Data Format Descriptor, a `KTXwriter` key/value entry, and the mip levels
//! stored smallest first, each aligned to lcm(texel size, 4).

use super::format::{EncodedTexture, PixelFormat};

/// The 12-byte KTX 2.0 file identifier.
pub const IDENTIFIER: [u8; 12] = [
    0xAB, 0x4B, 0x54, 0x58, 0x20, 0x32, 0x30, 0xBB, 0x0D, 0x0A, 0x1A, 0x0A,
];

// Khronos Data Format Specification 1.3, section 5 ("basic" descriptor block).
const KHR_DF_MODEL_RGBSDA: u32 = 1;
const KHR_DF_PRIMARIES_BT709: u32 = 1;
const KHR_DF_TRANSFER_LINEAR: u32 = 1;
const KHR_DF_VERSION: u32 = 2;
const KHR_DF_SAMPLE_DATATYPE_FLOAT: u32 = 0x80;
const KHR_DF_SAMPLE_DATATYPE_SIGNED: u32 = 0x40;
const KHR_DF_CHANNEL_ALPHA: u32 = 15;
// sampleLower / sampleUpper of a signed float channel: -1.0 and 1.0 as IEEE bits.
const FLOAT_LOWER: u32 = 0xBF80_0000;
const FLOAT_UPPER: u32 = 0x3F80_0000;

/// The Data Format Descriptor for `format`, including its leading total-size word.
pub fn data_format_descriptor(format: PixelFormat) -> Vec<u8> {
    let channels = format.channels() as u32;
    let bits = format.channel_bytes() * 8;
    let mut words: Vec<u32> = vec![
        0, // vendorId = Khronos, descriptorType = basic
        KHR_DF_VERSION | ((24 + 16 * channels) << 16),
        KHR_DF_MODEL_RGBSDA | (KHR_DF_PRIMARIES_BT709 << 8) | (KHR_DF_TRANSFER_LINEAR << 16),
        0,                    // texelBlockDimension 1×1×1×1 (stored minus one)
        format.texel_bytes(), // bytesPlane0
        0,
    ];
    for c in 0..channels {
        let channel_id = if c == 3 { KHR_DF_CHANNEL_ALPHA } else { c };
        let channel_type =
            channel_id | KHR_DF_SAMPLE_DATATYPE_FLOAT | KHR_DF_SAMPLE_DATATYPE_SIGNED;
        words.push((c * bits) | ((bits - 1) << 16) | (channel_type << 24));
        words.push(0); // sample position
        words.push(FLOAT_LOWER);
        words.push(FLOAT_UPPER);
    }
    let total = 4 + 4 * words.len() as u32;
    std::iter::once(total)
        .chain(words)
        .flat_map(u32::to_le_bytes)
        .collect()
}

fn key_value(key: &str, value: &str) -> Vec<u8> {
    let mut kv = Vec::new();
    kv.extend_from_slice(key.as_bytes());
    kv.push(0);
    kv.extend_from_slice(value.as_bytes());
    kv.push(0);
    let mut out = (kv.len() as u32).to_le_bytes().to_vec();
    out.extend(kv);
    while !out.len().is_multiple_of(4) {
        out.push(0);
    }
    out
}

fn lcm(a: usize, b: usize) -> usize {
    fn gcd(a: usize, b: usize) -> usize {
        if b == 0 {
            a
        } else {
            gcd(b, a % b)
        }
    }
    a / gcd(a, b) * b
}

/// Serialises `tex` as a KTX2 file (no supercompression).
pub fn encode(tex: &EncodedTexture) -> Vec<u8> {
    let level_count = tex.levels.len();
    let header_len = 80 + 24 * level_count;
    let dfd = data_format_descriptor(tex.format);
    let kvd = key_value("KTXwriter", concat!("splitsum ", env!("CARGO_PKG_VERSION")));
    let dfd_offset = header_len;
    let kvd_offset = dfd_offset + dfd.len();
    let mut out = Vec::new();
    out.extend_from_slice(&IDENTIFIER);
    for v in [
        tex.format.vk_format(),
        tex.format.channel_bytes(), // typeSize
        tex.width,
        tex.height,
        0, // pixelDepth
        0, // layerCount
        tex.faces,
        level_count as u32,
        0, // supercompressionScheme
        dfd_offset as u32,
        dfd.len() as u32,
        kvd_offset as u32,
        kvd.len() as u32,
    ] {
        out.extend_from_slice(&v.to_le_bytes());
    }
    out.extend_from_slice(&0u64.to_le_bytes()); // sgdByteOffset
    out.extend_from_slice(&0u64.to_le_bytes()); // sgdByteLength
                                                // Level data placement: smallest level first, each aligned.
    let align = lcm(tex.format.texel_bytes() as usize, 4);
    let mut offsets = vec![0usize; level_count];
    let mut cursor = kvd_offset + kvd.len();
    for m in (0..level_count).rev() {
        cursor = cursor.next_multiple_of(align);
        offsets[m] = cursor;
        cursor += tex.levels[m].len();
    }
    for (level, offset) in tex.levels.iter().zip(&offsets) {
        let len = level.len() as u64;
        out.extend_from_slice(&(*offset as u64).to_le_bytes());
        out.extend_from_slice(&len.to_le_bytes());
        out.extend_from_slice(&len.to_le_bytes()); // uncompressedByteLength
    }
    out.extend_from_slice(&dfd);
    out.extend_from_slice(&kvd);
    for m in (0..level_count).rev() {
        out.resize(offsets[m], 0);
        out.extend_from_slice(&tex.levels[m]);
    }
    out
}
