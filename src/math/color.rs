//! The sRGB transfer functions (IEC 61966-2-1): the decoding of 8- and 16-bit inputs, and
//! the encoding of the preview's pictures and Babylon's RGBD texels.

/// sRGB-encoded value in [0, 1] to linear.
pub fn srgb_to_linear(c: f32) -> f32 {
    if c <= 0.04045 {
        c / 12.92
    } else {
        ((c + 0.055) / 1.055).powf(2.4)
    }
}

/// The sRGB transfer function (IEC 61966-2-1) of a linear value in [0, 1] (clamped), as
/// 8 bits.
pub fn srgb8(v: f32) -> u8 {
    let v = v.clamp(0.0, 1.0);
    let e = if v <= 0.003_130_8 {
        12.92 * v
    } else {
        1.055 * v.powf(1.0 / 2.4) - 0.055
    };
    (e * 255.0).round() as u8
}
