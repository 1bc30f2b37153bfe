//! KTX 2.0 cubemaps (Khronos KTX File Format Specification 2.0). The writer: header, level
//! index, a Khronos Basic Data Format Descriptor, a `KTXwriter` key/value entry, and the
//! mip levels stored smallest first, each aligned to lcm(texel size, 4), optionally
//! Zstandard supercompressed level by level. The reader (through the `ktx2` crate): a
//! cube in one of splitsum's formats, level 0 or the whole chain.

use std::path::Path;

use super::format::{EncodedTexture, PixelFormat};
use super::limits::{check_cube_level0, check_dimensions};
use super::read_file;
use crate::environment::Cubemap;
use crate::{Error, Result};

/// The 12-byte KTX 2.0 file identifier.
pub const IDENTIFIER: [u8; 12] = [
    0xAB, 0x4B, 0x54, 0x58, 0x20, 0x32, 0x30, 0xBB, 0x0D, 0x0A, 0x1A, 0x0A,
];

// Khronos Data Format Specification 1.3, section 5 ("basic" descriptor block).
const KHR_DF_MODEL_RGBSDA: u32 = 1;
const KHR_DF_MODEL_BC6H: u32 = 133;
/// The one channel of a BC6H block (KDF 1.3, "BC6H").
const KHR_DF_CHANNEL_BC6H_COLOR: u32 = 0;
const KHR_DF_MODEL_ASTC: u32 = 162;
/// The one channel of an ASTC block (KDF 1.3, "ASTC").
const KHR_DF_CHANNEL_ASTC_DATA: u32 = 0;
const KHR_DF_PRIMARIES_BT709: u32 = 1;
const KHR_DF_TRANSFER_LINEAR: u32 = 1;
const KHR_DF_VERSION: u32 = 2;
const KHR_DF_SAMPLE_DATATYPE_FLOAT: u32 = 0x80;
const KHR_DF_SAMPLE_DATATYPE_SIGNED: u32 = 0x40;
const KHR_DF_SAMPLE_DATATYPE_EXPONENT: u32 = 0x20;
const KHR_DF_CHANNEL_R: u32 = 0;
const KHR_DF_CHANNEL_G: u32 = 1;
const KHR_DF_CHANNEL_B: u32 = 2;
const KHR_DF_CHANNEL_ALPHA: u32 = 15;
/// sampleLower / sampleUpper of float channels: −1.0 and 1.0 as IEEE bits.
const FLOAT_MINUS_ONE: u32 = 0xBF80_0000;
const FLOAT_ONE: u32 = 0x3F80_0000;
/// E5B9G9R9 (KDF 1.3 "Shared exponent" example; Khronos dfdutils): mantissa samples span
/// 0..8448 (= 2⁹ · 16.5, the mantissa's range through the exponent bias), exponent samples
/// carry the bias 15 and the maximum 31.
const RGB9E5_MANTISSA_UPPER: u32 = 8448;
const RGB9E5_EXPONENT_BIAS: u32 = 15;
const RGB9E5_EXPONENT_MAX: u32 = 31;

/// Supercompression scheme number of Zstandard (KTX 2.0, section 3.9).
pub const SUPERCOMPRESSION_ZSTD: u32 = 2;

/// One DFD sample: (bit offset, bit length, channel type with qualifiers, lower, upper).
type Sample = (u32, u32, u32, u32, u32);

fn samples(format: PixelFormat) -> Vec<Sample> {
    let float_signed = KHR_DF_SAMPLE_DATATYPE_FLOAT | KHR_DF_SAMPLE_DATATYPE_SIGNED;
    let float_channels = |count: u32, bits: u32| -> Vec<Sample> {
        (0..count)
            .map(|c| {
                let id = [
                    KHR_DF_CHANNEL_R,
                    KHR_DF_CHANNEL_G,
                    KHR_DF_CHANNEL_B,
                    KHR_DF_CHANNEL_ALPHA,
                ][c as usize];
                (
                    c * bits,
                    bits,
                    id | float_signed,
                    FLOAT_MINUS_ONE,
                    FLOAT_ONE,
                )
            })
            .collect()
    };
    match format {
        PixelFormat::Rg16f => float_channels(2, 16),
        PixelFormat::Rg32f => float_channels(2, 32),
        PixelFormat::Rgba16f => float_channels(4, 16),
        PixelFormat::Rgba32f => float_channels(4, 32),
        PixelFormat::Rg11b10f => [
            (0, 11, KHR_DF_CHANNEL_R),
            (11, 11, KHR_DF_CHANNEL_G),
            (22, 10, KHR_DF_CHANNEL_B),
        ]
        .into_iter()
        .map(|(off, len, id)| (off, len, id | KHR_DF_SAMPLE_DATATYPE_FLOAT, 0, FLOAT_ONE))
        .collect(),
        PixelFormat::Rgb9e5 => [KHR_DF_CHANNEL_R, KHR_DF_CHANNEL_G, KHR_DF_CHANNEL_B]
            .into_iter()
            .enumerate()
            .flat_map(|(i, id)| {
                [
                    (9 * i as u32, 9, id, 0, RGB9E5_MANTISSA_UPPER),
                    (
                        27,
                        5,
                        id | KHR_DF_SAMPLE_DATATYPE_EXPONENT,
                        RGB9E5_EXPONENT_BIAS,
                        RGB9E5_EXPONENT_MAX,
                    ),
                ]
            })
            .collect(),
        // One sample for the whole 128-bit block, unsigned float with the 0.0 and 1.0 limits
        // of KTX-Software's descriptor for VK_FORMAT_BC6H_UFLOAT_BLOCK.
        PixelFormat::Bc6h => vec![(
            0,
            128,
            KHR_DF_CHANNEL_BC6H_COLOR | KHR_DF_SAMPLE_DATATYPE_FLOAT,
            0,
            FLOAT_ONE,
        )],
        // One sample for the whole block; the HDR (SFLOAT) formats qualify it float and
        // signed with the limits −1.0 and 1.0, as the KTX 2.0 specification's ASTC
        // descriptors and KTX-Software's createDFDCompressed write them.
        PixelFormat::Astc4x4Hdr | PixelFormat::Astc6x6Hdr => vec![(
            0,
            128,
            KHR_DF_CHANNEL_ASTC_DATA | float_signed,
            FLOAT_MINUS_ONE,
            FLOAT_ONE,
        )],
    }
}

/// The Data Format Descriptor for `format`, including its leading total-size word.
pub fn data_format_descriptor(format: PixelFormat) -> Vec<u8> {
    let samples = samples(format);
    // 1×1×1×1 texels, or a block's footprint (each dimension stored minus one).
    let model = match format {
        PixelFormat::Bc6h => KHR_DF_MODEL_BC6H,
        PixelFormat::Astc4x4Hdr | PixelFormat::Astc6x6Hdr => KHR_DF_MODEL_ASTC,
        _ => KHR_DF_MODEL_RGBSDA,
    };
    let block = format
        .block_footprint()
        .map_or(0, |(w, h)| (w - 1) | ((h - 1) << 8));
    let mut words: Vec<u32> = vec![
        0, // vendorId = Khronos, descriptorType = basic
        KHR_DF_VERSION | ((24 + 16 * samples.len() as u32) << 16),
        model | (KHR_DF_PRIMARIES_BT709 << 8) | (KHR_DF_TRANSFER_LINEAR << 16),
        block,                // texelBlockDimension (each stored minus one)
        format.texel_bytes(), // bytesPlane0: a texel's, or a block's
        0,
    ];
    for (offset, len, channel_type, lower, upper) in samples {
        words.push(offset | ((len - 1) << 16) | (channel_type << 24));
        words.push(0); // sample position
        words.push(lower);
        words.push(upper);
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

/// Serialises `tex` as a KTX2 file; with `zstd_level`, each mip level is compressed
/// separately with Zstandard (supercompression scheme 2).
pub fn encode(tex: &EncodedTexture, zstd_level: Option<i32>) -> std::io::Result<Vec<u8>> {
    let level_count = tex.levels.len();
    let compressed: Vec<Vec<u8>> = match zstd_level {
        Some(level) => tex
            .levels
            .iter()
            .map(|l| zstd::bulk::compress(l, level))
            .collect::<std::io::Result<_>>()?,
        None => Vec::new(),
    };
    let stored: Vec<&Vec<u8>> = if zstd_level.is_some() {
        compressed.iter().collect()
    } else {
        tex.levels.iter().collect()
    };
    let header_len = 80 + 24 * level_count;
    let dfd = data_format_descriptor(tex.format);
    let kvd = key_value("KTXwriter", concat!("splitsum ", env!("CARGO_PKG_VERSION")));
    let dfd_offset = header_len;
    let kvd_offset = dfd_offset + dfd.len();
    let mut out = Vec::new();
    out.extend_from_slice(&IDENTIFIER);
    for v in [
        tex.format.vk_format(),
        tex.format.type_size(), // typeSize
        tex.width,
        tex.height,
        0, // pixelDepth
        0, // layerCount
        tex.faces,
        level_count as u32,
        if zstd_level.is_some() {
            SUPERCOMPRESSION_ZSTD
        } else {
            0
        },
        dfd_offset as u32,
        dfd.len() as u32,
        kvd_offset as u32,
        kvd.len() as u32,
    ] {
        out.extend_from_slice(&v.to_le_bytes());
    }
    out.extend_from_slice(&0u64.to_le_bytes()); // sgdByteOffset
    out.extend_from_slice(&0u64.to_le_bytes()); // sgdByteLength
                                                // Level data placement: smallest level first, each aligned to lcm(texel size, 4)
                                                // (to 1 when supercompressed).
    let align = if zstd_level.is_some() {
        1
    } else {
        lcm(tex.format.texel_bytes() as usize, 4)
    };
    let mut offsets = vec![0usize; level_count];
    let mut cursor = kvd_offset + kvd.len();
    for m in (0..level_count).rev() {
        cursor = cursor.next_multiple_of(align);
        offsets[m] = cursor;
        cursor += stored[m].len();
    }
    for m in 0..level_count {
        out.extend_from_slice(&(offsets[m] as u64).to_le_bytes());
        out.extend_from_slice(&(stored[m].len() as u64).to_le_bytes());
        out.extend_from_slice(&(tex.levels[m].len() as u64).to_le_bytes()); // uncompressedByteLength
    }
    out.extend_from_slice(&dfd);
    out.extend_from_slice(&kvd);
    for m in (0..level_count).rev() {
        out.resize(offsets[m], 0);
        out.extend_from_slice(stored[m]);
    }
    Ok(out)
}

/// Refuses DFDs the `ktx2` crate (0.5) would panic on instead of erroring: a basic block
/// whose texelBlockDimension byte is 255 (a fuzzing find, kept in tests/fuzz_regressions.rs).
fn precheck_ktx2_dfd(bytes: &[u8]) -> std::result::Result<(), String> {
    let word = |at: usize| -> Option<u32> {
        Some(u32::from_le_bytes(bytes.get(at..at + 4)?.try_into().ok()?))
    };
    let (Some(offset), Some(length)) = (word(48), word(52)) else {
        return Err("too short for a KTX2 header".into());
    };
    let (start, end) = (offset as usize, offset as usize + length as usize);
    if end > bytes.len() || length < 4 {
        return Err("the data format descriptor lies outside the file".into());
    }
    let mut block = start + 4;
    while block + 16 <= end {
        let (Some(kind), Some(version)) = (word(block), word(block + 4)) else {
            break;
        };
        let size = (version >> 16) as usize;
        if kind == 0 && bytes[block + 12..block + 16].contains(&255) {
            return Err(
                "the data format descriptor's texel block dimensions are out of range".into(),
            );
        }
        if size == 0 {
            break;
        }
        block += size;
    }
    Ok(())
}

/// Reads level 0 of a KTX2 cubemap in one of splitsum's formats.
pub fn read_cube(path: &Path) -> Result<Cubemap> {
    decode_cube(path, &read_file(path)?)
}

/// Decodes level 0 of a KTX2 cubemap from `bytes` (`path` names it in errors).
pub fn decode_cube(path: &Path, bytes: &[u8]) -> Result<Cubemap> {
    decode_ktx2_levels(path, bytes, 1)
}

/// Reads every level of a KTX2 cubemap (a prefiltered chain, as `bake` writes it).
pub fn read_cube_chain(path: &Path) -> Result<Cubemap> {
    decode_ktx2_levels(path, &read_file(path)?, u32::MAX)
}

/// Decodes the first `max_levels` levels of a KTX2 cubemap from `bytes`; each level must
/// be the full mip size of level 0 (a chain may stop before 1×1).
fn decode_ktx2_levels(path: &Path, bytes: &[u8], max_levels: u32) -> Result<Cubemap> {
    const F: &str = "KTX2";
    let bad = |message: String| Error::Decode {
        path: path.to_path_buf(),
        format: F,
        message,
    };
    precheck_ktx2_dfd(bytes).map_err(bad)?;
    let reader = ::ktx2::Reader::new(bytes).map_err(|e| bad(e.to_string()))?;
    let h = reader.header();
    let unsupported = |message: String| Error::UnsupportedInput {
        path: path.to_path_buf(),
        message,
    };
    if h.face_count != 6
        || h.pixel_width != h.pixel_height
        || h.pixel_depth > 1
        || h.layer_count > 1
    {
        return Err(unsupported(format!(
            "KTX2 texture is {}×{} with {} faces; a cubemap (6 square faces) is expected",
            h.pixel_width, h.pixel_height, h.face_count
        )));
    }
    let vk = h.format.map(|f| f.value()).unwrap_or(0);
    let pf = PixelFormat::from_vk_format(vk)
        .filter(|f| f.texel_bytes() >= 4 && !matches!(f, PixelFormat::Rg16f | PixelFormat::Rg32f))
        .ok_or_else(|| {
            unsupported(format!(
                "KTX2 format {:?} is not one splitsum reads (rgba16f, rgba32f, rgb9e5, rg11b10f, bc6h, astc-4x4-hdr, astc-6x6-hdr)",
                h.format
            ))
        })?;
    let n0 = h.pixel_width;
    check_dimensions(path, n0, n0)?;
    let mut levels = Vec::new();
    for (m, level) in reader.levels().enumerate().take(max_levels as usize) {
        let n = (n0 >> m).max(1);
        let exact = 6 * pf.image_bytes(n, n);
        let data = match h.supercompression_scheme {
            None => level.data.to_vec(),
            Some(::ktx2::SupercompressionScheme::Zstandard) => {
                // The header's uncompressed length must be exactly the level's size: it
                // sizes the decompression buffer, so an absurd value must never reach the
                // allocator.
                if level.uncompressed_byte_length != exact as u64 {
                    let (claimed, format) = (level.uncompressed_byte_length, pf.name());
                    return Err(bad(format!(
                        "level {m} claims {claimed} uncompressed bytes; a {n}×{n} {format} cube has {exact}"
                    )));
                }
                zstd::bulk::decompress(level.data, exact).map_err(|e| bad(format!("zstd: {e}")))?
            }
            Some(other) => {
                return Err(unsupported(format!(
                    "KTX2 supercompression {other:?} is not supported"
                )))
            }
        };
        if m == 0 {
            check_cube_level0(path, F, n, data.len(), pf)?;
        } else if data.len() < exact {
            return Err(bad(format!(
                "level {m} holds {} bytes, {exact} expected (truncated?)",
                data.len()
            )));
        }
        levels.push(pf.decode_faces(&data[..exact], n, 6));
    }
    if levels.is_empty() {
        return Err(bad("no mip levels".into()));
    }
    Ok(Cubemap { size: n0, levels })
}
