//! KTX 1.1 reader and writer (Khronos, "KTX File Format Specification", version 1.1) for
//! the cubemaps Filament loads: its `Ktx1Reader` (`Engine.createIblFromKtx1`,
//! `createSkyFromKtx1`) reads what cmgen writes, a non-array cubemap whose levels are
//! stored largest first, each as `imageSize` (the bytes of one face) followed by the six
//! faces +X, −X, +Y, −Y, +Z, −Z, rows top to bottom, with key/value data such as cmgen's
//! `sh` (the SH as text).
//!
//! One departure from the specification, for Filament: cmgen writes, and Filament's
//! `Ktx1Reader::toPixelDataType` reads, `GL_R11F_G11F_B10F` (0x8C3A) as the `glType` of
//! R11F_G11F_B10F texels, where the specification wants `GL_UNSIGNED_INT_10F_11F_11F_REV`
//! (0x8C3B); Filament maps only the former to its packed pixel type, so splitsum writes it.
//! The reader takes both.

use std::path::Path;

use super::format::{EncodedTexture, PixelFormat};
use crate::environment::Cubemap;
use crate::math::cubemap::FACES;
use crate::{Error, Result};

/// The 12-byte KTX 1.1 file identifier («KTX 11»\r\n\x1A\n).
pub const IDENTIFIER: [u8; 12] = [
    0xAB, 0x4B, 0x54, 0x58, 0x20, 0x31, 0x31, 0xBB, 0x0D, 0x0A, 0x1A, 0x0A,
];
/// Written in the file's byte order: reads back as this in a matching one.
const ENDIANNESS: u32 = 0x0403_0201;
/// Bytes of the header: identifier and 13 words.
const HEADER_BYTES: usize = 64;

// OpenGL enums (the OpenGL ES 3.0 headers).
const GL_HALF_FLOAT: u32 = 0x140B;
const GL_FLOAT: u32 = 0x1406;
const GL_RGB: u32 = 0x1907;
const GL_RGBA: u32 = 0x1908;
const GL_R11F_G11F_B10F: u32 = 0x8C3A;
const GL_UNSIGNED_INT_10F_11F_11F_REV: u32 = 0x8C3B;
const GL_RGBA16F: u32 = 0x881A;
const GL_RGBA32F: u32 = 0x8814;
/// `GL_COMPRESSED_RGB_BPTC_UNSIGNED_FLOAT` (ARB_texture_compression_bptc): BC6H unsigned.
const GL_COMPRESSED_RGB_BPTC_UNSIGNED_FLOAT: u32 = 0x8E8F;

/// The OpenGL description of a pixel format in a KTX 1 header.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct GlFormat {
    /// `glType` (0 for compressed formats).
    pub gl_type: u32,
    /// `glTypeSize`: the unit of endianness conversion.
    pub type_size: u32,
    /// `glFormat`: the unsized format.
    pub format: u32,
    /// `glInternalFormat`: the sized format.
    pub internal_format: u32,
    /// `glBaseInternalFormat`.
    pub base_internal_format: u32,
}

/// Whether `format` can be stored in KTX 1 for Filament ([`gl_format`]).
pub fn holds(format: PixelFormat) -> bool {
    gl_format(format).is_some()
}

/// The KTX 1 description of `format`; `None` for formats Filament cannot load from KTX 1
/// (RGB9_E5: its reader has no pixel type for `GL_UNSIGNED_INT_5_9_9_9_REV`) and for the
/// two-channel LUT formats, and for ASTC HDR, which splitsum writes only as KTX2 (GL
/// names ASTC's LDR and HDR data by the same internal formats, and no Filament check here
/// can render ASTC). BC6H is a compressed format: `glType`, `glTypeSize` 1 and
/// `glFormat` 0 as the specification wants, which Filament's reader maps to
/// `RGB_BPTC_UNSIGNED_FLOAT` (desktop GL and WebGL with `EXT_texture_compression_bptc`).
pub fn gl_format(format: PixelFormat) -> Option<GlFormat> {
    match format {
        PixelFormat::Bc6h => Some(GlFormat {
            gl_type: 0,
            type_size: 1,
            format: 0,
            internal_format: GL_COMPRESSED_RGB_BPTC_UNSIGNED_FLOAT,
            base_internal_format: GL_RGB,
        }),
        PixelFormat::Rg11b10f => Some(GlFormat {
            gl_type: GL_R11F_G11F_B10F, // cmgen's value, see the module documentation
            type_size: 4,
            format: GL_RGB,
            internal_format: GL_R11F_G11F_B10F,
            base_internal_format: GL_RGB,
        }),
        PixelFormat::Rgba16f => Some(GlFormat {
            gl_type: GL_HALF_FLOAT,
            type_size: 2,
            format: GL_RGBA,
            internal_format: GL_RGBA16F,
            base_internal_format: GL_RGBA,
        }),
        PixelFormat::Rgba32f => Some(GlFormat {
            gl_type: GL_FLOAT,
            type_size: 4,
            format: GL_RGBA,
            internal_format: GL_RGBA32F,
            base_internal_format: GL_RGBA,
        }),
        PixelFormat::Rgb9e5
        | PixelFormat::Rg16f
        | PixelFormat::Rg32f
        | PixelFormat::Astc4x4Hdr
        | PixelFormat::Astc6x6Hdr => None,
    }
}

/// The pixel format a header describes, if splitsum reads it.
fn pixel_format(h: &GlFormat) -> Option<PixelFormat> {
    match (h.internal_format, h.gl_type) {
        (GL_R11F_G11F_B10F, GL_R11F_G11F_B10F | GL_UNSIGNED_INT_10F_11F_11F_REV) => {
            Some(PixelFormat::Rg11b10f)
        }
        (GL_RGBA16F, GL_HALF_FLOAT) => Some(PixelFormat::Rgba16f),
        (GL_RGBA32F, GL_FLOAT) => Some(PixelFormat::Rgba32f),
        (GL_COMPRESSED_RGB_BPTC_UNSIGNED_FLOAT, 0) => Some(PixelFormat::Bc6h),
        _ => None,
    }
}

/// Pads `v` with zeros to a multiple of 4 bytes.
fn pad4(v: &mut Vec<u8>) {
    v.resize(v.len().next_multiple_of(4), 0);
}

/// Serialises a cubemap or 2D texture as KTX 1.1 with `key_values` (each value written as
/// given; text should end in a NUL, as the specification recommends). Errors name what
/// KTX 1 cannot hold for Filament.
pub fn encode(
    tex: &EncodedTexture,
    key_values: &[(&str, &[u8])],
) -> std::result::Result<Vec<u8>, String> {
    let gl = gl_format(tex.format).ok_or_else(|| {
        format!(
            "{} cannot be written as KTX 1 for Filament (its KTX 1 reader takes rg11b10f, rgba16f, rgba32f and bc6h)",
            tex.format.name()
        )
    })?;
    let mut kvd = Vec::new();
    for (key, value) in key_values {
        let size = key.len() + 1 + value.len();
        kvd.extend_from_slice(&(size as u32).to_le_bytes());
        kvd.extend_from_slice(key.as_bytes());
        kvd.push(0);
        kvd.extend_from_slice(value);
        pad4(&mut kvd); // valuePadding
    }
    let mut out = Vec::new();
    out.extend_from_slice(&IDENTIFIER);
    for v in [
        ENDIANNESS,
        gl.gl_type,
        gl.type_size,
        gl.format,
        gl.internal_format,
        gl.base_internal_format,
        tex.width,
        tex.height,
        0, // pixelDepth: a 2D or cube texture
        0, // numberOfArrayElements: not an array
        tex.faces,
        tex.levels.len() as u32,
        kvd.len() as u32,
    ] {
        out.extend_from_slice(&v.to_le_bytes());
    }
    out.extend_from_slice(&kvd);
    for level in &tex.levels {
        let face_bytes = level.len() / tex.faces as usize;
        // Rows of every format written here are whole 4-byte words (a BC6H block row 16
        // bytes a block), so the specification's row padding (GL_UNPACK_ALIGNMENT 4),
        // cubePadding and mipPadding are all empty.
        debug_assert!(face_bytes.is_multiple_of(4));
        // For a non-array cubemap imageSize is the size of one face.
        out.extend_from_slice(&(face_bytes as u32).to_le_bytes());
        out.extend_from_slice(level);
    }
    Ok(out)
}

/// A KTX 1 file as read: its format, size, key/value pairs and levels (each the
/// concatenation of its faces, largest level first).
#[derive(Clone, Debug)]
pub struct Ktx1 {
    /// The header's OpenGL format words.
    pub gl: GlFormat,
    /// Width of level 0.
    pub width: u32,
    /// Height of level 0.
    pub height: u32,
    /// 1 or 6.
    pub faces: u32,
    /// Key/value pairs in file order (values as stored, padding removed; the tests read
    /// Filament's SH from them).
    #[cfg_attr(not(feature = "internals"), allow(dead_code))]
    pub key_values: Vec<(String, Vec<u8>)>,
    /// Levels, largest first.
    pub levels: Vec<Vec<u8>>,
}

impl Ktx1 {
    /// The value of `key`, if present.
    #[cfg(any(test, feature = "internals"))]
    pub fn value(&self, key: &str) -> Option<&[u8]> {
        self.key_values
            .iter()
            .find(|(k, _)| k == key)
            .map(|(_, v)| v.as_slice())
    }
}

/// A little-endian word reader over `bytes` that reports truncation.
struct Words<'a> {
    bytes: &'a [u8],
    pos: usize,
}

impl Words<'_> {
    fn take(&mut self, n: usize, what: &str) -> std::result::Result<&[u8], String> {
        let end = self
            .pos
            .checked_add(n)
            .filter(|&e| e <= self.bytes.len())
            .ok_or_else(|| format!("truncated in {what} (byte {})", self.pos))?;
        let s = &self.bytes[self.pos..end];
        self.pos = end;
        Ok(s)
    }

    fn u32(&mut self, what: &str) -> std::result::Result<u32, String> {
        let b = self.take(4, what)?;
        Ok(u32::from_le_bytes([b[0], b[1], b[2], b[3]]))
    }
}

/// Parses a KTX 1.1 file (little-endian, uncompressed, not an array or 3D texture).
pub fn decode(bytes: &[u8]) -> std::result::Result<Ktx1, String> {
    if bytes.len() < HEADER_BYTES || bytes[..12] != IDENTIFIER {
        return Err("not a KTX 1.1 file (no KTX 11 identifier)".into());
    }
    let mut r = Words { bytes, pos: 12 };
    let endianness = r.u32("the header")?;
    if endianness != ENDIANNESS {
        return Err(format!(
            "endianness word {endianness:#010x}: only little-endian files are read"
        ));
    }
    let mut w = [0u32; 12];
    for v in &mut w {
        *v = r.u32("the header")?;
    }
    let [gl_type, type_size, format, internal_format, base_internal_format, width, height, depth, array, faces, levels, kv_bytes] =
        w;
    let gl = GlFormat {
        gl_type,
        type_size,
        format,
        internal_format,
        base_internal_format,
    };
    if (gl_type == 0 || format == 0) && internal_format != GL_COMPRESSED_RGB_BPTC_UNSIGNED_FLOAT {
        return Err(format!(
            "compressed format {internal_format:#x}: of the compressed formats only BPTC unsigned float (BC6H) is read"
        ));
    }
    if depth > 1 || array > 0 {
        return Err(format!(
            "a 3D or array texture (depth {depth}, {array} array elements): only 2D and cube textures are read"
        ));
    }
    if faces != 1 && faces != 6 {
        return Err(format!("{faces} faces: 1 or 6 expected"));
    }
    if width == 0 || height == 0 || width > 1 << 16 || height > 1 << 16 {
        return Err(format!("size {width}×{height} is out of range"));
    }
    let levels = levels.max(1);
    if levels > 17 {
        return Err(format!(
            "{levels} mip levels: at most 17 for a 65536 texture"
        ));
    }
    let mut key_values = Vec::new();
    let kv = r.take(kv_bytes as usize, "the key/value data")?;
    let mut k = Words { bytes: kv, pos: 0 };
    while k.pos < kv.len() {
        let size = k.u32("a key/value pair")? as usize;
        let pair = k.take(size, "a key/value pair")?;
        let nul = pair
            .iter()
            .position(|&b| b == 0)
            .ok_or("a key without its NUL terminator")?;
        key_values.push((
            String::from_utf8_lossy(&pair[..nul]).into_owned(),
            pair[nul + 1..].to_vec(),
        ));
        k.take(size.next_multiple_of(4) - size, "key/value padding")?;
    }
    let mut out = Vec::with_capacity(levels as usize);
    for m in 0..levels {
        let face_bytes = r.u32("a level's imageSize")? as usize;
        // The claimed size sizes the allocation: it must fit in what the file still holds
        // (a fuzzing find: an imageSize of 2 GB in a 6 kB file).
        let claimed = face_bytes.saturating_mul(faces as usize);
        if claimed > r.bytes.len() - r.pos {
            return Err(format!(
                "level {m} claims {claimed} bytes; the file holds {} more (truncated?)",
                r.bytes.len() - r.pos
            ));
        }
        let mut level = Vec::with_capacity(claimed);
        for _ in 0..faces {
            level.extend_from_slice(r.take(face_bytes, &format!("level {m}"))?);
            r.take(face_bytes.next_multiple_of(4) - face_bytes, "cube padding")?;
        }
        out.push(level);
    }
    Ok(Ktx1 {
        gl,
        width,
        height,
        faces,
        key_values,
        levels: out,
    })
}

/// Decodes a KTX 1 cubemap with every level (rg11b10f, rgba16f or rgba32f texels, as
/// splitsum and cmgen write them); errors name `path`.
pub fn decode_cube(path: &Path, bytes: &[u8]) -> Result<Cubemap> {
    let bad = |message: String| Error::Decode {
        path: path.to_path_buf(),
        format: "KTX 1",
        message,
    };
    let ktx = decode(bytes).map_err(bad)?;
    if ktx.faces != FACES as u32 || ktx.width != ktx.height {
        return Err(bad(format!(
            "a {}×{} texture with {} faces, not a cubemap",
            ktx.width, ktx.height, ktx.faces
        )));
    }
    super::limits::check_dimensions(path, ktx.width, ktx.height)?;
    let format = pixel_format(&ktx.gl).ok_or_else(|| {
        bad(format!(
            "glInternalFormat {:#x} with glType {:#x}: splitsum reads R11F_G11F_B10F, RGBA16F, RGBA32F and BPTC unsigned float",
            ktx.gl.internal_format, ktx.gl.gl_type
        ))
    })?;
    let mut levels = Vec::with_capacity(ktx.levels.len());
    for (m, bytes) in ktx.levels.iter().enumerate() {
        let n = (ktx.width >> m).max(1);
        let expected = FACES * format.image_bytes(n, n);
        if bytes.len() != expected {
            return Err(bad(format!(
                "level {m} holds {} bytes, {expected} expected for {n}×{n} faces",
                bytes.len()
            )));
        }
        levels.push(format.decode_faces(bytes, n, FACES as u32));
    }
    Ok(Cubemap {
        size: ktx.width,
        levels,
    })
}

/// Reads a KTX 1 cubemap file ([`decode_cube`]).
pub fn read_cube(path: &Path) -> Result<Cubemap> {
    let bytes = std::fs::read(path).map_err(|e| Error::io(path, e))?;
    decode_cube(path, &bytes)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::io::cubemap::encode_texture;

    fn cube(n: u32, levels: usize) -> Cubemap {
        Cubemap {
            size: n,
            levels: (0..levels)
                .map(|m| {
                    let s = (n >> m).max(1);
                    (0..Cubemap::level_len(s))
                        .map(|i| [i as f32 * 0.25, m as f32, 1.0 / (1.0 + i as f32), 1.0])
                        .collect()
                })
                .collect(),
        }
    }

    #[test]
    fn a_cube_reads_back_with_its_key_values_in_every_format() {
        let c = cube(8, 4);
        for format in [
            PixelFormat::Rgba32f,
            PixelFormat::Rgba16f,
            PixelFormat::Rg11b10f,
        ] {
            let bytes = encode(
                &encode_texture(&c, format, &Default::default()).unwrap(),
                &[("sh", b"1 2 3\n\0"), ("odd", b"abcde")],
            )
            .unwrap();
            let ktx = decode(&bytes).unwrap();
            assert_eq!((ktx.width, ktx.faces, ktx.levels.len()), (8, 6, 4));
            assert_eq!(ktx.value("sh"), Some(&b"1 2 3\n\0"[..]));
            assert_eq!(ktx.value("odd"), Some(&b"abcde"[..]));
            let back = decode_cube(Path::new("x.ktx"), &bytes).unwrap();
            let want: Vec<Vec<[f32; 4]>> = c
                .levels
                .iter()
                .map(|l| format.decode(&format.encode(l)))
                .collect();
            assert_eq!(back.levels, want, "{format:?}");
        }
    }

    #[test]
    fn the_layout_is_the_specifications() {
        let c = cube(4, 3);
        let texture = encode_texture(&c, PixelFormat::Rg11b10f, &Default::default()).unwrap();
        let bytes = encode(&texture, &[("sh", b"x")]).unwrap();
        let word = |i: usize| u32::from_le_bytes(bytes[i..i + 4].try_into().unwrap());
        assert_eq!(&bytes[..12], &IDENTIFIER);
        assert_eq!(word(12), 0x0403_0201);
        assert_eq!(word(16), GL_R11F_G11F_B10F, "glType as cmgen writes it");
        assert_eq!(word(24), GL_RGB, "glFormat");
        assert_eq!(word(28), GL_R11F_G11F_B10F, "glInternalFormat");
        assert_eq!((word(36), word(40), word(52)), (4, 4, 6), "4×4, 6 faces");
        assert_eq!(word(56), 3, "levels");
        // "sh\0x" is 4 bytes: size word + 4, no padding.
        assert_eq!(word(60), 8);
        assert_eq!(word(64), 4);
        // Level 0: imageSize = one face of 4×4 texels of 4 bytes.
        assert_eq!(word(72), 64);
        let total = 72 + (4 + 6 * 64) + (4 + 6 * 16) + (4 + 6 * 4);
        assert_eq!(bytes.len(), total);
    }

    #[test]
    fn bad_files_are_errors_not_panics() {
        let good = encode(&encode_texture(&cube(4, 2), PixelFormat::Rgba16f, &Default::default()).unwrap(), &[]).unwrap();
        for cut in [0, 11, 40, 64, 70, good.len() - 1] {
            assert!(
                decode_cube(Path::new("x.ktx"), &good[..cut]).is_err(),
                "{cut}"
            );
        }
        let mut big_endian = good.clone();
        big_endian[12..16].copy_from_slice(&ENDIANNESS.to_be_bytes());
        let e = decode(&big_endian).unwrap_err();
        assert!(e.contains("little-endian"), "{e}");
        let mut huge_kv = good.clone();
        huge_kv[60..64].copy_from_slice(&u32::MAX.to_le_bytes());
        assert!(decode(&huge_kv).is_err());
        assert!(encode(&encode_texture(&cube(4, 1), PixelFormat::Rgb9e5, &Default::default()).unwrap(), &[]).is_err());
    }
}
