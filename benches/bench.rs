//! `cargo bench`: peak memory, bake and cubemap timings, and the BRDF LUT's timings and
//! accuracy on both backends, printed as tables. `cargo bench --bench bench -- memory`
//! (or bake, cubemap, specular, lut, ltc, preview, bc6h, astc, view) runs only those
//! sections.
//!
//! CPU seconds come from /proc/self/stat (user + system, all threads), wall seconds from a
//! monotonic clock. GPU times are measured around the whole kernel call (upload, dispatch,
//! readback) after one warm-up call that also pays the driver's shader compilation.

#[path = "sections/astc.rs"]
mod astc;
#[path = "sections/bc6h.rs"]
mod bc6h;
#[path = "../tests/common/mod.rs"]
mod common;
#[path = "sections/ltc.rs"]
mod ltc;
#[path = "sections/view.rs"]
mod view;

use std::time::Instant;

use splitsum::math::brdf::{fresnel_schlick_weight, g1_schlick_ggx, k_ibl};
use splitsum::math::sampling::{hammersley, importance_sample_ggx};
use splitsum::plan::lut::{lut_texel_coords, LutQuadrature};

/// The sum of two consecutive clock-tick fields of /proc/self/stat, from `first` (counted
/// after the command name), in seconds (Linux; USER_HZ is 100 on every mainstream
/// architecture). None elsewhere.
fn stat_seconds(first: usize) -> Option<f64> {
    let stat = std::fs::read_to_string("/proc/self/stat").ok()?;
    let after = &stat[stat.rfind(')')? + 2..];
    let fields: Vec<&str> = after.split_whitespace().collect();
    let a: f64 = fields.get(first)?.parse().ok()?;
    let b: f64 = fields.get(first + 1)?.parse().ok()?;
    Some((a + b) / 100.0)
}

/// User + system CPU seconds of this process so far (utime, stime).
fn cpu_seconds() -> Option<f64> {
    stat_seconds(11)
}

/// User + system CPU seconds of this process's waited-for children so far (cutime,
/// cstime).
fn children_cpu_seconds() -> Option<f64> {
    stat_seconds(13)
}

/// CPU seconds of one run of `cmd` (a child process), or None if it cannot run.
fn child_cpu(cmd: &mut std::process::Command) -> Option<f64> {
    let before = children_cpu_seconds()?;
    let status = cmd
        .stdout(std::process::Stdio::null())
        .stderr(std::process::Stdio::null())
        .status()
        .ok()?;
    status
        .success()
        .then(|| children_cpu_seconds().map(|a| a - before))?
}

/// The whole default `splitsum bake` process against Filament's cmgen doing the cube 256,
/// the GGX chain 256 and SH3 (`cmgen --size=256 --sh=3 --ibl-ld`) on the same HDRI,
/// interleaved, [`RUNS`] runs each, CPU seconds (Debian: `apt-get install libfilament-tools`).
fn process_versus_cmgen() {
    let input = std::path::Path::new("tests/data/venice_sunset_1k.hdr");
    let out = std::path::PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("bench-vs-cmgen");
    let _ = std::fs::create_dir_all(&out);
    let splitsum = || {
        let mut c = std::process::Command::new(env!("CARGO_BIN_EXE_splitsum"));
        c.args(["bake", "--quiet", "-o"]).arg(&out).arg(input);
        c
    };
    let cmgen = || {
        let mut c = std::process::Command::new("cmgen");
        c.args(["--quiet", "--size=256", "--sh=3", "-f", "hdr"])
            .arg(format!("--ibl-ld={}", out.display()))
            .arg(input);
        c
    };
    println!("\n## The whole default bake process vs cmgen (cube 256 + GGX 256 + SH3), CPU s\n");
    compare_processes(
        &mut [
            ("splitsum bake (auto)", &mut splitsum()),
            ("cmgen", &mut cmgen()),
        ],
        1,
    );
}

/// `splitsum lut` (512², default model; auto and CPU backends) against cmgen's DFG LUT at
/// 128² and 512², the processes timed in one run.
fn lut_versus_cmgen() {
    let out = std::path::PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("bench-lut-vs-cmgen");
    let _ = std::fs::create_dir_all(&out);
    let splitsum = |backend: &str| {
        let mut c = std::process::Command::new(env!("CARGO_BIN_EXE_splitsum"));
        c.args(["lut", "--size", "512", "--backend", backend, "-o"])
            .arg(out.join(format!("splitsum-{backend}.png")));
        c
    };
    let cmgen = |size: u32| {
        let mut c = std::process::Command::new("cmgen");
        c.arg(format!(
            "--ibl-dfg={}",
            out.join(format!("cmgen{size}.png")).display()
        ))
        .arg(format!("--size={size}"));
        c
    };
    println!("\n## `splitsum lut` 512² vs cmgen's DFG LUT, whole processes, CPU s\n");
    compare_processes(
        &mut [
            ("splitsum lut 512² (auto)", &mut splitsum("auto")),
            ("splitsum lut 512² (cpu)", &mut splitsum("cpu")),
            ("cmgen --ibl-dfg 128²", &mut cmgen(128)),
            ("cmgen --ibl-dfg 512²", &mut cmgen(512)),
        ],
        2,
    );
}

/// Runs each command three times, interleaved, and prints each one's CPU seconds and its
/// ratio to command `reference`; says so and stops if a command (cmgen, from Debian's
/// `libfilament-tools`) is not installed.
/// Interleaved runs of each process in [`compare_processes`]: a shared machine's CPU time varies
/// by ±10 % from run to run, so a ratio near a bar needs more than three.
const RUNS: usize = 5;

fn compare_processes(commands: &mut [(&str, &mut std::process::Command)], reference: usize) {
    let mut times: Vec<Vec<f64>> = vec![Vec::new(); commands.len()];
    for _ in 0..RUNS {
        for (k, (name, cmd)) in commands.iter_mut().enumerate() {
            match child_cpu(cmd) {
                Some(t) => times[k].push(t),
                None => {
                    println!("({name} could not run; cmgen: `apt-get install libfilament-tools`)");
                    return;
                }
            }
        }
    }
    let mean = |v: &[f64]| v.iter().sum::<f64>() / v.len().max(1) as f64;
    println!(
        "| process | runs (CPU s) | mean | / {} |",
        commands[reference].0
    );
    println!("|---|---|---|---|");
    let first = mean(&times[reference]);
    for ((name, _), v) in commands.iter().zip(&times) {
        let runs: Vec<String> = v.iter().map(|t| format!("{t:.2}")).collect();
        println!(
            "| {name} | {} | {:.2} | {:.3} |",
            runs.join(", "),
            mean(v),
            mean(v) / first
        );
    }
}

/// Runs `f` `runs` times; returns (median wall s, mean CPU s).
fn measure(runs: usize, mut f: impl FnMut()) -> (f64, f64) {
    let mut walls = Vec::new();
    let cpu0 = cpu_seconds().unwrap_or(0.0);
    for _ in 0..runs {
        let t = Instant::now();
        f();
        walls.push(t.elapsed().as_secs_f64());
    }
    let cpu = (cpu_seconds().unwrap_or(0.0) - cpu0) / runs as f64;
    walls.sort_by(f64::total_cmp);
    (walls[runs / 2], cpu)
}

/// The LearnOpenGL-style estimator the quality bar compares against: N Hammersley GGX
/// samples, A += G_vis (1 − Fc), B += G_vis Fc with G_vis = G (v·h) / ((n·h)(n·v)).
fn monte_carlo_texel(n_dot_v: f32, roughness: f32, samples: u32) -> [f32; 2] {
    let v = [(1.0 - n_dot_v * n_dot_v).sqrt(), 0.0, n_dot_v];
    let alpha = roughness * roughness;
    let k = k_ibl(roughness);
    let mut ab = [0.0f32; 2];
    for i in 0..samples {
        let h = importance_sample_ggx(hammersley(i, samples), alpha);
        let v_dot_h = v[0] * h[0] + v[2] * h[2];
        let n_dot_l = 2.0 * v_dot_h * h[2] - v[2];
        if n_dot_l > 0.0 {
            let g = g1_schlick_ggx(n_dot_l, k) * g1_schlick_ggx(n_dot_v, k);
            let g_vis = g * v_dot_h / (h[2] * n_dot_v);
            let fc = fresnel_schlick_weight(v_dot_h);
            ab[0] += (1.0 - fc) * g_vis;
            ab[1] += fc * g_vis;
        }
    }
    [ab[0] / samples as f32, ab[1] / samples as f32]
}

/// A synthetic equirect with a sun and a sky gradient.
fn synthetic_equirect(width: u32) -> splitsum::Equirect {
    let h = width / 2;
    let data = (0..h)
        .flat_map(|y| (0..width).map(move |x| (x, y)))
        .map(|(x, y)| {
            let d = splitsum::math::cubemap::equirect_direction(
                (x as f32 + 0.5) / width as f32,
                (y as f32 + 0.5) / h as f32,
            );
            let sun = if d[0] * 0.6 + d[1] * 0.8 > 0.9995 {
                50_000.0
            } else {
                0.0
            };
            let sky = 0.5 + 0.5 * d[1].max(0.0);
            [sky + sun, sky * 1.1 + sun, sky * 1.3 + sun]
        })
        .collect();
    splitsum::Equirect {
        width,
        height: h,
        data,
    }
}

fn cubemap_benchmarks() {
    use splitsum::environment::{Environment, EquirectIntegral};
    use splitsum::stages::convert::environment_to_cube;
    println!("\n## HDRI → cubemap 512 with mips\n");
    println!("| input | stage | backend | wall s | CPU s |");
    println!("|---|---|---|---|---|");
    let venice = splitsum::io::input::load_environment(
        std::path::Path::new("tests/data/venice_sunset_1k.hdr"),
        &Default::default(),
    )
    .map(|l| l.env);
    let inputs: Vec<(String, Environment)> = [
        venice
            .ok()
            .map(|e| ("venice_sunset_1k.hdr (1024×512)".to_string(), e)),
        Some((
            "synthetic 8192×4096".to_string(),
            Environment::Equirect(synthetic_equirect(8192)),
        )),
    ]
    .into_iter()
    .flatten()
    .collect();
    let gpu = splitsum::backend::GpuBackend::new().ok();
    for (name, env) in &inputs {
        let Environment::Equirect(e) = env else {
            continue;
        };
        let (wall, cpu) = measure(1, || {
            EquirectIntegral::new(e.clone());
        });
        println!(
            "| {name} | cumulative tables (part of each conversion below) | cpu | {wall:.3} | {cpu:.3} |"
        );
        let mut backends: Vec<(&str, &dyn splitsum::backend::Backend)> =
            vec![("cpu", &splitsum::backend::CpuBackend)];
        if let Some(g) = &gpu {
            backends.push(("gpu", g));
        }
        for (label, backend) in backends {
            let (wall, cpu) = measure(1, || {
                environment_to_cube(backend, env, 512, true, 0.0).unwrap();
            });
            println!("| {name} | convert (tables, level 0, 9 mips, readback) | {label} | {wall:.3} | {cpu:.3} |");
        }
    }
}

/// Where the CPU backend's specular time goes: each level of venice_sunset_1k's default
/// 256 chain with its method.
fn specular_benchmarks() {
    use splitsum::backend::cpu::specular::prefilter_level;
    use splitsum::plan::chain::{
        chain_levels, level_method, mip_roughness, DEFAULT_MIN_MIP_SIZE, DEFAULT_SAMPLES,
    };
    use splitsum::plan::sources::split_hot_texels;
    println!("\n## CPU specular chain of venice_sunset_1k.hdr (256, default levels), per level\n");
    println!("| level | size | roughness | method | wall s | CPU s |");
    println!("|---|---|---|---|---|---|");
    let loaded = splitsum::io::input::load_environment(
        std::path::Path::new("tests/data/venice_sunset_1k.hdr"),
        &Default::default(),
    )
    .unwrap();
    let env = splitsum::stages::convert::environment_to_cube(
        &splitsum::backend::CpuBackend,
        &loaded.env,
        256,
        true,
        0.0,
    )
    .unwrap();
    let levels = chain_levels(env.size, DEFAULT_MIN_MIP_SIZE);
    let (wall, cpu) = measure(1, || {
        split_hot_texels(&env);
    });
    println!("| - | - | - | split hot texels | {wall:.3} | {cpu:.2} |");
    let sampled = split_hot_texels(&env);
    println!("| - | - | - | {} hot texels | - | - |", sampled.hot.len());
    for m in 1..levels {
        let r = mip_roughness(m, levels);
        let method = level_method(env.size, m, r, DEFAULT_SAMPLES);
        let size = env.level_size(m as usize);
        let (wall, cpu) = measure(1, || {
            prefilter_level(&env, None, &sampled, size, r, method);
        });
        println!("| {m} | {size} | {r:.3} | {method:?} | {wall:.3} | {cpu:.2} |");
    }
}

/// A full default bake of venice_sunset_1k.hdr (cubemap 256 with mips, specular 256 × 9
/// levels, irradiance 32, SH, LUT 512) per stage, on each backend.
/// The CPU backend, and the GPU one when an adapter exists.
fn cpu_and_gpu_backends() -> Vec<(&'static str, Box<dyn splitsum::backend::Backend>)> {
    let mut backends: Vec<(&str, Box<dyn splitsum::backend::Backend>)> =
        vec![("cpu", Box::new(splitsum::backend::CpuBackend))];
    if let Ok(g) = splitsum::backend::GpuBackend::new() {
        backends.push(("gpu", Box::new(g)));
    }
    backends
}

fn bake_benchmarks() {
    use splitsum::bake::{bake, BakeOptions};
    use splitsum::Stage;
    println!("\n## Full default bake of venice_sunset_1k.hdr, per stage\n");
    println!("| backend | stage | wall s | CPU s |");
    println!("|---|---|---|---|");
    let input = std::path::Path::new("tests/data/venice_sunset_1k.hdr");
    let out = std::path::PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("bench-bake");
    let mut backends = cpu_and_gpu_backends();
    if let Ok((auto, _)) = splitsum::backend::create_backend(splitsum::BackendChoice::Auto) {
        backends.push(("auto", auto));
    }
    for (label, backend) in &backends {
        let (lut_wall, lut_cpu) = measure(1, || {
            backend.brdf_lut(512, 512).unwrap();
        });
        println!("| {label} | brdf_lut 512 | {lut_wall:.3} | {lut_cpu:.3} |");
        let lut = backend.brdf_lut(512, 512).unwrap();
        let mut marks: Vec<(Stage, Instant, f64)> = Vec::new();
        let t0 = Instant::now();
        let c0 = cpu_seconds().unwrap_or(0.0);
        bake(
            backend.as_ref(),
            input,
            &out,
            &BakeOptions::default(),
            std::slice::from_ref(&lut),
            &mut |stage| {
                marks.push((stage, Instant::now(), cpu_seconds().unwrap_or(0.0)));
            },
        )
        .unwrap();
        let (t_end, c_end) = (Instant::now(), cpu_seconds().unwrap_or(0.0));
        for (k, (stage, t, c)) in marks.iter().enumerate() {
            let (tn, cn) = marks
                .get(k + 1)
                .map(|m| (m.1, m.2))
                .unwrap_or((t_end, c_end));
            println!(
                "| {label} | {} | {:.3} | {:.2} |",
                stage.name(),
                (tn - *t).as_secs_f64(),
                cn - c
            );
        }
        println!(
            "| {label} | **total incl. LUT** | {:.3} | {:.2} |",
            (t_end - t0).as_secs_f64() + lut_wall,
            c_end - c0 + lut_cpu
        );
    }
}

/// Peak resident memory of `splitsum bake` on synthetic 8k×4k and 16k×8k HDR files: the
/// child's VmHWM (a high-water mark) polled from /proc until it exits.
fn memory_benchmarks() {
    println!("\n## Peak memory of a default bake (synthetic .hdr with RLE, .exr float32 as splitsum writes it)\n");
    println!("| input | backend | peak RSS | wall s | result |");
    println!("|---|---|---|---|---|");
    let dir = std::path::PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("bench-memory");
    let _ = std::fs::create_dir_all(&dir);
    for (width, ext) in [
        (8192u32, "hdr"),
        (16384, "hdr"),
        (8192, "exr"),
        (16384, "exr"),
    ] {
        let input = dir.join(format!("synthetic_{width}.{ext}"));
        let e = synthetic_equirect(width);
        let bytes = if ext == "hdr" {
            splitsum::io::hdr::encode(e.width, e.height, &e.data)
        } else {
            match splitsum::io::exr::encode_rgb32(e.width, e.height, &e.data) {
                Ok(b) => b,
                Err(_) => continue,
            }
        };
        drop(e);
        if std::fs::write(&input, bytes).is_err() {
            continue;
        }
        for backend in ["auto", "cpu"] {
            let t = Instant::now();
            let Ok(mut child) = std::process::Command::new(env!("CARGO_BIN_EXE_splitsum"))
                .args(["bake", "--quiet", "--backend", backend, "-o"])
                .arg(dir.join("out"))
                .arg(&input)
                .spawn()
            else {
                continue;
            };
            let status_path = format!("/proc/{}/status", child.id());
            let mut peak_kb = 0u64;
            let status = loop {
                if let Ok(text) = std::fs::read_to_string(&status_path) {
                    if let Some(line) = text.lines().find(|l| l.starts_with("VmHWM:")) {
                        let kb = line
                            .split_whitespace()
                            .nth(1)
                            .and_then(|v| v.parse().ok())
                            .unwrap_or(0);
                        peak_kb = peak_kb.max(kb);
                    }
                }
                if let Ok(Some(status)) = child.try_wait() {
                    break status;
                }
                std::thread::sleep(std::time::Duration::from_millis(20));
            };
            println!(
                "| {width}×{} .{ext} | {backend} | {:.2} GB | {:.1} | {} |",
                width / 2,
                peak_kb as f64 / 1024.0 / 1024.0,
                t.elapsed().as_secs_f64(),
                if status.success() { "ok" } else { "FAILED" }
            );
        }
        let _ = std::fs::remove_file(&input);
    }
}

fn main() {
    // `cargo bench --bench bench -- memory lut` runs only the named sections.
    let wanted: Vec<String> = std::env::args()
        .skip(1)
        .filter(|a| !a.starts_with('-'))
        .collect();
    let run = |name: &str| wanted.is_empty() || wanted.iter().any(|w| w == name);
    if run("memory") {
        memory_benchmarks();
    }
    if run("bake") {
        bake_benchmarks();
        process_versus_cmgen();
    }
    if run("sun") {
        sun_benchmarks();
    }
    if run("cubemap") {
        cubemap_benchmarks();
    }
    if run("specular") {
        specular_benchmarks();
    }
    if run("lut") {
        lut_benchmarks();
        lut_versus_cmgen();
    }
    if run("ltc") {
        ltc::benchmarks();
    }
    if run("preview") {
        preview_benchmarks();
    }
    if run("bc6h") {
        bc6h::benchmarks();
    }
    if run("astc") {
        astc::benchmarks();
    }
    if run("view") {
        view::benchmarks();
    }
}

/// What finding the sun and filling its hole cost against a default CPU bake of the same
/// HDRI (the bar: at most 10 % of its CPU seconds), for the bundled HDRIs with and
/// without a sun and a studio: the search alone (`find_lights`, as `--sun keep` runs it),
/// the search and fill (`split_lights`), every area source's search, fill and shape
/// (`take_sources_out`), and whole CPU bakes in both modes, medians of 3.
fn sun_benchmarks() {
    use splitsum::bake::{bake, BakeOptions};
    use splitsum::{Stage, SunMode};
    println!("\n## The sun: search and fill against a default CPU bake\n");
    println!("| HDRI | lights | find CPU s | split CPU s | sources | sources CPU s | bake keep CPU s | bake split CPU s | sun stage / bake | background stage / bake | sources / bake |");
    println!("|---|---|---|---|---|---|---|---|---|---|---|");
    let out = std::path::PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("bench-sun");
    let cpu = splitsum::backend::CpuBackend;
    let lut = splitsum::backend::Backend::brdf_lut(&cpu, 512, 512).unwrap();
    for name in [
        "quarry_01_1k.hdr",
        "royal_esplanade_1k.hdr",
        "venice_sunset_1k.hdr",
        "studio_small_03_1k.hdr",
    ] {
        let input = std::path::Path::new("tests/data").join(name);
        let env = splitsum::io::input::load_input(&input, &Default::default())
            .unwrap()
            .env;
        let mut lights = 0;
        let (_, find_cpu) = measure(3, || lights = splitsum::find_lights(&env).len());
        let (_, split_cpu) = measure(3, || {
            splitsum::split_lights(&mut env.clone());
        });
        let mut sources = 0;
        let (_, sources_cpu) = measure(3, || sources = splitsum::take_sources_out(&env).0.len());
        // CPU seconds of the sun and background stages of the last bake measured.
        let stage_cpu = |sun: SunMode, stages: &mut Vec<(Stage, f64)>| {
            let opts = BakeOptions {
                sun,
                ..BakeOptions::default()
            };
            measure(3, || {
                let mut running: Option<(Stage, f64)> = None;
                stages.clear();
                bake(
                    &cpu,
                    &input,
                    &out,
                    &opts,
                    std::slice::from_ref(&lut),
                    &mut |stage| {
                        let now = cpu_seconds().unwrap_or(0.0);
                        if let Some((s, t)) = running.take() {
                            stages.push((s, now - t));
                        }
                        running = Some((stage, now));
                    },
                )
                .unwrap();
            })
            .1
        };
        let mut stages = Vec::new();
        let keep = stage_cpu(SunMode::Keep, &mut stages);
        let split = stage_cpu(SunMode::Split, &mut stages);
        let of = |wanted: Stage| {
            stages
                .iter()
                .filter(|(s, _)| *s == wanted)
                .fold(0.0, |sum, (_, t)| sum + t)
        };
        println!(
            "| {name} | {lights} | {find_cpu:.3} | {split_cpu:.3} | {sources} | {sources_cpu:.3} | {keep:.2} | {split:.2} | {:.1} % | {:.1} % | {:.1} % |",
            100.0 * of(Stage::Sun) / split,
            100.0 * of(Stage::Background) / split,
            100.0 * sources_cpu / keep
        );
    }
}

/// The preview's two renders on a default bake of the bundled HDRI, per backend: the
/// split-sum render (what `bake --preview` must add ≤ 0.5 CPU-s for) and the ground truth
/// at 512 and 2048 (the default) points.
fn preview_benchmarks() {
    use splitsum::backend::Backend;
    use splitsum::bake::{bake_environment, BakeOptions};
    use splitsum::environment::Environment;
    use splitsum::stages::preview::{render_preview, PreviewOptions};
    println!("\n## Preview of venice_sunset_1k.hdr (default bake, 64-pixel cells)\n");
    println!("| backend | lookup | truth points | split-sum wall s | truth wall s | whole preview CPU s |");
    println!("|---|---|---|---|---|---|");
    let loaded = splitsum::io::input::load_input(
        std::path::Path::new("tests/data/venice_sunset_1k.hdr"),
        &Default::default(),
    )
    .unwrap();
    let Environment::Equirect(e) = loaded.env else {
        unreachable!("the bundled HDRI is an equirect")
    };
    let cpu = splitsum::backend::CpuBackend;
    let baked = bake_environment(
        &cpu,
        Environment::Equirect(e),
        &BakeOptions::default(),
        &mut |_| {},
        &mut Vec::new(),
    )
    .unwrap();
    let lut = cpu.brdf_lut(512, 512).unwrap();
    let backends = cpu_and_gpu_backends();
    for (label, backend) in &backends {
        // The recipe's lookup with both truths, and the stretched lookup without its
        // grazing taps (the split-sum's cost: its truth is the same).
        let cases = [
            (splitsum::SpecularLookup::GENERIC, 512),
            (splitsum::SpecularLookup::GENERIC, 2048),
            (splitsum::SpecularLookup::Stretched, 512),
        ];
        for (lookup, truth_samples) in cases {
            let opts = PreviewOptions {
                truth_samples,
                shading: splitsum::Shading::GENERIC.with_lookup(lookup),
                ..PreviewOptions::default()
            };
            let mut p = None;
            let (_, cpu_s) = measure(1, || {
                p = Some(
                    render_preview(
                        backend.as_ref(),
                        &splitsum::stages::preview::BakedLight::of(
                            "venice_sunset_1k.hdr",
                            &baked,
                            &lut,
                        ),
                        &opts,
                    )
                    .unwrap(),
                );
            });
            let p = p.unwrap();
            println!(
                "| {label} | {} | {truth_samples} | {:.3} | {:.2} | {cpu_s:.2} |",
                lookup.id(),
                p.split_sum_seconds,
                p.truth_seconds
            );
        }
    }
}

fn lut_benchmarks() {
    let quad = LutQuadrature::default();
    println!("\n## BRDF LUT timings\n");
    println!("| size | backend | wall s (median) | CPU s | notes |");
    println!("|---|---|---|---|---|");
    let ctx = splitsum::gpu::GpuContext::new();
    for size in [128u32, 512] {
        match &ctx {
            Ok(ctx) => {
                let lut = || {
                    let model = Default::default();
                    splitsum::gpu::brdf_lut::brdf_lut(
                        &ctx.device,
                        &ctx.queue,
                        size,
                        size,
                        &quad,
                        model,
                    )
                    .unwrap();
                };
                let t = Instant::now();
                lut();
                let first = t.elapsed().as_secs_f64();
                let (wall, cpu) = measure(3, lut);
                println!(
                    "| {size} | gpu | {wall:.3} | {cpu:.3} | {}; first call {first:.3} s |",
                    ctx.adapter_description()
                );
            }
            Err(e) => println!("| {size} | gpu | - | - | unavailable: {e} |"),
        }
        let (wall, cpu) = measure(3, || {
            splitsum::backend::cpu::lut_interpolation::brdf_lut(
                size,
                size,
                &quad,
                Default::default(),
            );
        });
        println!(
            "| {size} | cpu | {wall:.3} | {cpu:.3} | rayon, {} threads |",
            rayon::current_num_threads()
        );
    }

    println!("\n## BRDF LUT accuracy against the converged integral (max |error| over A and B)\n");
    println!("| n·v | roughness | splitsum | 1024-sample Hammersley MC |");
    println!("|---|---|---|---|");
    let mut worst = [0.0f64; 2];
    for (i, j) in common::check_texels(512, 512) {
        let (nv, r) = lut_texel_coords(i, j, 512, 512);
        let (ra, rb) = common::reference_lut(nv as f64, r as f64);
        let err = |v: [f32; 2]| (v[0] as f64 - ra).abs().max((v[1] as f64 - rb).abs());
        let ours = err(splitsum::cpu::brdf_lut::brdf_lut_texel(
            nv,
            r,
            &quad,
            Default::default(),
        ));
        let mc = err(monte_carlo_texel(nv, r, 1024));
        worst = [worst[0].max(ours), worst[1].max(mc)];
    }
    for (nv, r) in [(0.5f32, 0.5f32), (0.05, 0.3), (0.9, 0.1), (0.3, 0.9)] {
        let (ra, rb) = common::reference_lut(nv as f64, r as f64);
        let err = |v: [f32; 2]| (v[0] as f64 - ra).abs().max((v[1] as f64 - rb).abs());
        println!(
            "| {nv} | {r} | {:.1e} | {:.1e} |",
            err(splitsum::cpu::brdf_lut::brdf_lut_texel(
                nv,
                r,
                &quad,
                Default::default()
            )),
            err(monte_carlo_texel(nv, r, 1024))
        );
    }
    println!(
        "| worst of {} texels of a 512² LUT | | {:.1e} | {:.1e} |",
        common::check_texels(512, 512).len(),
        worst[0],
        worst[1]
    );
}
