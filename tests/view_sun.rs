//! The viewer with the sun split out (`splitsum view --sun split`, the default): the sun
//! shaded as a directional light whose shadow map puts the object's shadow on the floor on
//! the side away from the sun, in the split-sum and in the truth alike; nothing of the
//! kind with the shadow off; the U and O keys; and the GPU and CPU renderers agreeing.

mod common;

use common::gpu;
use glam::{Vec2, Vec3};
use splitsum::stages::preview::picture::luminance;
use splitsum::view::camera::{Camera, Projection};
use splitsum::view::frame::{Mode, Surface, ViewLight};
use splitsum::view::gpu::GpuRenderer;
use splitsum::view::model::Model;
use splitsum::view::scene::{FLOOR_Y, OBJECT_CENTRE};
use splitsum::view::session::{CpuFrame, Renderer, Viewer};
use splitsum::view::state::{Action, Change};
use splitsum::view::{load_light, LightSource};
use splitsum::{BackendChoice, SunMode};

/// quarry_01_1k baked on the CPU with the sun split (and kept, as the alternate).
fn quarry() -> ViewLight {
    common::split_view_light("quarry_01_1k.hdr")
}

/// A viewer of `light` on `model` alone, drawn by the CPU renderer.
fn cpu_viewer(light: ViewLight, model: Model) -> Viewer {
    Viewer::new(
        light,
        vec![model],
        Renderer::Cpu(CpuFrame::default()),
        "test",
    )
    .unwrap()
}

/// Looking straight down (1° off, where the camera's basis is defined) on the floor
/// around the object, orthographic, 18 m across: quarry_01's sun at 10° casts the
/// sphere's shadow up to 8.5 m from the point below it.
fn overhead() -> Camera {
    Camera {
        position: Vec3::from(OBJECT_CENTRE) + 10.0 * Vec3::Y,
        yaw_deg: 0.0,
        pitch_deg: -89.0,
        projection: Projection::Orthographic { half_height: 9.0 },
    }
}

/// What counts as shadowed: under this fraction of the floor's median luminance. The
/// floor is lit evenly (everywhere it sees the same sky and the same sun), and quarry_01's
/// sun at 10° lights it a little under half: its shadow measures 0.57 of the median.
const DARK: f32 = 0.8;

/// Where the floor pixels of a frame darker than [`DARK`] × the floor's median lie,
/// seen from the point below the object's centre: (their count, the unit direction of
/// their centroid in the floor plane (x, z)). `radiance` gives a pixel's (RGB, surface
/// id).
fn dark_floor(v: &Viewer, size: (u32, u32), radiance: impl Fn(usize) -> [f32; 4]) -> (usize, Vec2) {
    let camera = v.frame_uniform(size).camera();
    let mut floor = Vec::new();
    for y in 0..size.1 {
        for x in 0..size.0 {
            let k = (y * size.0 + x) as usize;
            let c = radiance(k);
            if Surface::from_id(c[3]) != Surface::Floor {
                continue;
            }
            let (o, d) = camera.pixel_ray(x, y, size.0, size.1);
            let p = o + d * ((FLOOR_Y - o.y) / d.y);
            floor.push((
                Vec2::new(p.x, p.z - OBJECT_CENTRE[2]),
                luminance([c[0], c[1], c[2]]),
            ));
        }
    }
    let mut sorted: Vec<f32> = floor.iter().map(|f| f.1).collect();
    sorted.sort_by(f32::total_cmp);
    let median = sorted[sorted.len() / 2];
    let dark: Vec<Vec2> = floor
        .iter()
        .filter(|f| f.1 < DARK * median)
        .map(|f| f.0)
        .collect();
    let centroid = dark.iter().copied().sum::<Vec2>() / dark.len().max(1) as f32;
    (dark.len(), centroid.normalize_or_zero())
}

#[test]
fn shadow_falls_away_from_the_sun() {
    // The floor's darkest region (under 0.8 of the floor's median luminance) lies on the
    // side away from the sun: its centroid's direction in the floor plane within 5° of
    // the sun's azimuth turned by 180° (measured: under 1°), for the sphere and Spot, in
    // the split-sum frame and in the truth (which sees the sun through the same map);
    // with the shadow off (O) no floor pixel is that dark.
    let light = quarry();
    assert_eq!(light.sun_mode, SunMode::Split);
    let sun = light.split_lights()[0];
    let away = -Vec2::new(sun.direction[0], sun.direction[2]).normalize();
    let size = (200, 200);
    for model in [Model::sphere(), Model::spot().unwrap()] {
        let name = model.name.clone();
        let mut v = cpu_viewer(light.clone(), model);
        v.state.camera = overhead();
        v.state.hud = false;
        v.render_image(size).unwrap();
        let (shaded, _) = v.hdr().unwrap();
        let (count, dir) = dark_floor(&v, size, |k| shaded[k]);
        let angle = dir.angle_to(away).to_degrees().abs();
        assert!(
            count > 100 && angle <= 5.0,
            "{name} split-sum: {count} dark pixels, {angle}° from away"
        );

        v.state.mode = Mode::Truth;
        v.points_per_estimate = 16;
        v.render_image(size).unwrap();
        let (shaded, accum) = v.hdr().unwrap();
        let truth = |k: usize| {
            let a = accum[k];
            [a[0] / a[3], a[1] / a[3], a[2] / a[3], shaded[k][3]]
        };
        let (count, dir) = dark_floor(&v, size, truth);
        let angle = dir.angle_to(away).to_degrees().abs();
        assert!(
            count > 100 && angle <= 5.0,
            "{name} truth: {count} dark pixels, {angle}° from away"
        );

        v.state.mode = Mode::SplitSum;
        assert_eq!(v.apply(Action::ToggleShadow).unwrap(), Change::Scene);
        v.render_image(size).unwrap();
        let (shaded, _) = v.hdr().unwrap();
        let (count, _) = dark_floor(&v, size, |k| shaded[k]);
        assert_eq!(count, 0, "{name}: dark floor pixels with the shadow off");
    }
}

#[test]
fn sun_keys_and_hud() {
    // U swaps the light baked with the sun kept in and back; the HUD says which; O the
    // shadow. On an HDRI without a sun, U changes nothing and says why.
    let light = quarry();
    let mut v = cpu_viewer(light, Model::sphere());
    let sun_line = |v: &mut Viewer| {
        v.hud_lines()
            .into_iter()
            .find(|l| l.starts_with("sun "))
            .unwrap()
    };
    assert!(
        sun_line(&mut v).contains("split, shadow on"),
        "{}",
        sun_line(&mut v)
    );
    assert_eq!(v.apply(Action::ToggleShadow).unwrap(), Change::Scene);
    assert!(sun_line(&mut v).contains("split, shadow off"));
    assert_eq!(v.apply(Action::ToggleSun).unwrap(), Change::Scene);
    assert_eq!(v.light.sun_mode, SunMode::Keep);
    assert_eq!(v.frame_uniform((8, 8)).sun[..2], [0, 0]);
    assert!(sun_line(&mut v).contains("kept in the IBL"));
    assert_eq!(v.apply(Action::ToggleSun).unwrap(), Change::Scene);
    assert_eq!(v.light.sun_mode, SunMode::Split);
    assert_eq!(
        v.frame_uniform((8, 8)).sun[0],
        v.light.split_lights().len() as u32
    );
    assert!(splitsum::parse_keys("u o").unwrap() == [Action::ToggleSun, Action::ToggleShadow]);

    let venice = load_light(
        &LightSource::Bundled,
        BackendChoice::Cpu,
        SunMode::Split,
        &mut |_| {},
    )
    .unwrap();
    let mut v = cpu_viewer(venice, Model::sphere());
    assert_eq!(v.apply(Action::ToggleSun).unwrap(), Change::Nothing);
    assert!(v.hud_lines().iter().any(|l| l.contains("no sun found")));
}

#[test]
fn gpu_and_cpu_agree_with_the_sun() {
    // Spot under quarry_01 with the sun split and its shadow: the split-sum frames agree
    // within 1e-3 on 99.5 % of the pixels (the GPU's and the CPU's rounding can put a
    // receiver's depth on either side of a map texel's, up to a quarter of the sun apart
    // where the bilinear filter weighs that texel most, and the two rasterisers can
    // disagree on a silhouette pixel), and the truth's mean within 1e-3.
    let Some(ctx) = gpu() else { return };
    let light = quarry();
    let size = (160, 90);
    let render = |renderer: Renderer| common::viewer_frames(&light, renderer, size, 1);
    let gpu_renderer = GpuRenderer::new(ctx.device.clone(), ctx.queue.clone()).unwrap();
    let (gpu_shaded, gpu_accum) = render(Renderer::Gpu(Box::new(gpu_renderer)));
    let (cpu_shaded, cpu_accum) = render(Renderer::Cpu(CpuFrame::default()));
    common::assert_viewer_frames_agree((&gpu_shaded, &gpu_accum), (&cpu_shaded, &cpu_accum));
}

#[test]
fn forward_pass_draws_the_sun_as_the_deferred_passes_do() {
    // The forward pass is compiled for the frame's light counts (here the sun, then with
    // the point lights on too, then with the sun kept: none split out): each draws Spot
    // under quarry_01 with the sun's shadow as the deferred passes do, to the bar of
    // tests/view.rs (`forward_and_deferred_pictures_are_the_same`, which says why).
    let Some(ctx) = gpu() else { return };
    common::forward_matches_deferred(&ctx, &quarry(), (320, 180), &["", "l", "l u"]);
}
