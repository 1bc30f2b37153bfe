//! What the viewer's GPU renderer uploads when the light or the model changes: the
//! lights' shadow maps, and the floor's table and shadow grid (`view::floor`,
//! `view::floor_shadow`), as storage for the deferred kernels and as textures the forward
//! pass reads through the sampler.

use crate::gpu::compute::{storage_buffer, with_error_scope};
use crate::gpu::texture::{create_texture_2d, write_texels};
use crate::view::floor::FloorTable;
use crate::view::floor_shadow::{FloorShadows, FLOOR_SHADOW_HEADER};
use crate::Result;

/// The floor's table as storage.
pub(super) fn floor_buffer(device: &wgpu::Device, table: &FloorTable) -> wgpu::Buffer {
    storage_buffer(device, "view floor table", &table.entries)
}

/// The floor's shadow grid as storage.
pub(super) fn floor_shadow_buffer(device: &wgpu::Device, grid: &FloorShadows) -> wgpu::Buffer {
    storage_buffer(device, "view floor shadows", &grid.entries)
}

/// A texture of `format` and `layers` layers of `width` × `height` texels, `bytes` layer by
/// layer and rows top down, viewed as `dimension` (an array however many layers it has,
/// or one 2D layer), uploaded within an error scope named `stage`.
fn texture_with_texels(
    (device, queue): (&wgpu::Device, &wgpu::Queue),
    (stage, label): (&str, &str),
    format: wgpu::TextureFormat,
    ((width, height, layers), dimension): ((u32, u32, u32), wgpu::TextureViewDimension),
    bytes: &[u8],
) -> Result<wgpu::TextureView> {
    with_error_scope(device, stage, || {
        let texture = create_texture_2d(
            device,
            label,
            (width, height, layers),
            format,
            wgpu::TextureUsages::TEXTURE_BINDING | wgpu::TextureUsages::COPY_DST,
        );
        write_texels(queue, &texture, (0, 0), (width, height, layers), bytes);
        texture.create_view(&wgpu::TextureViewDescriptor {
            dimension: Some(dimension),
            ..Default::default()
        })
    })
}

/// An rgba32float texture of the floor's caches as the forward pass reads them through the
/// sampler (`shaders/common/view_floor_filter.wgsl`).
fn floor_texture(
    (device, queue): (&wgpu::Device, &wgpu::Queue),
    label: &str,
    size: ((u32, u32, u32), wgpu::TextureViewDimension),
    texels: &[[f32; 4]],
) -> Result<wgpu::TextureView> {
    texture_with_texels(
        (device, queue),
        ("uploading the floor's caches", label),
        wgpu::TextureFormat::Rgba32Float,
        size,
        bytemuck::cast_slice(texels),
    )
}

/// The floor's table as a texture: its header's columns, rows and layers, then its entries.
pub(super) fn floor_table_texture(
    device: &wgpu::Device,
    queue: &wgpu::Queue,
    table: &FloorTable,
) -> Result<wgpu::TextureView> {
    let [w, h, layers, _] = table.entries[0].map(|v| v as u32);
    floor_texture(
        (device, queue),
        "view floor table texels",
        ((w, h, layers), wgpu::TextureViewDimension::D2Array),
        &table.entries[1..],
    )
}

/// The floor's shadow grid as a texture: nodes² nodes after its header.
pub(super) fn floor_shadow_texture(
    device: &wgpu::Device,
    queue: &wgpu::Queue,
    grid: &FloorShadows,
) -> Result<wgpu::TextureView> {
    let n = grid.entries[0][0] as u32;
    floor_texture(
        (device, queue),
        "view floor shadow texels",
        ((n, n, 1), wgpu::TextureViewDimension::D2),
        &grid.entries[FLOOR_SHADOW_HEADER..],
    )
}

/// An r32float array texture of `layers` layers of `size`² `depth` texels (the shadow
/// maps), viewed as an array however many layers it has.
pub(super) fn shadow_texture(
    device: &wgpu::Device,
    queue: &wgpu::Queue,
    (size, layers): (u32, u32),
    depth: &[f32],
) -> Result<wgpu::TextureView> {
    texture_with_texels(
        (device, queue),
        ("uploading the lights' shadow maps", "view shadow maps"),
        wgpu::TextureFormat::R32Float,
        ((size, size, layers), wgpu::TextureViewDimension::D2Array),
        bytemuck::cast_slice(depth),
    )
}
