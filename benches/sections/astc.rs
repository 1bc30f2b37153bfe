//! `cargo bench --bench bench -- astc`: ASTC HDR at 4×4 and 6×6 against BC6H and rgb9e5
//! on a default bake: the texel error per level (log-space RMSE) per astc-encoder preset,
//! the sizes of the files and in video memory, the CPU seconds of a whole bake, and the
//! encoder's throughput per preset.

use splitsum::io::cubemap::{encode_texture, BlockEncoder};
use splitsum::io::PixelFormat;
use splitsum::plan::astc::AstcQuality;
use splitsum::plan::bc6h::Bc6hQuality;
use splitsum::Cubemap;

use crate::bc6h::{bake_command, baked, default_chain, level_rows, sizes_table};

const ASTC: [PixelFormat; 2] = [PixelFormat::Astc4x4Hdr, PixelFormat::Astc6x6Hdr];

/// `cube` encoded in `format` (ASTC at `quality`) and decoded by splitsum's reader.
fn stored(cube: &Cubemap, format: PixelFormat, quality: AstcQuality) -> Vec<Vec<[f32; 4]>> {
    let blocks = BlockEncoder {
        astc_quality: quality,
        ..Default::default()
    };
    crate::common::stored_with(cube, format, &blocks).1.levels
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
        level_rows(&b.specular, &columns);
    }
}

fn sizes() {
    sizes_table(
        "bench-astc-sizes",
        &[
            ("rgb9e5", "--zstd"),
            ("bc6h", "--zstd"),
            ("astc-4x4-hdr", "--zstd"),
            ("astc-4x4-hdr", "--no-zstd"),
            ("astc-6x6-hdr", "--zstd"),
            ("astc-6x6-hdr", "--no-zstd"),
        ],
    );
}

fn bake_cpu_seconds() {
    println!("\n## A default bake on the CPU backend, ASTC and BC6H against rgb9e5 (whole processes, CPU s)\n");
    let out = std::path::PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("bench-astc-bake");
    let formats = ["rgb9e5", "bc6h", "astc-4x4-hdr", "astc-6x6-hdr"];
    let names: Vec<String> = formats
        .iter()
        .map(|f| format!("bake --pixel-format {f}"))
        .collect();
    let mut commands: Vec<_> = formats
        .iter()
        .map(|f| bake_command(&out.join(f), f))
        .collect();
    let mut rows: Vec<(&str, &mut std::process::Command)> = names
        .iter()
        .map(String::as_str)
        .zip(commands.iter_mut())
        .collect();
    crate::compare_processes(&mut rows, 0);
}

fn throughput() {
    let (b, texels) = default_chain("astc-encoder alone, all threads,");
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
