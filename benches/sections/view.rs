//! `cargo bench --bench bench -- view`: the viewer's frame times at 1280×720 with Spot, as
//! the window draws them (G-buffer, shading, present into a texture, waiting for the
//! device; no readback), with the camera turning every frame (every pass runs) and still
//! (the present pass alone), and the ground truth's samples per second; on the GPU
//! renderer (the adapter wgpu finds: lavapipe here) and the CPU renderer.

use std::time::Instant;

use splitsum::gpu::GpuContext;
use splitsum::view::frame::Mode;
use splitsum::view::gpu::GpuRenderer;
use splitsum::view::session::{CpuFrame, Renderer, Viewer};
use splitsum::view::{load_light, LightSource, DEFAULT_SIZE};
use splitsum::BackendChoice;

/// Frames timed per row (after two warm-up frames).
const FRAMES: usize = 20;

/// Mean seconds of `frames` calls of `frame`, after two untimed ones.
fn time(frames: usize, mut frame: impl FnMut(usize)) -> f64 {
    frame(0);
    frame(1);
    let t = Instant::now();
    for i in 0..frames {
        frame(i + 2);
    }
    t.elapsed().as_secs_f64() / frames as f64
}

pub fn benchmarks() {
    println!("\n## The viewer at 1280×720 with Spot (mean of {FRAMES} frames)\n");
    let light = load_light(&LightSource::Bundled, BackendChoice::Auto, &mut |_| {}).unwrap();
    let models = splitsum::view::model::Model::bundled().unwrap();
    let size = DEFAULT_SIZE;
    let pixels = (size.0 * size.1) as f64;
    println!("| renderer | frame | ms | frames/s | truth Msamples/s |");
    println!("|---|---|---|---|---|");
    if let Ok(ctx) = GpuContext::new() {
        let renderer = GpuRenderer::new(ctx.device.clone(), ctx.queue.clone()).unwrap();
        let mut v = Viewer::new(
            light.clone(),
            models.clone(),
            Renderer::Gpu(Box::new(renderer)),
            "gpu",
        )
        .unwrap();
        let format = wgpu::TextureFormat::Rgba8Unorm;
        let target = splitsum::gpu::texture::create_texture_2d(
            &ctx.device,
            "bench target",
            (size.0, size.1, 1),
            format,
            wgpu::TextureUsages::RENDER_ATTACHMENT,
        );
        let view = target.create_view(&Default::default());
        let name = ctx.adapter_description();
        let moving = time(FRAMES, |i| {
            v.state.camera.yaw_deg = 0.05 * i as f32;
            v.render_to(size, (&view, format)).unwrap();
        });
        let still = time(FRAMES, |_| v.render_to(size, (&view, format)).unwrap());
        v.state.mode = Mode::Truth;
        v.points_per_estimate = 8;
        let truth = time(FRAMES / 4, |_| v.render_to(size, (&view, format)).unwrap());
        let rate = pixels * 8.0 / truth / 1e6;
        println!(
            "| gpu: {name} | camera turning | {:.1} | {:.1} | |",
            1e3 * moving,
            1.0 / moving
        );
        println!(
            "| gpu: {name} | still | {:.1} | {:.1} | |",
            1e3 * still,
            1.0 / still
        );
        println!(
            "| gpu: {name} | truth, 8 points | {:.1} | {:.2} | {rate:.1} |",
            1e3 * truth,
            1.0 / truth
        );
    }
    let mut v = Viewer::new(light, models, Renderer::Cpu(CpuFrame::default()), "cpu").unwrap();
    let moving = time(FRAMES / 4, |i| {
        v.state.camera.yaw_deg = 0.05 * i as f32;
        v.render_image(size).unwrap();
    });
    println!(
        "| cpu | camera turning | {:.1} | {:.1} | |",
        1e3 * moving,
        1.0 / moving
    );
}
