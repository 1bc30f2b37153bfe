//! `cargo bench --bench bench -- view`: the viewer's frame times at 1280×720 with Spot, as
//! the window draws them (into a texture, waiting for the device; no readback), with the
//! camera turning every frame (the GPU renderer's forward pass, and its deferred passes:
//! G-buffer, kernels, present, as the truth and heat views draw) and still (the present
//! pass alone), the ground truth's samples per second, the forward pass with quarry_01's
//! sun split out and its shadow and with studio_small_03's lamps as area lights and their
//! shadows (on and off), and the CPU renderer; the GPU renderer on the adapter
//! wgpu finds.

use splitsum::gpu::GpuContext;
use splitsum::view::frame::{Mode, ViewLight};
use splitsum::view::gpu::GpuRenderer;
use splitsum::view::session::{CpuFrame, Renderer, Viewer};
use splitsum::view::{load_light, LightSource, DEFAULT_SIZE};
use splitsum::BackendChoice;

/// Frames timed per row (after two warm-up frames).
const FRAMES: usize = 20;

/// (median wall seconds, mean CPU seconds of every thread) of `frames` calls of `frame`
/// with the frame's number, after two untimed ones. Both are printed: the wall time is
/// what a person sees, the CPU time steadier where the machine's cores are shared.
fn time(frames: usize, mut frame: impl FnMut(usize)) -> (f64, f64) {
    frame(0);
    frame(1);
    let mut i = 2;
    crate::measure(frames, || {
        frame(i);
        i += 1;
    })
}

fn row(renderer: &str, frame: &str, (wall, cpu): (f64, f64), truth_rate: Option<f64>) {
    println!(
        "| {renderer} | {frame} | {:.1} | {:.1} | {:.1} | {} |",
        1e3 * wall,
        1.0 / wall,
        1e3 * cpu,
        truth_rate.map_or(String::new(), |r| format!("{r:.1}"))
    );
}

pub fn benchmarks() {
    println!("\n## The viewer at 1280×720 with Spot (median of {FRAMES} frames)\n");
    let light = load_light(
        &LightSource::Bundled,
        BackendChoice::Auto,
        splitsum::SunMode::Split,
        &mut |_| {},
    )
    .unwrap();
    let models = splitsum::view::model::Model::bundled().unwrap();
    let size = DEFAULT_SIZE;
    let pixels = (size.0 * size.1) as f64;
    println!("| renderer | frame | ms | frames/s | CPU ms | truth Msamples/s |");
    println!("|---|---|---|---|---|---|");
    if let Ok(ctx) = GpuContext::new() {
        let name = format!("gpu: {}", ctx.adapter_description());
        let format = wgpu::TextureFormat::Rgba8Unorm;
        let target = splitsum::gpu::texture::create_texture_2d(
            &ctx.device,
            "bench target",
            (size.0, size.1, 1),
            format,
            wgpu::TextureUsages::RENDER_ATTACHMENT,
        );
        let view = target.create_view(&Default::default());
        // As the window draws the split-sum view (forward while it moves, the present pass
        // alone while it stands still), then with the deferred passes the truth and heat
        // views use, which draw the same picture.
        // A GPU viewer of `light` drawing the split-sum view by the forward pass or not.
        let gpu_viewer = |light: &ViewLight, forward: bool| {
            let mut renderer = GpuRenderer::new(ctx.device.clone(), ctx.queue.clone()).unwrap();
            renderer.set_forward(forward);
            let renderer = Renderer::Gpu(Box::new(renderer));
            Viewer::new(light.clone(), models.clone(), renderer, "gpu").unwrap()
        };
        // The frames of `v` with the camera turning.
        let turning = |v: &mut Viewer| {
            time(FRAMES, |i| {
                v.state.camera.yaw_deg = 0.05 * i as f32;
                v.render_to(size, (&view, format)).unwrap();
            })
        };
        for forward in [true, false] {
            let mut v = gpu_viewer(&light, forward);
            let moving = turning(&mut v);
            if forward {
                row(&name, "camera turning (forward pass)", moving, None);
                let still = time(FRAMES, |_| v.render_to(size, (&view, format)).unwrap());
                row(&name, "still (present pass)", still, None);
            } else {
                row(&name, "camera turning (deferred passes)", moving, None);
                v.state.mode = Mode::Truth;
                v.points_per_estimate = 8;
                let truth = time(FRAMES / 4, |_| v.render_to(size, (&view, format)).unwrap());
                row(
                    &name,
                    "truth, 8 points",
                    truth,
                    Some(pixels * 8.0 / truth.0 / 1e6),
                );
            }
        }
        // The sun split out of quarry_01 and shaded with its shadow map; a studio's lamps
        // split out as area lights (the LTC), each with its soft shadow, and with the
        // shadows off (O), which gives what they cost.
        for (file, lights) in [
            ("quarry_01_1k.hdr", "quarry_01's sun split with its shadow"),
            (
                "studio_small_03_1k.hdr",
                "studio_small_03's lamps as area lights, each with its shadow",
            ),
        ] {
            let split = load_light(
                &LightSource::File(format!("tests/data/{file}").into()),
                BackendChoice::Auto,
                splitsum::SunMode::Split,
                &mut |_| {},
            )
            .unwrap();
            let mut v = gpu_viewer(&split, true);
            let moving = turning(&mut v);
            row(
                &name,
                &format!("camera turning (forward), {lights}"),
                moving,
                None,
            );
            if split.has_area_lights() {
                v.state.shadow = false;
                let moving = turning(&mut v);
                row(
                    &name,
                    "camera turning (forward), the same with the shadows off",
                    moving,
                    None,
                );
            }
        }
    }
    let mut v = Viewer::new(light, models, Renderer::Cpu(CpuFrame::default()), "cpu").unwrap();
    let moving = time(FRAMES / 4, |i| {
        v.state.camera.yaw_deg = 0.05 * i as f32;
        v.render_image(size).unwrap();
    });
    row("cpu", "camera turning", moving, None);
}
