//! GPU equirect → cube with mips: binds `shaders/equirect_to_cube.wgsl` for level 0 and
//! `shaders/cube_downsample.wgsl` for each further level (CPU mirrors in `cpu/`).

use crate::cpu::equirect_to_cube::EquirectToCubeParams;
use crate::environment::{Cubemap, EquirectPyramid};
use crate::gpu::compute::{buffer_with_data, with_error_scope, ComputeKernel};
use crate::gpu::shaders;
use crate::gpu::texture::{
    create_cube_texture, cube_mip_view, read_cubemap, upload_equirect_pyramid,
};
use crate::Result;

/// Workgroup of both kernels (x, y over the face, z = face).
pub const WORKGROUP: [u32; 3] = [8, 8, 1];

/// Uniform block of `shaders/equirect_to_cube.wgsl` (layout checked in tests/shaders.rs).
#[repr(C)]
#[derive(Clone, Copy, Debug, bytemuck::Pod, bytemuck::Zeroable)]
pub struct EquirectToCubeUniform {
    /// Output face edge.
    pub face_size: u32,
    /// Sub-texel samples per axis.
    pub samples_per_axis: u32,
    /// Pyramid level held in mip 0 of the source texture.
    pub base_level: u32,
    /// Pyramid levels in all.
    pub level_count: u32,
    /// Size of pyramid level 0.
    pub source_size: [u32; 2],
    /// cos, sin of the rotation about +Y.
    pub rotation: [f32; 2],
}

/// Records the mip chain of `texture` (levels 1..) with the 2×2 solid-angle reduction.
pub fn record_cube_mips(
    device: &wgpu::Device,
    encoder: &mut wgpu::CommandEncoder,
    texture: &wgpu::Texture,
) -> Result<()> {
    let kernel = ComputeKernel::new(
        device,
        "cube_downsample",
        shaders::CUBE_DOWNSAMPLE,
        WORKGROUP,
    )?;
    for mip in 1..texture.mip_level_count() {
        let n = (texture.width() >> mip).max(1);
        let child = cube_mip_view(texture, mip - 1);
        let out = cube_mip_view(texture, mip);
        kernel.dispatch(
            device,
            encoder,
            &[
                wgpu::BindingResource::TextureView(&child),
                wgpu::BindingResource::TextureView(&out),
            ],
            [n, n, 6],
        );
    }
    Ok(())
}

/// Converts the pyramid to a cube of `params.face_size` with `mips` levels.
pub fn equirect_to_cube(
    device: &wgpu::Device,
    queue: &wgpu::Queue,
    pyramid: &EquirectPyramid,
    params: &EquirectToCubeParams,
    mips: u32,
) -> Result<Cubemap> {
    let kernel = ComputeKernel::new(
        device,
        "equirect_to_cube",
        shaders::EQUIRECT_TO_CUBE,
        WORKGROUP,
    )?;
    let (source, base_level) = upload_equirect_pyramid(device, queue, pyramid)?;
    let n = params.face_size;
    let mips = mips.clamp(1, Cubemap::full_mip_count(n));
    let cube = with_error_scope(
        device,
        "equirect_to_cube dispatch",
        || -> Result<wgpu::Texture> {
            let uniform = EquirectToCubeUniform {
                face_size: n,
                samples_per_axis: params.samples_per_axis,
                base_level,
                level_count: pyramid.level_count(),
                source_size: [pyramid.width, pyramid.height],
                rotation: params.rotation,
            };
            let ubuf = buffer_with_data(
                device,
                "equirect params",
                bytemuck::bytes_of(&uniform),
                wgpu::BufferUsages::UNIFORM,
            );
            let cube = create_cube_texture(device, "environment cube", n, mips);
            let source_view = source.create_view(&Default::default());
            let out = cube_mip_view(&cube, 0);
            let mut encoder = device.create_command_encoder(&Default::default());
            kernel.dispatch(
                device,
                &mut encoder,
                &[
                    ubuf.as_entire_binding(),
                    wgpu::BindingResource::TextureView(&source_view),
                    wgpu::BindingResource::TextureView(&out),
                ],
                [n, n, 6],
            );
            record_cube_mips(device, &mut encoder, &cube)?;
            queue.submit([encoder.finish()]);
            Ok(cube)
        },
    )??;
    read_cubemap(device, queue, &cube)
}
