//! [`Viewer`]: the viewer's state, light, models and renderer, one frame at a time. The
//! window ([`crate::view::window`]) and offscreen renders drive the same object, so a
//! screenshot shows exactly what the window would.
//!
//! The truth accumulates one estimate per frame while nothing that is seen changes (the
//! frame's uniform block, the model, the light); any change restarts it. Each estimate
//! uses [`Viewer::points_per_estimate`] quadrature points per lobe, rotated per pixel and
//! estimate, so k estimates of n points converge like one of k·n.

use std::time::Instant;

use image::RgbaImage;

use glam::Vec3;

use crate::environment::sun::SunMode;
use crate::plan::scene::disk_points;
use crate::view::cpu::{floor_table, present, shade_split_sum, shade_truth, Shadows};
use crate::view::floor::FloorTable;
use crate::view::floor_shadow::FloorShadows;
use crate::view::frame::{
    heat_mean, heat_table, light_table, FrameUniform, HdrFrame, Mode, PresentUniform, ViewLight,
};
use crate::view::gpu::{GpuRenderer, MAX_TRUTH_POINTS};
use crate::view::hud;
use crate::view::model::{Model, Shape};
use crate::view::raster::{rasterize, scene_vertices, GBuffer, Vertex};
use crate::view::scene::{floor_material, FLOOR_ROUGHNESS, POINT_LIGHTS};
use crate::view::shadow::ShadowMaps;
use crate::view::state::{Action, Change, ViewState, KEYS};
use crate::{Error, Result};

/// Quadrature points per lobe of one truth estimate unless the caller sets another count.
pub const DEFAULT_POINTS_PER_ESTIMATE: u32 = 64;
/// Keys the HUD lists on one line.
const KEYS_PER_LINE: usize = 5;
/// Seconds between refreshes of the HUD's frame time.
const HUD_REFRESH_SECONDS: f32 = 0.25;
/// Seconds a message stays in the HUD.
const MESSAGE_SECONDS: f32 = 8.0;

/// The CPU renderer's buffers, and the tables its passes read (made once, as the GPU
/// renderer uploads them once).
pub struct CpuFrame {
    vertices: Vec<Vertex>,
    sphere: bool,
    gbuffer: Option<GBuffer>,
    shaded: Vec<[f32; 4]>,
    accum: Vec<[f32; 4]>,
    lights: Vec<[f32; 4]>,
    heat: Vec<[f32; 4]>,
}

impl Default for CpuFrame {
    fn default() -> Self {
        Self {
            vertices: Vec::new(),
            sphere: false,
            gbuffer: None,
            shaded: Vec::new(),
            accum: Vec::new(),
            lights: light_table(&POINT_LIGHTS),
            heat: heat_table(),
        }
    }
}

/// Which renderer draws the frames.
pub enum Renderer {
    /// The wgpu renderer.
    Gpu(Box<GpuRenderer>),
    /// The CPU twin.
    Cpu(CpuFrame),
}

/// The viewer.
pub struct Viewer {
    /// What the user has set.
    pub state: ViewState,
    /// The baked light shown.
    pub light: ViewLight,
    /// The heat map's mean over the object, measured after a heat-view frame.
    heat_mean: Option<f32>,
    /// The shadow maps of the lights split out, for the light and model shown.
    shadow: ShadowMaps,
    /// The floor's table of the light shown (`view::floor`).
    floor: FloorTable,
    /// The shadow maps' grids on the floor (`view::floor_shadow`).
    floor_shadows: FloorShadows,
    /// The models on keys.
    pub models: Vec<Model>,
    /// Quadrature points per lobe of each truth estimate (1 ..= 256).
    pub points_per_estimate: u32,
    renderer: Renderer,
    truth_frame: u32,
    truth_samples: u64,
    last_frame: Option<FrameUniform>,
    scene_dirty: bool,
    messages: Vec<(String, Instant)>,
    frame_seconds: f32,
    /// The frame time the HUD shows, refreshed a few times a second (redrawing the HUD
    /// every frame would cost more than the frame).
    shown_frame_seconds: (f32, Instant),
    /// The size and lines of the HUD image last uploaded (a new size means new targets).
    last_hud: Option<((u32, u32), Vec<String>)>,
    backend: String,
}

impl Viewer {
    /// A viewer of `light` on `models` (at least one) drawn by `renderer`, described as
    /// `backend` in the HUD.
    pub fn new(
        light: ViewLight,
        models: Vec<Model>,
        renderer: Renderer,
        backend: impl Into<String>,
    ) -> Result<Viewer> {
        if models.is_empty() {
            return Err(Error::InvalidOption {
                option: "models",
                message: "the viewer needs a model".into(),
            });
        }
        let mut v = Viewer {
            state: ViewState::default(),
            light,
            heat_mean: None,
            shadow: ShadowMaps::default(),
            floor: FloorTable::empty(),
            floor_shadows: FloorShadows::new(&ShadowMaps::default()),
            models,
            points_per_estimate: DEFAULT_POINTS_PER_ESTIMATE,
            renderer,
            truth_frame: 0,
            truth_samples: 0,
            last_frame: None,
            scene_dirty: true,
            messages: Vec::new(),
            frame_seconds: 0.0,
            shown_frame_seconds: (0.0, Instant::now()),
            last_hud: None,
            backend: backend.into(),
        };
        if let Renderer::Gpu(g) = &mut v.renderer {
            g.set_light(&v.light)?;
        }
        v.update_floor()?;
        v.upload_model()?;
        Ok(v)
    }

    fn upload_model(&mut self) -> Result<()> {
        let model = &self.models[self.state.model.min(self.models.len() - 1)];
        match &mut self.renderer {
            Renderer::Gpu(g) => g.set_model(model)?,
            Renderer::Cpu(c) => {
                c.vertices = scene_vertices(model);
                c.sphere = matches!(model.shape, Shape::Sphere);
            }
        }
        self.scene_dirty = true;
        self.update_shadow()
    }

    /// Makes the shadow maps of the lights split out for the light and model shown (none
    /// with the lights kept) and uploads them to the GPU renderer (the CPU one reads them
    /// from here).
    fn update_shadow(&mut self) -> Result<()> {
        let model = &self.models[self.state.model.min(self.models.len() - 1)];
        let lights: Vec<(Vec3, f32)> = self
            .light
            .split_lights()
            .iter()
            .map(|l| (Vec3::from(l.direction), l.penumbra_spread()))
            .collect();
        self.shadow = ShadowMaps::new(&lights, model);
        self.floor_shadows = FloorShadows::new(&self.shadow);
        if let Renderer::Gpu(g) = &mut self.renderer {
            g.set_shadow(&self.shadow, &self.floor_shadows)?;
        }
        Ok(())
    }

    /// Makes the floor's table of the light shown and uploads it to the GPU renderer (the
    /// CPU one reads it from here).
    fn update_floor(&mut self) -> Result<()> {
        let floor = self.light.material(&floor_material(), FLOOR_ROUGHNESS);
        self.floor = floor_table(&self.light, &floor);
        if let Renderer::Gpu(g) = &mut self.renderer {
            g.set_floor(&self.floor)?;
        }
        Ok(())
    }

    /// Shows `light` from now on.
    pub fn set_light(&mut self, light: ViewLight) -> Result<()> {
        if let Renderer::Gpu(g) = &mut self.renderer {
            g.set_light(&light)?;
        }
        self.light = light;
        self.scene_dirty = true;
        self.update_floor()?;
        self.update_shadow()
    }

    /// Swaps in the light's other sun mode (`ViewLight::alternate`), or says why not.
    fn toggle_sun(&mut self) -> Result<Change> {
        let Some(mut next) = self.light.alternate.take() else {
            let why = match self.light.found.is_empty() {
                true => "no sun found in this environment: nothing to split".to_string(),
                false => format!(
                    "this bake was made with --sun {}: view the HDRI to switch",
                    self.light.sun_mode.name()
                ),
            };
            self.message(why);
            return Ok(Change::Nothing);
        };
        let current = std::mem::replace(&mut self.light, ViewLight::blank());
        next.alternate = Some(Box::new(current));
        self.set_light(*next)?;
        Ok(Change::Scene)
    }

    /// Applies a user's action.
    pub fn apply(&mut self, action: Action) -> Result<Change> {
        if action == Action::ToggleSun {
            return self.toggle_sun();
        }
        let model = self.state.model;
        let change = self.state.apply(action, self.models.len());
        if self.state.model != model {
            self.upload_model()?;
        }
        Ok(change)
    }

    /// A line in the HUD for a while (and the caller prints it on stderr).
    pub fn message(&mut self, text: impl Into<String>) {
        self.messages.push((text.into(), Instant::now()));
    }

    /// Seconds the last frame took.
    pub fn frame_seconds(&self) -> f32 {
        self.frame_seconds
    }

    /// Quadrature points per pixel and lobe accumulated so far.
    pub fn truth_samples(&self) -> u64 {
        self.truth_samples
    }

    /// The uniform block of a `size` frame of the current state (truth index 0).
    pub fn frame_uniform(&self, size: (u32, u32)) -> FrameUniform {
        let s = &self.state;
        let object = self.light.material(s.base_material(), s.roughness);
        let floor = self.light.material(&floor_material(), FLOOR_ROUGHNESS);
        let lights = if s.lights {
            POINT_LIGHTS.len() as u32
        } else {
            0
        };
        FrameUniform::new(
            &s.camera.frame(size.0, size.1),
            size,
            &object,
            &floor,
            lights,
            0,
        )
        .with_sun(
            &self.light,
            (
                if s.shadow { &self.shadow.blocks } else { &[] },
                self.shadow.size,
            ),
        )
    }

    /// The present pass's block for a `size` frame.
    pub fn present_uniform(&self, size: (u32, u32)) -> PresentUniform {
        let exposure = self.light.exposure * 2f32.powf(self.state.exposure_ev);
        PresentUniform::new(size, self.state.mode, exposure)
    }

    /// The HUD's lines (none with the HUD off). Line 1 is the material's.
    pub fn hud_lines(&mut self) -> Vec<String> {
        self.messages
            .retain(|(_, t)| t.elapsed().as_secs_f32() < MESSAGE_SECONDS);
        let s = &self.state;
        if !s.hud {
            return Vec::new();
        }
        let m = s.base_material();
        let kind = if m.metallic { "metal" } else { "dielectric" };
        let view = match s.mode {
            Mode::SplitSum => "split-sum (G: ground truth, H: heat map)".to_string(),
            Mode::Truth => format!("ground truth, {} samples a pixel", self.truth_samples),
            Mode::Heat => format!(
                "heat map |split-sum − truth| / truth, 0.1 % … 100 %, {} samples{}",
                self.truth_samples,
                self.heat_mean.map_or(String::new(), |m| format!(
                    " · object Σ|ΔY|/ΣY {:.2} %",
                    100.0 * m
                ))
            ),
        };
        let mut lines = vec![
            format!("splitsum view · {}", self.light.name),
            format!(
                "material {} {} ({kind}) · roughness {:.2}",
                s.material + 1,
                m.name,
                s.roughness
            ),
            format!(
                "model {} · exposure {:+.1} EV · lights {}",
                self.models[s.model].name,
                s.exposure_ev,
                if s.lights { "on" } else { "off" }
            ),
            format!("view: {view}"),
            self.sun_line(),
            match self.shown_frame_seconds.0 {
                t if t > 0.0 => format!("frame {:.1} ms · {}", 1e3 * t, self.backend),
                _ => format!("frame – · {}", self.backend),
            },
        ];
        lines.extend(self.messages.iter().map(|(m, _)| m.clone()));
        // The keys' short forms, a few to a line.
        let shorts: Vec<&str> = KEYS.iter().map(|k| k.3).collect();
        lines.extend(shorts.chunks(KEYS_PER_LINE).map(|c| c.join(" · ")));
        lines
    }

    /// The HUD's line on the lights: the first (a sun, or an area light and its width),
    /// where it is, its share of the light, how many more there are, and whether they are
    /// split out (each with its shadow, soft for an area light) or kept in the IBL.
    fn sun_line(&self) -> String {
        let Some(sun) = self.light.found.first() else {
            return "sun: none found (no compact dominant light)".into();
        };
        let what = match sun.shape {
            Some(_) => format!("area light {:.0}°", 2.0 * sun.angular_radius_deg),
            None => "sun".to_string(),
        };
        // Each light split out casts its shadow, soft for an area light.
        let split = self.light.split_lights();
        let shadow = match (split.len(), self.light.has_area_lights()) {
            (0 | 1, false) => "shadow",
            (0 | 1, true) => "soft shadow",
            _ => "shadows",
        };
        let more = match self.light.found.len() - 1 {
            0 => String::new(),
            n => format!(" · {n} more light{}", if n == 1 { "" } else { "s" }),
        };
        let place = format!(
            "{what} az {:.1}° el {:.1}° · {:.1} % of the light{more}",
            sun.azimuth_deg(),
            sun.elevation_deg(),
            100.0 * sun.share
        );
        match self.light.sun_mode {
            SunMode::Split => format!(
                "{place} · split, {shadow} {}",
                if self.state.shadow { "on" } else { "off" }
            ),
            SunMode::Keep => format!("{place} · kept in the IBL"),
        }
    }

    /// The frame's uniform for this call and whether the G-buffer must be redrawn (and the
    /// truth restarted).
    fn next_frame(&mut self, size: (u32, u32)) -> (FrameUniform, bool) {
        let mut frame = self.frame_uniform(size);
        let changed = self.scene_dirty || self.last_frame != Some(frame);
        if changed {
            self.truth_frame = 0;
            self.truth_samples = 0;
            self.heat_mean = None;
            self.last_frame = Some(frame);
            self.scene_dirty = false;
        }
        frame.truth_frame = self.truth_frame;
        (frame, changed)
    }

    fn truth_points(&self) -> Option<Vec<[f32; 4]>> {
        (self.state.mode != Mode::SplitSum)
            .then(|| disk_points(self.points_per_estimate.clamp(1, MAX_TRUTH_POINTS)))
    }

    /// Counts this frame's truth estimate (before the HUD is drawn, so it counts it).
    fn count_estimate(&mut self, points: &Option<Vec<[f32; 4]>>) {
        if let Some(p) = points {
            self.truth_samples += p.len() as u64;
        }
    }

    /// Counts the frame; refreshes the HUD's frame time a few times a second and, in the
    /// heat view, its mean (from a readback of the frame: every frame with `every_frame`,
    /// else when the frame time refreshes).
    fn finish_frame(
        &mut self,
        points: &Option<Vec<[f32; 4]>>,
        started: Instant,
        every_frame: bool,
    ) -> Result<()> {
        if points.is_some() {
            self.truth_frame += 1;
        }
        self.frame_seconds = started.elapsed().as_secs_f32();
        let refresh = self.shown_frame_seconds.1.elapsed().as_secs_f32() > HUD_REFRESH_SECONDS;
        if refresh {
            self.shown_frame_seconds = (self.frame_seconds, Instant::now());
        }
        if self.state.mode == Mode::Heat && (every_frame || refresh) {
            let (shaded, accum) = self.hdr()?;
            self.heat_mean = heat_mean(&shaded, &accum);
        }
        Ok(())
    }

    /// The heat map's energy-weighted mean over the object as the HUD shows it (the
    /// preview's figure of a sphere), measured after the last heat-view frame.
    pub fn heat_mean(&self) -> Option<f32> {
        self.heat_mean
    }

    /// The HUD image when its lines or the frame's size changed since the last upload.
    fn hud_image(&mut self, size: (u32, u32)) -> Result<Option<RgbaImage>> {
        let lines = self.hud_lines();
        if self
            .last_hud
            .as_ref()
            .is_some_and(|(s, l)| *s == size && *l == lines)
        {
            return Ok(None);
        }
        let img = hud::draw(&lines, size.0, size.1).map_err(|message| Error::Encode {
            path: "HUD".into(),
            format: "text",
            message,
        })?;
        self.last_hud = Some((size, lines));
        Ok(Some(img))
    }

    /// Renders one frame into `target` (a window's surface texture) on the GPU renderer.
    pub fn render_to(
        &mut self,
        size: (u32, u32),
        target: (&wgpu::TextureView, wgpu::TextureFormat),
    ) -> Result<()> {
        let started = Instant::now();
        let (frame, changed) = self.next_frame(size);
        let points = self.truth_points();
        self.count_estimate(&points);
        let present = self.present_uniform(size);
        let hud = self.hud_image(size)?;
        let Renderer::Gpu(g) = &mut self.renderer else {
            return Err(Error::Gpu {
                stage: "viewer window".into(),
                message: "a window needs the GPU renderer".into(),
            });
        };
        g.render(
            &frame,
            &present,
            changed,
            points.as_deref(),
            hud.as_ref(),
            target,
        )?;
        g.wait()?;
        self.finish_frame(&points, started, false)
    }

    /// Renders one frame of `size` and returns the picture (8-bit sRGB).
    pub fn render_image(&mut self, size: (u32, u32)) -> Result<RgbaImage> {
        let started = Instant::now();
        let (frame, changed) = self.next_frame(size);
        let points = self.truth_points();
        self.count_estimate(&points);
        let present_block = self.present_uniform(size);
        self.last_hud = None;
        let hud = self.hud_image(size)?;
        let image = match &mut self.renderer {
            Renderer::Gpu(g) => g.render_image(
                &frame,
                &present_block,
                changed,
                points.as_deref(),
                hud.as_ref(),
            )?,
            Renderer::Cpu(c) => {
                // The CPU passes read the maps' texels and the floor's grids where they are.
                let shadow = Shadows {
                    maps: &self.shadow.depth,
                    floor: &self.floor_shadows,
                };
                if changed {
                    let g = rasterize(&frame, &c.vertices, c.sphere);
                    c.shaded =
                        shade_split_sum(&frame, (&self.light, &self.floor), &c.lights, shadow, &g);
                    c.accum = vec![[0.0; 4]; c.shaded.len()];
                    c.gbuffer = Some(g);
                }
                if let (Some(p), Some(g)) = (&points, &c.gbuffer) {
                    shade_truth(&frame, &self.light, p, &c.lights, shadow, g, &mut c.accum);
                }
                let blank;
                let hud = match &hud {
                    Some(h) => h,
                    None => {
                        blank = RgbaImage::new(size.0, size.1);
                        &blank
                    }
                };
                present(&present_block, &c.heat, &c.shaded, &c.accum, hud)
            }
        };
        self.finish_frame(&points, started, true)?;
        Ok(image)
    }

    /// The last frame's split-sum (radiance, surface id) and truth accumulation (radiance
    /// × points, points) per pixel, before exposure and tone mapping.
    pub fn hdr(&mut self) -> Result<HdrFrame> {
        match &mut self.renderer {
            Renderer::Gpu(g) => g.read_hdr(),
            Renderer::Cpu(c) => Ok((c.shaded.clone(), c.accum.clone())),
        }
    }
}
