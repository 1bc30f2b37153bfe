//! The partition a texel belongs to, from the block's 10-bit partition index (the seed), the
//! texel's position and the partition count: the procedural pattern ASTC uses instead of a
//! table. Follows the Khronos Data Format Specification 1.3, ASTC chapter, section
//! "Partition Pattern Generation" (`select_partition` and `hash52`).

/// Blocks with fewer texels than this are "small": their coordinates are doubled before
/// hashing (DFS "Partition Pattern Generation"; the spec says "less than 31", which selects
/// the same 2D footprints as Arm's "less than 32" since no footprint has 31 texels).
pub const SMALL_BLOCK_TEXELS: u32 = 31;

/// The spec's 32-bit hash of the partition seed.
fn hash52(p: u32) -> u32 {
    let mut p = p;
    p ^= p >> 15;
    p = p.wrapping_sub(p << 17);
    p = p.wrapping_add(p << 7);
    p = p.wrapping_add(p << 4);
    p ^= p >> 5;
    p = p.wrapping_add(p << 16);
    p ^= p >> 7;
    p ^= p >> 3;
    p ^= p << 6;
    p ^= p >> 17;
    p
}

/// The partition (0..`partition_count`) of the texel at (`x`, `y`, `z`) in a block whose
/// partition index is `seed`; `small_block` when the block has fewer than
/// [`SMALL_BLOCK_TEXELS`] texels.
pub fn select_partition(
    seed: u32,
    x: u32,
    y: u32,
    z: u32,
    partition_count: u32,
    small_block: bool,
) -> u32 {
    let (x, y, z) = if small_block {
        (x << 1, y << 1, z << 1)
    } else {
        (x, y, z)
    };
    // The partition count is folded into the seed: 1024 seeds per count.
    let seed = seed + (partition_count - 1) * 1024;
    let rnum = hash52(seed);
    // Twelve 4-bit seeds from the hash, squared to bias them towards small values.
    let nibble = |shift: u32| {
        let s = rnum.rotate_right(shift) & 0xF;
        s * s
    };
    let mut s = [
        nibble(0),
        nibble(4),
        nibble(8),
        nibble(12),
        nibble(16),
        nibble(20),
        nibble(24),
        nibble(28),
        nibble(18),
        nibble(22),
        nibble(26),
        nibble(30), // the spec's (rnum >> 30) | (rnum << 2)
    ];
    let (sh1, sh2) = if seed & 1 != 0 {
        (
            if seed & 2 != 0 { 4 } else { 5 },
            if partition_count == 3 { 6 } else { 5 },
        )
    } else {
        (
            if partition_count == 3 { 6 } else { 5 },
            if seed & 2 != 0 { 4 } else { 5 },
        )
    };
    let sh3 = if seed & 0x10 != 0 { sh1 } else { sh2 };
    for (i, v) in s.iter_mut().enumerate() {
        // seed1..seed8 alternate sh1, sh2; seed9..seed12 use sh3.
        let shift = match i {
            0..=7 if i % 2 == 0 => sh1,
            0..=7 => sh2,
            _ => sh3,
        };
        *v >>= shift;
    }
    let [s1, s2, s3, s4, s5, s6, s7, s8, s9, s10, s11, s12] = s;
    // Four sawtooth functions of position; the largest names the partition.
    let a = (s1 * x + s2 * y + s11 * z + (rnum >> 14)) & 0x3F;
    let b = (s3 * x + s4 * y + s12 * z + (rnum >> 10)) & 0x3F;
    let mut c = (s5 * x + s6 * y + s9 * z + (rnum >> 6)) & 0x3F;
    let mut d = (s7 * x + s8 * y + s10 * z + (rnum >> 2)) & 0x3F;
    if partition_count < 4 {
        d = 0;
    }
    if partition_count < 3 {
        c = 0;
    }
    if a >= b && a >= c && a >= d {
        0
    } else if b >= c && b >= d {
        1
    } else if c >= d {
        2
    } else {
        3
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn hash_matches_the_multiplicative_form() {
        // Arm's encoder folds the first three steps into one multiply by
        // (2^4 + 1)(2^7 + 1)(2^17 - 1) = 0xEEDE0891; both forms must agree.
        for p in [0u32, 1, 1023, 1024, 2047, 3071, 4095, 0xDEAD_BEEF] {
            let mut q = p ^ (p >> 15);
            q = q.wrapping_mul(0xEEDE_0891);
            q ^= q >> 5;
            q = q.wrapping_add(q << 16);
            q ^= q >> 7;
            q ^= q >> 3;
            q ^= q << 6;
            q ^= q >> 17;
            assert_eq!(hash52(p), q, "{p}");
        }
    }

    /// Partition maps from Arm astc-encoder's partition tables (`partition_of_texel`):
    /// footprint, seed, partition count, then each texel's partition, row-major.
    const ARM_MAPS: &[(u32, u32, u32, u32, &str)] = &[
        (4, 4, 1, 2, "0110111011001100"),
        (4, 4, 0, 3, "2000200021112111"),
        (4, 4, 1023, 3, "1012001202110211"),
        (4, 4, 513, 4, "1222222222002011"),
        (4, 4, 1, 4, "0233023322332233"),
        (6, 6, 1023, 2, "011100001100001100001100000100000100"),
        (6, 6, 1023, 3, "100212000212000211002211002211002211"),
        (6, 6, 0, 4, "221000210000120000120000220000220000"),
        (
            12,
            10,
            0,
            3,
            "200000011111200000000111200000000001200000000000211111111111\
             211111111111211111111111211111111111211111111111200111111111",
        ),
        (
            12,
            10,
            900,
            4,
            "000223011100000223011100000220011000000200110000000300110000\
             003200100000000201000000030201000000000000000000000000000000",
        ),
    ];

    #[test]
    fn matches_arm_partition_maps() {
        for &(w, h, seed, count, map) in ARM_MAPS {
            let small = w * h < SMALL_BLOCK_TEXELS;
            let got: String = (0..w * h)
                .map(|i| {
                    let p = select_partition(seed, i % w, i / w, 0, count, small);
                    char::from(b'0' + p as u8)
                })
                .collect();
            assert_eq!(got, map, "{w}x{h} seed {seed} count {count}");
        }
    }
}
