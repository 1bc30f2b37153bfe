//! `splitsum view`: an interactive viewer of a bake, the sandbox of the document splitsum
//! grew from. One object stands above a floor under the baked light; the user walks
//! around it (WASD and the mouse), switches materials and models, turns the roughness, and
//! one key away sees the ground truth of the same view, or the heat map of where the
//! split-sum approximation departs from it.
//!
//! - [`scene`]: the placements, materials and point lights; [`camera`]: the camera;
//!   [`model`]: Spot, the sphere, the torus and OBJ/glTF files; [`state`]: what the user
//!   controls and the keys.
//! - [`frame`]: what one frame reads (the light, the uniform blocks); [`floor`]: the
//!   floor's shading by view direction; [`floor_shadow`]: the shadows on the floor; [`raster`] and [`cpu`]: the CPU renderer; [`gpu`]: the wgpu renderer; [`hud`]: the HUD.
//! - [`session::Viewer`]: the state, light, models and renderer, frame by frame, driven by
//!   the window ([`window`]) or by [`render_screenshot`] offscreen.
//!
//! The shading is the preview's, function for function: split-sum as the README tells an
//! engine to (`split_sum_shade`), the truth as the full reflectance integral
//! (`truth_shade`), the same tone mapping.

pub mod camera;
pub mod cpu;
pub mod floor;
pub mod floor_shadow;
pub mod frame;
pub mod gpu;
pub mod hud;
pub mod model;
pub mod raster;
pub mod scene;
pub mod session;
pub mod shadow;
pub mod state;
pub mod window;

use std::path::{Path, PathBuf};

use image::RgbaImage;

use crate::backend::BackendChoice;
use crate::bake::{read_bake_dir, BakeOptions, Baker};
use crate::environment::sun::SunMode;
use crate::environment::Environment;
use crate::gpu::context::GpuContext;
use crate::plan::lut::{LutModel, DEFAULT_LUT_SIZE};
use crate::plan::shading::LightBrdf;
use crate::view::frame::ViewLight;
use crate::view::gpu::GpuRenderer;
use crate::view::model::Model;
use crate::view::session::{CpuFrame, Renderer, Viewer};
use crate::view::state::Action;
use crate::{Error, Result};

/// The bundled environment (Poly Haven's CC0 "Venice Sunset", `tests/data/README.md`).
const BUNDLED_HDRI: &[u8] = include_bytes!("../../tests/data/venice_sunset_1k.hdr");
/// Its name in the HUD.
pub const BUNDLED_NAME: &str = "venice_sunset_1k.hdr (bundled)";
/// Window and screenshot size unless asked otherwise.
pub const DEFAULT_SIZE: (u32, u32) = (1280, 720);
/// Largest edge of a window or screenshot.
pub const MAX_EDGE: u32 = 8192;

/// Where the light comes from.
#[derive(Clone, Debug, PartialEq)]
pub enum LightSource {
    /// The bundled HDRI.
    Bundled,
    /// An HDRI (baked with the bake defaults) or a generic bake folder.
    File(PathBuf),
}

/// How `splitsum view` runs.
#[derive(Clone, Debug, PartialEq)]
pub struct ViewOptions {
    /// An HDRI or a bake folder; `None`: the bundled HDRI.
    pub input: Option<PathBuf>,
    /// A model file shown after the three bundled ones (and first).
    pub model: Option<PathBuf>,
    /// Window or screenshot size in pixels.
    pub size: (u32, u32),
    /// The backend of the bake (and offscreen, of the renderer).
    pub backend: BackendChoice,
    /// Render offscreen into this PNG instead of opening a window.
    pub screenshot: Option<PathBuf>,
    /// Actions applied before the first frame.
    pub keys: Vec<Action>,
    /// Frames rendered offscreen (the truth accumulates one estimate a frame).
    pub frames: u32,
    /// How an HDRI's sun is baked at start: split out (a light with a shadow, the
    /// default) or kept in the IBL; U swaps.
    pub sun: SunMode,
}

impl Default for ViewOptions {
    fn default() -> Self {
        ViewOptions {
            input: None,
            model: None,
            size: DEFAULT_SIZE,
            backend: BackendChoice::Auto,
            screenshot: None,
            keys: Vec::new(),
            frames: 1,
            sun: SunMode::Split,
        }
    }
}

impl ViewOptions {
    /// Checks the sizes and frame count.
    pub fn validate(&self) -> Result<()> {
        let (w, h) = self.size;
        if w == 0 || h == 0 || w > MAX_EDGE || h > MAX_EDGE {
            return Err(Error::InvalidOption {
                option: "size",
                message: format!("{w}x{h} is not from 1x1 to {MAX_EDGE}x{MAX_EDGE}"),
            });
        }
        if self.frames == 0 || self.frames > 100_000 {
            return Err(Error::InvalidOption {
                option: "frames",
                message: format!("{} is not from 1 to 100000", self.frames),
            });
        }
        Ok(())
    }

    /// The light's source.
    pub fn light_source(&self) -> LightSource {
        self.input
            .clone()
            .map_or(LightSource::Bundled, LightSource::File)
    }

    /// The models on keys: Spot, the sphere, the torus, then the `--model` file.
    pub fn models(&self) -> Result<Vec<Model>> {
        let mut models = Model::bundled()?;
        if let Some(path) = &self.model {
            models.push(Model::load(path)?);
        }
        Ok(models)
    }

    /// Puts `viewer` in its starting state: the `--model` file shown if given, then the
    /// `--keys` applied.
    pub fn initial_state(&self, viewer: &mut Viewer) -> Result<()> {
        if self.model.is_some() {
            viewer.apply(Action::Model(viewer.models.len() - 1))?;
        }
        for &key in &self.keys {
            viewer.apply(key)?;
        }
        Ok(())
    }
}

/// The viewer's light from `source`: an HDRI baked in memory with the bake defaults and
/// `sun` on `backend` (progress reported as text), and when it has a sun, baked in the
/// other sun mode too (`ViewLight::alternate`); or a generic bake folder read as `preview`
/// reads it. The LUT is the folder's, or the default model's.
pub fn load_light(
    source: &LightSource,
    backend: BackendChoice,
    sun: SunMode,
    progress: &mut dyn FnMut(String),
) -> Result<ViewLight> {
    let mut baker = Baker::new(BakeOptions {
        backend,
        sun,
        ground_truth: true,
        ..BakeOptions::default()
    })?;
    let (name, env) = match source {
        LightSource::File(dir) if dir.is_dir() => {
            progress(format!("reading {}", dir.display()));
            let (baked, lut) = read_bake_dir(dir)?;
            let lut = match lut {
                Some(l) => l,
                None => baker.lut(LutModel::default(), DEFAULT_LUT_SIZE)?,
            };
            let name = dir.display().to_string();
            return ViewLight::new(name, &baked, lut, &mut || {
                baker.shared_ltc_table(LightBrdf::GENERIC)
            });
        }
        LightSource::File(path) => {
            progress(format!("reading {}", path.display()));
            let loaded = baker.load(path, Some(baker.options().specular_size))?;
            for w in loaded.warnings {
                progress(format!("warning: {w}"));
            }
            let name = path.file_name().map_or_else(
                || path.display().to_string(),
                |n| n.to_string_lossy().into_owned(),
            );
            (name, loaded.env)
        }
        LightSource::Bundled => {
            let e = crate::io::hdr::decode(Path::new(BUNDLED_NAME), BUNDLED_HDRI)?;
            (BUNDLED_NAME.to_string(), Environment::Equirect(e))
        }
    };
    let baked = baker.bake_environment_with_progress(env.clone(), &mut |stage| {
        progress(format!("baking {name}: {}", stage.name()));
    })?;
    let lut = baker.lut(LutModel::default(), DEFAULT_LUT_SIZE)?;
    let mut ltc = || baker.shared_ltc_table(LightBrdf::GENERIC);
    let mut light = ViewLight::new(&name, &baked, lut.clone(), &mut ltc)?;
    if !baked.lights.is_empty() {
        let other = sun.other();
        baker.set_sun(other);
        let baked = baker.bake_environment_with_progress(env, &mut |stage| {
            progress(format!(
                "baking {name} with --sun {}: {}",
                other.name(),
                stage.name()
            ));
        })?;
        light.alternate = Some(Box::new(ViewLight::new(&name, &baked, lut, &mut || {
            baker.shared_ltc_table(LightBrdf::GENERIC)
        })?));
    }
    Ok(light)
}

/// Writes `img` as a PNG at `path` (a temporary file, then renamed).
pub fn screenshot_path(path: &Path, img: &RgbaImage) -> Result<()> {
    let mut png = std::io::Cursor::new(Vec::new());
    img.write_to(&mut png, image::ImageFormat::Png)
        .map_err(|e| Error::Encode {
            path: path.into(),
            format: "PNG",
            message: e.to_string(),
        })?;
    crate::io::atomic::write_atomic(path, &png.into_inner())
}

/// The offscreen renderer `backend` asks for: the GPU's, or with `Auto` the CPU's when no
/// adapter is found; with its description.
pub fn offscreen_renderer(backend: BackendChoice) -> Result<(Renderer, String)> {
    let gpu = || -> Result<(Renderer, String)> {
        let context = GpuContext::new()?;
        let description = context.adapter_description();
        let renderer = GpuRenderer::new(context.device.clone(), context.queue.clone())?;
        Ok((Renderer::Gpu(Box::new(renderer)), description))
    };
    let cpu = || {
        (
            Renderer::Cpu(CpuFrame::default()),
            "cpu renderer".to_string(),
        )
    };
    match backend {
        BackendChoice::Cpu => Ok(cpu()),
        BackendChoice::Gpu => gpu(),
        BackendChoice::Auto => match gpu() {
            Err(Error::NoAdapter { .. }) => Ok(cpu()),
            other => other,
        },
    }
}

/// Renders `opts.frames` frames offscreen after the keys and returns the last picture.
pub fn render_screenshot(
    opts: &ViewOptions,
    progress: &mut dyn FnMut(String),
) -> Result<RgbaImage> {
    opts.validate()?;
    let models = opts.models()?;
    let light = load_light(&opts.light_source(), opts.backend, opts.sun, progress)?;
    let (renderer, description) = offscreen_renderer(opts.backend)?;
    let mut viewer = Viewer::new(light, models, renderer, description)?;
    opts.initial_state(&mut viewer)?;
    let mut img = None;
    for _ in 0..opts.frames {
        img = Some(viewer.render_image(opts.size)?);
    }
    img.ok_or_else(|| Error::InvalidOption {
        option: "frames",
        message: "no frame rendered".into(),
    })
}

/// `splitsum view`: offscreen with `opts.screenshot` (the PNG written), otherwise a
/// window until Escape.
pub fn run(opts: ViewOptions, progress: &mut dyn FnMut(String)) -> Result<()> {
    opts.validate()?;
    if let Some(path) = &opts.screenshot {
        crate::io::check_output_extension(path, "a screenshot", &["png"])?;
        let img = render_screenshot(&opts, progress)?;
        return screenshot_path(path, &img);
    }
    // A bad model is refused before a window opens.
    let models = opts.models()?;
    window::run_window(opts, models)
}
