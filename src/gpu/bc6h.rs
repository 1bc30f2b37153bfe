//! BC6H on the GPU: the `block_compression` crate's WGSL port of ISPC's kernel, fed with
//! the input both backends read ([`crate::plan::bc6h::encoder_input`]): each level is
//! uploaded as an `Rgba16Float` array of six faces padded to whole blocks, one compression
//! task per face writes its blocks into the level's storage buffer, and every level is
//! read back after one submission.

use std::sync::Mutex;

use block_compression::{CompressionVariant, GpuBlockCompressor};

use crate::environment::Cubemap;
use crate::gpu::compute::{map_read, with_error_scope};
use crate::gpu::texture::{create_texture_2d, write_texels};
use crate::plan::bc6h::{encoder_input, face_bytes, padded_edge, Bc6hQuality};
use crate::Result;

/// A device's encoder, created (its pipeline compiled) on first use.
#[derive(Default)]
pub struct CompressorCache(Mutex<Option<GpuBlockCompressor>>);

/// The BC6H blocks of every level of `cube`, each level its six faces one after the other.
pub fn encode_bc6h(
    device: &wgpu::Device,
    queue: &wgpu::Queue,
    cache: &CompressorCache,
    cube: &Cubemap,
    quality: Bc6hQuality,
) -> Result<Vec<Vec<u8>>> {
    let mut guard = cache.0.lock().unwrap_or_else(|e| e.into_inner());
    let compressor =
        guard.get_or_insert_with(|| GpuBlockCompressor::new(device.clone(), queue.clone()));
    let (staging, sizes) = with_error_scope(device, "bc6h", || {
        let mut levels = Vec::with_capacity(cube.levels.len());
        for m in 0..cube.levels.len() {
            let n = cube.level_size(m);
            let p = padded_edge(n);
            let variant = CompressionVariant::BC6H(quality.settings(n));
            let texture = create_texture_2d(
                device,
                "bc6h source",
                (p, p, 6),
                wgpu::TextureFormat::Rgba16Float,
                wgpu::TextureUsages::TEXTURE_BINDING | wgpu::TextureUsages::COPY_DST,
            );
            for face in 0..6u32 {
                write_texels(
                    queue,
                    &texture,
                    (0, face),
                    (p, p, 1),
                    bytemuck::cast_slice(&encoder_input(cube, m, face)),
                );
            }
            let size = (6 * face_bytes(n)) as u64;
            let blocks = device.create_buffer(&wgpu::BufferDescriptor {
                label: Some("bc6h blocks"),
                size,
                usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_SRC,
                mapped_at_creation: false,
            });
            for face in 0..6u32 {
                let view = texture.create_view(&wgpu::TextureViewDescriptor {
                    dimension: Some(wgpu::TextureViewDimension::D2),
                    base_array_layer: face,
                    array_layer_count: Some(1),
                    ..Default::default()
                });
                compressor.add_compression_task(
                    variant,
                    &view,
                    p,
                    p,
                    &blocks,
                    None,
                    Some(face * face_bytes(n) as u32),
                );
            }
            levels.push((texture, blocks, size));
        }
        let mut encoder = device.create_command_encoder(&Default::default());
        {
            let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
                label: Some("bc6h"),
                timestamp_writes: None,
            });
            compressor.compress(&mut pass);
        }
        let total: u64 = levels.iter().map(|l| l.2).sum();
        let staging = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("bc6h readback"),
            size: total,
            usage: wgpu::BufferUsages::COPY_DST | wgpu::BufferUsages::MAP_READ,
            mapped_at_creation: false,
        });
        let mut offset = 0;
        for (_, blocks, size) in &levels {
            encoder.copy_buffer_to_buffer(blocks, 0, &staging, offset, *size);
            offset += size;
        }
        queue.submit([encoder.finish()]);
        (staging, levels.iter().map(|l| l.2 as usize).collect::<Vec<_>>())
    })?;
    let bytes = map_read(device, &staging)?;
    let mut out = Vec::with_capacity(sizes.len());
    let mut at = 0;
    for size in sizes {
        out.push(bytes[at..at + size].to_vec());
        at += size;
    }
    Ok(out)
}
