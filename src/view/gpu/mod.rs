//! The viewer's GPU renderer: the G-buffer raster pass (`shaders/view_gbuffer.wgsl`),
//! the split-sum and truth kernels (`view_split_sum.wgsl`, `view_truth.wgsl`) and the
//! present pass (`view_present.wgsl`) into a window's surface or an offscreen texture.
//! CPU twin: [`crate::view::cpu`] with [`crate::view::raster`]. Pipelines and buffers:
//! `pipelines`; reading frames back: `readback`.

use image::RgbaImage;

use crate::gpu::compute::{
    bind_group, buffer_with_data, storage_buffer, uniform_buffer, with_error_scope, ComputeKernel,
};
use crate::gpu::preview::{SplitSumUniform, TruthUniform};
use crate::gpu::shaders;
use crate::gpu::texture::{create_texture_2d, upload_bordered_cube, upload_lut_pairs};
use crate::view::frame::{heat_table, light_table, FrameUniform, PresentUniform, ViewLight};
use crate::view::model::{Model, Shape};
use crate::view::raster::{scene_vertices, sphere_box_vertices, Vertex};
use crate::view::scene::POINT_LIGHTS;
use crate::{Error, Result};

mod pipelines;
mod readback;

pub use pipelines::present_source;
use pipelines::{buffer, render_pipeline};

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
    truth_env_size: u32,
    hot_count: u32,
}

/// The per-size targets.
struct Targets {
    size: (u32, u32),
    position: wgpu::TextureView,
    normal: wgpu::TextureView,
    depth: wgpu::TextureView,
    shaded: wgpu::Buffer,
    accum: wgpu::Buffer,
    hud: wgpu::Texture,
}

/// The viewer's renderer on one device.
pub struct GpuRenderer {
    device: wgpu::Device,
    queue: wgpu::Queue,
    mesh_pipeline: wgpu::RenderPipeline,
    sphere_pipeline: wgpu::RenderPipeline,
    present_module: wgpu::ShaderModule,
    /// The present pass per target format, compiled on first use.
    present_pipelines: Vec<(wgpu::TextureFormat, wgpu::RenderPipeline)>,
    split_sum: ComputeKernel,
    truth: ComputeKernel,
    frame: wgpu::Buffer,
    present: wgpu::Buffer,
    truth_params: wgpu::Buffer,
    points: wgpu::Buffer,
    lights: wgpu::Buffer,
    heat: wgpu::Buffer,
    light: Option<LightTextures>,
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

impl GpuRenderer {
    /// Compiles the passes on `device`.
    pub fn new(device: wgpu::Device, queue: wgpu::Queue) -> Result<GpuRenderer> {
        let split_sum = ComputeKernel::new(
            &device,
            "view_split_sum",
            shaders::VIEW_SPLIT_SUM,
            WORKGROUP,
        )?;
        let truth = ComputeKernel::new(&device, "view_truth", shaders::VIEW_TRUTH, WORKGROUP)?;
        let (mesh_pipeline, sphere_pipeline, present_module) =
            with_error_scope(&device, "viewer pipelines", || {
                let gbuffer = device.create_shader_module(wgpu::ShaderModuleDescriptor {
                    label: Some("view_gbuffer"),
                    source: wgpu::ShaderSource::Wgsl(shaders::VIEW_GBUFFER.into()),
                });
                let layout = wgpu::VertexBufferLayout {
                    array_stride: std::mem::size_of::<Vertex>() as u64,
                    step_mode: wgpu::VertexStepMode::Vertex,
                    attributes: &wgpu::vertex_attr_array![0 => Float32x4, 1 => Float32x4],
                };
                let gtargets = [Some(GBUFFER_FORMAT.into()), Some(GBUFFER_FORMAT.into())];
                let mesh = render_pipeline(
                    &device,
                    &gbuffer,
                    "fs_mesh",
                    &gtargets,
                    &[Some(layout.clone())],
                    true,
                );
                let sphere = render_pipeline(
                    &device,
                    &gbuffer,
                    "fs_sphere",
                    &gtargets,
                    &[Some(layout)],
                    true,
                );
                let present = device.create_shader_module(wgpu::ShaderModuleDescriptor {
                    label: Some("view_present"),
                    source: wgpu::ShaderSource::Wgsl(present_source().into()),
                });
                (mesh, sphere, present)
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
        Ok(GpuRenderer {
            device,
            queue,
            mesh_pipeline,
            sphere_pipeline,
            present_module,
            present_pipelines: Vec::new(),
            split_sum,
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

    /// The present pass writing `format`.
    fn present_pipeline(&mut self, format: wgpu::TextureFormat) -> Result<()> {
        if !self.present_pipelines.iter().any(|(f, _)| *f == format) {
            let pipeline = with_error_scope(&self.device, "the viewer's present pass", || {
                render_pipeline(
                    &self.device,
                    &self.present_module,
                    "fs_main",
                    &[Some(format.into())],
                    &[],
                    false,
                )
            })?;
            self.present_pipelines.push((format, pipeline));
        }
        Ok(())
    }

    /// Uploads the baked light.
    pub fn set_light(&mut self, light: &ViewLight) -> Result<()> {
        let (device, queue) = (&self.device, &self.queue);
        let lut = upload_lut_pairs(device, queue, "view lut", &light.lut)?;
        let textures = with_error_scope(device, "uploading the viewer's light", || {
            let spec = &light.specular;
            let split_sum = SplitSumUniform {
                specular_size: spec.size,
                specular_levels: spec.levels.len() as u32,
                irradiance_size: light.irradiance.size,
                lut_width: light.lut.width,
                lut_height: light.lut.height,
                _pad0: 0,
                _pad1: 0,
                _pad2: 0,
            };
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
                split_sum: uniform_buffer(device, "view split-sum", &split_sum),
                truth_env_size: light.env.size,
                hot_count: light.hot.len() as u32,
            }
        })?;
        self.light = Some(textures);
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

    fn targets(&mut self, size: (u32, u32)) -> Result<&Targets> {
        if self.targets.as_ref().map(|t| t.size) != Some(size) {
            let device = &self.device;
            let texture = |label: &str, format: wgpu::TextureFormat, usage: wgpu::TextureUsages| {
                create_texture_2d(device, label, (size.0, size.1, 1), format, usage)
            };
            let pixels = size.0 as u64 * size.1 as u64;
            let gusage =
                wgpu::TextureUsages::RENDER_ATTACHMENT | wgpu::TextureUsages::TEXTURE_BINDING;
            let storage = wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_SRC;
            let targets = with_error_scope(device, "creating the viewer's targets", || Targets {
                size,
                position: texture("view position", GBUFFER_FORMAT, gusage)
                    .create_view(&Default::default()),
                normal: texture("view normal", GBUFFER_FORMAT, gusage)
                    .create_view(&Default::default()),
                depth: texture(
                    "view depth",
                    DEPTH_FORMAT,
                    wgpu::TextureUsages::RENDER_ATTACHMENT,
                )
                .create_view(&Default::default()),
                shaded: buffer(device, "view shaded", 16 * pixels, storage),
                accum: buffer(device, "view accum", 16 * pixels, storage),
                hud: texture(
                    "view hud",
                    wgpu::TextureFormat::Rgba8Unorm,
                    wgpu::TextureUsages::TEXTURE_BINDING | wgpu::TextureUsages::COPY_DST,
                ),
            })?;
            self.targets = Some(targets);
        }
        self.targets
            .as_ref()
            .ok_or_else(|| gpu_error("viewer targets", "missing"))
    }

    /// Records and submits one frame into `target`: the G-buffer and split-sum passes
    /// when `geometry_changed`, one truth estimate with `points` when given, then the
    /// present pass with `hud` (when given, a new HUD image) over it.
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
        self.present_pipeline(format)?;
        let present_pipeline = self
            .present_pipelines
            .iter()
            .find(|(f, _)| *f == format)
            .map(|(_, p)| p)
            .ok_or_else(|| gpu_error("viewer frame", "no present pass"))?;
        let (Some(light), Some((vertices, count)), Some(t)) =
            (&self.light, &self.vertices, &self.targets)
        else {
            return Err(gpu_error("viewer frame", "no light or model uploaded"));
        };
        let (device, queue) = (&self.device, &self.queue);
        with_error_scope(device, "viewer frame", || {
            queue.write_buffer(&self.frame, 0, bytemuck::bytes_of(frame));
            queue.write_buffer(&self.present, 0, bytemuck::bytes_of(present));
            if let Some(image) = hud {
                queue.write_texture(
                    wgpu::TexelCopyTextureInfo {
                        texture: &t.hud,
                        mip_level: 0,
                        origin: wgpu::Origin3d::ZERO,
                        aspect: wgpu::TextureAspect::All,
                    },
                    image.as_raw(),
                    wgpu::TexelCopyBufferLayout {
                        offset: 0,
                        bytes_per_row: Some(4 * size.0),
                        rows_per_image: Some(size.1),
                    },
                    t.hud.size(),
                );
            }
            let mut encoder = device.create_command_encoder(&Default::default());
            let bind = |pipeline: &wgpu::RenderPipeline, resources: &[wgpu::BindingResource]| {
                bind_group(device, None, &pipeline.get_bind_group_layout(0), resources)
            };
            if geometry_changed {
                let clear = wgpu::Operations {
                    load: wgpu::LoadOp::Clear(wgpu::Color::TRANSPARENT),
                    store: wgpu::StoreOp::Store,
                };
                let attachment = |view| {
                    Some(wgpu::RenderPassColorAttachment {
                        view,
                        resolve_target: None,
                        ops: clear,
                        depth_slice: None,
                    })
                };
                let mesh_group = bind(&self.mesh_pipeline, &[self.frame.as_entire_binding()]);
                let sphere_group = bind(&self.sphere_pipeline, &[self.frame.as_entire_binding()]);
                let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
                    label: Some("view gbuffer"),
                    color_attachments: &[attachment(&t.position), attachment(&t.normal)],
                    depth_stencil_attachment: Some(wgpu::RenderPassDepthStencilAttachment {
                        view: &t.depth,
                        depth_ops: Some(wgpu::Operations {
                            load: wgpu::LoadOp::Clear(1.0),
                            store: wgpu::StoreOp::Store,
                        }),
                        stencil_ops: None,
                    }),
                    timestamp_writes: None,
                    occlusion_query_set: None,
                    multiview_mask: None,
                });
                pass.set_pipeline(&self.mesh_pipeline);
                pass.set_bind_group(0, &mesh_group, &[]);
                pass.set_vertex_buffer(0, vertices.slice(..));
                pass.draw(0..*count, 0..1);
                if self.sphere {
                    pass.set_pipeline(&self.sphere_pipeline);
                    pass.set_bind_group(0, &sphere_group, &[]);
                    pass.set_vertex_buffer(0, self.sphere_box.slice(..));
                    pass.draw(0..36, 0..1);
                }
                drop(pass);
                self.split_sum.dispatch(
                    device,
                    &mut encoder,
                    &[
                        self.frame.as_entire_binding(),
                        light.split_sum.as_entire_binding(),
                        wgpu::BindingResource::TextureView(&light.specular),
                        wgpu::BindingResource::TextureView(&light.irradiance),
                        wgpu::BindingResource::TextureView(&light.lut),
                        self.lights.as_entire_binding(),
                        wgpu::BindingResource::TextureView(&t.position),
                        wgpu::BindingResource::TextureView(&t.normal),
                        t.shaded.as_entire_binding(),
                    ],
                    [size.0, size.1, 1],
                );
            }
            if let Some(points) = points {
                let n = points.len().min(MAX_TRUTH_POINTS as usize);
                queue.write_buffer(&self.points, 0, bytemuck::cast_slice(&points[..n]));
                let params = TruthUniform {
                    env_size: light.truth_env_size,
                    hot_count: light.hot_count,
                    point_count: n as u32,
                    _pad: 0,
                };
                queue.write_buffer(&self.truth_params, 0, bytemuck::bytes_of(&params));
                self.truth.dispatch(
                    device,
                    &mut encoder,
                    &[
                        self.frame.as_entire_binding(),
                        self.truth_params.as_entire_binding(),
                        wgpu::BindingResource::TextureView(&light.env),
                        wgpu::BindingResource::TextureView(&light.cold),
                        light.hot.as_entire_binding(),
                        self.points.as_entire_binding(),
                        self.lights.as_entire_binding(),
                        wgpu::BindingResource::TextureView(&t.position),
                        wgpu::BindingResource::TextureView(&t.normal),
                        t.accum.as_entire_binding(),
                    ],
                    [size.0, size.1, 1],
                );
            }
            let hud_view = t.hud.create_view(&Default::default());
            let group = bind(
                present_pipeline,
                &[
                    self.present.as_entire_binding(),
                    t.shaded.as_entire_binding(),
                    t.accum.as_entire_binding(),
                    self.heat.as_entire_binding(),
                    wgpu::BindingResource::TextureView(&hud_view),
                ],
            );
            let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
                label: Some("view present"),
                color_attachments: &[Some(wgpu::RenderPassColorAttachment {
                    view: target,
                    resolve_target: None,
                    ops: wgpu::Operations {
                        load: wgpu::LoadOp::Clear(wgpu::Color::BLACK),
                        store: wgpu::StoreOp::Store,
                    },
                    depth_slice: None,
                })],
                depth_stencil_attachment: None,
                timestamp_writes: None,
                occlusion_query_set: None,
                multiview_mask: None,
            });
            pass.set_pipeline(present_pipeline);
            pass.set_bind_group(0, &group, &[]);
            pass.draw(0..3, 0..1);
            drop(pass);
            queue.submit([encoder.finish()]);
        })
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
