//! ASTC HDR: the encoder (Arm's astc-encoder through vendor/astcenc) against splitsum's own
//! decoder (`io::astc`), that decoder against Arm's on the same blocks and on random
//! ones, the texel error against the source, faces smaller than a block, the KTX2
//! container (with and without zstd, read back by splitsum and described as the `ktx2`
//! crate describes the format), and the targets and containers that refuse it.
mod common;

use common::{hdr_chain, log_rmse, output_dir, small_bake as bake, splitsum, Lcg};
use splitsum::environment::Cubemap;
use splitsum::io::cubemap::BlockEncoder;
use splitsum::io::PixelFormat;
use splitsum::plan::astc::AstcQuality;
use splitsum_astcenc::{Context, Preset};

const FORMATS: [PixelFormat; 2] = [PixelFormat::Astc4x4Hdr, PixelFormat::Astc6x6Hdr];

/// `cube` through ASTC at `quality` and back through splitsum's decoder.
fn round_trip(
    cube: &Cubemap,
    format: PixelFormat,
    quality: AstcQuality,
) -> (Vec<Vec<u8>>, Cubemap) {
    let blocks = BlockEncoder {
        astc_quality: quality,
        ..Default::default()
    };
    common::stored_with(cube, format, &blocks)
}

/// Whether two decoded texels are the same half floats (NaN, the error colour, equal to
/// NaN).
fn same(a: &[f32; 4], b: &[f32; 4]) -> bool {
    a.iter()
        .zip(b)
        .all(|(x, y)| x.to_bits() == y.to_bits() || (x.is_nan() && y.is_nan()))
}

/// splitsum's decoder against Arm's (`astcenc_decompress_image`, HDR profile, f32 out),
/// texel for texel and bit for bit: on what the encoder wrote for a sunny HDRI at both
/// footprints and every preset (every level, faces of 1² to 32²), and on 20 000 random
/// blocks at each of six footprints (legal and illegal encodings, void extents, every
/// endpoint mode the bits select; an illegal block is the error colour in both).
#[test]
fn decoder_matches_arms_decoder_bit_for_bit() {
    assert!(splitsum_astcenc::layout_matches());
    let cube = hdr_chain();
    for format in FORMATS {
        let (bw, bh) = format.block_footprint().unwrap();
        for quality in AstcQuality::ALL {
            let (blocks, ours) = round_trip(&cube, format, quality);
            let mut arm = Context::hdr(bw, bh, Preset::Fastest, 1).unwrap();
            for (m, level) in blocks.iter().enumerate() {
                let n = cube.level_size(m);
                let face = format.image_bytes(n, n);
                for f in 0..6 {
                    let theirs = arm
                        .decompress(n, n, &level[f * face..(f + 1) * face])
                        .unwrap();
                    let mine = &ours.levels[m][f * (n * n) as usize..(f + 1) * (n * n) as usize];
                    let differ = mine
                        .iter()
                        .zip(&theirs)
                        .filter(|(a, b)| !same(a, b))
                        .count();
                    assert_eq!(
                        differ,
                        0,
                        "{} {} level {m} face {f}",
                        format.name(),
                        quality.name()
                    );
                }
            }
        }
    }
    let mut rng = Lcg(0xa57c);
    for (bw, bh) in [(4, 4), (6, 6), (8, 8), (12, 12), (10, 5), (5, 4)] {
        const BLOCKS: u32 = 20_000;
        let bytes: Vec<u8> = (0..BLOCKS * 16)
            .map(|_| (rng.next() * 256.0) as u8)
            .collect();
        // One row of blocks: an image BLOCKS footprints wide.
        let (w, h) = (BLOCKS * bw, bh);
        let theirs = Context::hdr(bw, bh, Preset::Fastest, 2)
            .unwrap()
            .decompress(w, h, &bytes)
            .unwrap();
        let mine = splitsum::io::astc::decode_image(&bytes, w, h, bw, bh);
        let differ = (0..BLOCKS as usize)
            .filter(|&b| {
                (0..bh as usize).any(|y| {
                    (0..bw as usize).any(|x| {
                        let k = y * w as usize + b * bw as usize + x;
                        !same(&mine[k], &theirs[k])
                    })
                })
            })
            .count();
        assert_eq!(
            differ, 0,
            "{bw}x{bh}: {differ} of {BLOCKS} random blocks decode differently"
        );
    }
}

/// How far a level may be from its source, log RMSE per channel: the worst measured on
/// this chain with a margin, against ~1 for a wrong block, face or level order. The
/// encoder weighs each channel by its share of luminance (`plan::astc::CHANNEL_WEIGHTS`),
/// so where one block holds a whole face with the sun (the 2² level) it keeps the
/// luminance and gives up some colour: 0.082 there at both footprints (0.009 with equal
/// weights); elsewhere 4×4 measures 0.008 (32²) to 0.045 (4²), 6×6 0.021 to 0.070.
/// (BC6H on the same chain: 0.008 at 32² to 0.025 at 4², tests/bc6h.rs.)
const BAR: f64 = 0.09;

/// The encoder against the source through splitsum's decoder, every level and preset:
/// log RMSE per level within [`BAR`], faces smaller than a block (2² and 1² at 4×4, 4²
/// to 1² at 6×6) included.
#[test]
fn encoding_round_trips_within_the_formats_error() {
    let cube = hdr_chain();
    for format in FORMATS {
        for quality in AstcQuality::ALL {
            let (blocks, decoded) = round_trip(&cube, format, quality);
            for (m, level) in blocks.iter().enumerate() {
                let n = cube.level_size(m);
                assert_eq!(level.len(), 6 * format.image_bytes(n, n), "level {m}");
                let e = log_rmse(&cube, &decoded, m);
                println!(
                    "{} {} level {m} ({n}²): log RMSE {e:.4}",
                    format.name(),
                    quality.name()
                );
                assert!(
                    e <= BAR,
                    "{} {} level {m}: {e}",
                    format.name(),
                    quality.name()
                );
            }
        }
    }
}

/// A constant face is one endpoint pair, whatever the footprint: it comes back within
/// the HDR endpoints' precision (12-bit LNS values, 2⁻⁸ relative) of its value.
#[test]
fn constant_faces_come_back_to_the_endpoint_precision() {
    for format in FORMATS {
        for n in [8u32, 4, 2, 1] {
            let value = [3.25f32, 0.125, 700.0, 1.0];
            let cube = Cubemap {
                size: n,
                levels: vec![vec![value; Cubemap::level_len(n)]],
            };
            let (_, decoded) = round_trip(&cube, format, AstcQuality::default());
            for t in &decoded.levels[0] {
                for c in 0..3 {
                    let rel = (t[c] - value[c]).abs() / value[c];
                    assert!(
                        rel <= 4e-3,
                        "{} {n}²: {t:?} against {value:?}",
                        format.name()
                    );
                }
                assert_eq!(t[3], 1.0);
            }
        }
    }
}

/// KTX2 with and without zstd, for the generic, bevy and three targets (each with its
/// warning of where ASTC HDR is sampled): the vkFormat of each
/// footprint, the data format descriptor the `ktx2` crate generates for that format (the
/// ASTC colour model, the footprint, one float-and-signed sample, as KTX-Software
/// writes it), each level's size in whole blocks, and splitsum's reader (as `inspect` and
/// `bake` read an input) decoding what was baked, close to the rgba16f bake of the same
/// input.
#[test]
fn ktx2_holds_astc_hdr_for_its_targets() {
    let dir = output_dir("astc-ktx2");
    let reference_dir = dir.join("rgba16f");
    let o = bake(&reference_dir, &["--pixel-format", "rgba16f", "--no-zstd"]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let reference =
        splitsum::io::ktx2::read_cube_chain(&reference_dir.join("venice_sunset_1k/specular.ktx2"))
            .unwrap();
    for (format, vk) in [
        (PixelFormat::Astc4x4Hdr, ktx2::Format::ASTC_4x4_SFLOAT_BLOCK),
        (PixelFormat::Astc6x6Hdr, ktx2::Format::ASTC_6x6_SFLOAT_BLOCK),
    ] {
        for (target, zstd) in [
            ("generic", "--no-zstd"),
            ("generic", "--zstd"),
            ("bevy", "--zstd"),
            ("three", "--zstd"),
        ] {
            let sub = dir.join(format!("{}-{target}{zstd}", format.name()));
            let o = bake(
                &sub,
                &["--target", target, "--pixel-format", format.name(), zstd],
            );
            let err = String::from_utf8_lossy(&o.stderr);
            assert!(o.status.success(), "{err}");
            assert!(
                err.contains("samples ASTC HDR") || err.contains("ASTC HDR is sampled"),
                "{err}"
            );
            let files: &[&str] = match target {
                "three" => &["specular.ktx2"],
                _ => &["specular.ktx2", "irradiance.ktx2"],
            };
            for file in files {
                let path = sub.join("venice_sunset_1k").join(file);
                let bytes = std::fs::read(&path).unwrap();
                let reader = ktx2::Reader::new(&bytes[..]).unwrap();
                let h = reader.header();
                assert_eq!(h.format, Some(vk));
                assert_eq!((h.face_count, h.type_size), (6, 1));
                let (want, _) = ktx2::dfd::Basic::from_format(vk).unwrap();
                assert_eq!(reader.basic_dfd(), Some(&want), "{path:?}");
                for (m, level) in reader.levels().enumerate() {
                    let n = (h.pixel_width >> m).max(1);
                    assert_eq!(
                        level.uncompressed_byte_length as usize,
                        6 * format.image_bytes(n, n)
                    );
                }
            }
            let path = sub.join("venice_sunset_1k/specular.ktx2");
            let chain = splitsum::io::ktx2::read_cube_chain(&path).unwrap();
            assert_eq!(chain.levels.len(), 6);
            if target == "generic" {
                for m in 0..chain.levels.len() {
                    let e = log_rmse(&reference, &chain, m);
                    assert!(
                        e <= 0.04,
                        "{} level {m}: log RMSE {e} against rgba16f",
                        format.name()
                    );
                }
            }
            // `inspect` reads it as an input.
            let o = splitsum().arg("inspect").arg(&path).output().unwrap();
            assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
        }
    }
}

/// DDS has no DXGI format for ASTC and is refused before the input is read (by `bake` and
/// `cubemap`, as is Filament's KTX 1); the targets
/// whose engine or recipe does not load ASTC HDR (gltf, filament's KTX 1, Babylon's RGBD
/// .env) are refused with the reason, exit status 2 and nothing written.
#[test]
fn dds_and_targets_without_astc_are_refused() {
    let dir = output_dir("astc-refused");
    for (args, says) in [
        (&["--container", "dds"][..], "cannot be written as dds"),
        (&["--target", "gltf"][..], "cannot use astc-4x4-hdr"),
        (&["--target", "filament"][..], "cannot be written as KTX 1"),
        (&["--target", "babylon"][..], "RGBD PNGs"),
    ] {
        let out = dir.join(args.join("-"));
        let o = bake(&out, &[args, &["--pixel-format", "astc-4x4-hdr"]].concat());
        let err = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(2), "{args:?}: {err}");
        assert!(err.contains(says), "{args:?}: {err}");
        assert!(!out.exists(), "{args:?} wrote {out:?}");
    }
    // `cubemap` refuses a container that cannot hold the format before it reads the input.
    for (ext, says) in [
        ("dds", "DXGI has no such format"),
        ("ktx", "Filament's KTX 1"),
    ] {
        let path = dir.join(format!("sky.{ext}"));
        let o = splitsum()
            .args([
                "cubemap",
                "tests/data/no-such-input.hdr",
                "--pixel-format",
                "astc-4x4-hdr",
            ])
            .arg("-o")
            .arg(&path)
            .output()
            .unwrap();
        let err = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(2), "{ext}: {err}");
        assert!(err.contains(says), "{ext}: {err}");
        assert!(!path.exists());
    }
}
