//! The viewer's GPU renderer, two paths to one picture:
//!
//! - **forward** (the split-sum view while it changes, as when the camera moves): the
//!   object's G-buffer (the G-buffer pass's pipelines, the object alone), then one render
//!   pass (`shaders/view_forward.wgsl`) shades each object pixel from it, each floor
//!   fragment from the floor's caches (`view::floor`, `view::floor_shadow`, read through
//!   the sampler as textures, `caches`), then the
//!   background, and writes the displayed colour with the HUD over it;
//! - **deferred** (the truth and heat views, the HDR a test reads back, and a split-sum
//!   view standing still): the G-buffer raster pass (`view_gbuffer.wgsl`), the split-sum
//!   and truth kernels (`view_split_sum.wgsl`, `view_truth.wgsl`) into per-pixel buffers,
//!   and the present pass (`view_present.wgsl`), which alone redraws a still view.
//!
//! Both call the same WGSL functions on the same surface. The forward path skips writing
//! and reading the per-pixel buffers of the floor and the sky, which on a software
//! rasteriser cost more than their shading. It is compiled for the frame's light counts (`ForwardKey` in `pipelines`),
//! and it reads the chains through the sampler's bilinear filter: one `textureSampleLevel`
//! where the deferred kernels fetch four texels, the same texels and weights up to the
//! hardware's sub-texel precision. Together these take a third off its frame on lavapipe
//! (docs/accuracy.md, "The viewer"). The deferred path is the exact one: CPU twin
//! [`crate::view::cpu`] with [`crate::view::raster`]. Pipelines and buffers:
//! `pipelines`; the per-size targets: `targets`; the light's and the floor's uploads:
//! `caches`; reading frames back: `readback`.

use image::RgbaImage;

use crate::gpu::compute::{
    buffer_with_data, storage_buffer, uniform_buffer, with_error_scope, ComputeKernel,
};
use crate::gpu::preview::{SplitSumUniform, TruthUniform};
use crate::gpu::shaders;
use crate::gpu::texture::{upload_bordered_cube, upload_lut_pairs};
use crate::view::floor::FloorTable;
use crate::view::floor_shadow::FloorShadows;
use crate::view::frame::{heat_table, light_table, FrameUniform, Mode, PresentUniform, ViewLight};
use crate::view::model::{Model, Shape};
use crate::view::raster::{scene_vertices, sphere_box_vertices};
use crate::view::scene::POINT_LIGHTS;
use crate::view::shadow::{ShadowMaps, EMPTY_DEPTH};
use crate::{Error, Result};

mod caches;
mod passes;
mod pipelines;
mod readback;
mod targets;

use caches::{
    floor_buffer, floor_shadow_buffer, floor_shadow_texture, floor_table_texture, shadow_texture,
};
use pipelines::{
    buffer, render_pipeline, vertex_layout, Depth, DisplayPipelines, ForwardKey, ForwardPipelines,
};
pub use pipelines::{forward_source, present_source};
use targets::Targets;

/// Workgroup of the shading kernels.
const WORKGROUP: [u32; 3] = [8, 8, 1];
/// Most quadrature points one truth estimate uses.
pub const MAX_TRUTH_POINTS: u32 = 256;
/// The G-buffer's formats: (position, id) and (normal, 0) in full floats, depth.
const GBUFFER_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba32Float;
const DEPTH_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Depth32Float;

/// The baked light on the device.
struct LightTextures {
    specular: wgpu::TextureView,
    irradiance: wgpu::TextureView,
    lut: wgpu::TextureView,
    env: wgpu::TextureView,
    cold: wgpu::TextureView,
    hot: wgpu::Buffer,
    split_sum: wgpu::Buffer,
    /// `ViewLight::sun_texels` (one zero entry when there are none: a binding is never
    /// empty).
    sun_texels: wgpu::Buffer,
    truth_env_size: u32,
    hot_count: u32,
}

/// The viewer's renderer on one device.
pub struct GpuRenderer {
    device: wgpu::Device,
    queue: wgpu::Queue,
    /// The forward pass's sampler (bilinear, clamped to the edge) of the light's chains.
    cube_linear: wgpu::Sampler,
    mesh_pipeline: wgpu::RenderPipeline,
    sphere_pipeline: wgpu::RenderPipeline,
    present_module: wgpu::ShaderModule,
    forward_module: wgpu::ShaderModule,
    /// The display passes per target format, compiled on first use.
    display_pipelines: Vec<DisplayPipelines>,
    /// The forward pass's surface pipelines per key, compiled on first use (a key the
    /// viewer's toggles come back to is not compiled again).
    forward_pipelines: Vec<ForwardPipelines>,
    /// Whether the split-sum view is drawn by the forward pass (else by the deferred one).
    forward: bool,
    /// Whether the G-buffer and the split-sum buffer hold the last frame drawn.
    deferred_current: bool,
    split_sum: ComputeKernel,
    /// Whether `split_sum`, `truth` and the forward pipelines shade area lights (`AREA_LIGHTS`):
    /// 1 when the light shown has one.
    area_lights: u32,
    truth: ComputeKernel,
    frame: wgpu::Buffer,
    present: wgpu::Buffer,
    truth_params: wgpu::Buffer,
    points: wgpu::Buffer,
    lights: wgpu::Buffer,
    heat: wgpu::Buffer,
    light: Option<LightTextures>,
    /// The lights' shadow maps, a layer each (one 1 × 1 empty layer until maps are set).
    shadow: wgpu::TextureView,
    /// The floor's table (`view::floor`; a table of zeros until one is set).
    floor: wgpu::Buffer,
    /// The shadow maps' grids on the floor (`view::floor_shadow`; none until set).
    floor_shadow: wgpu::Buffer,
    /// The table as a texture, which the forward pass reads through the sampler
    /// (`floor_table_texture`; uploaded only where the forward pass can draw, a 2 × 2
    /// table of zeros elsewhere).
    floor_table_texels: wgpu::TextureView,
    /// The grid as a texture, as `floor_table_texels` (`floor_shadow_texture`).
    floor_shadow_texels: wgpu::TextureView,
    /// The forward pass's sampler of the floor's table: bilinear, repeating across its
    /// columns (the azimuth), clamped across its rows.
    floor_repeat: wgpu::Sampler,
    vertices: Option<(wgpu::Buffer, u32)>,
    sphere_box: wgpu::Buffer,
    sphere: bool,
    targets: Option<Targets>,
}

fn gpu_error(stage: &str, message: impl Into<String>) -> Error {
    Error::Gpu {
        stage: stage.into(),
        message: message.into(),
    }
}

/// A shading kernel of the viewer (`label`, `source`), compiled with or without area
/// lights (`AREA_LIGHTS`: their LTC shading and soft shadows).
fn shading_kernel(
    device: &wgpu::Device,
    (label, source): (&'static str, &str),
    area_lights: u32,
) -> Result<ComputeKernel> {
    ComputeKernel::with_constants(
        device,
        label,
        source,
        WORKGROUP,
        &[("AREA_LIGHTS", area_lights as f64)],
    )
}

/// The deferred split-sum kernel and the truth kernel.
const SPLIT_SUM_KERNEL: (&str, &str) = ("view_split_sum", shaders::VIEW_SPLIT_SUM);
const TRUTH_KERNEL: (&str, &str) = ("view_truth", shaders::VIEW_TRUTH);

impl GpuRenderer {
    /// Compiles the passes on `device`.
    pub fn new(device: wgpu::Device, queue: wgpu::Queue) -> Result<GpuRenderer> {
        let split_sum = shading_kernel(&device, SPLIT_SUM_KERNEL, 0)?;
        let truth = shading_kernel(&device, TRUTH_KERNEL, 0)?;
        let (mesh_pipeline, sphere_pipeline, present_module, forward_module) =
            with_error_scope(&device, "viewer pipelines", || {
                let gbuffer = device.create_shader_module(wgpu::ShaderModuleDescriptor {
                    label: Some("view_gbuffer"),
                    source: wgpu::ShaderSource::Wgsl(shaders::VIEW_GBUFFER.into()),
                });
                let layout = vertex_layout();
                let gtargets = [Some(GBUFFER_FORMAT.into()), Some(GBUFFER_FORMAT.into())];
                let mesh = render_pipeline(
                    &device,
                    &gbuffer,
                    ("vs_main", "fs_mesh"),
                    &gtargets,
                    &[Some(layout.clone())],
                    Depth::Nearest,
                    &[],
                );
                let sphere = render_pipeline(
                    &device,
                    &gbuffer,
                    ("vs_main", "fs_sphere"),
                    &gtargets,
                    &[Some(layout)],
                    Depth::Nearest,
                    &[],
                );
                let present = device.create_shader_module(wgpu::ShaderModuleDescriptor {
                    label: Some("view_present"),
                    source: wgpu::ShaderSource::Wgsl(present_source().into()),
                });
                let forward = device.create_shader_module(wgpu::ShaderModuleDescriptor {
                    label: Some("view_forward"),
                    source: wgpu::ShaderSource::Wgsl(forward_source().into()),
                });
                (mesh, sphere, present, forward)
            })?;
        let uniform = wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST;
        let storage = wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_DST;
        let frame = buffer(
            &device,
            "view frame",
            std::mem::size_of::<FrameUniform>() as u64,
            uniform,
        );
        let present = buffer(
            &device,
            "view present",
            std::mem::size_of::<PresentUniform>() as u64,
            uniform,
        );
        let truth_params = buffer(
            &device,
            "view truth",
            std::mem::size_of::<TruthUniform>() as u64,
            uniform,
        );
        let points = buffer(
            &device,
            "view points",
            16 * MAX_TRUTH_POINTS as u64,
            storage,
        );
        let lights = storage_buffer(&device, "view lights", &light_table(&POINT_LIGHTS));
        let heat = storage_buffer(&device, "view heat table", &heat_table());
        let sphere_box = buffer_with_data(
            &device,
            "view sphere box",
            bytemuck::cast_slice(&sphere_box_vertices()),
            wgpu::BufferUsages::VERTEX,
        );
        let shadow = shadow_texture(&device, &queue, (1, 1), &[EMPTY_DEPTH])?;
        let (table, grid) = (
            FloorTable::empty(),
            FloorShadows::new(&ShadowMaps::default()),
        );
        let floor = floor_buffer(&device, &table);
        let floor_shadow = floor_shadow_buffer(&device, &grid);
        let floor_table_texels = floor_table_texture(&device, &queue, &table)?;
        let floor_shadow_texels = floor_shadow_texture(&device, &queue, &grid)?;
        let floor_repeat = device.create_sampler(&wgpu::SamplerDescriptor {
            label: Some("view floor table, bilinear, repeating across columns"),
            address_mode_u: wgpu::AddressMode::Repeat,
            mag_filter: wgpu::FilterMode::Linear,
            min_filter: wgpu::FilterMode::Linear,
            ..Default::default()
        });
        let cube_linear = device.create_sampler(&wgpu::SamplerDescriptor {
            label: Some("view chains, bilinear"),
            mag_filter: wgpu::FilterMode::Linear,
            min_filter: wgpu::FilterMode::Linear,
            ..Default::default()
        });
        Ok(GpuRenderer {
            shadow,
            floor,
            floor_shadow,
            floor_table_texels,
            floor_shadow_texels,
            floor_repeat,
            cube_linear,
            device,
            queue,
            mesh_pipeline,
            sphere_pipeline,
            present_module,
            forward_module,
            display_pipelines: Vec::new(),
            forward_pipelines: Vec::new(),
            forward: true,
            deferred_current: false,
            split_sum,
            area_lights: 0,
            truth,
            frame,
            present,
            truth_params,
            points,
            lights,
            heat,
            light: None,
            vertices: None,
            sphere_box,
            sphere: false,
            targets: None,
        })
    }

    /// Compiles the display passes writing `format` unless they are.
    fn display_pipelines(&mut self, format: wgpu::TextureFormat) -> Result<()> {
        if !self.display_pipelines.iter().any(|p| p.format == format) {
            let (device, present, forward) =
                (&self.device, &self.present_module, &self.forward_module);
            let pipelines = with_error_scope(device, "the viewer's display passes", || {
                DisplayPipelines::new(device, (present, forward), format)
            })?;
            self.display_pipelines.push(pipelines);
        }
        Ok(())
    }

    /// The display passes compiled for `format` (by `display_pipelines`).
    fn compiled_display(&self, format: wgpu::TextureFormat) -> Result<&DisplayPipelines> {
        self.display_pipelines
            .iter()
            .find(|p| p.format == format)
            .ok_or_else(|| gpu_error("viewer frame", "no display passes"))
    }

    /// Compiles the forward pass's surface pipelines for `key` unless they are.
    fn forward_pipelines(&mut self, key: ForwardKey) -> Result<()> {
        if !self.forward_pipelines.iter().any(|p| p.key == key) {
            let (device, forward) = (&self.device, &self.forward_module);
            let pipelines = with_error_scope(device, "the viewer's forward pass", || {
                ForwardPipelines::new(device, forward, key)
            })?;
            self.forward_pipelines.push(pipelines);
        }
        Ok(())
    }

    /// The forward pass's surface pipelines compiled for `key` (by `forward_pipelines`).
    fn compiled_forward(&self, key: ForwardKey) -> Result<&ForwardPipelines> {
        self.forward_pipelines
            .iter()
            .find(|p| p.key == key)
            .ok_or_else(|| gpu_error("viewer frame", "no forward pipelines"))
    }

    /// Whether the split-sum view is drawn by the forward pass while it changes (the
    /// default, on a device that filters rgba32float textures) or always by the deferred
    /// passes, which give the same picture (a test compares them).
    pub fn set_forward(&mut self, forward: bool) {
        self.forward = forward;
    }

    /// Whether the split-sum view is drawn by the forward pass while it changes: asked
    /// for ([`GpuRenderer::set_forward`]) and possible on this device, which must filter
    /// rgba32float textures (`FLOAT32_FILTERABLE`; without it every frame is drawn by the
    /// deferred passes).
    pub fn draws_forward(&self) -> bool {
        self.forward && self.can_draw_forward()
    }

    /// Whether this device can draw the forward pass at all (it filters rgba32float
    /// textures): where it cannot, the floor's caches are not uploaded as textures.
    fn can_draw_forward(&self) -> bool {
        self.device
            .features()
            .contains(wgpu::Features::FLOAT32_FILTERABLE)
    }

    /// Uploads the baked light.
    pub fn set_light(&mut self, light: &ViewLight) -> Result<()> {
        let (device, queue) = (&self.device, &self.queue);
        let lut = upload_lut_pairs(device, queue, "view lut", &light.lut)?;
        let textures = with_error_scope(device, "uploading the viewer's light", || {
            let spec = &light.specular;
            // The viewer shades as the README's recipe (`ViewLight::split_sum`).
            let split_sum = SplitSumUniform::new(&light.split_sum(), spec.levels.len() as u32);
            LightTextures {
                specular: upload_bordered_cube(
                    device,
                    queue,
                    "view specular",
                    spec,
                    spec.levels.len(),
                ),
                // The kernels read level 0 of these.
                irradiance: upload_bordered_cube(
                    device,
                    queue,
                    "view irradiance",
                    &light.irradiance,
                    1,
                ),
                lut: lut.create_view(&Default::default()),
                env: upload_bordered_cube(device, queue, "view environment", &light.env, 1),
                cold: upload_bordered_cube(device, queue, "view cold texels", &light.cold, 1),
                hot: storage_buffer(device, "view hot texels", &light.hot),
                sun_texels: storage_buffer(
                    device,
                    "view sun texels",
                    if light.sun_texels.is_empty() {
                        &[[0.0; 4]; 2]
                    } else {
                        &light.sun_texels[..]
                    },
                ),
                split_sum: uniform_buffer(device, "view split-sum", &split_sum),
                truth_env_size: light.env.size,
                hot_count: light.hot.len() as u32,
            }
        })?;
        self.light = Some(textures);
        let area_lights = u32::from(light.has_area_lights());
        if area_lights != self.area_lights {
            self.split_sum = shading_kernel(&self.device, SPLIT_SUM_KERNEL, area_lights)?;
            self.truth = shading_kernel(&self.device, TRUTH_KERNEL, area_lights)?;
            self.area_lights = area_lights;
        }
        Ok(())
    }

    /// Uploads the lights' shadow maps and their grids on the floor (none: one empty layer;
    /// the frame's `sun` says how many the kernels read).
    pub fn set_shadow(&mut self, maps: &ShadowMaps, floor: &FloorShadows) -> Result<()> {
        self.floor_shadow =
            with_error_scope(&self.device, "uploading the floor's shadows", || {
                floor_shadow_buffer(&self.device, floor)
            })?;
        if self.can_draw_forward() {
            self.floor_shadow_texels = floor_shadow_texture(&self.device, &self.queue, floor)?;
        }
        self.shadow = if maps.is_empty() {
            shadow_texture(&self.device, &self.queue, (1, 1), &[EMPTY_DEPTH])?
        } else {
            shadow_texture(
                &self.device,
                &self.queue,
                (maps.size, maps.len() as u32),
                &maps.depth,
            )?
        };
        Ok(())
    }

    /// Uploads the floor's table.
    pub fn set_floor(&mut self, table: &FloorTable) -> Result<()> {
        self.floor = with_error_scope(&self.device, "uploading the floor's table", || {
            floor_buffer(&self.device, table)
        })?;
        if self.can_draw_forward() {
            self.floor_table_texels = floor_table_texture(&self.device, &self.queue, table)?;
        }
        Ok(())
    }

    /// Uploads a model's triangles (and the floor's).
    pub fn set_model(&mut self, model: &Model) -> Result<()> {
        let vertices = scene_vertices(model);
        let buffer = with_error_scope(&self.device, "uploading the model", || {
            buffer_with_data(
                &self.device,
                "view vertices",
                bytemuck::cast_slice(&vertices),
                wgpu::BufferUsages::VERTEX,
            )
        })?;
        self.vertices = Some((buffer, vertices.len() as u32));
        self.sphere = matches!(model.shape, Shape::Sphere);
        Ok(())
    }

    /// Records and submits one frame into `target`: the forward pass in the split-sum view
    /// when `geometry_changed` (and [`GpuRenderer::set_forward`] left it on); else the
    /// G-buffer and split-sum passes when `geometry_changed` or the buffers hold an older
    /// frame, one truth estimate with `points` when given, then the present pass. `hud`,
    /// when given, is a new HUD image to lay over the frame.
    pub fn render(
        &mut self,
        frame: &FrameUniform,
        present: &PresentUniform,
        geometry_changed: bool,
        points: Option<&[[f32; 4]]>,
        hud: Option<&RgbaImage>,
        (target, format): (&wgpu::TextureView, wgpu::TextureFormat),
    ) -> Result<()> {
        let size = (frame.width, frame.height);
        self.targets(size)?;
        self.display_pipelines(format)?;
        // The split-sum view is drawn by the forward pass while the view changes; once it
        // stands still, the deferred passes draw it once more, and the frames after that
        // are the present pass alone (the same picture for less work).
        let split_sum_view = points.is_none() && present.mode == Mode::SplitSum as u32;
        let forward = self.draws_forward() && split_sum_view && geometry_changed;
        let deferred = !forward && (geometry_changed || !self.deferred_current);
        let forward_key = ForwardKey::of(frame, format, self.area_lights);
        if forward {
            self.forward_pipelines(forward_key)?;
        }
        with_error_scope(&self.device, "viewer frame", || -> Result<()> {
            self.queue
                .write_buffer(&self.frame, 0, bytemuck::bytes_of(frame));
            self.queue
                .write_buffer(&self.present, 0, bytemuck::bytes_of(present));
            if let Some(image) = hud {
                self.upload_hud(image, size);
            }
            let mut encoder = self.device.create_command_encoder(&Default::default());
            if forward {
                self.encode_forward(&mut encoder, (target, forward_key))?;
            } else {
                if deferred {
                    self.encode_deferred_split_sum(&mut encoder)?;
                }
                if let Some(points) = points {
                    self.encode_truth(&mut encoder, points)?;
                }
                self.encode_present(&mut encoder, (target, format))?;
            }
            self.queue.submit([encoder.finish()]);
            Ok(())
        })??;
        if forward {
            self.deferred_current = false;
        } else if deferred {
            self.deferred_current = true;
        }
        Ok(())
    }

    /// Brings the G-buffer and the split-sum buffer up to the last frame drawn (the
    /// forward pass writes neither), for a readback.
    pub(super) fn update_deferred(&mut self) -> Result<()> {
        if !self.deferred_current {
            with_error_scope(&self.device, "viewer frame", || -> Result<()> {
                let mut encoder = self.device.create_command_encoder(&Default::default());
                self.encode_deferred_split_sum(&mut encoder)?;
                self.queue.submit([encoder.finish()]);
                Ok(())
            })??;
            self.deferred_current = true;
        }
        Ok(())
    }

    /// Waits for the submitted work (so a frame's time is measured, and a lost device
    /// is noticed).
    pub fn wait(&self) -> Result<()> {
        self.device
            .poll(wgpu::PollType::wait_indefinitely())
            .map(|_| ())
            .map_err(|e| gpu_error("viewer frame", e.to_string()))
    }
}
