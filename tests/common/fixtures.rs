//! Fixtures of the integration tests: the binary, output folders under `target/`, the
//! backends and GPU context (skipped with a message without an adapter, unless required),
//! the bundled HDRIs, random directions, the vector arithmetic of synthetic environments,
//! and the peers (cmgen) some tests compare with.

use std::f64::consts::PI;
use std::path::{Path, PathBuf};

/// The splitsum binary of this build.
pub fn splitsum() -> std::process::Command {
    std::process::Command::new(env!("CARGO_BIN_EXE_splitsum"))
}

/// SHA-256 of `bytes`, lower-case hex.
pub fn sha256_hex(bytes: &[u8]) -> String {
    use sha2::Digest;
    sha2::Sha256::digest(bytes)
        .iter()
        .map(|b| format!("{b:02x}"))
        .collect()
}

/// Texels to check in a W×H LUT: a spread grid plus the grazing column, the first and last
/// columns and rows (roughness ≈ 0 and ≈ 1). At least 32.
pub fn check_texels(width: u32, height: u32) -> Vec<(u32, u32)> {
    let mut out = Vec::new();
    let n = 6;
    for a in 0..n {
        for b in 0..n {
            let i = ((a as f64 + 0.37) / n as f64 * width as f64) as u32;
            let j = ((b as f64 + 0.61) / n as f64 * height as f64) as u32;
            out.push((i, j));
        }
    }
    for b in 0..n {
        let j = ((b as f64 + 0.5) / n as f64 * height as f64) as u32;
        out.push((0, j));
        out.push((width - 1, j));
    }
    for a in 0..n {
        let i = ((a as f64 + 0.5) / n as f64 * width as f64) as u32;
        out.push((i, 0));
        out.push((i, height - 1));
    }
    out.extend([
        (0, 0),
        (0, height - 1),
        (width - 1, 0),
        (width - 1, height - 1),
    ]);
    out
}

/// A fresh folder under `target/test-output/<name>` for a test's files.
pub fn output_dir(name: &str) -> PathBuf {
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join(name);
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// The GPU context for GPU tests. Without an adapter the test is skipped with a message,
/// unless `SPLITSUM_REQUIRE_GPU=1` (set by `.ci/run`, which installs lavapipe), in which
/// case a missing adapter fails the test.
pub fn gpu() -> Option<splitsum::gpu::GpuContext> {
    match splitsum::gpu::GpuContext::new() {
        Ok(ctx) => Some(ctx),
        Err(e) => {
            if std::env::var("SPLITSUM_REQUIRE_GPU").is_ok_and(|v| v == "1") {
                panic!("SPLITSUM_REQUIRE_GPU=1 but no GPU context: {e}");
            }
            eprintln!("skipping GPU test: {e}");
            None
        }
    }
}

/// Both backends when a GPU is available (see [`gpu`]), else the CPU alone.
pub fn backends() -> Vec<Box<dyn splitsum::backend::Backend>> {
    let mut v: Vec<Box<dyn splitsum::backend::Backend>> =
        vec![Box::new(splitsum::backend::CpuBackend)];
    if let Some(ctx) = gpu() {
        v.push(Box::new(splitsum::backend::GpuBackend { ctx }));
    }
    v
}

/// The backend a test's figures are rendered on: the GPU where there is one (see [`gpu`]),
/// else the CPU.
pub fn preferred_backend() -> Box<dyn splitsum::backend::Backend> {
    match gpu() {
        Some(ctx) => Box::new(splitsum::backend::GpuBackend { ctx }),
        None => Box::new(splitsum::backend::CpuBackend),
    }
}

/// The bundled HDRI `tests/data/<name>` baked on the CPU with its lights split, keeping the
/// truth's environment (what the preview's figures read).
pub fn bake_split(name: &str) -> splitsum::BakedEnvironment {
    let path = std::path::Path::new("tests/data").join(name);
    let env = splitsum::io::input::load_input(&path, &Default::default())
        .unwrap()
        .env;
    let opts = splitsum::BakeOptions {
        sun: splitsum::SunMode::Split,
        ground_truth: true,
        ..splitsum::BakeOptions::default()
    };
    splitsum::bake::bake_environment(
        &splitsum::backend::CpuBackend,
        env,
        &opts,
        &mut |_| {},
        &mut Vec::new(),
    )
    .unwrap()
}

/// Every bundled HDRI in `tests/data` (all equirects).
pub const BUNDLED_HDRIS: [&str; 7] = [
    "quarry_01_1k.hdr",
    "royal_esplanade_1k.hdr",
    "venice_sunset_1k.hdr",
    "pedestrian_overpass_1k.hdr",
    "studio_small_03_1k.hdr",
    "venice_sunset_1k_f32_piz.exr",
    "blender_studiolight_interior.exr",
];

/// An HDRI from `tests/data` as an equirect (the tests' real environments).
pub fn test_equirect(name: &str) -> splitsum::Equirect {
    use splitsum::environment::Environment;
    let path = std::path::Path::new("tests/data").join(name);
    match splitsum::io::input::load_environment(&path, &Default::default())
        .unwrap()
        .env
    {
        Environment::Equirect(e) => e,
        Environment::Cube(_) => panic!("{name} is not an equirect"),
    }
}

/// A small deterministic generator (an LCG with Knuth's MMIX constants), so random test
/// positions are the same on every run.
pub struct Lcg(pub u64);

impl Lcg {
    /// The next number in [0, 1).
    pub fn next(&mut self) -> f64 {
        self.0 = self
            .0
            .wrapping_mul(6_364_136_223_846_793_005)
            .wrapping_add(1_442_695_040_888_963_407);
        (self.0 >> 11) as f64 / (1u64 << 53) as f64
    }
}

/// `count` directions uniform on the sphere (cos θ and φ uniform) from `seed`.
pub fn uniform_directions(count: usize, seed: u64) -> Vec<[f64; 3]> {
    let mut rng = Lcg(seed);
    (0..count)
        .map(|_| {
            let y = 1.0 - 2.0 * rng.next();
            let phi = 2.0 * PI * rng.next();
            let r = (1.0 - y * y).sqrt();
            [r * phi.cos(), y, r * phi.sin()]
        })
        .collect()
}

/// cmgen (Filament's baker, Debian libfilament-tools) on PATH, for the peer comparisons.
pub fn which_cmgen() -> Result<PathBuf, ()> {
    std::env::var_os("PATH")
        .and_then(|p| {
            std::env::split_paths(&p)
                .map(|d| d.join("cmgen"))
                .find(|c| c.is_file())
        })
        .ok_or(())
}

/// A peer comparison whose peer is missing skips, except where SPLITSUM_REQUIRE_PEERS=1
/// (`.ci/run` sets it, so CI cannot pass without comparing).
pub fn skip_peer(why: &str) {
    assert!(
        std::env::var("SPLITSUM_REQUIRE_PEERS").as_deref() != Ok("1"),
        "{why}, and SPLITSUM_REQUIRE_PEERS=1"
    );
    eprintln!("{why}; skipping");
}

/// `chain` stored in `format` (BC6H encoded at `quality` by the CPU encoder, ASTC by
/// astc-encoder at its default preset) and read back: the texels an engine samples from
/// the file.
pub fn stored(
    chain: &splitsum::Cubemap,
    format: splitsum::io::PixelFormat,
    quality: splitsum::plan::bc6h::Bc6hQuality,
) -> splitsum::Cubemap {
    let blocks = splitsum::io::cubemap::BlockEncoder {
        quality,
        ..Default::default()
    };
    stored_with(chain, format, &blocks).1
}

/// `chain` encoded in `format` by `blocks` (each level's bytes) and read back by
/// splitsum's decoder.
pub fn stored_with(
    chain: &splitsum::Cubemap,
    format: splitsum::io::PixelFormat,
    blocks: &splitsum::io::cubemap::BlockEncoder,
) -> (Vec<Vec<u8>>, splitsum::Cubemap) {
    let texture = splitsum::io::cubemap::encode_texture(chain, format, blocks).unwrap();
    let levels = texture
        .levels
        .iter()
        .enumerate()
        .map(|(m, b)| format.decode_faces(b, chain.level_size(m), 6))
        .collect();
    let cube = splitsum::Cubemap {
        size: chain.size,
        levels,
    };
    (texture.levels, cube)
}

/// Log-space RMSE over every channel of every texel of level `m`, as GPURealTimeBC6H and
/// ISPC report a block format's error: √(mean((ln(1 + a) − ln(1 + b))²)).
pub fn log_rmse(a: &splitsum::Cubemap, b: &splitsum::Cubemap, m: usize) -> f64 {
    let (mut sum, mut count) = (0.0f64, 0usize);
    for (ta, tb) in a.levels[m].iter().zip(&b.levels[m]) {
        for c in 0..3 {
            let d = (ta[c].max(0.0) as f64).ln_1p() - (tb[c].max(0.0) as f64).ln_1p();
            sum += d * d;
            count += 1;
        }
    }
    (sum / count as f64).sqrt()
}

/// quarry_01 (a sun of ~40 000 at this size beside a sky of ~1) as a 32² cube with every
/// level down to 1², so faces smaller than a block of any block format.
pub fn hdr_chain() -> splitsum::Cubemap {
    let e = test_equirect("quarry_01_1k.hdr");
    splitsum::stages::convert::environment_to_cube(
        &splitsum::backend::CpuBackend,
        &splitsum::Environment::Equirect(e),
        32,
        true,
        0.0,
    )
    .unwrap()
}

/// A 32² CPU bake of venice_sunset into `dir` with `args` (the full chain unless `args`
/// sets another minimum).
pub fn small_bake(dir: &Path, args: &[&str]) -> std::process::Output {
    let min = if args.contains(&"--min-mip-size") {
        &[][..]
    } else {
        &["--min-mip-size", "1"][..]
    };
    splitsum()
        .args([
            "bake",
            "tests/data/venice_sunset_1k.hdr",
            "--backend",
            "cpu",
            "-q",
        ])
        .args(["--specular-size", "32", "--irradiance-size", "8"])
        .args(min)
        .args(args)
        .arg("-o")
        .arg(dir)
        .output()
        .unwrap()
}

/// Runs `cmd` and returns its output, failing the test with its stderr unless it succeeds.
pub fn run_ok(cmd: &mut std::process::Command) -> std::process::Output {
    let out = cmd.output().unwrap_or_else(|e| panic!("{cmd:?}: {e}"));
    assert!(
        out.status.success(),
        "{cmd:?}: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    out
}

/// How far two pictures of one size are apart: (the largest difference of a channel in
/// 8-bit steps, how many pixels differ at all).
pub fn step_differences(a: &image::RgbaImage, b: &image::RgbaImage) -> (u8, usize) {
    assert_eq!(a.dimensions(), b.dimensions());
    a.pixels()
        .zip(b.pixels())
        .map(|(p, q)| {
            p.0.iter()
                .zip(q.0.iter())
                .map(|(x, y)| x.abs_diff(*y))
                .max()
                .unwrap_or(0)
        })
        .fold((0, 0), |(worst, n), step| {
            (worst.max(step), n + (step > 0) as usize)
        })
}

/// The bar of the viewer's forward pass against its deferred passes on `ctx`'s adapter:
/// (the largest step, the most differing pixels per thousand). On a software adapter
/// (lavapipe), whose filter weighs texels in floats, one step in 0.1 %; a hardware filter
/// weighs them to its sub-texel precision (8 bits on most GPUs), which moves a read by up
/// to 1/512 of two neighbouring texels' difference, up to about 1 % of the value at the
/// background's sharpest edges: two steps in 5 % (an estimate; no hardware GPU was at hand
/// to measure it).
pub fn forward_pass_bar(ctx: &splitsum::gpu::GpuContext) -> (u8, usize) {
    if ctx.adapter_info.device_type == wgpu::DeviceType::Cpu {
        (1, 1)
    } else {
        (2, 50)
    }
}

/// Spot under `light` drawn by the GPU renderer's forward pass and by its deferred passes
/// at `size` after each set of `--keys` tokens in `keys`: the two pictures within
/// [`forward_pass_bar`] (where the adapter cannot draw the forward pass, says so and
/// checks nothing).
pub fn forward_matches_deferred(
    ctx: &splitsum::gpu::GpuContext,
    light: &splitsum::view::frame::ViewLight,
    size: (u32, u32),
    keys: &[&str],
) {
    use splitsum::view::gpu::GpuRenderer;
    use splitsum::view::model::Model;
    use splitsum::view::session::{Renderer, Viewer};
    let (bar_steps, bar_per_mille) = forward_pass_bar(ctx);
    let render = |forward: bool, keys: &str| {
        let mut r = GpuRenderer::new(ctx.device.clone(), ctx.queue.clone()).unwrap();
        r.set_forward(forward);
        if forward && !r.draws_forward() {
            return None;
        }
        let models = vec![Model::spot().unwrap()];
        let mut v = Viewer::new(light.clone(), models, Renderer::Gpu(Box::new(r)), "test").unwrap();
        v.state.hud = false;
        for action in splitsum::parse_keys(keys).unwrap() {
            v.apply(action).unwrap();
        }
        Some(v.render_image(size).unwrap())
    };
    for keys in keys {
        let Some(forward) = render(true, keys) else {
            println!(
                "skipped: {} does not filter rgba32float textures",
                ctx.adapter_description()
            );
            return;
        };
        let deferred = render(false, keys).unwrap();
        let (worst, differing) = step_differences(&forward, &deferred);
        let n = (size.0 * size.1) as usize;
        println!("keys {keys:?}: {differing} of {n} pixels differ, by up to {worst} steps");
        assert!(
            worst <= bar_steps && differing * 1000 <= bar_per_mille * n,
            "keys {keys:?}: {differing} of {n} pixels differ, by up to {worst} steps"
        );
    }
}

/// The split-sum frame and the truth's accumulation of a viewer of Spot under `light`
/// drawn by `renderer` at `size`, with `frames` truth estimates of 16 points.
pub fn viewer_frames(
    light: &splitsum::view::frame::ViewLight,
    renderer: splitsum::view::session::Renderer,
    size: (u32, u32),
    frames: u32,
) -> (Vec<[f32; 4]>, Vec<[f32; 4]>) {
    use splitsum::view::frame::Mode;
    use splitsum::view::model::Model;
    use splitsum::view::session::Viewer;
    let mut v = Viewer::new(
        light.clone(),
        vec![Model::spot().unwrap()],
        renderer,
        "test",
    )
    .unwrap();
    v.state.hud = false;
    v.render_image(size).unwrap();
    let (shaded, _) = v.hdr().unwrap();
    v.state.mode = Mode::Truth;
    v.points_per_estimate = 16;
    for _ in 0..frames {
        v.render_image(size).unwrap();
    }
    let (_, accum) = v.hdr().unwrap();
    (shaded, accum)
}

/// The bundled HDRI `tests/data/<name>` baked for the viewer on the CPU with its lights
/// split (and kept, as the alternate).
pub fn split_view_light(name: &str) -> splitsum::view::frame::ViewLight {
    let path = std::path::Path::new("tests/data").join(name);
    splitsum::view::load_light(
        &splitsum::view::LightSource::File(path),
        splitsum::BackendChoice::Cpu,
        splitsum::SunMode::Split,
        &mut |_| {},
    )
    .unwrap()
}

/// The viewer's GPU and CPU frames of one view agree: the split-sum HDR pixels (RGB,
/// surface id) on the same surface and within 1e-3 relative at ≥ 99.5 % of the pixels,
/// and the truth accumulations' means (RGB·weight, weight) within 1e-3. Returns how many
/// pixels agree and the largest relative difference.
pub fn assert_viewer_frames_agree(
    (gpu_shaded, gpu_accum): (&[[f32; 4]], &[[f32; 4]]),
    (cpu_shaded, cpu_accum): (&[[f32; 4]], &[[f32; 4]]),
) -> (usize, f32) {
    use splitsum::stages::preview::picture::luminance;
    let n = gpu_shaded.len();
    let mut worst = 0.0f32;
    let close = (0..n)
        .filter(|&k| {
            gpu_shaded[k][3] == cpu_shaded[k][3]
                && (0..3).all(|c| {
                    let (a, b) = (gpu_shaded[k][c], cpu_shaded[k][c]);
                    let d = (a - b).abs() / b.abs().max(1e-3);
                    worst = worst.max(d);
                    d <= 1e-3
                })
        })
        .count();
    assert!(
        close as f64 >= 0.995 * n as f64,
        "{close} of {n} pixels agree"
    );
    let mean = |a: &[[f32; 4]]| {
        a.iter()
            .map(|p| luminance([p[0], p[1], p[2]]) as f64 / p[3] as f64)
            .sum::<f64>()
    };
    let (g, c) = (mean(gpu_accum), mean(cpu_accum));
    assert!((g - c).abs() <= 1e-3 * c, "truth: {g} vs {c}");
    (close, worst)
}

/// a · b.
pub fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

/// a / |a|.
pub fn normalize(a: [f64; 3]) -> [f64; 3] {
    let l = dot(a, a).sqrt();
    a.map(|v| v / l)
}

/// a × b.
pub fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

/// The unit direction of azimuth and elevation in degrees (docs/conventions.md: azimuth 0
/// along +X, 90 along +Z; elevation above the XZ plane).
pub fn direction(azimuth_deg: f64, elevation_deg: f64) -> [f64; 3] {
    let (a, e) = (azimuth_deg.to_radians(), elevation_deg.to_radians());
    [e.cos() * a.cos(), e.sin(), e.cos() * a.sin()]
}

/// The angle between unit vectors, in degrees.
pub fn angle_deg(a: [f64; 3], b: [f64; 3]) -> f64 {
    dot(a, b).clamp(-1.0, 1.0).acos().to_degrees()
}
