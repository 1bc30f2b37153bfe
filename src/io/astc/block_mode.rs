//! The 11-bit block mode of a 2D ASTC block: the weight grid's size, the weights' value
//! range and whether there are two weight planes, with the legality checks the spec puts on
//! them. Follows the Khronos Data Format Specification 1.3, ASTC chapter, sections
//! "Block Mode" (tables "ASTC weight range encodings" and "ASTC 2D block mode layout") and
//! "Illegal Encodings".

use super::ise::Range;

/// The weight ranges selected by the 3-bit R field with H = 0, indexed by R (R = 0 and 1
/// are invalid; DFS table "ASTC weight range encodings", low-precision column).
const LOW_PRECISION_WEIGHTS: [Option<Range>; 8] = [
    None,
    None,
    Some(Range::bits(1)),  // 0..1
    Some(Range::trit(0)),  // 0..2
    Some(Range::bits(2)),  // 0..3
    Some(Range::quint(0)), // 0..4
    Some(Range::trit(1)),  // 0..5
    Some(Range::bits(3)),  // 0..7
];

/// The weight ranges selected by R with H = 1 (same table, high-precision column).
const HIGH_PRECISION_WEIGHTS: [Option<Range>; 8] = [
    None,
    None,
    Some(Range::quint(1)), // 0..9
    Some(Range::trit(2)),  // 0..11
    Some(Range::bits(4)),  // 0..15
    Some(Range::quint(2)), // 0..19
    Some(Range::trit(3)),  // 0..23
    Some(Range::bits(5)),  // 0..31
];

/// At most this many weights in a block, both planes counted (DFS "Illegal Encodings").
pub const MAX_WEIGHTS: u32 = 64;
/// The weights' integer sequence must take at least this many bits (DFS "Illegal Encodings").
const MIN_WEIGHT_BITS: u32 = 24;
/// ... and at most this many.
const MAX_WEIGHT_BITS: u32 = 96;

/// What a legal block mode says about the block's weights.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct BlockMode {
    /// Weight grid columns (N in the spec).
    pub grid_w: u32,
    /// Weight grid rows (M in the spec).
    pub grid_h: u32,
    /// Two weight planes (the D bit).
    pub dual_plane: bool,
    /// The range each stored weight is quantised to.
    pub weight_range: Range,
}

impl BlockMode {
    /// The number of stored weights, both planes counted.
    pub fn weight_count(&self) -> u32 {
        self.grid_w * self.grid_h * if self.dual_plane { 2 } else { 1 }
    }

    /// The length in bits of the weights' integer sequence.
    pub fn weight_bits(&self) -> u32 {
        self.weight_range.sequence_bits(self.weight_count())
    }
}

/// Bit `i` of `v`.
const fn bit(v: u32, i: u32) -> u32 {
    (v >> i) & 1
}

/// Bits `lo .. lo + count` of `v`.
const fn bits(v: u32, lo: u32, count: u32) -> u32 {
    (v >> lo) & ((1 << count) - 1)
}

/// Decodes the 11-bit block `mode` of a 2D block with a `block_w`×`block_h` footprint:
/// `None` when the mode is reserved or illegal for this footprint (more than 64 weights,
/// fewer than 24 or more than 96 weight bits, or a grid larger than the footprint). The
/// void-extent pattern must be recognised before calling this; here it reads as reserved.
pub fn decode(mode: u32, block_w: u32, block_h: u32) -> Option<BlockMode> {
    // Field names as in DFS table "ASTC 2D block mode layout".
    let a = bits(mode, 5, 2);
    let b = bits(mode, 7, 2);
    let mut dual_plane = bit(mode, 10) == 1;
    let mut high_precision = bit(mode, 9) == 1;
    let r0 = bit(mode, 4);
    let (grid_w, grid_h, r);
    if bits(mode, 0, 2) != 0 {
        // The first five rows: R2 R1 in bits 1:0.
        r = (bit(mode, 1) << 2) | (bit(mode, 0) << 1) | r0;
        (grid_w, grid_h) = match bits(mode, 2, 2) {
            0b00 => (b + 4, a + 2),
            0b01 => (b + 8, a + 2),
            0b10 => (a + 2, b + 8),
            _ if bit(mode, 8) == 0 => (a + 2, bit(mode, 7) + 6),
            _ => (bit(mode, 7) + 2, a + 2),
        };
    } else {
        // The remaining rows: R2 R1 in bits 3:2; R2 = R1 = 0 is reserved.
        r = (bit(mode, 3) << 2) | (bit(mode, 2) << 1) | r0;
        if r < 2 {
            return None;
        }
        (grid_w, grid_h) = match bits(mode, 7, 2) {
            0b00 => (12, a + 2),
            0b01 => (a + 2, 12),
            0b10 => {
                // Bits 10:9 are B here, so D = H = 0.
                dual_plane = false;
                high_precision = false;
                (a + 6, bits(mode, 9, 2) + 6)
            }
            _ => match a {
                0b00 => (6, 10),
                0b01 => (10, 6),
                _ => return None,
            },
        };
    }
    let table = if high_precision {
        &HIGH_PRECISION_WEIGHTS
    } else {
        &LOW_PRECISION_WEIGHTS
    };
    let weight_range = table[r as usize]?;
    let block_mode = BlockMode {
        grid_w,
        grid_h,
        dual_plane,
        weight_range,
    };
    let weight_bits = block_mode.weight_bits();
    let legal = block_mode.weight_count() <= MAX_WEIGHTS
        && (MIN_WEIGHT_BITS..=MAX_WEIGHT_BITS).contains(&weight_bits)
        && grid_w <= block_w
        && grid_h <= block_h;
    legal.then_some(block_mode)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn decodes_the_layout_rows() {
        // Row "B+4 × A+2": bits 1:0 = 10 (R2 = 1, R1 = 0), R0 = 0 → R = 100 (0..3); A = 2.
        let m = decode(0b000_0100_0010, 12, 12).unwrap();
        assert_eq!((m.grid_w, m.grid_h, m.dual_plane), (4, 4, false));
        assert_eq!(m.weight_range, Range::bits(2));
        // Row "6 × 10" with R = 111 and H = 1 (0..31) would need 300 bits: illegal.
        assert_eq!(decode(0b011_1001_1100, 12, 12), None);
        // Row "6 × 10" with R = 010, H = 0: 60 one-bit weights.
        let m = decode(0b001_1000_0100, 12, 12).unwrap();
        assert_eq!((m.grid_w, m.grid_h), (6, 10));
        assert_eq!(m.weight_range, Range::bits(1));
        assert_eq!(m.weight_bits(), 60);
        // The same grid is taller than a 12×8 footprint.
        assert_eq!(decode(0b001_1000_0100, 12, 8), None);
        // Row "A+6 × B+6": bits 10:9 are B (= 3), so never dual plane; A = 1.
        let m = decode(0b111_0010_0100, 12, 12).unwrap();
        assert_eq!((m.grid_w, m.grid_h, m.dual_plane), (7, 9, false));
        assert_eq!(m.weight_range, Range::bits(1));
        // Reserved: bits 3:0 all zero.
        assert_eq!(decode(0b000_0001_0000, 12, 12), None);
        // The void-extent pattern reads as reserved here.
        assert_eq!(decode(0x1FC, 12, 12), None);
        // Row "6 × 10" family with bits 6:5 = 1x is reserved.
        assert_eq!(decode(0b001_1100_0100, 12, 12), None);
    }

    #[test]
    fn dual_plane_and_weight_limits() {
        // D = 1, row "B+4 × A+2" with B = 0, A = 2; R = 011 (0..2).
        let mode = (1 << 10) | (2 << 5) | 0b1_0001;
        let m = decode(mode, 4, 4).unwrap();
        assert!(m.dual_plane);
        assert_eq!(m.weight_range, Range::trit(0));
        assert_eq!(m.weight_count(), 32);
        assert_eq!(m.weight_bits(), 52);
        // Row "B+2 × A+2" as a 2×2 grid of one-bit weights: 4 bits < 24, illegal.
        assert_eq!(decode(0b001_0000_1101, 4, 4), None);
        // A 2×2 grid of 0..31 weights, dual plane: 8 × 5 = 40 bits, legal.
        let m = decode((1 << 10) | (1 << 9) | 0b001_0001_1111, 4, 4).unwrap();
        assert_eq!((m.grid_w, m.grid_h, m.dual_plane), (2, 2, true));
        assert_eq!(m.weight_range, Range::bits(5));
    }
}
