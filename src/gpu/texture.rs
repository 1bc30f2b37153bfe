//! Texture helpers shared by the kernels: uploads, cube textures with per-mip array views,
//! and reading a whole cubemap back.

use crate::environment::Cubemap;
use crate::gpu::compute::{read_texture_level, with_error_scope};
use crate::Result;

/// Uploads a `width`×`height` RGB image as an `Rgba32Float` 2D texture (A = 1), read with
/// `textureLoad`.
pub fn upload_rgb_texture(
    device: &wgpu::Device,
    queue: &wgpu::Queue,
    label: &str,
    width: u32,
    height: u32,
    data: &[[f32; 3]],
) -> Result<wgpu::Texture> {
    with_error_scope(device, "uploading the environment", || {
        let size = wgpu::Extent3d {
            width,
            height,
            depth_or_array_layers: 1,
        };
        let texture = device.create_texture(&wgpu::TextureDescriptor {
            label: Some(label),
            size,
            mip_level_count: 1,
            sample_count: 1,
            dimension: wgpu::TextureDimension::D2,
            format: wgpu::TextureFormat::Rgba32Float,
            usage: wgpu::TextureUsages::TEXTURE_BINDING | wgpu::TextureUsages::COPY_DST,
            view_formats: &[],
        });
        let rgba: Vec<[f32; 4]> = data.iter().map(|t| [t[0], t[1], t[2], 1.0]).collect();
        queue.write_texture(
            wgpu::TexelCopyTextureInfo {
                texture: &texture,
                mip_level: 0,
                origin: wgpu::Origin3d::ZERO,
                aspect: wgpu::TextureAspect::All,
            },
            bytemuck::cast_slice(&rgba),
            wgpu::TexelCopyBufferLayout {
                offset: 0,
                bytes_per_row: Some(width * 16),
                rows_per_image: Some(height),
            },
            size,
        );
        texture
    })
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

/// An `Rgba32Float` 2D texture a kernel writes (storage) and the CPU reads back (copy).
pub fn create_storage_texture_2d(
    device: &wgpu::Device,
    label: &str,
    width: u32,
    height: u32,
) -> wgpu::Texture {
    device.create_texture(&wgpu::TextureDescriptor {
        label: Some(label),
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
    })
}

/// A 2D-array view of every mip of a cube texture, as the kernels sample it.
pub fn cube_array_view(texture: &wgpu::Texture) -> wgpu::TextureView {
    texture.create_view(&wgpu::TextureViewDescriptor {
        dimension: Some(wgpu::TextureViewDimension::D2Array),
        ..Default::default()
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
