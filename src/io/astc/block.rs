//! Reading the fields of one 128-bit 2D block: void-extent blocks, and for the others the
//! block mode, partition count and index, colour endpoint modes, the colour values' range
//! and values, the dual-plane channel and the stored weights, with every illegal encoding
//! the spec lists recognised. Follows the Khronos Data Format Specification 1.3, ASTC
//! chapter, sections "Block Layout", "Color Endpoint Mode", "Data Size Determination",
//! "Weight Decoding", "Dual-Plane Decoding", "Void-Extent Blocks" and "Illegal Encodings".

use super::block_mode::{self, BlockMode, MAX_WEIGHTS};
use super::endpoints::{self, value_count};
use super::ise::{self, Range};

/// Block mode bits 8:0 of a void-extent block (DFS "ASTC 2D block mode layout").
const VOID_EXTENT_MODE: u32 = 0x1FC;
/// Bits 8:0 of the block mode.
const VOID_EXTENT_MODE_MASK: u32 = 0x1FF;
/// A 2D void extent's four 13-bit coordinates all ones: no extent, just a constant colour.
const VOID_EXTENT_ALL_ONES: u32 = 0x1FFF;
/// Bits of each 2D void-extent coordinate.
const VOID_EXTENT_COORD_BITS: u32 = 13;

/// Bits before the colour values of a single-partition block (11 mode, 2 partition count,
/// 4 CEM; DFS "ASTC single-partition block layout").
const SINGLE_PARTITION_CONFIG_BITS: u32 = 17;
/// Bits before the colour values of a multi-partition block (11 mode, 2 partition count,
/// 10 partition index, 6 CEM; DFS "ASTC multi-partition block layout").
const MULTI_PARTITION_CONFIG_BITS: u32 = 29;
/// Bits of the partition index.
const PARTITION_INDEX_BITS: u32 = 10;
/// At most this many colour values in a block (DFS "Illegal Encodings").
pub const MAX_COLOR_VALUES: usize = 18;
/// Bits of the dual-plane colour component selector.
const CCS_BITS: u32 = 2;

/// Colour value ranges from the largest down to the smallest legal one (0..5); the block
/// uses the first whose sequence fits the bits left (DFS "Data Size Determination").
const COLOR_RANGES: [Range; 17] = [
    Range::bits(8),
    Range::trit(6),
    Range::quint(5),
    Range::bits(7),
    Range::trit(5),
    Range::quint(4),
    Range::bits(6),
    Range::trit(4),
    Range::quint(3),
    Range::bits(5),
    Range::trit(3),
    Range::quint(2),
    Range::bits(4),
    Range::trit(2),
    Range::quint(1),
    Range::bits(3),
    Range::trit(1),
];

/// The fields of a legal non-void-extent block.
#[derive(Clone, Debug)]
pub struct Block {
    /// The weight grid, range and plane count.
    pub mode: BlockMode,
    /// 1 to 4 partitions.
    pub partition_count: u32,
    /// The partition pattern seed (0 for one partition).
    pub partition_index: u32,
    /// Each partition's colour endpoint mode.
    pub cems: [u32; 4],
    /// The unquantised colour values (0..255) of all partitions, in order.
    pub color_values: [u8; MAX_COLOR_VALUES],
    /// The channel (0 = R .. 3 = A) that uses the second weight plane, if dual plane.
    pub plane2_channel: Option<usize>,
    /// The stored weights as integer-sequence values, planes interleaved per grid point.
    pub weights: [u8; MAX_WEIGHTS as usize],
}

/// What a 128-bit block holds.
#[derive(Clone, Debug)]
pub enum Parsed {
    /// A constant colour: four FP16 values when `hdr`, else four UNORM16 values.
    VoidExtent {
        /// The colour is FP16 (else UNORM16).
        hdr: bool,
        /// R, G, B, A.
        color: [u16; 4],
    },
    /// An ordinary block.
    Normal(Block),
    /// An illegal encoding: every texel is the error colour.
    Error,
}

/// Bits `lo .. lo + count` of the block.
fn field(bits: u128, lo: u32, count: u32) -> u32 {
    ((bits >> lo) & ((1u128 << count) - 1)) as u32
}

/// Reads the block `bytes` of a `block_w`×`block_h` footprint.
pub fn parse(bytes: &[u8; 16], block_w: u32, block_h: u32) -> Parsed {
    let bits = u128::from_le_bytes(*bytes);
    let mode = field(bits, 0, 11);
    if mode & VOID_EXTENT_MODE_MASK == VOID_EXTENT_MODE {
        return parse_void_extent(bits);
    }
    match parse_normal(bits, mode, block_w, block_h) {
        Some(block) => Parsed::Normal(block),
        None => Parsed::Error,
    }
}

/// A 2D void-extent block (DFS "ASTC 2D void-extent block layout overview").
fn parse_void_extent(bits: u128) -> Parsed {
    // Bits 11:10 are ones in the 2D layout; anything else is reserved.
    if field(bits, 10, 2) != 0b11 {
        return Parsed::Error;
    }
    let coord = |i: u32| {
        field(
            bits,
            12 + i * VOID_EXTENT_COORD_BITS,
            VOID_EXTENT_COORD_BITS,
        )
    };
    let (min_s, max_s, min_t, max_t) = (coord(0), coord(1), coord(2), coord(3));
    let all_ones = [min_s, max_s, min_t, max_t]
        .iter()
        .all(|&c| c == VOID_EXTENT_ALL_ONES);
    if !all_ones && (min_s >= max_s || min_t >= max_t) {
        return Parsed::Error;
    }
    let color = [0, 1, 2, 3].map(|c| field(bits, 64 + 16 * c, 16) as u16);
    Parsed::VoidExtent {
        hdr: field(bits, 9, 1) == 1,
        color,
    }
}

/// An ordinary block; `None` if it is an illegal encoding.
fn parse_normal(bits: u128, mode: u32, block_w: u32, block_h: u32) -> Option<Block> {
    let mode = block_mode::decode(mode, block_w, block_h)?;
    let partition_count = field(bits, 11, 2) + 1;
    if mode.dual_plane && partition_count == 4 {
        return None;
    }
    let weight_bits = mode.weight_bits();
    // The bits below the weights, from the top down: extra CEM bits, then the CCS.
    let mut below_weights = 128 - weight_bits;
    let mut cems = [0u32; 4];
    let (partition_index, mut config_bits) = if partition_count == 1 {
        cems[0] = field(bits, 13, 4);
        (0, SINGLE_PARTITION_CONFIG_BITS)
    } else {
        let index = field(bits, 13, PARTITION_INDEX_BITS);
        let low = field(bits, 23, 6);
        let selector = low & 0b11;
        if selector == 0 {
            // One full CEM in bits 28:25 shared by every partition.
            cems = [low >> 2; 4];
            (index, MULTI_PARTITION_CONFIG_BITS)
        } else {
            // DFS "ASTC multi-partition color endpoint mode layout": after the 2-bit
            // selector come one class bit C_i per partition then two mode bits M_i each;
            // what does not fit in bits 28:23 sits just below the weights.
            let extra = 3 * partition_count - 4;
            below_weights -= extra;
            let cem_bits = low | (field(bits, below_weights, extra) << 6);
            let base_class = selector - 1;
            for (i, cem) in cems.iter_mut().enumerate().take(partition_count as usize) {
                let i = i as u32;
                let class = base_class + ((cem_bits >> (2 + i)) & 1);
                let low_bits = (cem_bits >> (2 + partition_count + 2 * i)) & 0b11;
                *cem = (class << 2) | low_bits;
            }
            (index, MULTI_PARTITION_CONFIG_BITS + extra)
        }
    };
    let plane2_channel = if mode.dual_plane {
        below_weights -= CCS_BITS;
        config_bits += CCS_BITS;
        Some(field(bits, below_weights, CCS_BITS) as usize)
    } else {
        None
    };

    let value_total: usize = cems[..partition_count as usize]
        .iter()
        .map(|&c| value_count(c))
        .sum();
    if value_total > MAX_COLOR_VALUES {
        return None;
    }
    let remaining = 128u32.checked_sub(config_bits + weight_bits)?;
    let color_range = COLOR_RANGES
        .iter()
        .copied()
        .find(|r| r.sequence_bits(value_total as u32) <= remaining)?;
    let color_start = if partition_count == 1 {
        SINGLE_PARTITION_CONFIG_BITS
    } else {
        MULTI_PARTITION_CONFIG_BITS
    };
    let mut color_values = [0u8; MAX_COLOR_VALUES];
    let color_values_used = &mut color_values[..value_total];
    ise::decode(color_range, bits, color_start, color_values_used);
    for v in color_values_used.iter_mut() {
        *v = endpoints::unquantize(color_range, u32::from(*v));
    }

    // The weights fill from bit 127 downwards: read them from the bit-reversed block.
    let mut weights = [0u8; MAX_WEIGHTS as usize];
    let weight_count = mode.weight_count() as usize;
    ise::decode(
        mode.weight_range,
        bits.reverse_bits(),
        0,
        &mut weights[..weight_count],
    );

    Some(Block {
        mode,
        partition_count,
        partition_index,
        cems,
        color_values,
        plane2_channel,
        weights,
    })
}
