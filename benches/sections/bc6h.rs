//! `cargo bench --bench bench -- bc6h`: BC6H against the uncompressed formats on a default
//! bake: the texel error per level (log-space RMSE, as GPURealTimeBC6H and ISPC report
//! it), the sizes of the files and in video memory, the CPU seconds of a whole bake, and the
//! encoder's throughput on each backend.

use splitsum::backend::CpuBackend;
use splitsum::bake::{bake_environment, BakeOptions};
use splitsum::io::PixelFormat;
use splitsum::plan::bc6h::Bc6hQuality;
use splitsum::Cubemap;

/// √(mean((ln(1 + a) − ln(1 + b))²)) over every channel of two levels.
pub fn log_rmse(a: &[[f32; 4]], b: &[[f32; 4]]) -> f64 {
    let sum: f64 = a
        .iter()
        .zip(b)
        .flat_map(|(x, y)| (0..3).map(move |c| (x[c] as f64).ln_1p() - (y[c] as f64).ln_1p()))
        .map(|d| d * d)
        .sum();
    (sum / (3 * a.len()) as f64).sqrt()
}

/// The default bake of `name` in memory on the CPU backend.
pub fn baked(name: &str) -> splitsum::BakedEnvironment {
    let e = crate::common::test_equirect(name);
    bake_environment(
        &CpuBackend,
        splitsum::Environment::Equirect(e),
        &BakeOptions::default(),
        &mut |_| {},
        &mut Vec::new(),
    )
    .unwrap()
}

fn texel_errors() {
    println!("\n## Texel error per level of the default specular chain, log-space RMSE\n");
    for name in ["venice_sunset_1k.hdr", "quarry_01_1k.hdr"] {
        let b = baked(name);
        println!("{name}:\n");
        println!(
            "| level | edge | bc6h fast | bc6h basic | bc6h slow | rgb9e5 | rg11b10f | rgba16f |"
        );
        println!("|---|---|---|---|---|---|---|---|");
        let mut columns = Vec::new();
        for q in Bc6hQuality::ALL {
            columns.push(crate::common::stored(&b.specular, PixelFormat::Bc6h, q).levels);
        }
        for f in [
            PixelFormat::Rgb9e5,
            PixelFormat::Rg11b10f,
            PixelFormat::Rgba16f,
        ] {
            columns.push(crate::common::stored(&b.specular, f, Bc6hQuality::default()).levels);
        }
        level_rows(&b.specular, &columns);
    }
}

/// One row per level of `chain`: its index, edge and each column's log RMSE against it.
pub fn level_rows(chain: &Cubemap, columns: &[Vec<Vec<[f32; 4]>>]) {
    for m in 0..chain.levels.len() {
        let cells: Vec<String> = columns
            .iter()
            .map(|c| format!("{:.4}", log_rmse(&c[m], &chain.levels[m])))
            .collect();
        println!("| {m} | {} | {} |", chain.level_size(m), cells.join(" | "));
    }
    println!();
}

/// Bytes in video memory of every level of a cube in `format`.
pub fn video_bytes(cube: &Cubemap, format: PixelFormat) -> usize {
    (0..cube.levels.len())
        .map(|m| 6 * format.image_bytes(cube.level_size(m), cube.level_size(m)))
        .sum()
}

fn sizes() {
    sizes_table(
        "bench-bc6h-sizes",
        &[
            ("rgb9e5", "--zstd"),
            ("bc6h", "--zstd"),
            ("bc6h", "--no-zstd"),
            ("rgba16f", "--zstd"),
        ],
    );
}

/// The table of the default bake's `specular.ktx2` + `irradiance.ktx2` sizes
/// (venice_sunset_1k), in the file and in video memory, for each (pixel format, zstd flag)
/// of `rows`, against the first; the bakes go to `target/tmp/<out>`.
pub fn sizes_table(out: &str, rows: &[(&str, &str)]) {
    println!(
        "\n## Sizes of the default bake's specular.ktx2 + irradiance.ktx2 (venice_sunset_1k)\n"
    );
    let out = std::path::PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join(out);
    let b = baked("venice_sunset_1k.hdr");
    println!("| format | files, bytes | / first | video memory, bytes | / first |");
    println!("|---|---|---|---|---|");
    let mut reference = None;
    for &(format, zstd) in rows {
        let dir = out.join(format!("{format}{zstd}"));
        let status = bake_command(&dir, format)
            .args([zstd, "--no-lut", "--no-sh"])
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

/// A default bake of venice_sunset_1k on the CPU backend in `format`, quiet, into `dir`.
pub fn bake_command(dir: &std::path::Path, format: &str) -> std::process::Command {
    let mut c = std::process::Command::new(env!("CARGO_BIN_EXE_splitsum"));
    c.args([
        "bake",
        "tests/data/venice_sunset_1k.hdr",
        "--backend",
        "cpu",
        "-q",
    ])
    .args(["--pixel-format", format, "-o"])
    .arg(dir);
    c
}

fn bake_cpu_seconds() {
    println!(
        "\n## A default bake on the CPU backend, bc6h against rgb9e5 (whole processes, CPU s)\n"
    );
    let out = std::path::PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("bench-bc6h-bake");
    crate::compare_processes(
        &mut [
            (
                "bake --pixel-format rgb9e5",
                &mut bake_command(&out.join("rgb9e5"), "rgb9e5"),
            ),
            (
                "bake --pixel-format bc6h",
                &mut bake_command(&out.join("bc6h"), "bc6h"),
            ),
        ],
        0,
    );
}

fn throughput() {
    let (b, texels) = default_chain("The BC6H encoder alone");
    println!("| backend | preset | first call wall s | wall s | CPU s | Mtexel/s (wall) |");
    println!("|---|---|---|---|---|---|");
    for (name, backend) in crate::cpu_and_gpu_backends() {
        // A software adapter takes minutes a preset: the default one alone there.
        let presets: &[Bc6hQuality] = if name == "cpu" {
            &Bc6hQuality::ALL
        } else {
            &[Bc6hQuality::default()]
        };
        for &q in presets {
            let first = std::time::Instant::now();
            backend.encode_bc6h(&b.specular, q).unwrap();
            let first = first.elapsed().as_secs_f64();
            let (wall, cpu) = crate::measure(1, || {
                backend.encode_bc6h(&b.specular, q).unwrap();
            });
            println!(
                "| {name} | {} | {first:.2} | {wall:.3} | {cpu:.2} | {:.1} |",
                q.name(),
                texels as f64 / wall / 1e6
            );
        }
    }
}

/// The default bake of venice_sunset_1k and its specular chain's texel count, after a
/// heading "`what` on the default chain (its edges, levels, 6 faces)".
pub fn default_chain(what: &str) -> (splitsum::BakedEnvironment, usize) {
    let b = baked("venice_sunset_1k.hdr");
    let levels = b.specular.levels.len();
    println!(
        "\n## {what} on the default chain ({}² → {}², {levels} levels, 6 faces)\n",
        b.specular.size,
        b.specular.level_size(levels - 1)
    );
    let texels = (0..levels)
        .map(|m| 6 * (b.specular.level_size(m) as usize).pow(2))
        .sum();
    (b, texels)
}

/// Every table of the section.
pub fn benchmarks() {
    texel_errors();
    sizes();
    bake_cpu_seconds();
    throughput();
}
