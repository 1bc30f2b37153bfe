//! The sRGB transfer functions (IEC 61966-2-1): the decoding of 8- and 16-bit inputs, and
//! the encoding of the preview's pictures and Babylon's RGBD texels; and the Rec. 709
//! luminance weights.

/// Rec. 709 luminance weights of linear RGB (ITU-R BT.709, the Y row of its RGB to XYZ
/// matrix), in f64.
pub const LUMINANCE_F64: [f64; 3] = [0.2126, 0.7152, 0.0722];
/// [`LUMINANCE_F64`] in f32.
pub const LUMINANCE: [f32; 3] = [
    LUMINANCE_F64[0] as f32,
    LUMINANCE_F64[1] as f32,
    LUMINANCE_F64[2] as f32,
];

/// The luminance Y of linear RGB `c` ([`LUMINANCE`]).
pub fn luminance(c: [f32; 3]) -> f32 {
    LUMINANCE[0] * c[0] + LUMINANCE[1] * c[1] + LUMINANCE[2] * c[2]
}

/// [`luminance`] in f64.
pub fn luminance_f64(c: [f64; 3]) -> f64 {
    LUMINANCE_F64[0] * c[0] + LUMINANCE_F64[1] * c[1] + LUMINANCE_F64[2] * c[2]
}

/// Largest linear value on the sRGB curve's linear segment.
pub const SRGB_LINEAR_MAX: f32 = 0.003_130_8;
/// Largest encoded value on the linear segment (as IEC 61966-2-1 rounds it).
pub const SRGB_ENCODED_LINEAR_MAX: f32 = 0.04045;
/// Slope of the linear segment.
pub const SRGB_SLOPE: f32 = 12.92;
/// Offset of the power segment: encoded = (1 + a) v^(1/γ) − a.
pub const SRGB_OFFSET: f32 = 0.055;
/// Exponent γ of the power segment.
pub const SRGB_GAMMA: f32 = 2.4;

/// sRGB-encoded value in [0, 1] to linear.
pub fn srgb_to_linear(c: f32) -> f32 {
    if c <= SRGB_ENCODED_LINEAR_MAX {
        c / SRGB_SLOPE
    } else {
        ((c + SRGB_OFFSET) / (1.0 + SRGB_OFFSET)).powf(SRGB_GAMMA)
    }
}

/// The sRGB transfer function (IEC 61966-2-1) of a linear value in [0, 1] (clamped).
pub fn linear_to_srgb(v: f32) -> f32 {
    let v = v.clamp(0.0, 1.0);
    if v <= SRGB_LINEAR_MAX {
        SRGB_SLOPE * v
    } else {
        (1.0 + SRGB_OFFSET) * v.powf(1.0 / SRGB_GAMMA) - SRGB_OFFSET
    }
}

/// The sRGB transfer function (IEC 61966-2-1) of a linear value in [0, 1] (clamped), as
/// 8 bits.
pub fn srgb8(v: f32) -> u8 {
    (linear_to_srgb(v) * 255.0).round() as u8
}
