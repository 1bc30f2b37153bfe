//! BC6H: the GPU encoder (the `block_compression` crate's WGSL port of ISPC's kernel)
//! against the CPU one (its CPU port), both against the decoder and the source texels,
//! faces smaller than a block, the containers (KTX2 with and without zstd, DDS read back
//! by an independent decoder, KTX 1 for Filament), and the targets that refuse it.
mod common;

use common::{hdr_chain, log_rmse, output_dir, small_bake as bake};
use splitsum::backend::{Backend, CpuBackend};
use splitsum::environment::Cubemap;
use splitsum::io::PixelFormat;
use splitsum::plan::bc6h::{face_bytes, Bc6hQuality};

/// `cube` through BC6H on `backend` and back.
fn round_trip(
    backend: &dyn Backend,
    cube: &Cubemap,
    quality: Bc6hQuality,
) -> (Vec<Vec<u8>>, Cubemap) {
    let blocks = backend.encode_bc6h(cube, quality).unwrap();
    let levels = blocks
        .iter()
        .enumerate()
        .map(|(m, b)| PixelFormat::Bc6h.decode_faces(b, cube.level_size(m), 6))
        .collect();
    (
        blocks,
        Cubemap {
            size: cube.size,
            levels,
        },
    )
}

/// The encoder against the decoder and the source, every level and preset: within
/// BC6H's error, log RMSE ≤ 0.04 per level (measured 0.008 at 32² to 0.025 at 4², where
/// one block holds a whole face, the sun's included; a wrong block or face order gives
/// ~1), faces of 2² and 1² (padded to one block by repetition) no worse than the rest.
#[test]
fn encoding_round_trips_within_the_formats_error() {
    let cube = hdr_chain();
    for quality in Bc6hQuality::ALL {
        let (blocks, decoded) = round_trip(&CpuBackend, &cube, quality);
        for (m, level) in blocks.iter().enumerate() {
            let n = cube.level_size(m);
            assert_eq!(level.len(), 6 * face_bytes(n), "level {m}");
            assert_eq!(decoded.levels[m].len(), cube.levels[m].len());
            let e = log_rmse(&cube, &decoded, m);
            println!("{} level {m} ({n}²): log RMSE {e:.4}", quality.name());
            assert!(e <= 0.04, "{} level {m}: {e}", quality.name());
        }
    }
}

/// A constant face is one endpoint pair: BC6H holds it to the half-float quantisation of
/// its endpoints (the 10-bit endpoints of its one-region mode map back to half floats
/// within 1/1024 relative).
#[test]
fn constant_faces_come_back_to_the_endpoint_precision() {
    for n in [4u32, 2, 1] {
        let value = [3.25f32, 0.125, 700.0, 1.0];
        let cube = Cubemap {
            size: n,
            levels: vec![vec![value; Cubemap::level_len(n)]],
        };
        let (_, decoded) = round_trip(&CpuBackend, &cube, Bc6hQuality::default());
        for t in &decoded.levels[0] {
            for c in 0..3 {
                let rel = (t[c] - value[c]).abs() / value[c];
                assert!(rel <= 2e-3, "{n}²: {t:?} against {value:?}");
            }
        }
    }
}

/// The GPU encoder against the CPU one on the same input: how many blocks are the same
/// bytes, and how far their decoded texels are apart. The two are ports of one kernel
/// whose mode and partition choices compare squared errors in f32; where two choices are
/// within rounding of each other, a GPU that fuses or reorders that arithmetic may pick
/// another, so the bar is on the decoded texels (log RMSE between the two ≤ 0.02, below
/// either's own error against the source) and on most blocks being identical (≥ 90 %).
/// Measured on lavapipe: every block identical.
#[test]
fn gpu_encoding_matches_cpu() {
    let Some(ctx) = common::gpu() else { return };
    let gpu = splitsum::backend::GpuBackend { ctx };
    let cube = hdr_chain();
    let quality = Bc6hQuality::default();
    let (cpu_blocks, cpu) = round_trip(&CpuBackend, &cube, quality);
    let (gpu_blocks, decoded) = round_trip(&gpu, &cube, quality);
    let (mut same, mut total) = (0, 0);
    for (a, b) in cpu_blocks.iter().zip(&gpu_blocks) {
        assert_eq!(a.len(), b.len());
        for (x, y) in a.chunks_exact(16).zip(b.chunks_exact(16)) {
            same += usize::from(x == y);
            total += 1;
        }
    }
    println!("identical blocks: {same} of {total}");
    for m in 0..cube.levels.len() {
        let apart = log_rmse(&cpu, &decoded, m);
        println!("level {m}: GPU vs CPU log RMSE {apart:.5}");
        assert!(apart <= 0.02, "level {m}: {apart}");
    }
    assert!(same * 10 >= total * 9, "{same} of {total} blocks identical");
}

/// KTX2 with and without zstd: the `ktx2` crate reads BC6H_UFLOAT_BLOCK with the data
/// format descriptor it generates for that format itself (a 4×4 block of 16 bytes, one
/// unsigned-float sample), each level's size in whole blocks (the 2² and 1²
/// levels one block a face), and splitsum's reader decodes what was baked.
#[test]
fn ktx2_holds_bc6h_with_and_without_zstd() {
    let dir = output_dir("bc6h-ktx2");
    for (sub, zstd) in [("plain", "--no-zstd"), ("zstd", "--zstd")] {
        let o = bake(&dir.join(sub), &["--pixel-format", "bc6h", zstd]);
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
        let path = dir.join(sub).join("venice_sunset_1k/specular.ktx2");
        let bytes = std::fs::read(&path).unwrap();
        let reader = ktx2::Reader::new(&bytes[..]).unwrap();
        let h = reader.header();
        assert_eq!(h.format, Some(ktx2::Format::BC6H_UFLOAT_BLOCK));
        assert_eq!((h.face_count, h.level_count, h.type_size), (6, 6, 1));
        // The descriptor the ktx2 crate generates for the format, as KTX-Software does.
        let (want, _) = ktx2::dfd::Basic::from_format(ktx2::Format::BC6H_UFLOAT_BLOCK).unwrap();
        assert_eq!(reader.basic_dfd(), Some(&want));
        for (m, level) in reader.levels().enumerate() {
            let n = 32u32 >> m;
            assert_eq!(level.uncompressed_byte_length as usize, 6 * face_bytes(n));
        }
        let chain = splitsum::io::ktx2::read_cube_chain(&path).unwrap();
        assert_eq!(chain.levels.len(), 6);
        assert!(chain.levels[0]
            .iter()
            .all(|t| t[..3].iter().all(|v| v.is_finite() && *v >= 0.0)));
    }
}

/// DDS (DX10 header, DXGI_FORMAT_BC6H_UF16, linear size, every level) read back through
/// an independent decoder, `texture2ddecoder`'s, which outputs 8-bit texels: on an
/// environment scaled into [0, 1] (where its clamp is not in the way), it agrees with
/// splitsum's decoding within one 8-bit step.
#[test]
fn dds_reads_back_through_another_decoder() {
    let dir = output_dir("bc6h-dds");
    // venice_sunset's radiance reaches ~44: 2^-6 brings it under 1.
    let o = bake(
        &dir,
        &[
            "--pixel-format",
            "bc6h",
            "--container",
            "dds",
            "--exposure",
            "-6",
        ],
    );
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let path = dir.join("venice_sunset_1k/specular.dds");
    let dds = ddsfile::Dds::read(&std::fs::read(&path).unwrap()[..]).unwrap();
    let header10 = dds.header10.as_ref().unwrap();
    assert_eq!(header10.dxgi_format, ddsfile::DxgiFormat::BC6H_UF16);
    assert_eq!(dds.get_num_mipmap_levels(), 6);
    assert_eq!(dds.header.linear_size, Some(face_bytes(32) as u32));
    let ours = splitsum::io::dds::read_cube(&path).unwrap();
    // Level 0 of the first face, as the other decoder sees it.
    let face0 = &dds.data[..face_bytes(32)];
    let mut rgba = vec![0u32; 32 * 32];
    texture2ddecoder::decode_bc6(face0, 32, 32, &mut rgba, false).unwrap();
    let mut worst = 0i32;
    for (k, p) in rgba.iter().enumerate() {
        // texture2ddecoder packs B, G, R, A from the low byte up.
        let theirs = [(p >> 16) & 0xFF, (p >> 8) & 0xFF, p & 0xFF].map(|v| v as i32);
        let t = ours.levels[0][k];
        for c in 0..3 {
            let mine = (t[c].clamp(0.0, 1.0) * 255.0).round() as i32;
            worst = worst.max((mine - theirs[c]).abs());
        }
    }
    assert!(worst <= 1, "worst 8-bit difference {worst}");
}

/// Filament's KTX 1 holds BC6H as GL_COMPRESSED_RGB_BPTC_UNSIGNED_FLOAT (with a warning
/// that it is desktop only); the glTF Sample Viewer and Babylon's .env cannot hold it and
/// are refused before the input is read.
#[test]
fn targets_write_or_refuse_bc6h() {
    let dir = output_dir("bc6h-targets");
    let o = bake(
        &dir.join("filament"),
        &[
            "--target",
            "filament",
            "--pixel-format",
            "bc6h",
            "--min-mip-size",
            "4",
        ],
    );
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(o.status.success(), "{err}");
    assert!(
        err.contains("warning: target filament: Filament reads BC6H"),
        "{err}"
    );
    let ibl = dir.join("filament/venice_sunset_1k/venice_sunset_1k_ibl.ktx");
    let ktx = splitsum::io::ktx1::decode(&std::fs::read(&ibl).unwrap()).unwrap();
    assert_eq!(ktx.gl.internal_format, 0x8E8F);
    assert_eq!(splitsum::io::ktx1::read_cube(&ibl).unwrap().levels.len(), 4);
    for (target, says) in [("gltf", "cannot use bc6h"), ("babylon", "RGBD PNGs")] {
        let o = bake(
            &dir.join(target),
            &["--target", target, "--pixel-format", "bc6h"],
        );
        let err = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(2), "{target}: {err}");
        assert!(err.contains(says), "{target}: {err}");
        assert!(!dir.join(target).exists());
    }
}
