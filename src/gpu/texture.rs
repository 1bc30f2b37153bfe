//! Texture helpers shared by the kernels: uploads, cube textures with per-mip array views,
//! and reading a whole cubemap back.

use crate::environment::{Cubemap, EquirectPyramid};
use crate::gpu::compute::{read_texture_level, with_error_scope};
use crate::Result;

/// Uploads the pyramid's kept levels as the mips of one `Rgba32Float` 2D texture, skipping
/// levels wider than the device's `max_texture_dimension_2d` (a 32k input on a 16k-limit
/// device reads its 16k level instead of failing). Returns the texture and the pyramid
/// level held in its mip 0.
pub fn upload_equirect_pyramid(
    device: &wgpu::Device,
    queue: &wgpu::Queue,
    pyramid: &EquirectPyramid,
) -> Result<(wgpu::Texture, u32)> {
    let limit = device.limits().max_texture_dimension_2d;
    let skip = pyramid
        .stored()
        .iter()
        .take_while(|l| l.width > limit || l.height > limit)
        .count()
        .min(pyramid.stored().len() - 1);
    let levels = &pyramid.stored()[skip..];
    with_error_scope(device, "uploading the environment", || {
        let texture = device.create_texture(&wgpu::TextureDescriptor {
            label: Some("equirect pyramid"),
            size: wgpu::Extent3d {
                width: levels[0].width,
                height: levels[0].height,
                depth_or_array_layers: 1,
            },
            mip_level_count: levels.len() as u32,
            sample_count: 1,
            dimension: wgpu::TextureDimension::D2,
            format: wgpu::TextureFormat::Rgba32Float,
            usage: wgpu::TextureUsages::TEXTURE_BINDING | wgpu::TextureUsages::COPY_DST,
            view_formats: &[],
        });
        for (mip, level) in levels.iter().enumerate() {
            let rgba: Vec<[f32; 4]> = level.data.iter().map(|t| [t[0], t[1], t[2], 1.0]).collect();
            queue.write_texture(
                wgpu::TexelCopyTextureInfo {
                    texture: &texture,
                    mip_level: mip as u32,
                    origin: wgpu::Origin3d::ZERO,
                    aspect: wgpu::TextureAspect::All,
                },
                bytemuck::cast_slice(&rgba),
                wgpu::TexelCopyBufferLayout {
                    offset: 0,
                    bytes_per_row: Some(level.width * 16),
                    rows_per_image: Some(level.height),
                },
                wgpu::Extent3d {
                    width: level.width,
                    height: level.height,
                    depth_or_array_layers: 1,
                },
            );
        }
        texture
    })
    .map(|t| (t, pyramid.first_level + skip as u32))
}

/// An `Rgba32Float` cube texture (6 array layers) with `mips` levels, usable as a storage
/// target, a sampled source and a copy source.
pub fn create_cube_texture(
    device: &wgpu::Device,
    label: &str,
    size: u32,
    mips: u32,
) -> wgpu::Texture {
    device.create_texture(&wgpu::TextureDescriptor {
        label: Some(label),
        size: wgpu::Extent3d {
            width: size,
            height: size,
            depth_or_array_layers: 6,
        },
        mip_level_count: mips,
        sample_count: 1,
        dimension: wgpu::TextureDimension::D2,
        format: wgpu::TextureFormat::Rgba32Float,
        usage: wgpu::TextureUsages::STORAGE_BINDING
            | wgpu::TextureUsages::TEXTURE_BINDING
            | wgpu::TextureUsages::COPY_SRC
            | wgpu::TextureUsages::COPY_DST,
        view_formats: &[],
    })
}

/// A 2D-array view of one mip of a cube texture (dispatch z = face).
pub fn cube_mip_view(texture: &wgpu::Texture, mip: u32) -> wgpu::TextureView {
    texture.create_view(&wgpu::TextureViewDescriptor {
        label: Some("cube mip"),
        dimension: Some(wgpu::TextureViewDimension::D2Array),
        base_mip_level: mip,
        mip_level_count: Some(1),
        base_array_layer: 0,
        array_layer_count: Some(6),
        ..Default::default()
    })
}

/// Reads every mip of a cube texture back into a [`Cubemap`].
pub fn read_cubemap(
    device: &wgpu::Device,
    queue: &wgpu::Queue,
    texture: &wgpu::Texture,
) -> Result<Cubemap> {
    let mut levels = Vec::new();
    for mip in 0..texture.mip_level_count() {
        let flat = read_texture_level(device, queue, texture, mip)?;
        levels.push(
            flat.chunks_exact(4)
                .map(|t| [t[0], t[1], t[2], t[3]])
                .collect(),
        );
    }
    Ok(Cubemap {
        size: texture.width(),
        levels,
    })
}
