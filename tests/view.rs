//! `splitsum view`: the viewer renders what the preview renders (the same maths), its GPU
//! and CPU renderers agree, and the command line's offscreen path and its refusals.
//!
//! The viewer is checked against the preview on its sphere seen by the preview's camera:
//! an orthographic view along +X in which the sphere covers the same pixels as a preview
//! cell (radius 0.45 of a 64-pixel frame), so pixel (x, y) has the same normal and view
//! direction in both.

mod common;

use common::{gpu, output_dir, run_ok, splitsum, step_differences, test_equirect};
use glam::Vec3;
use splitsum::backend::{Backend, CpuBackend, GpuBackend};
use splitsum::bake::{bake_environment, BakeOptions};
use splitsum::environment::Environment;
use splitsum::plan::lut::DEFAULT_LUT_SIZE;
use splitsum::plan::scene::{
    pixel_geometry, PixelGeometry, Scene, MATERIALS, ROUGHNESS, SPHERE_RADIUS,
};
use splitsum::stages::preview::picture::luminance;
use splitsum::stages::preview::{render_preview, BakedLight, PreviewOptions};
use splitsum::view::camera::{Camera, Projection};
use splitsum::view::frame::{Mode, ViewLight};
use splitsum::view::gpu::GpuRenderer;
use splitsum::view::model::Model;
use splitsum::view::scene::{FIT_HALF_EXTENT, OBJECT_CENTRE};
use splitsum::view::session::{CpuFrame, Renderer, Viewer};
use splitsum::{BakedEnvironment, BrdfLut};

/// The preview's cell edge, and the viewer's frame.
const CELL: u32 = 64;
/// The preview's roughness columns compared here: 0, 0.25, 0.5, 1.
const COLUMNS: [usize; 4] = [0, 1, 2, 4];

/// The viewer's light of a venice_sunset bake (no area light: its LTC table is never asked
/// for; the CPU backend's where it would be).
fn venice_light(baked: &BakedEnvironment, lut: BrdfLut) -> ViewLight {
    ViewLight::new("venice", baked, lut, &mut || {
        splitsum::backend::shared_ltc_table(
            &splitsum::backend::CpuBackend,
            splitsum::plan::shading::LightBrdf::GENERIC,
        )
    })
    .unwrap()
}

/// The default bake of venice_sunset_1k and the default LUT, on `backend`.
fn bake(backend: &dyn Backend) -> (BakedEnvironment, BrdfLut) {
    let env = Environment::Equirect(test_equirect("venice_sunset_1k.hdr"));
    let baked = bake_environment(
        backend,
        env,
        &BakeOptions::default(),
        &mut |_| {},
        &mut Vec::new(),
    )
    .unwrap();
    let lut = backend
        .brdf_lut(DEFAULT_LUT_SIZE, DEFAULT_LUT_SIZE)
        .unwrap();
    (baked, lut)
}

/// The preview's camera in the viewer: along +X (yaw 90°), orthographic, the sphere's
/// radius 0.45 of the frame's height.
fn preview_camera() -> Camera {
    Camera {
        position: Vec3::from(OBJECT_CENTRE) - 3.5 * Vec3::X,
        yaw_deg: 90.0,
        pitch_deg: 0.0,
        projection: Projection::Orthographic {
            half_height: FIT_HALF_EXTENT / (2.0 * SPHERE_RADIUS),
        },
    }
}

fn renderers() -> Vec<(&'static str, Renderer)> {
    let mut out = vec![("cpu", Renderer::Cpu(CpuFrame::default()))];
    if let Some(ctx) = gpu() {
        let r = GpuRenderer::new(ctx.device.clone(), ctx.queue.clone()).unwrap();
        out.push(("gpu", Renderer::Gpu(Box::new(r))));
    }
    out
}

/// A viewer of `light` on the sphere alone, through the preview's camera.
fn sphere_viewer(light: &ViewLight, renderer: Renderer) -> Viewer {
    let mut v = Viewer::new(light.clone(), vec![Model::sphere()], renderer, "test").unwrap();
    v.state.camera = preview_camera();
    v.state.hud = false;
    v
}

/// Per sphere pixel of a preview cell (row `material`, column `column`): (pixel index in
/// the cell, index in the panel).
fn cell_pixels(scene: &Scene, material: usize, column: usize) -> Vec<(usize, usize)> {
    let s = scene.uniform();
    let mut out = Vec::new();
    for y in 0..CELL {
        for x in 0..CELL {
            let (px, py) = (column as u32 * CELL + x, material as u32 * CELL + y);
            if let PixelGeometry::Sphere { .. } = pixel_geometry(&s, px, py) {
                out.push(((y * CELL + x) as usize, (py * s.width + px) as usize));
            }
        }
    }
    out
}

/// The viewer's split-sum pixels equal the preview's split-sum render of the same sphere
/// within 1e-3 (relative; the same functions on the same inputs, so only rounding of the
/// sphere's normal separates them), for each material at r = 0, 0.25, 0.5, 1, on each
/// renderer; and the viewer's default exposure is the preview's.
#[test]
fn split_sum_equals_the_previews() {
    let (baked, lut) = bake(&CpuBackend);
    let light = venice_light(&baked, lut.clone());
    let opts = PreviewOptions {
        cell: CELL,
        truth_samples: 0,
        ..Default::default()
    };
    let preview = render_preview(
        &CpuBackend,
        &BakedLight::of("venice_sunset_1k.hdr", &baked, &lut),
        &opts,
    )
    .unwrap();
    assert_eq!(preview.exposure, light.exposure);
    let scene = Scene { cell: CELL };
    for (name, renderer) in renderers() {
        let mut viewer = sphere_viewer(&light, renderer);
        let mut worst = 0.0f32;
        for (m, _) in MATERIALS.iter().enumerate() {
            for c in COLUMNS {
                viewer.state.material = m;
                viewer.state.roughness = ROUGHNESS[c];
                viewer.render_image((CELL, CELL)).unwrap();
                let (shaded, _) = viewer.hdr().unwrap();
                let pixels = cell_pixels(&scene, m, c);
                let on_sphere = shaded.iter().filter(|s| s[3] == 1.0).count();
                // The two disc tests (r² < 1 against a non-negative discriminant) may
                // disagree on a pixel whose centre lies on the rim.
                assert!(
                    on_sphere.abs_diff(pixels.len()) <= 4,
                    "{name}: {on_sphere} vs {}",
                    pixels.len()
                );
                for &(k, p) in &pixels {
                    if shaded[k][3] != 1.0 {
                        continue;
                    }
                    for (&a, &b) in shaded[k].iter().zip(&preview.split_sum[p]) {
                        let d = (a - b).abs() / b.abs().max(1e-3);
                        worst = worst.max(d);
                        assert!(
                            d <= 1e-3,
                            "{name} {} r = {}: pixel {k} {a} vs {b}",
                            MATERIALS[m].name,
                            ROUGHNESS[c]
                        );
                    }
                }
            }
        }
        println!("{name}: worst relative difference {worst:.2e}");
    }
}

/// The viewer's converged truth (32 estimates of 64 points, 2048 a pixel and lobe) matches
/// the preview's truth (2048 points) within 1 % energy-weighted, Σ|ΔY| / ΣY over each
/// sphere: both are unbiased estimates of the same integral with independent quadrature
/// rotations, so what is left is their noise (measured: at most 0.64 %). And the heat
/// view's mean over the sphere, the HUD's figure, is the preview's figure of that sphere
/// within 1 % (a point of per cent; the same split-sum, so what is left is the two truths'
/// noise).
#[test]
fn truth_matches_the_previews() {
    let Some(ctx) = gpu() else { return };
    let backend = GpuBackend { ctx };
    let (baked, lut) = bake(&CpuBackend);
    let light = venice_light(&baked, lut.clone());
    let opts = PreviewOptions {
        cell: CELL,
        truth_samples: 2048,
        ..Default::default()
    };
    let preview = render_preview(
        &backend,
        &BakedLight::of("venice_sunset_1k.hdr", &baked, &lut),
        &opts,
    )
    .unwrap();
    let renderer = GpuRenderer::new(backend.ctx.device.clone(), backend.ctx.queue.clone()).unwrap();
    let mut viewer = sphere_viewer(&light, Renderer::Gpu(Box::new(renderer)));
    viewer.state.mode = Mode::Heat;
    viewer.points_per_estimate = 64;
    let scene = Scene { cell: CELL };
    let mut worst = 0.0f64;
    let mut worst_figure = 0.0f32;
    for (m, _) in MATERIALS.iter().enumerate() {
        for c in COLUMNS {
            viewer.state.material = m;
            viewer.state.roughness = ROUGHNESS[c];
            for _ in 0..32 {
                viewer.render_image((CELL, CELL)).unwrap();
            }
            assert_eq!(viewer.truth_samples(), 2048);
            let (_, accum) = viewer.hdr().unwrap();
            let (mut diff, mut total) = (0.0f64, 0.0f64);
            for (k, p) in cell_pixels(&scene, m, c) {
                if accum[k][3] <= 0.0 {
                    continue;
                }
                let mean = [0, 1, 2].map(|i| accum[k][i] / accum[k][3]);
                let (a, b) = (luminance(mean) as f64, luminance(preview.truth[p]) as f64);
                diff += (a - b).abs();
                total += b;
            }
            let rel = diff / total;
            worst = worst.max(rel);
            let hud = viewer.heat_mean().unwrap();
            let figure = preview.stats[m * ROUGHNESS.len() + c].mean_relative;
            worst_figure = worst_figure.max((hud - figure).abs());
            assert!(
                (hud - figure).abs() <= 0.01,
                "{} r = {}: the HUD's {:.2} %, the preview's {:.2} %",
                MATERIALS[m].name,
                ROUGHNESS[c],
                100.0 * hud,
                100.0 * figure
            );
            assert!(
                rel <= 0.01,
                "{} r = {}: {:.3} %",
                MATERIALS[m].name,
                ROUGHNESS[c],
                100.0 * rel
            );
        }
    }
    println!(
        "worst energy-weighted difference {:.3} %, HUD against the preview's figure {:.3} points",
        100.0 * worst,
        100.0 * worst_figure
    );
}

/// The GPU and CPU renderers agree on a perspective frame of Spot with the point lights
/// on: the same surface at ≥ 99.5 % of the pixels (rasterisers may split a pixel on an
/// edge differently), the split-sum there within 1e-3 relative, one truth estimate within
/// 1e-3 on the mean of the frame, and the pictures within two 8-bit steps.
#[test]
fn gpu_and_cpu_frames_agree() {
    let Some(ctx) = gpu() else { return };
    let (baked, lut) = bake(&CpuBackend);
    let light = venice_light(&baked, lut);
    let size = (160, 90);
    let render = |renderer: Renderer| {
        let mut v =
            Viewer::new(light.clone(), Model::bundled().unwrap(), renderer, "test").unwrap();
        v.state.roughness = 0.35;
        v.state.lights = true;
        v.state.hud = false;
        let split = v.render_image(size).unwrap();
        let (shaded, _) = v.hdr().unwrap();
        v.state.mode = Mode::Truth;
        v.points_per_estimate = 16;
        v.render_image(size).unwrap();
        let (_, accum) = v.hdr().unwrap();
        (split, shaded, accum)
    };
    let gpu_renderer = GpuRenderer::new(ctx.device.clone(), ctx.queue.clone()).unwrap();
    let (gpu_img, gpu_shaded, gpu_accum) = render(Renderer::Gpu(Box::new(gpu_renderer)));
    let (cpu_img, cpu_shaded, cpu_accum) = render(Renderer::Cpu(CpuFrame::default()));
    let n = gpu_shaded.len();
    let same: Vec<usize> = (0..n)
        .filter(|&k| gpu_shaded[k][3] == cpu_shaded[k][3])
        .collect();
    assert!(
        same.len() as f64 >= 0.995 * n as f64,
        "{} of {n} pixels agree on the surface",
        same.len()
    );
    let objects = same.iter().filter(|&&k| gpu_shaded[k][3] == 1.0).count();
    assert!(objects > 500, "Spot covers {objects} pixels");
    let mut worst = 0.0f32;
    for &k in &same {
        for c in 0..3 {
            let (a, b) = (gpu_shaded[k][c], cpu_shaded[k][c]);
            worst = worst.max((a - b).abs() / b.abs().max(1e-3));
        }
    }
    assert!(
        worst <= 1e-3,
        "split-sum: worst relative difference {worst:e}"
    );
    let mean = |a: &[[f32; 4]]| {
        same.iter()
            .map(|&k| luminance([a[k][0], a[k][1], a[k][2]]) as f64 / a[k][3] as f64)
            .sum::<f64>()
    };
    let (g, c) = (mean(&gpu_accum), mean(&cpu_accum));
    assert!((g - c).abs() <= 1e-3 * c, "truth: {g} vs {c}");
    let steps = gpu_img
        .pixels()
        .zip(cpu_img.pixels())
        .filter(|(a, b)| a.0.iter().zip(b.0.iter()).any(|(x, y)| x.abs_diff(*y) > 2))
        .count();
    assert!(
        steps as f64 <= 0.005 * n as f64,
        "{steps} pixels differ by more than two steps"
    );
}

/// Offscreen from the command line: the picture is written with the size asked for, the
/// keys applied (copper on the sphere: the centre is copper-coloured), and refusals are one
/// clear line with the usage exit code.
#[test]
fn command_line() {
    let dir = output_dir("view_cli");
    let png = dir.join("view.png");
    run_ok(
        splitsum()
            .args([
                "view",
                "--backend",
                "cpu",
                "--size",
                "96x64",
                "--keys",
                "2 m2 hud",
                "--screenshot",
            ])
            .arg(&png),
    );
    let img = image::open(&png).unwrap().to_rgb8();
    assert_eq!(img.dimensions(), (96, 64));
    let c = img.get_pixel(48, 32).0;
    assert!(c[0] > c[1] && c[1] > c[2], "copper centre {c:?}");

    let fails = |args: &[&str], needle: &str, code: i32| {
        let out = splitsum()
            .args(args)
            .env_remove("DISPLAY")
            .env_remove("WAYLAND_DISPLAY")
            .output()
            .unwrap();
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(code), "{args:?}: {err}");
        assert!(err.contains(needle), "{args:?}: {err}");
        assert_eq!(err.lines().count(), 1, "{args:?}: {err}");
    };
    fails(&["view"], "--screenshot", 2);
    fails(
        &["view", "--keys", "2 q", "--screenshot", "x.png"],
        "'q'",
        2,
    );
    fails(
        &["view", "--size", "0x10", "--screenshot", "x.png"],
        "--size",
        2,
    );
    fails(&["view", "--screenshot", "x.jpg"], "x.jpg", 2);
    let not_a_model = dir.join("notes.txt");
    std::fs::write(&not_a_model, "hello").unwrap();
    let m = not_a_model.to_str().unwrap();
    fails(
        &[
            "view",
            "--backend",
            "cpu",
            "--model",
            m,
            "--screenshot",
            "y.png",
        ],
        "notes.txt",
        1,
    );
    assert!(!std::path::Path::new("y.png").exists());
}

/// What the window does with a dropped file that is not an image: the light's loader
/// refuses it with one line naming the file (the window shows that line in the HUD and on
/// stderr and keeps the previous light).
#[test]
fn a_dropped_file_that_is_not_an_image_is_one_clear_line() {
    use splitsum::view::{load_light, LightSource};
    let dir = output_dir("view_drop");
    let notes = dir.join("notes.txt");
    std::fs::write(&notes, "not an image").unwrap();
    let err = load_light(
        &LightSource::File(notes),
        splitsum::BackendChoice::Cpu,
        splitsum::SunMode::Split,
        &mut |_| {},
    )
    .unwrap_err()
    .to_string();
    assert!(
        err.contains("notes.txt") && err.lines().count() == 1,
        "{err}"
    );
}

/// The GPU renderer's two paths to the split-sum picture, the forward pass the window
/// draws while the view changes and the deferred passes (G-buffer, split-sum kernel,
/// present pass) that draw it once it stands still, give the same picture (HUD, point
/// lights, Spot and the ray-cast sphere): the same WGSL functions of the same surface,
/// the chains read through the sampler's bilinear filter in the one and by four texel
/// fetches in the other. On a software adapter (lavapipe, CI's) at most one 8-bit step
/// apart (the compiler may order a sum differently in the two shaders) in 0.1 % of the
/// pixels (measured: none differ); on a hardware filter the bar of
/// `common::forward_pass_bar`, which says why. Checked on a frame
/// drawn forward against the same frame drawn by a renderer kept on the deferred passes,
/// and (without the HUD, whose frame time may change between frames) against the same
/// view's next two frames (standing still: deferred passes, then the present pass alone).
#[test]
fn forward_and_deferred_pictures_are_the_same() {
    let Some(ctx) = gpu() else { return };
    let (bar_steps, bar_per_mille) = common::forward_pass_bar(&ctx);
    let probe = GpuRenderer::new(ctx.device.clone(), ctx.queue.clone()).unwrap();
    if !probe.draws_forward() {
        println!("skipped: {} does not filter rgba32float textures, so every frame is drawn by the deferred passes", ctx.adapter_description());
        return;
    }
    let (baked, lut) = bake(&CpuBackend);
    let light = venice_light(&baked, lut);
    let size = (320, 180);
    let render = |forward: bool, model: usize, hud: bool| {
        let mut r = GpuRenderer::new(ctx.device.clone(), ctx.queue.clone()).unwrap();
        r.set_forward(forward);
        let models = Model::bundled().unwrap();
        let mut v = Viewer::new(light.clone(), models, Renderer::Gpu(Box::new(r)), "test").unwrap();
        v.state.model = model;
        v.state.roughness = 0.35;
        v.state.lights = true;
        v.state.hud = hud;
        [(); 3].map(|_| v.render_image(size).unwrap())
    };
    for model in 0..Model::bundled().unwrap().len() {
        let [forward, ..] = render(true, model, true);
        let [deferred, ..] = render(false, model, true);
        let [moving, still, still_again] = render(true, model, false);
        for (name, a, b) in [
            ("deferred", &forward, deferred),
            ("still", &moving, still),
            ("still again", &moving, still_again),
        ] {
            let (worst, differing) = step_differences(a, &b);
            let n = (size.0 * size.1) as usize;
            println!(
                "model {model}, {name}: {differing} of {n} pixels differ, by up to {worst} steps"
            );
            assert!(
                worst <= bar_steps && differing * 1000 <= bar_per_mille * n,
                "model {model}, {name}: {differing} of {n} pixels differ, by up to {worst} steps"
            );
        }
    }
}

/// A target that stores sRGB itself gets linear values from the display passes, which it
/// encodes on store: the same picture as a plain 8-bit target, which gets the encoded
/// values (whether the target stores sRGB is a constant of each display pipeline, one a
/// target format). Within one step, the store's own rounding of the encoding; a pipeline
/// made for the other kind of target would encode twice or not at all, tens of steps off.
/// The forward pass (the first frame) and the present pass alone (the third) both.
#[test]
fn an_srgb_target_shows_the_same_picture() {
    let Some(ctx) = gpu() else { return };
    let (baked, lut) = bake(&CpuBackend);
    let light = venice_light(&baked, lut);
    let size = (160, 90);
    let viewer = || {
        let r = GpuRenderer::new(ctx.device.clone(), ctx.queue.clone()).unwrap();
        let mut v = Viewer::new(
            light.clone(),
            Model::bundled().unwrap(),
            Renderer::Gpu(Box::new(r)),
            "test",
        )
        .unwrap();
        v.state.hud = false;
        v
    };
    let format = wgpu::TextureFormat::Rgba8UnormSrgb;
    let texture = splitsum::gpu::texture::create_texture_2d(
        &ctx.device,
        "srgb target",
        (size.0, size.1, 1),
        format,
        wgpu::TextureUsages::RENDER_ATTACHMENT | wgpu::TextureUsages::COPY_SRC,
    );
    let view = texture.create_view(&Default::default());
    let (mut srgb, mut plain) = (viewer(), viewer());
    for frame in 0..3 {
        srgb.render_to(size, (&view, format)).unwrap();
        let bytes =
            splitsum::gpu::compute::read_texture_bytes(&ctx.device, &ctx.queue, &texture, 0)
                .unwrap();
        let stored = image::RgbaImage::from_raw(size.0, size.1, bytes).unwrap();
        let expected = plain.render_image(size).unwrap();
        let (worst, differing) = step_differences(&stored, &expected);
        println!("frame {frame}: {differing} pixels differ, by up to {worst} steps");
        assert!(worst <= 1, "frame {frame}: up to {worst} steps off");
    }
}
