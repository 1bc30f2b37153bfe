//! The viewer's render pipelines and buffers: the display passes' sources (present and
//! forward) with the Rust constants they read, the display passes compiled per target
//! format and the forward pass's surfaces per format and light counts, and the helpers
//! that create pipelines and buffers.

use crate::gpu::shaders;
use crate::math::color::{
    SRGB_ENCODED_LINEAR_MAX, SRGB_GAMMA, SRGB_LINEAR_MAX, SRGB_OFFSET, SRGB_SLOPE,
};
use crate::stages::preview::picture::{
    HEAT_BACKGROUND, LUMINANCE, PBR_NEUTRAL_DESATURATION, PBR_NEUTRAL_START_COMPRESSION,
};

use crate::view::frame::FrameUniform;
use crate::view::raster::Vertex;

use super::DEPTH_FORMAT;

/// A [`Vertex`]: (position, surface id) and (normal, 0).
const VERTEX_ATTRIBUTES: [wgpu::VertexAttribute; 2] =
    wgpu::vertex_attr_array![0 => Float32x4, 1 => Float32x4];

/// The vertex buffer layout of the model, floor and sphere-box draws.
pub(super) fn vertex_layout() -> wgpu::VertexBufferLayout<'static> {
    wgpu::VertexBufferLayout {
        array_stride: std::mem::size_of::<Vertex>() as u64,
        step_mode: wgpu::VertexStepMode::Vertex,
        attributes: &VERTEX_ATTRIBUTES,
    }
}

/// The WGSL constants the display passes read (`common/view_display.wgsl` and the present
/// pass's heat map), written from the Rust ones so none is typed twice.
fn display_constants() -> String {
    let bg = HEAT_BACKGROUND.0.map(|v| v as f32 / 255.0);
    format!(
        "const PBR_NEUTRAL_START_COMPRESSION: f32 = {:?};\n\
         const PBR_NEUTRAL_DESATURATION: f32 = {:?};\n\
         const SRGB_LINEAR_MAX: f32 = {:?};\n\
         const SRGB_ENCODED_LINEAR_MAX: f32 = {:?};\n\
         const SRGB_SLOPE: f32 = {:?};\n\
         const SRGB_OFFSET: f32 = {:?};\n\
         const SRGB_GAMMA: f32 = {:?};\n\
         const LUMINANCE: vec3<f32> = vec3<f32>({:?}, {:?}, {:?});\n\
         const HEAT_BACKGROUND: vec3<f32> = vec3<f32>({:?}, {:?}, {:?});\n",
        PBR_NEUTRAL_START_COMPRESSION,
        PBR_NEUTRAL_DESATURATION,
        SRGB_LINEAR_MAX,
        SRGB_ENCODED_LINEAR_MAX,
        SRGB_SLOPE,
        SRGB_OFFSET,
        SRGB_GAMMA,
        LUMINANCE[0],
        LUMINANCE[1],
        LUMINANCE[2],
        bg[0],
        bg[1],
        bg[2],
    )
}

/// The display passes for one target format: the present pass and the forward pass's
/// background.
pub(super) struct DisplayPipelines {
    pub(super) format: wgpu::TextureFormat,
    pub(super) present: wgpu::RenderPipeline,
    pub(super) background: wgpu::RenderPipeline,
}

/// What the forward pass's surface pipelines are compiled for: the target's format and the
/// frame's light counts, which are constants of the shader (`POINT_LIGHTS`, `SUN_LIGHTS`
/// in `shaders/view_forward.wgsl`), so that its light loops are unrolled or gone: a
/// software rasteriser pays for a loop even when it runs zero times (docs/accuracy.md,
/// "The viewer").
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) struct ForwardKey {
    pub(super) format: wgpu::TextureFormat,
    /// `FrameUniform::light_count`.
    pub(super) point_lights: u32,
    /// `FrameUniform::sun[0]`.
    pub(super) sun_lights: u32,
    /// 1 when an area light is among them (`AREA_LIGHTS` in `common/view_sun.wgsl`).
    pub(super) area_lights: u32,
}

impl ForwardKey {
    pub(super) fn of(
        frame: &FrameUniform,
        format: wgpu::TextureFormat,
        area_lights: u32,
    ) -> ForwardKey {
        ForwardKey {
            format,
            point_lights: frame.light_count,
            sun_lights: frame.sun[0],
            area_lights,
        }
    }
}

/// The forward pass's object and floor pipelines for one [`ForwardKey`].
pub(super) struct ForwardPipelines {
    pub(super) key: ForwardKey,
    /// The object shaded from its G-buffer: one triangle over the frame, drawn where a
    /// surface left its depth.
    pub(super) object: wgpu::RenderPipeline,
    /// The floor shaded from its caches.
    pub(super) floor: wgpu::RenderPipeline,
}

impl DisplayPipelines {
    /// The present pass (`present`'s module) and the forward pass's background (`forward`'s)
    /// writing `format`.
    pub(super) fn new(
        device: &wgpu::Device,
        (present, forward): (&wgpu::ShaderModule, &wgpu::ShaderModule),
        format: wgpu::TextureFormat,
    ) -> DisplayPipelines {
        let targets = [Some(format.into())];
        let constants = [target_constant(format)];
        DisplayPipelines {
            format,
            present: render_pipeline(
                device,
                present,
                ("vs_main", "fs_main"),
                &targets,
                &[],
                Depth::None,
                &constants,
            ),
            background: render_pipeline(
                device,
                forward,
                ("vs_background", "fs_background"),
                &targets,
                &[],
                Depth::Behind,
                &constants,
            ),
        }
    }
}

impl ForwardPipelines {
    /// The forward pass's object and floor pipelines (`forward`'s module) for `key`.
    pub(super) fn new(
        device: &wgpu::Device,
        forward: &wgpu::ShaderModule,
        key: ForwardKey,
    ) -> ForwardPipelines {
        let targets = [Some(key.format.into())];
        let constants = [
            ("POINT_LIGHTS", key.point_lights as f64),
            ("SUN_LIGHTS", key.sun_lights as f64),
            ("AREA_LIGHTS", key.area_lights as f64),
            target_constant(key.format),
        ];
        ForwardPipelines {
            key,
            object: render_pipeline(
                device,
                forward,
                ("vs_background", "fs_object"),
                &targets,
                &[],
                Depth::Covered,
                &constants,
            ),
            floor: render_pipeline(
                device,
                forward,
                ("vs_main", "fs_floor"),
                &targets,
                &[Some(vertex_layout())],
                Depth::Nearest,
                &constants,
            ),
        }
    }
}

/// The display's constant for a target of `format`: whether it stores sRGB itself
/// (`TARGET_IS_SRGB` in `shaders/common/view_display.wgsl`).
fn target_constant(format: wgpu::TextureFormat) -> (&'static str, f64) {
    ("TARGET_IS_SRGB", u32::from(format.is_srgb()) as f64)
}

/// The present pass's source: the Rust constants it needs, then `view_present.wgsl`.
pub fn present_source() -> String {
    display_constants() + shaders::VIEW_PRESENT_BODY
}

/// The forward pass's source: the Rust constants it needs, then `view_forward.wgsl`.
pub fn forward_source() -> String {
    display_constants() + shaders::VIEW_FORWARD_BODY
}

pub(super) fn buffer(
    device: &wgpu::Device,
    label: &str,
    size: u64,
    usage: wgpu::BufferUsages,
) -> wgpu::Buffer {
    device.create_buffer(&wgpu::BufferDescriptor {
        label: Some(label),
        size,
        usage,
        mapped_at_creation: false,
    })
}

/// How a pass uses the depth buffer.
#[derive(Clone, Copy)]
pub(super) enum Depth {
    /// No depth buffer.
    None,
    /// Nearest wins: tested (less) and written.
    Nearest,
    /// Drawn where nothing nearer is (less or equal), not written: the forward pass's
    /// background on the far plane.
    Behind,
    /// Drawn where a surface left its depth (the stored depth nearer than the fragment's
    /// on the far plane), not written: the forward pass's object from its G-buffer.
    Covered,
}

fn depth_state(write: bool, compare: wgpu::CompareFunction) -> wgpu::DepthStencilState {
    wgpu::DepthStencilState {
        format: DEPTH_FORMAT,
        depth_write_enabled: Some(write),
        depth_compare: Some(compare),
        stencil: Default::default(),
        bias: Default::default(),
    }
}

/// A render pipeline of `module`'s `vertex` and `fragment` entry points, the fragment
/// stage's pipeline-overridable `constants` set (by name).
pub(super) fn render_pipeline(
    device: &wgpu::Device,
    module: &wgpu::ShaderModule,
    (vertex, fragment): (&str, &str),
    targets: &[Option<wgpu::ColorTargetState>],
    vertex_buffers: &[Option<wgpu::VertexBufferLayout>],
    depth: Depth,
    constants: &[(&str, f64)],
) -> wgpu::RenderPipeline {
    device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
        label: Some(fragment),
        layout: None,
        vertex: wgpu::VertexState {
            module,
            entry_point: Some(vertex),
            compilation_options: Default::default(),
            buffers: vertex_buffers,
        },
        primitive: wgpu::PrimitiveState::default(),
        depth_stencil: match depth {
            Depth::None => None,
            Depth::Nearest => Some(depth_state(true, wgpu::CompareFunction::Less)),
            Depth::Behind => Some(depth_state(false, wgpu::CompareFunction::LessEqual)),
            Depth::Covered => Some(depth_state(false, wgpu::CompareFunction::Greater)),
        },
        multisample: Default::default(),
        fragment: Some(wgpu::FragmentState {
            module,
            entry_point: Some(fragment),
            compilation_options: wgpu::PipelineCompilationOptions {
                constants,
                ..Default::default()
            },
            targets,
        }),
        multiview_mask: None,
        cache: None,
    })
}
