//! Integer sequence decoding: the value ranges ASTC packs weights and colour endpoint values
//! in (n plain bits per value, optionally with one base-3 "trit" or base-5 "quint" digit on
//! top), the length in bits of a packed sequence, and the unpacking of a sequence from a
//! 128-bit block. Follows the Khronos Data Format Specification 1.3, ASTC chapter,
//! sections "Integer Sequence Encoding" and "Data Size Determination".

/// The most-significant digit a range carries above its plain bits (DFS "ASTC range forms").
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Digit {
    /// `0 ..= 2^n - 1`: plain bits only.
    None,
    /// `0 ..= 3·2^n - 1`: one trit above the n bits; five trits pack into 8 bits.
    Trit,
    /// `0 ..= 5·2^n - 1`: one quint above the n bits; three quints pack into 7 bits.
    Quint,
}

/// A value range of an integer sequence: `bits` plain low bits plus an optional trit or quint.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Range {
    /// The digit above the plain bits.
    pub digit: Digit,
    /// The number of plain low bits of each value.
    pub bits: u32,
}

/// Values per packed trit block, and the bits the block's trits take (DFS "ASTC encoding for
/// different ranges": 5 values, `8 + 5n` bits).
const TRITS_PER_BLOCK: u32 = 5;
/// Bits holding the five trits of one trit block.
const TRIT_BLOCK_DIGIT_BITS: u32 = 8;
/// Values per packed quint block (DFS: 3 values, `7 + 3n` bits).
const QUINTS_PER_BLOCK: u32 = 3;
/// Bits holding the three quints of one quint block.
const QUINT_BLOCK_DIGIT_BITS: u32 = 7;

/// How many bits of the packed digit field follow value `i` of a trit block (DFS
/// "ASTC trit-based packing": `T[1:0]` after m0, `T[3:2]` after m1, `T[4]` after m2,
/// `T[6:5]` after m3, `T[7]` after m4).
const TRIT_BITS_AFTER: [u32; 5] = [2, 2, 1, 2, 1];
/// How many bits of the packed digit field follow value `i` of a quint block (DFS
/// "ASTC quint-based packing": `Q[2:0]` after m0, `Q[4:3]` after m1, `Q[6:5]` after m2).
const QUINT_BITS_AFTER: [u32; 3] = [3, 2, 2];

impl Range {
    /// A range of plain bits.
    pub const fn bits(bits: u32) -> Self {
        Range {
            digit: Digit::None,
            bits,
        }
    }

    /// A range of one trit over `bits` plain bits.
    pub const fn trit(bits: u32) -> Self {
        Range {
            digit: Digit::Trit,
            bits,
        }
    }

    /// A range of one quint over `bits` plain bits.
    pub const fn quint(bits: u32) -> Self {
        Range {
            digit: Digit::Quint,
            bits,
        }
    }

    /// The number of distinct values (the range is `0 ..= levels - 1`).
    #[cfg(test)]
    pub const fn levels(self) -> u32 {
        let digit = match self.digit {
            Digit::None => 1,
            Digit::Trit => 3,
            Digit::Quint => 5,
        };
        digit << self.bits
    }

    /// The length in bits of a packed sequence of `count` values (DFS "Data Size
    /// Determination": `ceil(8·count/5)` for trits, `ceil(7·count/3)` for quints, plus the
    /// plain bits of every value).
    pub const fn sequence_bits(self, count: u32) -> u32 {
        let digits = match self.digit {
            Digit::None => 0,
            Digit::Trit => (TRIT_BLOCK_DIGIT_BITS * count).div_ceil(TRITS_PER_BLOCK),
            Digit::Quint => (QUINT_BLOCK_DIGIT_BITS * count).div_ceil(QUINTS_PER_BLOCK),
        };
        digits + self.bits * count
    }
}

/// Reads bit fields of a packed sequence that starts at bit `start` of `stream` and is `len`
/// bits long; bits past its end read as zero (DFS: "If there are insufficient bits in the
/// stream to fill the final block, then unused (higher order) bits are assumed to be 0").
struct SequenceReader {
    stream: u128,
    end: u32,
    at: u32,
}

impl SequenceReader {
    /// The next `count` (at most 8) bits, least-significant first.
    fn take(&mut self, count: u32) -> u32 {
        let mut value = 0;
        for i in 0..count {
            let bit = self.at + i;
            if bit < self.end && bit < u128::BITS {
                value |= (((self.stream >> bit) & 1) as u32) << i;
            }
        }
        self.at += count;
        value
    }
}

/// Unpacks `out.len()` values of `range` packed from bit `start` of `stream` (bit 0 is the
/// least-significant bit of the little-endian block). Every input gives some values; bits
/// past the end of the block read as zero.
pub fn decode(range: Range, stream: u128, start: u32, out: &mut [u8]) {
    let count = out.len() as u32;
    let mut reader = SequenceReader {
        stream,
        end: start.saturating_add(range.sequence_bits(count)),
        at: start,
    };
    let n = range.bits;
    match range.digit {
        Digit::None => {
            for value in out.iter_mut() {
                *value = reader.take(n) as u8;
            }
        }
        Digit::Trit => {
            for chunk in out.chunks_mut(TRITS_PER_BLOCK as usize) {
                let mut low = [0u32; 5];
                let mut packed = 0u32;
                let mut shift = 0;
                for (i, bits_after) in TRIT_BITS_AFTER.iter().enumerate().take(chunk.len()) {
                    low[i] = reader.take(n);
                    packed |= reader.take(*bits_after) << shift;
                    shift += bits_after;
                }
                let trits = unpack_trits(packed);
                for (i, value) in chunk.iter_mut().enumerate() {
                    *value = ((trits[i] << n) | low[i]) as u8;
                }
            }
        }
        Digit::Quint => {
            for chunk in out.chunks_mut(QUINTS_PER_BLOCK as usize) {
                let mut low = [0u32; 3];
                let mut packed = 0u32;
                let mut shift = 0;
                for (i, bits_after) in QUINT_BITS_AFTER.iter().enumerate().take(chunk.len()) {
                    low[i] = reader.take(n);
                    packed |= reader.take(*bits_after) << shift;
                    shift += bits_after;
                }
                let quints = unpack_quints(packed);
                for (i, value) in chunk.iter_mut().enumerate() {
                    *value = ((quints[i] << n) | low[i]) as u8;
                }
            }
        }
    }
}

/// Bits `hi..=lo` of `v` (the spec's `v[hi:lo]` notation).
const fn field(v: u32, hi: u32, lo: u32) -> u32 {
    (v >> lo) & ((1 << (hi - lo + 1)) - 1)
}

/// The five trits t0..t4 packed in the 8 bits `t` (DFS "Integer Sequence Encoding", the
/// trit decoding procedure, transcribed step by step).
pub fn unpack_trits(t: u32) -> [u32; 5] {
    let (c, t4, t3);
    if field(t, 4, 2) == 0b111 {
        c = (field(t, 7, 5) << 2) | field(t, 1, 0);
        t4 = 2;
        t3 = 2;
    } else {
        c = field(t, 4, 0);
        if field(t, 6, 5) == 0b11 {
            t4 = 2;
            t3 = field(t, 7, 7);
        } else {
            t4 = field(t, 7, 7);
            t3 = field(t, 6, 5);
        }
    }
    let (t2, t1, t0);
    if field(c, 1, 0) == 0b11 {
        t2 = 2;
        t1 = field(c, 4, 4);
        t0 = (field(c, 3, 3) << 1) | (field(c, 2, 2) & !field(c, 3, 3) & 1);
    } else if field(c, 3, 2) == 0b11 {
        t2 = 2;
        t1 = 2;
        t0 = field(c, 1, 0);
    } else {
        t2 = field(c, 4, 4);
        t1 = field(c, 3, 2);
        t0 = (field(c, 1, 1) << 1) | (field(c, 0, 0) & !field(c, 1, 1) & 1);
    }
    [t0, t1, t2, t3, t4]
}

/// The three quints q0..q2 packed in the 7 bits `q` (DFS "Integer Sequence Encoding", the
/// quint decoding procedure; the spec's `q2 = T[6:5]` reads `Q[6:5]`).
pub fn unpack_quints(q: u32) -> [u32; 3] {
    if field(q, 2, 1) == 0b11 && field(q, 6, 5) == 0b00 {
        let not_q0 = !field(q, 0, 0) & 1;
        let q2 =
            (field(q, 0, 0) << 2) | ((field(q, 4, 4) & not_q0) << 1) | (field(q, 3, 3) & not_q0);
        return [4, 4, q2];
    }
    let (q2, c);
    if field(q, 2, 1) == 0b11 {
        q2 = 4;
        c = (field(q, 4, 3) << 3) | ((!field(q, 6, 5) & 0b11) << 1) | field(q, 0, 0);
    } else {
        q2 = field(q, 6, 5);
        c = field(q, 4, 0);
    }
    let (q1, q0) = if field(c, 2, 0) == 0b101 {
        (4, field(c, 4, 3))
    } else {
        (field(c, 4, 3), field(c, 2, 0))
    };
    [q0, q1, q2]
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Packs `values` the way an encoder does, finding each block's digit field by search
    /// over the decoder (every digit combination has a packing: checked below).
    fn encode(range: Range, values: &[u32], start: u32) -> u128 {
        let n = range.bits;
        let mut stream = 0u128;
        let mut at = start;
        let mut put = |v: u32, count: u32, at: &mut u32| {
            stream |= ((v as u128) & ((1u128 << count) - 1)) << *at;
            *at += count;
        };
        match range.digit {
            Digit::None => values.iter().for_each(|&v| put(v, n, &mut at)),
            Digit::Trit => {
                for chunk in values.chunks(5) {
                    let mut want = [0u32; 5];
                    chunk.iter().enumerate().for_each(|(i, v)| want[i] = v >> n);
                    let packed = (0..256).find(|&t| unpack_trits(t) == want).unwrap();
                    let mut shift = 0;
                    for (i, &v) in chunk.iter().enumerate() {
                        put(v, n, &mut at);
                        put(packed >> shift, TRIT_BITS_AFTER[i], &mut at);
                        shift += TRIT_BITS_AFTER[i];
                    }
                }
            }
            Digit::Quint => {
                for chunk in values.chunks(3) {
                    let mut want = [0u32; 3];
                    chunk.iter().enumerate().for_each(|(i, v)| want[i] = v >> n);
                    let packed = (0..128).find(|&q| unpack_quints(q) == want).unwrap();
                    let mut shift = 0;
                    for (i, &v) in chunk.iter().enumerate() {
                        put(v, n, &mut at);
                        put(packed >> shift, QUINT_BITS_AFTER[i], &mut at);
                        shift += QUINT_BITS_AFTER[i];
                    }
                }
            }
        }
        assert_eq!(at - start, range.sequence_bits(values.len() as u32));
        stream
    }

    #[test]
    fn known_trit_and_quint_packings() {
        // Entries of Arm astc-encoder's trits_of_integer / quints_of_integer tables.
        assert_eq!(unpack_trits(0), [0, 0, 0, 0, 0]);
        assert_eq!(unpack_trits(3), [0, 0, 2, 0, 0]);
        assert_eq!(unpack_trits(7), [1, 0, 2, 0, 0]);
        assert_eq!(unpack_trits(19), [0, 1, 2, 0, 0]);
        assert_eq!(unpack_trits(28), [0, 0, 0, 2, 2]);
        assert_eq!(unpack_trits(31), [0, 0, 2, 2, 2]);
        assert_eq!(unpack_trits(45), [1, 2, 2, 1, 0]);
        assert_eq!(unpack_quints(5), [0, 4, 0]);
        assert_eq!(unpack_quints(6), [4, 4, 0]);
        assert_eq!(unpack_quints(7), [4, 4, 4]);
        assert_eq!(unpack_quints(13), [1, 4, 0]);
        assert_eq!(unpack_quints(22), [4, 4, 2]);
        assert_eq!(unpack_quints(29), [3, 4, 0]);
    }

    #[test]
    fn every_digit_combination_has_a_packing() {
        let mut trits = std::collections::HashSet::new();
        for t in 0..256 {
            let d = unpack_trits(t);
            assert!(d.iter().all(|&x| x < 3));
            trits.insert(d);
        }
        assert_eq!(trits.len(), 243);
        let mut quints = std::collections::HashSet::new();
        for q in 0..128 {
            let d = unpack_quints(q);
            assert!(d.iter().all(|&x| x < 5));
            quints.insert(d);
        }
        assert_eq!(quints.len(), 125);
    }

    #[test]
    fn sequence_lengths_match_the_spec() {
        assert_eq!(Range::trit(0).sequence_bits(5), 8);
        assert_eq!(Range::trit(2).sequence_bits(7), 14 + 12);
        assert_eq!(Range::quint(1).sequence_bits(4), 4 + 10);
        assert_eq!(Range::bits(3).sequence_bits(16), 48);
        assert_eq!(Range::trit(6).levels(), 192);
        assert_eq!(Range::quint(5).levels(), 160);
    }

    #[test]
    fn round_trips_over_every_range_and_length() {
        let ranges = [
            Range::bits(1),
            Range::trit(0),
            Range::bits(2),
            Range::quint(0),
            Range::trit(1),
            Range::quint(2),
            Range::trit(4),
            Range::bits(8),
            Range::quint(5),
            Range::trit(6),
        ];
        let mut seed = 0x1234_5678u32;
        for range in ranges {
            for count in 1..=18u32 {
                if range.sequence_bits(count) + 9 > 128 {
                    continue;
                }
                let values: Vec<u32> = (0..count)
                    .map(|_| {
                        seed = seed.wrapping_mul(1_664_525).wrapping_add(1_013_904_223);
                        (seed >> 8) % range.levels()
                    })
                    .collect();
                // Garbage after the sequence must not leak into the last block's digits.
                let end = 9 + range.sequence_bits(count);
                let garbage = if end < 128 { u128::MAX << end } else { 0 };
                let stream = encode(range, &values, 9) | garbage;
                let mut out = vec![0u8; count as usize];
                decode(range, stream, 9, &mut out);
                let got: Vec<u32> = out.iter().map(|&v| v as u32).collect();
                assert_eq!(got, values, "{range:?} × {count}");
            }
        }
    }
}
