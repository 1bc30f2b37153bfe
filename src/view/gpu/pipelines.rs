//! The viewer's render pipelines and buffers: the present pass's source with the Rust
//! constants it reads, and the helpers that create pipelines and buffers.

use crate::gpu::shaders;
use crate::math::color::{
    SRGB_ENCODED_LINEAR_MAX, SRGB_GAMMA, SRGB_LINEAR_MAX, SRGB_OFFSET, SRGB_SLOPE,
};
use crate::stages::preview::picture::{
    HEAT_BACKGROUND, LUMINANCE, PBR_NEUTRAL_DESATURATION, PBR_NEUTRAL_START_COMPRESSION,
};

use super::DEPTH_FORMAT;

/// The present pass's source: the Rust constants it needs, then `view_present.wgsl`.
pub fn present_source() -> String {
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
         const HEAT_BACKGROUND: vec3<f32> = vec3<f32>({:?}, {:?}, {:?});\n{}",
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
        shaders::VIEW_PRESENT_BODY
    )
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

pub(super) fn render_pipeline(
    device: &wgpu::Device,
    module: &wgpu::ShaderModule,
    fragment: &str,
    targets: &[Option<wgpu::ColorTargetState>],
    vertex_buffers: &[Option<wgpu::VertexBufferLayout>],
    depth: bool,
) -> wgpu::RenderPipeline {
    device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
        label: Some(fragment),
        layout: None,
        vertex: wgpu::VertexState {
            module,
            entry_point: Some("vs_main"),
            compilation_options: Default::default(),
            buffers: vertex_buffers,
        },
        primitive: wgpu::PrimitiveState::default(),
        depth_stencil: depth.then(|| wgpu::DepthStencilState {
            format: DEPTH_FORMAT,
            depth_write_enabled: Some(true),
            depth_compare: Some(wgpu::CompareFunction::Less),
            stencil: Default::default(),
            bias: Default::default(),
        }),
        multisample: Default::default(),
        fragment: Some(wgpu::FragmentState {
            module,
            entry_point: Some(fragment),
            compilation_options: Default::default(),
            targets,
        }),
        multiview_mask: None,
        cache: None,
    })
}
