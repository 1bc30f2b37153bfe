//! GPU BRDF LUT: binds `shaders/brdf_lut.wgsl` (CPU mirror: `cpu::brdf_lut`).

use crate::gpu::compute::{
    read_texture_level, storage_buffer, uniform_buffer, with_error_scope, ComputeKernel,
};
use crate::gpu::shaders;
use crate::gpu::texture::create_storage_texture_2d;
use crate::plan::lut::{BrdfLut, LutModel, LutQuadrature};
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
        let uniform = uniform_buffer(device, "lut params", &params);
        let rules = storage_buffer(device, "lut rules", &quad.nodes);
        let texture = create_storage_texture_2d(device, "brdf lut", width, height);
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
    Ok(BrdfLut::new(width, height, data))
}
