//! Texel weights: unquantising the stored weights to 0..64 and the bilinear infill from a
//! weight grid smaller than the footprint to one weight per texel. Follows the Khronos Data
//! Format Specification 1.3, ASTC chapter, sections "Weight Unquantization" (tables "ASTC
//! weight unquantization values" and "ASTC weight unquantization parameters") and
//! "Weight Infill" (the 2D case).

use super::ise::{Digit, Range};

/// Unquantised weights span 0..=64, so interpolation divides by 64 (DFS "Weight
/// Unquantization": the 0..63 result is stretched by adding 1 above 32).
pub const WEIGHT_MAX: u32 = 64;
/// Unquantised weights first span 0..63 (6 bits).
const WEIGHT_BITS: u32 = 6;
/// Above this the 0..63 weight gets 1 added, to reach 64.
const WEIGHT_STRETCH_ABOVE: u32 = 32;

/// Unquantises a stored weight `v` of `range` to 0..=64.
pub fn unquantize(range: Range, v: u32) -> u32 {
    let n = range.bits;
    let t = match (range.digit, n) {
        (Digit::None, _) => replicate(v, n, WEIGHT_BITS),
        // Ranges with a digit and no plain bits: DFS table "ASTC weight unquantization values".
        (Digit::Trit, 0) => [0, 32, 63][(v % 3) as usize],
        (Digit::Quint, 0) => [0, 16, 32, 47, 63][(v % 5) as usize],
        (digit, _) => {
            // DFS table "ASTC weight unquantization parameters": A is the lowest bit `a`
            // repeated 7 times; B spreads the bits above it in the pattern shown (bit 6 first);
            // C is the scale; D is the trit or quint.
            let (pattern, c): (&[u8; 7], u32) = match (digit, n) {
                (Digit::Trit, 1) => (b"0000000", 50),
                (Digit::Quint, 1) => (b"0000000", 28),
                (Digit::Trit, 2) => (b"b000b0b", 23),
                (Digit::Quint, 2) => (b"b0000b0", 13),
                (Digit::Trit, _) => (b"cb000cb", 11),
                (Digit::Quint, _) => (b"0000000", 0), // no such weight range
                (Digit::None, _) => (b"0000000", 0),  // handled above
            };
            let m = v & ((1 << n) - 1);
            let d = v >> n;
            let a = if m & 1 != 0 { 0x7F } else { 0 };
            let b = spread_bits(pattern, m);
            let mut t = d * c + b;
            t ^= a;
            (a & 0x20) | (t >> 2)
        }
    };
    if t > WEIGHT_STRETCH_ABOVE {
        t + 1
    } else {
        t
    }
}

/// Repeats the `from`-bit value `v` from its most-significant bit down to fill `to` bits
/// (the spec's "bit replication").
pub fn replicate(v: u32, from: u32, to: u32) -> u32 {
    if from == 0 {
        return 0;
    }
    let mut out = 0;
    let mut filled = 0;
    while filled < to {
        out = (out << from) | v;
        filled += from;
    }
    out >> (filled - to)
}

/// Builds the value whose bits (most-significant first) follow `pattern`: `'0'` is a zero bit
/// and a letter is a bit of `m`, `'a'` its bit 0, `'b'` its bit 1, and so on. This is how the
/// spec's unquantisation tables write the B input.
pub fn spread_bits(pattern: &[u8], m: u32) -> u32 {
    pattern.iter().fold(0, |acc, &p| {
        let bit = if p.is_ascii_lowercase() {
            (m >> (p - b'a')) & 1
        } else {
            0
        };
        (acc << 1) | bit
    })
}

/// The largest footprint side (12) and so the most texels of a block.
pub const MAX_TEXELS: usize = 144;

/// Infills one plane: `grid` holds the plane's unquantised weights (row-major, `grid_w`
/// columns), and `out` receives one weight per texel of the `block_w`×`block_h` footprint,
/// row-major. Grid indices past `grid` read as 0 (they cannot occur for a legal mode).
pub fn infill(grid: &[u32], grid_w: u32, grid_h: u32, block_w: u32, block_h: u32, out: &mut [u32]) {
    let ds = scale_factor(block_w);
    let dt = scale_factor(block_h);
    let at = |i: u32| grid.get(i as usize).copied().unwrap_or(0);
    for t in 0..block_h {
        for s in 0..block_w {
            // Texel position in 4.4 fixed point on the weight grid.
            let gs = (ds * s * (grid_w - 1) + 32) >> 6;
            let gt = (dt * t * (grid_h - 1) + 32) >> 6;
            let (js, fs) = (gs >> 4, gs & 0xF);
            let (jt, ft) = (gt >> 4, gt & 0xF);
            let v0 = js + jt * grid_w;
            // Bilinear weights of the four grid neighbours, summing to 16.
            let w11 = (fs * ft + 8) >> 4;
            let w10 = ft - w11;
            let w01 = fs - w11;
            let w00 = 16 - fs - ft + w11;
            // A neighbour with zero contribution may lie past the grid's edge; skip it.
            let mut sum = 8;
            for (w, i) in [
                (w00, v0),
                (w01, v0 + 1),
                (w10, v0 + grid_w),
                (w11, v0 + grid_w + 1),
            ] {
                if w != 0 {
                    sum += at(i) * w;
                }
            }
            if let Some(o) = out.get_mut((t * block_w + s) as usize) {
                *o = sum >> 4;
            }
        }
    }
}

/// The spec's per-axis scale `D = floor((1024 + floor(B / 2)) / (B - 1))` for a footprint side
/// `b` (at least 2).
fn scale_factor(b: u32) -> u32 {
    (1024 + b / 2) / b.saturating_sub(1).max(1)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Arm astc-encoder's unquantised weights per range (astcenc_weight_quant_xfer_tables.cpp,
    /// the first column: quantised value order).
    #[test]
    fn unquantisation_matches_the_reference_tables() {
        let cases: [(Range, &[u32]); 7] = [
            (Range::trit(0), &[0, 32, 64]),
            (Range::quint(0), &[0, 16, 32, 48, 64]),
            (Range::bits(2), &[0, 21, 43, 64]),
            // Scrambled order: the value index is the integer-sequence value.
            (Range::trit(1), &[0, 64, 12, 52, 25, 39]),
            (Range::quint(1), &[0, 64, 7, 57, 14, 50, 21, 43, 28, 36]),
            (
                Range::trit(2),
                &[0, 64, 17, 47, 5, 59, 23, 41, 11, 53, 28, 36],
            ),
            (
                Range::trit(3),
                &[
                    0, 64, 8, 56, 16, 48, 24, 40, 2, 62, 11, 53, 19, 45, 27, 37, 5, 59, 13, 51, 22,
                    42, 30, 34,
                ],
            ),
        ];
        for (range, want) in cases {
            let got: Vec<u32> = (0..range.levels()).map(|v| unquantize(range, v)).collect();
            assert_eq!(got, want, "{range:?}");
        }
        let q20: Vec<u32> = (0..20).map(|v| unquantize(Range::quint(2), v)).collect();
        assert_eq!(
            q20,
            [0, 64, 16, 48, 3, 61, 19, 45, 6, 58, 23, 41, 9, 55, 26, 38, 13, 51, 29, 35]
        );
        assert_eq!(unquantize(Range::bits(5), 16), 34);
        assert_eq!(unquantize(Range::bits(3), 4), 37);
    }

    #[test]
    fn replication_and_patterns() {
        assert_eq!(replicate(0b101, 3, 8), 0b1011_0110);
        assert_eq!(replicate(1, 1, 6), 0b11_1111);
        assert_eq!(replicate(0b10110, 5, 8), 0b1011_0101);
        assert_eq!(spread_bits(b"cb000cb", 0b110), 0b1100011);
        assert_eq!(spread_bits(b"b000b0bb0", 0b10), 0b1_0001_0110);
    }

    #[test]
    fn full_grid_infill_is_the_identity() {
        let grid: Vec<u32> = (0..36).collect();
        let mut out = [0u32; 36];
        infill(&grid, 6, 6, 6, 6, &mut out);
        assert_eq!(out.to_vec(), grid);
    }

    #[test]
    fn infill_interpolates_a_ramp() {
        // A 2×2 grid 0, 64 / 0, 64 across an 8-wide footprint: a horizontal ramp whose ends are
        // exact and which never decreases.
        let mut out = [0u32; 64];
        infill(&[0, 64, 0, 64], 2, 2, 8, 8, &mut out);
        for row in out.chunks(8) {
            assert_eq!(row[0], 0);
            assert_eq!(row[7], 64);
            assert!(row.windows(2).all(|w| w[0] <= w[1]));
            assert_eq!(row, &out[..8]);
        }
    }
}
