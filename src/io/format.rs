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
    /// Four 16-bit floats.
    Rgba16f,
    /// Four 32-bit floats.
    Rgba32f,
}

impl PixelFormat {
    /// Channels stored per texel.
    pub fn channels(self) -> usize {
        match self {
            PixelFormat::Rg16f | PixelFormat::Rg32f => 2,
            PixelFormat::Rgba16f | PixelFormat::Rgba32f => 4,
        }
    }

    /// Bytes of one channel value (the KTX2 `typeSize`).
    pub fn channel_bytes(self) -> u32 {
        match self {
            PixelFormat::Rg16f | PixelFormat::Rgba16f => 2,
            PixelFormat::Rg32f | PixelFormat::Rgba32f => 4,
        }
    }

    /// Bytes per texel.
    pub fn texel_bytes(self) -> u32 {
        self.channels() as u32 * self.channel_bytes()
    }

    /// The `VkFormat` number (Vulkan spec, "Formats").
    pub fn vk_format(self) -> u32 {
        match self {
            PixelFormat::Rg16f => 83,    // VK_FORMAT_R16G16_SFLOAT
            PixelFormat::Rg32f => 103,   // VK_FORMAT_R32G32_SFLOAT
            PixelFormat::Rgba16f => 97,  // VK_FORMAT_R16G16B16A16_SFLOAT
            PixelFormat::Rgba32f => 109, // VK_FORMAT_R32G32B32A32_SFLOAT
        }
    }

    /// The `DXGI_FORMAT` number (DXGI_FORMAT enumeration).
    pub fn dxgi_format(self) -> u32 {
        match self {
            PixelFormat::Rg16f => 34,   // DXGI_FORMAT_R16G16_FLOAT
            PixelFormat::Rg32f => 16,   // DXGI_FORMAT_R32G32_FLOAT
            PixelFormat::Rgba16f => 10, // DXGI_FORMAT_R16G16B16A16_FLOAT
            PixelFormat::Rgba32f => 2,  // DXGI_FORMAT_R32G32B32A32_FLOAT
        }
    }

    /// Short name used in messages and manifests.
    pub fn name(self) -> &'static str {
        match self {
            PixelFormat::Rg16f => "rg16f",
            PixelFormat::Rg32f => "rg32f",
            PixelFormat::Rgba16f => "rgba16f",
            PixelFormat::Rgba32f => "rgba32f",
        }
    }

    /// Encodes texels given as `channels()` floats each, little endian.
    pub fn encode(self, values: &[f32]) -> Vec<u8> {
        match self.channel_bytes() {
            2 => values
                .iter()
                .flat_map(|&v| f16::from_f32(v).to_le_bytes())
                .collect(),
            _ => values.iter().flat_map(|v| v.to_le_bytes()).collect(),
        }
    }
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

impl EncodedTexture {
    /// Size of mip `m` along an edge of `base` texels.
    pub fn level_extent(base: u32, m: usize) -> u32 {
        (base >> m).max(1)
    }
}
