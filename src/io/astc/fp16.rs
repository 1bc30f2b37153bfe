//! The HDR profile's conversions of interpolated 16-bit values to FP16 — UNORM16 (LDR
//! channels) by round-to-zero division by 65536 and 16-bit LNS (HDR channels) by the
//! spec's mantissa transform — and the exact widening of FP16 to f32. Follows the Khronos
//! Data Format Specification 1.3, ASTC chapter, section "Weight Application".

/// FP16 1.0.
pub const FP16_ONE: u16 = 0x3C00;
/// The largest finite FP16 value; HDR results that would be +Inf or NaN become this.
const FP16_MAX_FINITE: u16 = 0x7BFF;
/// FP16 mantissa bits.
const FP16_MANTISSA_BITS: u32 = 10;
/// FP16 exponent bias.
const FP16_BIAS: u32 = 15;
/// f32 exponent bias.
const F32_BIAS: u32 = 127;
/// f32 mantissa bits.
const F32_MANTISSA_BITS: u32 = 23;
/// Bits of the LNS mantissa (the low 11 bits of the 16-bit interpolated value).
const LNS_MANTISSA_BITS: u32 = 11;

/// An interpolated UNORM16 channel as FP16: 65535 is exactly 1.0, anything else is
/// `c / 65536` rounded toward zero.
pub fn unorm16_to_fp16(c: u16) -> u16 {
    if c == u16::MAX {
        return FP16_ONE;
    }
    let c = u32::from(c);
    if c == 0 {
        return 0;
    }
    // c / 65536 = 2^(p - 16) · 1.f with p the position of c's leading one.
    let p = 31 - c.leading_zeros();
    let biased = (p + FP16_BIAS).saturating_sub(16);
    if biased == 0 {
        // Subnormal (c < 4): c · 2^-16 = (c << 8) · 2^-24, exact.
        return (c << 8) as u16;
    }
    // The fraction below the leading one, truncated to 10 bits.
    let fraction = if p >= FP16_MANTISSA_BITS {
        c >> (p - FP16_MANTISSA_BITS)
    } else {
        c << (FP16_MANTISSA_BITS - p)
    } & ((1 << FP16_MANTISSA_BITS) - 1);
    ((biased << FP16_MANTISSA_BITS) | fraction) as u16
}

/// An interpolated 16-bit LNS channel as FP16: the top 5 bits are the exponent and the low
/// 11 bits a mantissa mapped piecewise-linearly onto FP16's 10 (the spec's `Mt`).
pub fn lns_to_fp16(c: u16) -> u16 {
    let c = u32::from(c);
    let e = c >> LNS_MANTISSA_BITS;
    let m = c & ((1 << LNS_MANTISSA_BITS) - 1);
    let mt = if m < 512 {
        3 * m
    } else if m >= 1536 {
        5 * m - 2048
    } else {
        4 * m - 512
    };
    let cf = (e << FP16_MANTISSA_BITS) + (mt >> 3);
    (cf as u16).min(FP16_MAX_FINITE)
}

/// Widens FP16 to f32 exactly; NaNs keep their payload and become quiet.
pub fn fp16_to_f32(h: u16) -> f32 {
    let h = u32::from(h);
    let sign = (h >> 15) << 31;
    let exponent = (h >> FP16_MANTISSA_BITS) & 0x1F;
    let mantissa = h & ((1 << FP16_MANTISSA_BITS) - 1);
    let shift = F32_MANTISSA_BITS - FP16_MANTISSA_BITS;
    let bits = match exponent {
        0 => {
            // Zero or subnormal: mantissa · 2^-24, exact in f32.
            let magnitude = mantissa as f32 * (1.0 / 16_777_216.0);
            sign | magnitude.to_bits()
        }
        0x1F if mantissa == 0 => sign | f32::INFINITY.to_bits(),
        // NaN: f32 exponent all ones, payload kept, quiet bit set.
        0x1F => sign | 0x7F80_0000 | (mantissa << shift) | 0x0040_0000,
        _ => sign | ((exponent + F32_BIAS - FP16_BIAS) << F32_MANTISSA_BITS) | (mantissa << shift),
    };
    f32::from_bits(bits)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn unorm16_conversion() {
        assert_eq!(unorm16_to_fp16(0), 0);
        assert_eq!(unorm16_to_fp16(1), 0x0100);
        assert_eq!(unorm16_to_fp16(3), 0x0300);
        assert_eq!(unorm16_to_fp16(4), 0x0400);
        assert_eq!(unorm16_to_fp16(0xFFFF), FP16_ONE);
        assert_eq!(unorm16_to_fp16(0x8000), 0x3800); // 0.5
                                                     // 0xFFFE / 65536 = 0.99997: truncated to 0x3BFF, not rounded up to 1.0.
        assert_eq!(unorm16_to_fp16(0xFFFE), 0x3BFF);
        // Every value: exact round-toward-zero of c / 65536.
        for c in 0..0xFFFFu32 {
            let h = unorm16_to_fp16(c as u16);
            let exact = c as f64 / 65536.0;
            let got = f64::from(fp16_to_f32(h));
            let next = f64::from(fp16_to_f32(h + 1));
            assert!(got <= exact && exact < next, "{c}");
        }
    }

    #[test]
    fn lns_conversion() {
        // 0x780 << 4 is 1.0 in the spec.
        assert_eq!(lns_to_fp16(0x7800), FP16_ONE);
        assert_eq!(lns_to_fp16(0), 0);
        assert_eq!(lns_to_fp16(0xFFFF), FP16_MAX_FINITE);
        assert_eq!(lns_to_fp16(0xF800), FP16_MAX_FINITE);
        assert_eq!(lns_to_fp16(0xF7FF), 0x7BFF);
        // M = 1024: 4·1024 − 512 = 3584 → 448.
        assert_eq!(lns_to_fp16(0x7C00), 0x3C00 + 448);
    }

    #[test]
    fn widening() {
        assert_eq!(fp16_to_f32(FP16_ONE), 1.0);
        assert_eq!(fp16_to_f32(0x7BFF), 65504.0);
        assert_eq!(fp16_to_f32(0x0001), 2f32.powi(-24));
        assert_eq!(fp16_to_f32(0x8000).to_bits(), 0x8000_0000);
        assert_eq!(fp16_to_f32(0xC000), -2.0);
        assert_eq!(fp16_to_f32(0x7C00), f32::INFINITY);
        assert_eq!(fp16_to_f32(0xFFFF).to_bits(), 0xFFFF_E000);
        assert_eq!(fp16_to_f32(0x7C01).to_bits(), 0x7FC0_2000);
        for h in 0..=0xFFFFu16 {
            let f = fp16_to_f32(h);
            let expect = half::f16::from_bits(h).to_f32();
            assert!(
                f.to_bits() == expect.to_bits() || (f.is_nan() && expect.is_nan()),
                "{h:#x}"
            );
        }
    }
}
