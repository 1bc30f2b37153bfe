//! Whole-block checks of the decoder: void-extent blocks, illegal encodings, image assembly,
//! and real blocks (from Arm's encoder and random legal encodings) with the texels Arm's
//! astc-encoder decodes them to with `ASTCENC_PRF_HDR` and f32 output.

use super::*;

mod arm_cases;
use arm_cases::{BIG_BLOCK, BIG_SAMPLES, CASES, ERROR_BLOCKS};

/// Bits of an f32 texel, for exact comparison.
fn bits(t: [f32; 4]) -> [u32; 4] {
    t.map(f32::to_bits)
}

/// Whether two decoded channels are the same value (NaN equal to any NaN).
fn same(a: f32, b: f32) -> bool {
    a.to_bits() == b.to_bits() || (a.is_nan() && b.is_nan())
}

/// An FP16 bit pattern widened by the `half` crate (independent of this decoder's own).
fn widen(h: u16) -> f32 {
    half::f16::from_bits(h).to_f32()
}

/// A block and what Arm's decoder gives it.
struct Case {
    /// What the block exercises.
    what: &'static str,
    /// Footprint width.
    w: u32,
    /// Footprint height.
    h: u32,
    /// The block.
    block: [u8; 16],
    /// Arm's texels as FP16, RGBA per texel, row-major.
    texels: &'static [u16],
}

#[test]
fn real_blocks_match_arm() {
    for case in CASES {
        let mut out = [[0.0f32; 4]; 144];
        decode_block(&case.block, case.w, case.h, &mut out);
        let n = (case.w * case.h) as usize;
        assert_eq!(case.texels.len(), n * 4, "{}", case.what);
        for (i, want) in case.texels.chunks(4).enumerate() {
            for c in 0..4 {
                let (got, want) = (out[i][c], widen(want[c]));
                assert!(
                    same(got, want),
                    "{}: texel {i} channel {c}: {got} != {want}",
                    case.what
                );
            }
        }
    }
}

#[test]
fn big_block_samples_match_arm() {
    let mut out = [[0.0f32; 4]; 144];
    decode_block(&BIG_BLOCK, 12, 12, &mut out);
    for sample in BIG_SAMPLES.chunks(5) {
        let i = sample[0] as usize;
        for c in 0..4 {
            assert!(
                same(out[i][c], widen(sample[1 + c])),
                "texel {i} channel {c}"
            );
        }
    }
}

/// Asserts that `block` decodes to the error colour at `w`×`h`.
fn assert_error(block: &[u8; 16], w: u32, h: u32, why: &str) {
    let mut out = [[0.0f32; 4]; 144];
    decode_block(block, w, h, &mut out);
    let n = (w * h) as usize;
    assert!(
        out[..n].iter().all(|t| bits(*t) == bits(ERROR_TEXEL)),
        "{why}"
    );
}

#[test]
fn illegal_blocks_are_errors() {
    for block in &ERROR_BLOCKS {
        assert_error(block, 4, 4, "random block Arm rejects");
    }
    let block = |v: u128| v.to_le_bytes();
    assert_error(&block(0), 4, 4, "reserved block mode");
    // Mode 0x451: dual-plane 4×4 grid of 0..2 weights, legal with three partitions.
    let mut out = [[0.0f32; 4]; 16];
    decode_block(&block(0x451 | (2 << 11)), 4, 4, &mut out);
    assert!(out.iter().all(|t| !t[0].is_nan()));
    assert_error(
        &block(0x451 | (3 << 11)),
        4,
        4,
        "dual plane with four partitions",
    );
    // Four partitions all of class 3: 32 colour values > 18.
    let four_class3 = 0x42 | (3 << 11) | (0x3F << 23);
    assert_error(&block(four_class3), 4, 4, "more than 18 colour values");
    // An 8×4 grid of 0..7 weights takes 96 bits, leaving 15 for colour: enough for CEM 0's
    // two values but not CEM 15's eight (fewer than 0..5 each).
    decode_block(&block(0x57), 8, 8, &mut out);
    assert!(out.iter().all(|t| !t[0].is_nan()));
    assert_error(
        &block(0x57 | (15 << 13)),
        8,
        8,
        "colour values below range 0..5",
    );
    // The same mode's grid is wider than a 4×4 footprint.
    assert_error(&block(0x57), 4, 4, "weight grid larger than the footprint");
}

#[test]
fn illegal_footprints_and_short_outputs() {
    let block = CASES[0].block;
    assert!(is_legal_footprint(10, 5) && !is_legal_footprint(4, 5) && !is_legal_footprint(0, 0));
    assert_error(&block, 7, 7, "not an ASTC footprint");
    // A short output gets the texels that fit; nothing panics.
    let mut full = [[0.0f32; 4]; 16];
    decode_block(&block, 4, 4, &mut full);
    let mut short = [[9.0f32; 4]; 5];
    decode_block(&block, 4, 4, &mut short);
    assert_eq!(
        short.map(bits),
        <[[f32; 4]; 5]>::try_from(&full[..5]).unwrap().map(bits)
    );
    decode_block(&block, 4, 4, &mut []);
}

#[test]
fn images_crop_padding_and_blacken_missing_blocks() {
    // A 7×6 image of 4×4 blocks: 2×2 blocks, the right and bottom ones cropped; the last
    // block's bytes are missing.
    let blocks: Vec<[u8; 16]> = CASES[..3].iter().map(|c| c.block).collect();
    let bytes: Vec<u8> = blocks.iter().flatten().copied().collect();
    let image = decode_image(&bytes, 7, 6, 4, 4);
    assert_eq!(image.len(), 42);
    for (k, block) in blocks.iter().enumerate() {
        let mut texels = [[0.0f32; 4]; 16];
        decode_block(block, 4, 4, &mut texels);
        let (x0, y0) = ((k % 2) * 4, (k / 2) * 4);
        for y in y0..(y0 + 4).min(6) {
            for x in x0..(x0 + 4).min(7) {
                let want = texels[(y - y0) * 4 + (x - x0)];
                assert_eq!(bits(image[y * 7 + x]), bits(want), "({x}, {y})");
            }
        }
    }
    for y in 4..6 {
        for x in 4..7 {
            assert_eq!(image[y * 7 + x], MISSING_TEXEL);
        }
    }
    assert!(decode_image(&bytes, 0, 0, 4, 4).is_empty());
    let bad = decode_image(&bytes, 3, 2, 3, 3);
    assert!(bad.iter().all(|t| bits(*t) == bits(ERROR_TEXEL)));
}

/// A 2D void-extent block with all-ones extents and the given colour.
fn void_extent(hdr: bool, color: [u16; 4]) -> [u8; 16] {
    let mut b = [0xFFu8; 16];
    b[0] = 0xFC;
    b[1] = if hdr { 0xFF } else { 0xFD };
    for (c, v) in color.iter().enumerate() {
        b[8 + 2 * c..10 + 2 * c].copy_from_slice(&v.to_le_bytes());
    }
    b
}

#[test]
fn hdr_void_extent_is_its_fp16_constant() {
    // 2.5, 60000 (0x7B53), 1e-4 (0x068E), 1.0.
    let block = void_extent(true, [0x4100, 0x7B53, 0x068E, 0x3C00]);
    let mut out = [[0.0; 4]; 36];
    decode_block(&block, 6, 6, &mut out);
    let want = [2.5, 60000.0, widen(0x068E), 1.0];
    assert!(out.iter().all(|t| bits(*t) == bits(want)));
}

#[test]
fn ldr_void_extent_converts_unorm16() {
    // UNORM16 65535 is exactly 1.0; others are c / 65536 rounded toward zero.
    let block = void_extent(false, [0xFFFF, 0x8000, 0, 0xFFFE]);
    let mut out = [[0.0; 4]; 16];
    decode_block(&block, 4, 4, &mut out);
    let want = [1.0, 0.5, 0.0, widen(0x3BFF)];
    assert!(out.iter().all(|t| bits(*t) == bits(want)));
}

#[test]
fn bad_void_extents_are_errors() {
    // Extents all zero: min S >= max S.
    let mut block = [0u8; 16];
    block[0] = 0xFC;
    block[1] = 0x0D; // bits 8, 10, 11 set; bit 9 (HDR) clear
    assert_error(&block, 4, 4, "empty void extent");
    // Reserved bits 11:10 not both one.
    let mut block = void_extent(true, [0; 4]);
    block[1] &= !0x08;
    assert_error(&block, 4, 4, "reserved void-extent bits");
}
