//! `cargo bench --bench bench -- astc`: ASTC HDR at 4×4 and 6×6 against BC6H and rgb9e5
//! on a default bake: the texel error per level (log-space RMSE) per astc-encoder preset,
//! the sizes of the files and in video memory, the CPU seconds of a whole bake, and the
//! encoder's throughput per preset.

use splitsum::io::cubemap::{encode_texture, BlockEncoder};
use splitsum::io::PixelFormat;
use splitsum::plan::astc::AstcQuality;
use splitsum::plan::bc6h::Bc6hQuality;
use splitsum::Cubemap;

use crate::bc6h::{baked, log_rmse, video_bytes};

const ASTC: [PixelFormat; 2] = [PixelFormat::Astc4x4Hdr, PixelFormat::Astc6x6Hdr];

/// `cube` encoded in `format` (ASTC at `quality`) and decoded by splitsum's reader.
fn stored(cube: &Cubemap, format: PixelFormat, quality: AstcQuality) -> Vec<Vec<[f32; 4]>> {
    let blocks = BlockEncoder {
        astc_quality: quality,
        ..Default::default()
    };
    let texture = encode_texture(cube, format, &blocks).unwrap();
    texture
        .levels
        .iter()
        .enumerate()
        .map(|(m, b)| format.decode_faces(b, cube.level_size(m), 6))
        .collect()
}

fn texel_errors() {
    println!("\n## Texel error per level of the default specular chain, log-space RMSE\n");
    for name in ["venice_sunset_1k.hdr", "quarry_01_1k.hdr"] {
        let b = baked(name);
        let mut header = vec!["level".to_string(), "edge".into()];
        let mut columns = Vec::new();
        for format in ASTC {
            for q in AstcQuality::ALL {
                header.push(format!("{} {}", format.name(), q.name()));
                columns.push(stored(&b.specular, format, q));
            }
        }
        header.push("bc6h fast".into());
        columns
            .push(crate::common::stored(&b.specular, PixelFormat::Bc6h, Bc6hQuality::Fast).levels);
        header.push("rgb9e5".into());
        columns.push(
            crate::common::stored(&b.specular, PixelFormat::Rgb9e5, Bc6hQuality::Fast).levels,
        );
        println!("{name}:\n\n| {} |", header.join(" | "));
        println!("|{}", "---|".repeat(header.len()));
        for m in 0..b.specular.levels.len() {
            let cells: Vec<String> = columns
                .iter()
                .map(|c| format!("{:.4}", log_rmse(&c[m], &b.specular.levels[m])))
                .collect();
            println!(
                "| {m} | {} | {} |",
                b.specular.level_size(m),
                cells.join(" | ")
            );
        }
        println!();
    }
}

fn sizes() {
    println!(
        "\n## Sizes of the default bake's specular.ktx2 + irradiance.ktx2 (venice_sunset_1k)\n"
    );
    let out = std::path::PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("bench-astc-sizes");
    let b = baked("venice_sunset_1k.hdr");
    println!("| format | files, bytes | / rgb9e5 + zstd | video memory, bytes | / rgb9e5 |");
    println!("|---|---|---|---|---|");
    let mut reference = None;
    for (format, zstd) in [
        ("rgb9e5", "--zstd"),
        ("bc6h", "--zstd"),
        ("astc-4x4-hdr", "--zstd"),
        ("astc-4x4-hdr", "--no-zstd"),
        ("astc-6x6-hdr", "--zstd"),
        ("astc-6x6-hdr", "--no-zstd"),
    ] {
        let dir = out.join(format!("{format}{zstd}"));
        let status = std::process::Command::new(env!("CARGO_BIN_EXE_splitsum"))
            .args([
                "bake",
                "tests/data/venice_sunset_1k.hdr",
                "--backend",
                "cpu",
                "-q",
            ])
            .args(["--pixel-format", format, zstd, "--no-lut", "--no-sh", "-o"])
            .arg(&dir)
            .status()
            .unwrap();
        assert!(status.success());
        let file = |n: &str| {
            std::fs::metadata(dir.join("venice_sunset_1k").join(n))
                .unwrap()
                .len()
        };
        let files = file("specular.ktx2") + file("irradiance.ktx2");
        let pf = splitsum::CUBE_PIXEL_FORMATS
            .iter()
            .find(|(n, _)| *n == format)
            .unwrap()
            .1;
        let video = video_bytes(&b.specular, pf) + video_bytes(&b.irradiance, pf);
        let (rf, rv) = *reference.get_or_insert((files, video));
        println!(
            "| {format} {zstd} | {files} | {:.3} | {video} | {:.3} |",
            files as f64 / rf as f64,
            video as f64 / rv as f64
        );
    }
}

fn bake_cpu_seconds() {
    println!("\n## A default bake on the CPU backend, ASTC and BC6H against rgb9e5 (whole processes, CPU s)\n");
    let out = std::path::PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("bench-astc-bake");
    let bake = |format: &str| {
        let mut c = std::process::Command::new(env!("CARGO_BIN_EXE_splitsum"));
        c.args([
            "bake",
            "tests/data/venice_sunset_1k.hdr",
            "--backend",
            "cpu",
            "-q",
        ])
        .args(["--pixel-format", format, "-o"])
        .arg(out.join(format));
        c
    };
    crate::compare_processes(
        &mut [
            ("bake --pixel-format rgb9e5", &mut bake("rgb9e5")),
            ("bake --pixel-format bc6h", &mut bake("bc6h")),
            (
                "bake --pixel-format astc-4x4-hdr",
                &mut bake("astc-4x4-hdr"),
            ),
            (
                "bake --pixel-format astc-6x6-hdr",
                &mut bake("astc-6x6-hdr"),
            ),
        ],
        0,
    );
}

fn throughput() {
    let b = baked("venice_sunset_1k.hdr");
    let levels = b.specular.levels.len();
    println!(
        "\n## astc-encoder alone on the default chain ({}² → {}², {levels} levels, 6 faces), all threads\n",
        b.specular.size,
        b.specular.level_size(levels - 1)
    );
    let texels: usize = (0..b.specular.levels.len())
        .map(|m| 6 * (b.specular.level_size(m) as usize).pow(2))
        .sum();
    println!("| format | preset | wall s | CPU s | Mtexel/s (wall) |");
    println!("|---|---|---|---|---|");
    for format in ASTC {
        for q in AstcQuality::ALL {
            let blocks = BlockEncoder {
                astc_quality: q,
                ..Default::default()
            };
            let (wall, cpu) = crate::measure(1, || {
                encode_texture(&b.specular, format, &blocks).unwrap();
            });
            println!(
                "| {} | {} | {wall:.3} | {cpu:.2} | {:.1} |",
                format.name(),
                q.name(),
                texels as f64 / wall / 1e6
            );
        }
    }
}

/// Every table of the section.
pub fn benchmarks() {
    texel_errors();
    sizes();
    bake_cpu_seconds();
    throughput();
}
