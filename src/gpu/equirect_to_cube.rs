//! GPU equirect → cube with mips: binds `shaders/equirect_to_cube.wgsl` for level 0 and
//! `shaders/cube_downsample.wgsl` for each further level (CPU mirrors in `cpu/`).

use crate::plan::convert::EquirectToCubeParams;
use crate::environment::{Cubemap, Equirect, EquirectIntegral};
use crate::gpu::compute::{buffer_with_data, with_error_scope, ComputeKernel};
use crate::gpu::shaders;
use crate::gpu::texture::{create_cube_texture, cube_mip_view, read_cubemap, upload_rgb_texture};
use crate::Result;

/// Workgroup of both kernels (x, y over the face, z = face).
pub const WORKGROUP: [u32; 3] = [8, 8, 1];

/// Uniform block of `shaders/equirect_to_cube.wgsl` (layout checked in tests/shaders.rs).
#[repr(C)]
#[derive(Clone, Copy, Debug, bytemuck::Pod, bytemuck::Zeroable)]
pub struct EquirectToCubeUniform {
    /// Output face edge.
    pub face_size: u32,
    /// Padding (WGSL aligns the vec2s that follow to 8 bytes).
    pub pad: u32,
    /// Width and height of the source level.
    pub source_size: [u32; 2],
    /// cos, sin of the rotation about +Y.
    pub rotation: [f32; 2],
    /// Padding to a whole 16-byte block.
    pub pad2: [u32; 2],
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

/// Converts the source level to a cube of `params.face_size` with `mips` levels.
pub fn equirect_to_cube(
    device: &wgpu::Device,
    queue: &wgpu::Queue,
    source: &EquirectIntegral,
    params: &EquirectToCubeParams,
    mips: u32,
) -> Result<Cubemap> {
    let kernel = ComputeKernel::new(
        device,
        "equirect_to_cube",
        shaders::EQUIRECT_TO_CUBE,
        WORKGROUP,
    )?;
    // A level wider than the device's 2D texture limit is read one halving coarser per
    // step until it fits (the same exact area filter as the pyramid's).
    let limit = device.limits().max_texture_dimension_2d;
    let reduced;
    let source = if source.width > limit || source.height > limit {
        let mut image = Equirect {
            width: source.width,
            height: source.height,
            data: source.radiance.clone(),
        };
        while image.width > limit || image.height > limit {
            image = image.downsample();
        }
        reduced = EquirectIntegral::new(image);
        &reduced
    } else {
        source
    };
    let (w, h) = (source.width, source.height);
    let textures = [
        upload_rgb_texture(device, queue, "radiance", w, h, &source.radiance)?,
        upload_rgb_texture(device, queue, "from north", w, h, &source.from_north)?,
        upload_rgb_texture(device, queue, "from south", w, h, &source.from_south)?,
    ];
    let n = params.face_size;
    let mips = mips.clamp(1, Cubemap::full_mip_count(n));
    let cube = with_error_scope(
        device,
        "equirect_to_cube dispatch",
        || -> Result<wgpu::Texture> {
            let uniform = EquirectToCubeUniform {
                face_size: n,
                pad: 0,
                source_size: [w, h],
                rotation: params.rotation,
                pad2: [0; 2],
            };
            let ubuf = buffer_with_data(
                device,
                "equirect params",
                bytemuck::bytes_of(&uniform),
                wgpu::BufferUsages::UNIFORM,
            );
            let cube = create_cube_texture(device, "environment cube", n, mips);
            let rows = buffer_with_data(
                device,
                "row boundaries",
                bytemuck::cast_slice(&source.rows),
                wgpu::BufferUsages::STORAGE,
            );
            let columns = buffer_with_data(
                device,
                "column boundaries",
                bytemuck::cast_slice(&source.columns),
                wgpu::BufferUsages::STORAGE,
            );
            let views = textures
                .each_ref()
                .map(|t| t.create_view(&Default::default()));
            let out = cube_mip_view(&cube, 0);
            let mut encoder = device.create_command_encoder(&Default::default());
            kernel.dispatch(
                device,
                &mut encoder,
                &[
                    ubuf.as_entire_binding(),
                    wgpu::BindingResource::TextureView(&views[0]),
                    wgpu::BindingResource::TextureView(&views[1]),
                    wgpu::BindingResource::TextureView(&views[2]),
                    rows.as_entire_binding(),
                    columns.as_entire_binding(),
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
