//! What the check's apps share: their float-image cameras, capturing the images until the
//! renders are final, and PNGs of them for people.

use std::collections::HashMap;
use std::path::Path;
use std::sync::{Arc, Mutex};
use std::time::{Duration, Instant};

use bevy::asset::UntypedAssetId;
use bevy::camera::{Exposure, Hdr, RenderTarget};
use bevy::core_pipeline::tonemapping::Tonemapping;
use bevy::prelude::*;
use bevy::render::render_resource::TextureFormat;
use bevy::render::view::screenshot::{Screenshot, ScreenshotCaptured};

/// Marks the check's own cameras (the one the README's recipe spawns has none).
#[derive(Component)]
pub struct CheckCamera;

/// The captures, by shot index, shared with the screenshot observers.
#[derive(Resource, Clone, Default)]
pub struct Captures(pub Arc<Mutex<HashMap<usize, Vec<Vec<f32>>>>>);

impl Captures {
    /// Whether each of `count` shots has been captured at least twice, its last two
    /// captures equal and not black: the renders are final.
    pub fn stable(&self, count: usize) -> bool {
        let map = self.0.lock().unwrap();
        count == map.len()
            && map.values().all(|v| {
                v.len() >= 2
                    && v[v.len() - 1] == v[v.len() - 2]
                    && v[v.len() - 1].iter().any(|&x| x > 0.0)
            })
    }

    /// Screenshots each of `targets` (RGBA float images) into its index's captures.
    pub fn request<'a>(
        &self,
        commands: &mut Commands,
        targets: impl Iterator<Item = &'a Handle<Image>>,
    ) {
        for (i, target) in targets.enumerate() {
            let store = self.0.clone();
            commands.spawn(Screenshot::image(target.clone())).observe(
                move |captured: On<ScreenshotCaptured>| {
                    let floats = captured
                        .image
                        .data
                        .as_deref()
                        .unwrap_or(&[])
                        .chunks_exact(4)
                        .map(|b| f32::from_le_bytes([b[0], b[1], b[2], b[3]]))
                        .collect();
                    store.lock().unwrap().entry(i).or_default().push(floats);
                },
            );
        }
    }
}

/// A `size`² RGBA float image for a check camera to render into and the check to read.
pub fn float_target(images: &mut Assets<Image>, size: u32) -> Handle<Image> {
    images.add(Image::new_target_texture(
        size,
        size,
        TextureFormat::Rgba32Float,
        None,
    ))
}

/// A check camera drawn as the `order`-th into the float image `target` with vertical
/// field of view `fov` (radians): linear radiance (no tone mapping, no MSAA) at Bevy's
/// default exposure.
pub fn check_camera(
    order: usize,
    target: &Handle<Image>,
    fov: f32,
    transform: Transform,
) -> impl Bundle {
    (
        CheckCamera,
        Camera3d::default(),
        Camera {
            order: order as isize,
            clear_color: ClearColorConfig::Custom(Color::NONE),
            ..default()
        },
        RenderTarget::Image(target.clone().into()),
        Projection::Perspective(PerspectiveProjection { fov, ..default() }),
        transform,
        Hdr,
        Tonemapping::None,
        Msaa::Off,
        Exposure::default(),
    )
}

/// Frames between capture rounds once everything has loaded; a shot counts as final when
/// two rounds in a row are identical (pipelines compile asynchronously, so the first frames
/// may lack a mesh or a skybox).
pub const CAPTURE_EVERY: u32 = 15;
pub const TIMEOUT: Duration = Duration::from_secs(600);

/// Where a check's app stands: the assets its shots wait for, and the frames since.
pub struct Progress {
    pub assets: Vec<UntypedAssetId>,
    loaded_at: Option<u32>,
    frame: u32,
    started: Instant,
}

impl Default for Progress {
    fn default() -> Self {
        Progress {
            assets: Vec::new(),
            loaded_at: None,
            frame: 0,
            started: Instant::now(),
        }
    }
}

/// What a check's app does this frame.
enum Step {
    /// Nothing: an asset is loading, or it is not a capture round.
    Wait,
    /// A capture round.
    Capture,
    /// Give up: an asset failed to load, or no stable renders before [`TIMEOUT`].
    Fail(String),
}

/// One frame of a check app's capture loop: counts it in `progress`, ends the app with
/// an error (naming `label`) where an asset failed or the renders never settle, and on a
/// capture round screenshots each of `targets`; true when every render is final (the
/// caller writes them and ends the app).
pub fn capture_round<'a>(
    progress: &mut Progress,
    assets: &AssetServer,
    captures: &Captures,
    commands: &mut Commands,
    exit: &mut MessageWriter<AppExit>,
    label: &str,
    targets: impl ExactSizeIterator<Item = &'a Handle<Image>>,
) -> bool {
    match progress.step(assets) {
        Step::Wait => false,
        Step::Fail(e) => {
            eprintln!("error: {label}: {e}");
            exit.write(AppExit::error());
            false
        }
        Step::Capture if captures.stable(targets.len()) => true,
        Step::Capture => {
            captures.request(commands, targets);
            false
        }
    }
}

impl Progress {
    /// Counts this frame and says what to do in it.
    fn step(&mut self, assets: &AssetServer) -> Step {
        self.frame += 1;
        if self.started.elapsed() > TIMEOUT {
            return Step::Fail(format!("no stable renders after {TIMEOUT:?}"));
        }
        for id in &self.assets {
            if let Some(bevy::asset::LoadState::Failed(e)) = assets.get_load_state(*id) {
                return Step::Fail(format!("Bevy failed to load an asset: {e}"));
            }
        }
        let Some(loaded_at) = self.loaded_at else {
            if self
                .assets
                .iter()
                .all(|id| assets.is_loaded_with_dependencies(*id))
            {
                self.loaded_at = Some(self.frame);
            }
            return Step::Wait;
        };
        if (self.frame - loaded_at) % CAPTURE_EVERY == 0 {
            Step::Capture
        } else {
            Step::Wait
        }
    }
}

/// A Reinhard-mapped 8-bit PNG of a float capture, for people.
pub fn save_png(path: &Path, data: &[f32], size: u32) {
    let mut rgb = Vec::with_capacity((3 * size * size) as usize);
    for y in 0..size {
        for x in 0..size {
            rgb.extend(crate::evaluate::pixel(data, size, x, y).map(|v| {
                let v = v.max(0.0);
                (255.0 * (v / (1.0 + v)).powf(1.0 / 2.2)).round() as u8
            }));
        }
    }
    let file = std::fs::File::create(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    let mut encoder = png::Encoder::new(std::io::BufWriter::new(file), size, size);
    encoder.set_color(png::ColorType::Rgb);
    encoder.set_depth(png::BitDepth::Eight);
    let mut writer = encoder
        .write_header()
        .unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    writer
        .write_image_data(&rgb)
        .unwrap_or_else(|e| panic!("{}: {e}", path.display()));
}
