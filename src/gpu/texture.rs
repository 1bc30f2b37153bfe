//! Texture helpers shared by the kernels: uploads, cube textures with per-mip array views,
//! and reading a whole cubemap back.

use crate::environment::sample::BorderedCube;
use crate::environment::Cubemap;
use crate::plan::lut::BrdfLut;
use crate::gpu::compute::{read_texture_level, with_error_scope};
use crate::Result;

/// A 2D texture (an array of `layers` when more than one) of one mip level.
pub fn create_texture_2d(
    device: &wgpu::Device,
    label: &str,
    (width, height, layers): (u32, u32, u32),
    format: wgpu::TextureFormat,
    usage: wgpu::TextureUsages,
) -> wgpu::Texture {
    device.create_texture(&wgpu::TextureDescriptor {
        label: Some(label),
        size: wgpu::Extent3d {
            width,
            height,
            depth_or_array_layers: layers,
        },
        mip_level_count: 1,
        sample_count: 1,
        dimension: wgpu::TextureDimension::D2,
        format,
        usage,
        view_formats: &[],
    })
}

/// Writes `data` into `texture` (an uncompressed format) at mip `mip` from array layer
/// `first_layer`: `layers` tightly packed images of `width`×`height` texels, each at its
/// layer's top-left corner.
pub fn write_texels(
    queue: &wgpu::Queue,
    texture: &wgpu::Texture,
    (mip, first_layer): (u32, u32),
    (width, height, layers): (u32, u32, u32),
    data: &[u8],
) {
    // None only for compressed and depth formats, which nothing writes through here; a
    // zero row length then fails wgpu's validation in the caller's error scope.
    let texel_bytes = texture.format().block_copy_size(None).unwrap_or(0);
    queue.write_texture(
        wgpu::TexelCopyTextureInfo {
            texture,
            mip_level: mip,
            origin: wgpu::Origin3d {
                x: 0,
                y: 0,
                z: first_layer,
            },
            aspect: wgpu::TextureAspect::All,
        },
        data,
        wgpu::TexelCopyBufferLayout {
            offset: 0,
            bytes_per_row: Some(width * texel_bytes),
            rows_per_image: Some(height),
        },
        wgpu::Extent3d {
            width,
            height,
            depth_or_array_layers: layers,
        },
    );
}

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
    let rgba: Vec<[f32; 4]> = data.iter().map(|t| [t[0], t[1], t[2], 1.0]).collect();
    upload_rgba_texture(device, queue, label, width, height, &rgba)
}

/// The split-sum LUT as `shaders/common/split_sum.wgsl` reads it: an `Rgba32Float` texture
/// whose texel (i, j) holds (A, B) of texel (i, j) and of its right neighbour (i + 1, j),
/// clamped to the last column, so that a bilinear lookup's four taps are two loads of the
/// same values.
pub fn upload_lut_pairs(
    device: &wgpu::Device,
    queue: &wgpu::Queue,
    label: &str,
    lut: &BrdfLut,
) -> Result<wgpu::Texture> {
    let pairs: Vec<[f32; 4]> = (0..lut.height)
        .flat_map(|j| {
            (0..lut.width).map(move |i| {
                let ([a, b], [c, d]) = (lut.get(i, j), lut.get((i + 1).min(lut.width - 1), j));
                [a, b, c, d]
            })
        })
        .collect();
    upload_rgba_texture(device, queue, label, lut.width, lut.height, &pairs)
}

/// Uploads a `width`×`height` RGBA image as an `Rgba32Float` 2D texture, read with
/// `textureLoad`.
fn upload_rgba_texture(
    device: &wgpu::Device,
    queue: &wgpu::Queue,
    label: &str,
    width: u32,
    height: u32,
    rgba: &[[f32; 4]],
) -> Result<wgpu::Texture> {
    with_error_scope(device, &format!("uploading the {label} texture"), || {
        let texture = create_texture_2d(
            device,
            label,
            (width, height, 1),
            wgpu::TextureFormat::Rgba32Float,
            wgpu::TextureUsages::TEXTURE_BINDING | wgpu::TextureUsages::COPY_DST,
        );
        write_texels(queue, &texture, (0, 0), (width, height, 1), bytemuck::cast_slice(rgba));
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
    create_texture_2d(
        device,
        label,
        (width, height, 1),
        wgpu::TextureFormat::Rgba32Float,
        wgpu::TextureUsages::STORAGE_BINDING | wgpu::TextureUsages::COPY_SRC,
    )
}

/// The first `levels` levels of `cube` with their borders ([`BorderedCube`]) as an
/// `Rgba32Float` 2D array texture of one mip, viewed as an array: level m's faces are
/// layers 6m … 6m + 5, each (n + 2)² at the top left of a layer of level 0's (n₀ + 2)², as
/// `shaders/common/cube_fetch_bordered.wgsl` reads it.
#[cfg_attr(not(feature = "view"), allow(dead_code))]
pub fn upload_bordered_cube(
    device: &wgpu::Device,
    queue: &wgpu::Queue,
    label: &str,
    cube: &Cubemap,
    levels: usize,
) -> wgpu::TextureView {
    let bordered = if levels < cube.levels.len() {
        BorderedCube::new(&Cubemap {
            size: cube.size,
            levels: cube.levels[..levels].to_vec(),
        })
    } else {
        BorderedCube::new(cube)
    };
    let edge = bordered.size() + 2;
    let levels = bordered.level_count() as u32;
    let texture = create_texture_2d(
        device,
        label,
        (edge, edge, 6 * levels),
        wgpu::TextureFormat::Rgba32Float,
        wgpu::TextureUsages::TEXTURE_BINDING | wgpu::TextureUsages::COPY_DST,
    );
    for m in 0..levels {
        let p = cube.level_size(m as usize) + 2;
        write_texels(
            queue,
            &texture,
            (0, 6 * m),
            (p, p, 6),
            bytemuck::cast_slice(bordered.level(m as usize)),
        );
    }
    texture.create_view(&wgpu::TextureViewDescriptor {
        dimension: Some(wgpu::TextureViewDimension::D2Array),
        ..Default::default()
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
