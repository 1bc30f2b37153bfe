//! Pixel formats of the GPU-ready outputs and their encodings, with the Vulkan and DXGI
//! format numbers the KTX2 and DDS writers need.

use half::f16;

/// A pixel format splitsum writes.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum PixelFormat {
    /// Two 16-bit floats (R, G): LUTs.
    Rg16f,
    /// Two 32-bit floats (R, G): LUTs with `--f32`.
    Rg32f,
    /// Four 16-bit floats (A = 1).
    Rgba16f,
    /// Four 32-bit floats (A = 1).
    Rgba32f,
    /// Shared-exponent RGB, 9-bit mantissas and a 5-bit exponent in 32 bits.
    Rgb9e5,
    /// Unsigned floats: R and G with 6-bit mantissas, B with 5, 5-bit exponents, 32 bits.
    Rg11b10f,
    /// BC6H unsigned float (BPTC): 4×4 texels in 16 bytes, half-float endpoints; encoded
    /// by a backend (`plan::bc6h`), decoded here.
    Bc6h,
    /// ASTC HDR at 4×4 texels a 16-byte block (8 bits a texel): half-float results, encoded
    /// by astc-encoder (`plan::astc`), decoded by splitsum's own decoder (`io::astc`).
    Astc4x4Hdr,
    /// ASTC HDR at 6×6 texels a 16-byte block (3.56 bits a texel).
    Astc6x6Hdr,
}

/// The pixel formats a cubemap can be written in, by their command-line names.
pub const CUBE_PIXEL_FORMATS: &[(&str, PixelFormat)] = &[
    ("rgba16f", PixelFormat::Rgba16f),
    ("rgba32f", PixelFormat::Rgba32f),
    ("rgb9e5", PixelFormat::Rgb9e5),
    ("rg11b10f", PixelFormat::Rg11b10f),
    ("bc6h", PixelFormat::Bc6h),
    ("astc-4x4-hdr", PixelFormat::Astc4x4Hdr),
    ("astc-6x6-hdr", PixelFormat::Astc6x6Hdr),
];

impl PixelFormat {
    /// What it stores, in a line (with its Vulkan name).
    pub fn description(self) -> &'static str {
        match self {
            PixelFormat::Bc6h => "BC6H unsigned float, 1 byte a texel in the file and in video memory (BC6H_UFLOAT_BLOCK)",
            PixelFormat::Astc4x4Hdr => "ASTC HDR 4×4, 1 byte a texel in the file and in video memory, for phones and Apple GPUs (ASTC_4x4_SFLOAT_BLOCK)",
            PixelFormat::Astc6x6Hdr => "ASTC HDR 6×6, 0.44 bytes a texel in the file and in video memory, for phones and Apple GPUs (ASTC_6x6_SFLOAT_BLOCK)",
            PixelFormat::Rg16f => "2 × 16-bit float (R16G16_SFLOAT)",
            PixelFormat::Rg32f => "2 × 32-bit float (R32G32_SFLOAT)",
            PixelFormat::Rgba16f => "4 × 16-bit float (R16G16B16A16_SFLOAT)",
            PixelFormat::Rgba32f => "4 × 32-bit float (R32G32B32A32_SFLOAT)",
            PixelFormat::Rgb9e5 => "shared exponent (E5B9G9R9_UFLOAT_PACK32)",
            PixelFormat::Rg11b10f => "packed unsigned floats (B10G11R11_UFLOAT_PACK32)",
        }
    }

    /// Bytes per texel, or per block for a block format ([`PixelFormat::is_block`]).
    pub fn texel_bytes(self) -> u32 {
        match self {
            PixelFormat::Rg16f | PixelFormat::Rgb9e5 | PixelFormat::Rg11b10f => 4,
            PixelFormat::Rg32f | PixelFormat::Rgba16f => 8,
            PixelFormat::Rgba32f
            | PixelFormat::Bc6h
            | PixelFormat::Astc4x4Hdr
            | PixelFormat::Astc6x6Hdr => 16,
        }
    }

    /// The texels a block holds, wide and high, for a block format (BC6H and ASTC 4×4,
    /// ASTC 6×6); `None` for a texel format.
    pub fn block_footprint(self) -> Option<(u32, u32)> {
        match self {
            PixelFormat::Bc6h | PixelFormat::Astc4x4Hdr => Some((4, 4)),
            PixelFormat::Astc6x6Hdr => Some((6, 6)),
            _ => None,
        }
    }

    /// Whether texels are stored in blocks (BC6H, ASTC).
    pub fn is_block(self) -> bool {
        self.block_footprint().is_some()
    }

    /// Whether it is one of the ASTC HDR formats.
    pub fn is_astc(self) -> bool {
        matches!(self, PixelFormat::Astc4x4Hdr | PixelFormat::Astc6x6Hdr)
    }

    /// Bytes of one `width`×`height` image.
    pub fn image_bytes(self, width: u32, height: u32) -> usize {
        match self.block_footprint() {
            Some((bw, bh)) => {
                (width.div_ceil(bw) * height.div_ceil(bh)) as usize * self.texel_bytes() as usize
            }
            None => (width * height) as usize * self.texel_bytes() as usize,
        }
    }

    /// The largest value a channel holds: texels above it are clipped to it.
    pub fn max_value(self) -> f32 {
        match self {
            PixelFormat::Rg32f | PixelFormat::Rgba32f => f32::MAX,
            PixelFormat::Rg16f
            | PixelFormat::Rgba16f
            | PixelFormat::Bc6h
            | PixelFormat::Astc4x4Hdr
            | PixelFormat::Astc6x6Hdr => f16::MAX.to_f32(),
            PixelFormat::Rgb9e5 => rgb9e5_max(),
            PixelFormat::Rg11b10f => ufloat_to_f32(0x7BF, 6).min(ufloat_to_f32(0x3DF, 5)),
        }
    }

    /// The KTX2 `typeSize`: the size of the unit to byte-swap (the channel for float
    /// formats, the whole 32-bit word for packed ones).
    pub fn type_size(self) -> u32 {
        match self {
            PixelFormat::Rg16f | PixelFormat::Rgba16f => 2,
            PixelFormat::Bc6h | PixelFormat::Astc4x4Hdr | PixelFormat::Astc6x6Hdr => 1,
            _ => 4,
        }
    }

    /// The `VkFormat` number (Vulkan spec, "Formats").
    pub fn vk_format(self) -> u32 {
        match self {
            PixelFormat::Rg16f => 83,     // VK_FORMAT_R16G16_SFLOAT
            PixelFormat::Rg32f => 103,    // VK_FORMAT_R32G32_SFLOAT
            PixelFormat::Rgba16f => 97,   // VK_FORMAT_R16G16B16A16_SFLOAT
            PixelFormat::Rgba32f => 109,  // VK_FORMAT_R32G32B32A32_SFLOAT
            PixelFormat::Rgb9e5 => 123,   // VK_FORMAT_E5B9G9R9_UFLOAT_PACK32
            PixelFormat::Rg11b10f => 122, // VK_FORMAT_B10G11R11_UFLOAT_PACK32
            PixelFormat::Bc6h => 143,     // VK_FORMAT_BC6H_UFLOAT_BLOCK
            // VK_EXT_texture_compression_astc_hdr, core in Vulkan 1.3
            PixelFormat::Astc4x4Hdr => 1_000_066_000, // VK_FORMAT_ASTC_4x4_SFLOAT_BLOCK
            PixelFormat::Astc6x6Hdr => 1_000_066_004, // VK_FORMAT_ASTC_6x6_SFLOAT_BLOCK
        }
    }

    /// The `DXGI_FORMAT` number (DXGI_FORMAT enumeration); `None` for ASTC, which Direct3D
    /// does not sample and DXGI has no HDR number for.
    pub fn dxgi_format(self) -> Option<u32> {
        Some(match self {
            PixelFormat::Rg16f => 34,    // DXGI_FORMAT_R16G16_FLOAT
            PixelFormat::Rg32f => 16,    // DXGI_FORMAT_R32G32_FLOAT
            PixelFormat::Rgba16f => 10,  // DXGI_FORMAT_R16G16B16A16_FLOAT
            PixelFormat::Rgba32f => 2,   // DXGI_FORMAT_R32G32B32A32_FLOAT
            PixelFormat::Rgb9e5 => 67,   // DXGI_FORMAT_R9G9B9E5_SHAREDEXP
            PixelFormat::Rg11b10f => 26, // DXGI_FORMAT_R11G11B10_FLOAT
            PixelFormat::Bc6h => 95,     // DXGI_FORMAT_BC6H_UF16
            PixelFormat::Astc4x4Hdr | PixelFormat::Astc6x6Hdr => return None,
        })
    }

    /// The format with this `VkFormat` number, if splitsum writes it.
    pub fn from_vk_format(vk: u32) -> Option<Self> {
        ALL.into_iter().find(|f| f.vk_format() == vk)
    }

    /// The format with this `DXGI_FORMAT` number, if splitsum writes it.
    pub fn from_dxgi_format(dxgi: u32) -> Option<Self> {
        ALL.into_iter().find(|f| f.dxgi_format() == Some(dxgi))
    }

    /// Short name used on the command line, in messages and manifests.
    pub fn name(self) -> &'static str {
        match self {
            PixelFormat::Rg16f => "rg16f",
            PixelFormat::Rg32f => "rg32f",
            PixelFormat::Rgba16f => "rgba16f",
            PixelFormat::Rgba32f => "rgba32f",
            PixelFormat::Rgb9e5 => "rgb9e5",
            PixelFormat::Rg11b10f => "rg11b10f",
            PixelFormat::Bc6h => "bc6h",
            PixelFormat::Astc4x4Hdr => "astc-4x4-hdr",
            PixelFormat::Astc6x6Hdr => "astc-6x6-hdr",
        }
    }

    /// Encodes RGBA texels of a texel format, little endian (RG formats keep R and G;
    /// packed formats RGB). Values beyond a format's range are clamped to its largest
    /// finite value (half: ±65504), never turned into infinity. A block format's images are
    /// encoded whole, by a backend (`io::cubemap::encode_texture`); here they give no
    /// bytes.
    pub fn encode(self, texels: &[[f32; 4]]) -> Vec<u8> {
        let half =
            |v: f32| f16::from_f32(v.clamp(f16::MIN.to_f32(), f16::MAX.to_f32())).to_le_bytes();
        let mut out = Vec::with_capacity(texels.len() * self.texel_bytes() as usize);
        for t in texels {
            match self {
                PixelFormat::Rg16f => t[..2].iter().for_each(|&v| out.extend(half(v))),
                PixelFormat::Rg32f => t[..2].iter().for_each(|v| out.extend(v.to_le_bytes())),
                PixelFormat::Rgba16f => t.iter().for_each(|&v| out.extend(half(v))),
                PixelFormat::Rgba32f => t.iter().for_each(|v| out.extend(v.to_le_bytes())),
                PixelFormat::Rgb9e5 => out.extend(pack_rgb9e5([t[0], t[1], t[2]]).to_le_bytes()),
                PixelFormat::Rg11b10f => {
                    out.extend(pack_rg11b10f([t[0], t[1], t[2]]).to_le_bytes())
                }
                PixelFormat::Bc6h | PixelFormat::Astc4x4Hdr | PixelFormat::Astc6x6Hdr => {
                    return Vec::new()
                }
            }
        }
        out
    }

    /// Decodes the square `n`² faces of an image (`faces` of them, one after the other)
    /// back to RGBA texels: [`PixelFormat::decode`] for a texel format, each face's blocks
    /// for a block format (`bytes` must hold [`PixelFormat::image_bytes`] per face).
    pub fn decode_faces(self, bytes: &[u8], n: u32, faces: u32) -> Vec<[f32; 4]> {
        let Some((bw, bh)) = self.block_footprint() else {
            return self.decode(bytes);
        };
        let face = self.image_bytes(n, n);
        bytes
            .chunks_exact(face)
            .take(faces as usize)
            .flat_map(|b| match self {
                PixelFormat::Bc6h => super::bc6h::decode_face(b, n),
                _ => super::astc::decode_image(b, n, n, bw, bh),
            })
            .collect()
    }

    /// Decodes texels written by [`encode`](Self::encode) back to RGBA (missing channels:
    /// 0 for B, 1 for A); a block format through [`PixelFormat::decode_faces`].
    pub fn decode(self, bytes: &[u8]) -> Vec<[f32; 4]> {
        let h = |b: &[u8]| f16::from_le_bytes([b[0], b[1]]).to_f32();
        let f = |b: &[u8]| f32::from_le_bytes([b[0], b[1], b[2], b[3]]);
        let w = |b: &[u8]| u32::from_le_bytes([b[0], b[1], b[2], b[3]]);
        bytes
            .chunks_exact(self.texel_bytes() as usize)
            .map(|b| match self {
                PixelFormat::Rg16f => [h(&b[0..]), h(&b[2..]), 0.0, 1.0],
                PixelFormat::Rg32f => [f(&b[0..]), f(&b[4..]), 0.0, 1.0],
                PixelFormat::Rgba16f => [h(&b[0..]), h(&b[2..]), h(&b[4..]), h(&b[6..])],
                PixelFormat::Rgba32f => [f(&b[0..]), f(&b[4..]), f(&b[8..]), f(&b[12..])],
                PixelFormat::Rgb9e5 => {
                    let [r, g, b] = unpack_rgb9e5(w(b));
                    [r, g, b, 1.0]
                }
                PixelFormat::Rg11b10f => {
                    let [r, g, b] = unpack_rg11b10f(w(b));
                    [r, g, b, 1.0]
                }
                // Only through decode_faces, which knows the image's size.
                PixelFormat::Bc6h | PixelFormat::Astc4x4Hdr | PixelFormat::Astc6x6Hdr => {
                    [0.0, 0.0, 0.0, 1.0]
                }
            })
            .collect()
    }
}

const ALL: [PixelFormat; 9] = [
    PixelFormat::Rg16f,
    PixelFormat::Rg32f,
    PixelFormat::Rgba16f,
    PixelFormat::Rgba32f,
    PixelFormat::Rgb9e5,
    PixelFormat::Rg11b10f,
    PixelFormat::Bc6h,
    PixelFormat::Astc4x4Hdr,
    PixelFormat::Astc6x6Hdr,
];

const RGB9E5_MANTISSA_BITS: i32 = 9;
const RGB9E5_EXP_BIAS: i32 = 15;
const RGB9E5_MAX_EXP: i32 = 31;

/// Largest value RGB9E5 represents: (2⁹ − 1)/2⁹ · 2^(31 − 15) = 65408.
pub fn rgb9e5_max() -> f32 {
    let n = RGB9E5_MANTISSA_BITS;
    ((1 << n) - 1) as f32 / (1 << n) as f32 * ((RGB9E5_MAX_EXP - RGB9E5_EXP_BIAS) as f32).exp2()
}

/// Packs RGB into E5B9G9R9 exactly as the Vulkan specification's "Shared Exponent"
/// conversion: clamp to [0, max], shared exponent from the largest channel, round to
/// nearest, bump the exponent if the largest mantissa rounds up to 2⁹.
pub fn pack_rgb9e5(rgb: [f32; 3]) -> u32 {
    let n = RGB9E5_MANTISSA_BITS;
    let max = rgb9e5_max();
    let c = rgb.map(|v| if v.is_nan() { 0.0 } else { v.clamp(0.0, max) });
    let max_c = c[0].max(c[1]).max(c[2]);
    let mut exp_shared = if max_c > 0.0 {
        (-RGB9E5_EXP_BIAS - 1).max(max_c.log2().floor() as i32) + 1 + RGB9E5_EXP_BIAS
    } else {
        0
    };
    let scale = |e: i32| ((e - RGB9E5_EXP_BIAS - n) as f32).exp2();
    let max_s = (max_c / scale(exp_shared) + 0.5).floor() as u32;
    if max_s == 1 << n {
        exp_shared += 1;
    }
    let m = c.map(|v| ((v / scale(exp_shared) + 0.5).floor() as u32).min((1 << n) - 1));
    m[0] | (m[1] << 9) | (m[2] << 18) | ((exp_shared as u32) << 27)
}

/// Unpacks E5B9G9R9.
pub fn unpack_rgb9e5(p: u32) -> [f32; 3] {
    let e = (p >> 27) as i32;
    let scale = ((e - RGB9E5_EXP_BIAS - RGB9E5_MANTISSA_BITS) as f32).exp2();
    [p & 0x1ff, (p >> 9) & 0x1ff, (p >> 18) & 0x1ff].map(|m| m as f32 * scale)
}

/// An unsigned float with a 5-bit exponent (bias 15) and `mbits` mantissa bits, from an
/// f32 with round-to-nearest-even; negative and NaN give 0, values above the largest
/// finite value clamp to it (never infinity), subnormals are kept.
pub fn f32_to_ufloat(v: f32, mbits: u32) -> u32 {
    if v.is_nan() || v <= 0.0 {
        return 0;
    }
    let max_finite = (30u32 << mbits) | ((1 << mbits) - 1);
    let bits = v.to_bits();
    let exp = ((bits >> 23) & 0xff) as i32 - 127;
    if exp < -14 {
        // Subnormal: v = m · 2^(−14 − mbits).
        let m = (v * ((14 + mbits) as f32).exp2()).round_ties_even() as u32;
        return m.min(max_finite); // m = 2^mbits is the smallest normal, encoded the same way
    }
    let shift = 23 - mbits;
    let mant = bits & 0x7f_ffff;
    let mut m = mant >> shift;
    let rem = mant & ((1 << shift) - 1);
    let half = 1 << (shift - 1);
    let mut e = exp + 15;
    if rem > half || (rem == half && m & 1 == 1) {
        m += 1;
        if m == 1 << mbits {
            m = 0;
            e += 1;
        }
    }
    if e >= 31 {
        return max_finite;
    }
    ((e as u32) << mbits) | m
}

/// Inverse of [`f32_to_ufloat`].
pub fn ufloat_to_f32(u: u32, mbits: u32) -> f32 {
    let e = (u >> mbits) as i32;
    let m = (u & ((1 << mbits) - 1)) as f32;
    if e == 0 {
        m * ((-14 - mbits as i32) as f32).exp2()
    } else {
        (1.0 + m / (1u32 << mbits) as f32) * ((e - 15) as f32).exp2()
    }
}

/// Packs RGB into B10G11R11_UFLOAT (R bits 0–10, G 11–21, B 22–31).
pub fn pack_rg11b10f(rgb: [f32; 3]) -> u32 {
    f32_to_ufloat(rgb[0], 6) | (f32_to_ufloat(rgb[1], 6) << 11) | (f32_to_ufloat(rgb[2], 5) << 22)
}

/// Unpacks B10G11R11_UFLOAT.
pub fn unpack_rg11b10f(p: u32) -> [f32; 3] {
    [
        ufloat_to_f32(p & 0x7ff, 6),
        ufloat_to_f32((p >> 11) & 0x7ff, 6),
        ufloat_to_f32(p >> 22, 5),
    ]
}

/// Encoded texture data ready for a container: `levels[m]` holds mip m (level 0 first),
/// each the concatenation of its `faces` images (cubemaps: +X, −X, +Y, −Y, +Z, −Z), rows
/// top to bottom.
#[derive(Clone, Debug)]
pub struct EncodedTexture {
    /// Pixel format of every level.
    pub format: PixelFormat,
    /// Width of level 0.
    pub width: u32,
    /// Height of level 0.
    pub height: u32,
    /// 1 for a 2D texture, 6 for a cubemap.
    pub faces: u32,
    /// Encoded mip levels, largest first.
    pub levels: Vec<Vec<u8>>,
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rgb9e5_follows_the_vulkan_rules() {
        assert_eq!(pack_rgb9e5([0.0; 3]), 0);
        assert_eq!(
            unpack_rgb9e5(pack_rgb9e5([1.0, 0.5, 0.25])),
            [1.0, 0.5, 0.25]
        );
        // Clamped, not wrapped: above the maximum gives the maximum.
        assert_eq!(unpack_rgb9e5(pack_rgb9e5([1e9, 0.0, 0.0]))[0], rgb9e5_max());
        assert_eq!(rgb9e5_max(), 65408.0);
        // Relative error of the largest channel ≤ 2^-10 (half a mantissa step).
        for v in [0.1f32, 3.3, 777.7, 12345.6] {
            let back = unpack_rgb9e5(pack_rgb9e5([v, v / 3.0, 0.0]))[0];
            assert!((back - v).abs() / v <= 1.0 / 1024.0 + 1e-7, "{v} -> {back}");
        }
    }

    #[test]
    fn ufloat_rounds_to_nearest_even_and_clamps() {
        assert_eq!(ufloat_to_f32(f32_to_ufloat(1.0, 6), 6), 1.0);
        assert_eq!(ufloat_to_f32(f32_to_ufloat(1e9, 6), 6), 65024.0);
        assert_eq!(ufloat_to_f32(f32_to_ufloat(1e9, 5), 5), 64512.0);
        assert_eq!(f32_to_ufloat(-3.0, 6), 0);
        // Halfway between 1 and 1 + 2^-6 rounds to even (1.0).
        assert_eq!(ufloat_to_f32(f32_to_ufloat(1.0 + 1.0 / 128.0, 6), 6), 1.0);
        // Subnormals survive.
        let tiny = 3.0 * (-20f32).exp2();
        assert_eq!(ufloat_to_f32(f32_to_ufloat(tiny, 6), 6), tiny);
        for v in [0.001f32, 0.7, 42.0, 30000.0] {
            let back = unpack_rg11b10f(pack_rg11b10f([v, v, v]));
            assert!(
                (back[0] - v).abs() / v <= 1.0 / 128.0 && (back[2] - v).abs() / v <= 1.0 / 64.0
            );
        }
    }
}
