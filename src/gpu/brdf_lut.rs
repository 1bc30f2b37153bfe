//! GPU BRDF LUT: binds `shaders/brdf_lut.wgsl` (CPU mirror: `cpu::brdf_lut`).

use crate::gpu::compute::{buffer_with_data, read_texture_level, with_error_scope, ComputeKernel};
use crate::gpu::shaders;
use crate::lut::{BrdfLut, LutModel, LutQuadrature};
use crate::Result;

/// Workgroup of the LUT kernel (x = n·v, y = roughness).
pub const WORKGROUP: [u32; 3] = [8, 8, 1];

/// Computes a width×height LUT of `model` on the GPU.
pub fn brdf_lut(
    device: &wgpu::Device,
    queue: &wgpu::Queue,
    width: u32,
    height: u32,
    quad: &LutQuadrature,
    model: LutModel,
) -> Result<BrdfLut> {
    let kernel = ComputeKernel::new(device, "brdf_lut", shaders::BRDF_LUT, WORKGROUP)?;
    let texture = with_error_scope(device, "brdf_lut dispatch", || {
        let params = quad.params(width, height, model);
        let uniform = buffer_with_data(
            device,
            "lut params",
            bytemuck::bytes_of(&params),
            wgpu::BufferUsages::UNIFORM,
        );
        let rules = buffer_with_data(
            device,
            "lut rules",
            bytemuck::cast_slice(&quad.nodes),
            wgpu::BufferUsages::STORAGE,
        );
        let texture = device.create_texture(&wgpu::TextureDescriptor {
            label: Some("brdf lut"),
            size: wgpu::Extent3d {
                width,
                height,
                depth_or_array_layers: 1,
            },
            mip_level_count: 1,
            sample_count: 1,
            dimension: wgpu::TextureDimension::D2,
            format: wgpu::TextureFormat::Rgba32Float,
            usage: wgpu::TextureUsages::STORAGE_BINDING | wgpu::TextureUsages::COPY_SRC,
            view_formats: &[],
        });
        let view = texture.create_view(&Default::default());
        let mut encoder = device.create_command_encoder(&Default::default());
        kernel.dispatch(
            device,
            &mut encoder,
            &[
                uniform.as_entire_binding(),
                rules.as_entire_binding(),
                wgpu::BindingResource::TextureView(&view),
            ],
            [width, height, 1],
        );
        queue.submit([encoder.finish()]);
        texture
    })?;
    let rgba = read_texture_level(device, queue, &texture, 0)?;
    let data = rgba.chunks_exact(4).map(|t| [t[0], t[1]]).collect();
    Ok(BrdfLut {
        width,
        height,
        data,
    })
}
