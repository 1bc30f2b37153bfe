//! GPU prefiltered specular and irradiance: binds `shaders/prefilter_sampled.wgsl` and
//! `shaders/convolve_exact.wgsl` (CPU mirrors in `cpu/prefilter_specular.rs` and
//! `cpu/irradiance.rs`); the method per level is chosen by the same Rust function.

use crate::environment::texels::{irradiance_source_level, moment_texels, MomentTexel, SourceTexel};
use crate::plan::sheen::sheen_chain;
use crate::plan::sources::{exact_source_texels, ggx_lobe_samples, split_hot_texels};
use crate::plan::chain::{level_method, LevelMethod, SpecularChain};
use crate::environment::{Cubemap, IrradianceSource};
use crate::gpu::compute::{storage_buffer, uniform_buffer, with_error_scope, ComputeKernel};
use crate::gpu::shaders;
use crate::gpu::texture::{
    create_cube_texture, cube_array_view, cube_mip_view, read_cubemap, write_texels,
};
use crate::Result;

/// Workgroup of both kernels (x, y over the face, z = face).
pub const WORKGROUP: [u32; 3] = [8, 8, 1];

/// Uniform block of `prefilter_sampled.wgsl` (layout checked in tests/shaders.rs).
#[repr(C)]
#[derive(Clone, Copy, Debug, bytemuck::Pod, bytemuck::Zeroable)]
pub struct PrefilterUniform {
    /// Environment level-0 edge.
    pub env_size: u32,
    /// Environment mip count.
    pub env_levels: u32,
    /// Output level edge.
    pub out_size: u32,
    /// GGX points drawn per texel (N).
    pub samples: u32,
    /// Roughness of the level.
    pub roughness: f32,
    /// Lobe samples above the horizon (the length of the lobe table).
    pub lobe_count: u32,
    /// Number of hot texels summed exactly.
    pub hot_count: u32,
    /// Padding.
    pub _pad: u32,
}

/// Uniform block of `convolve_exact.wgsl` (layout checked in tests/shaders.rs).
#[repr(C)]
#[derive(Clone, Copy, Debug, bytemuck::Pod, bytemuck::Zeroable)]
pub struct ConvolveUniform {
    /// Output level edge.
    pub out_size: u32,
    /// Number of source texels.
    pub count: u32,
    /// 0: prefiltered specular, 1: irradiance / π, 2: prefiltered sheen.
    pub mode: u32,
    /// Roughness (modes 0 and 2).
    pub roughness: f32,
    /// Number of hot cells (mode 1).
    pub hot_count: u32,
    /// Padding to a whole 16-byte block.
    pub pad0: u32,
    /// Padding.
    pub pad1: u32,
    /// Padding.
    pub pad2: u32,
}

/// Uploads every level of `cube` into a new cube texture with `cube.levels.len()` mips.
pub fn upload_cube(
    device: &wgpu::Device,
    queue: &wgpu::Queue,
    cube: &Cubemap,
    mips: u32,
) -> wgpu::Texture {
    let texture = create_cube_texture(device, "cube", cube.size, mips);
    for (m, level) in cube.levels.iter().enumerate().take(mips as usize) {
        let n = cube.level_size(m);
        write_texels(queue, &texture, (m as u32, 0), (n, n, 6), bytemuck::cast_slice(level));
    }
    texture
}

/// What an exact convolution sums.
enum ExactSource<'a> {
    /// Mode 0: prefiltered specular at a roughness.
    Specular(&'a [SourceTexel], f32),
    /// Mode 2: prefiltered sheen (Charlie) at a roughness.
    Sheen(&'a [SourceTexel], f32),
    /// Mode 1: irradiance, from the cold texels and the hot cells.
    Irradiance(&'a [MomentTexel], &'a [MomentTexel]),
}

/// Records one exact convolution into `target` (a mip view).
fn record_exact(
    device: &wgpu::Device,
    encoder: &mut wgpu::CommandEncoder,
    kernel: &ComputeKernel,
    source: &ExactSource<'_>,
    out_size: u32,
    target: &wgpu::TextureView,
) {
    let (count, mode, roughness, bytes, hot): (usize, u32, f32, &[u8], &[MomentTexel]) =
        match source {
            ExactSource::Specular(s, r) => (s.len(), 0, *r, bytemuck::cast_slice(s), &[]),
            ExactSource::Sheen(s, r) => (s.len(), 2, *r, bytemuck::cast_slice(s), &[]),
            ExactSource::Irradiance(m, h) => (m.len(), 1, 0.0, bytemuck::cast_slice(m), h),
        };
    let uniform = ConvolveUniform {
        out_size,
        count: count as u32,
        mode,
        roughness,
        hot_count: hot.len() as u32,
        pad0: 0,
        pad1: 0,
        pad2: 0,
    };
    let hbuf = storage_buffer(device, "hot cells", hot);
    let ubuf = uniform_buffer(device, "convolve params", &uniform);
    let sbuf = storage_buffer(device, "convolve source", bytes);
    kernel.dispatch(
        device,
        encoder,
        &[
            ubuf.as_entire_binding(),
            sbuf.as_entire_binding(),
            wgpu::BindingResource::TextureView(target),
            hbuf.as_entire_binding(),
        ],
        [out_size, out_size, 6],
    );
}

/// The prefiltered chain of `env` (every mip present), as `backend::cpu::specular::prefilter_specular`.
pub fn prefilter_specular(
    device: &wgpu::Device,
    queue: &wgpu::Queue,
    env: &Cubemap,
    source_split: Option<&IrradianceSource>,
    chain: SpecularChain,
    samples: u32,
) -> Result<Cubemap> {
    let sampled = ComputeKernel::new(
        device,
        "prefilter_sampled",
        shaders::PREFILTER_SAMPLED,
        WORKGROUP,
    )?;
    let exact = ComputeKernel::new(device, "convolve_exact", shaders::CONVOLVE_EXACT, WORKGROUP)?;
    let levels = chain.levels.clamp(1, Cubemap::full_mip_count(env.size));
    let chain = SpecularChain { levels, ..chain };
    let split = split_hot_texels(env);
    let out = with_error_scope(device, "prefilter_specular dispatch", || {
        let source = upload_cube(device, queue, &split.rest, env.levels.len() as u32);
        let hot_buf = storage_buffer(device, "hot texels", &split.hot);
        let source_view = cube_array_view(&source);
        // Level 0 is the environment itself.
        let out = upload_cube(
            device,
            queue,
            &Cubemap {
                size: env.size,
                levels: vec![env.levels[0].clone()],
            },
            levels,
        );
        let mut encoder = device.create_command_encoder(&Default::default());
        for m in 1..levels {
            let r = chain.mip_roughness(m);
            let n = (env.size >> m).max(1);
            let target = cube_mip_view(&out, m);
            match level_method(env.size, m, r, samples) {
                LevelMethod::Exact { source_mip } => {
                    let texels = exact_source_texels(env, source_split, source_mip as usize);
                    let source = ExactSource::Specular(&texels, r);
                    record_exact(device, &mut encoder, &exact, &source, n, &target)
                }
                LevelMethod::Sampled { samples } => {
                    let lobe = ggx_lobe_samples(samples, r, env.size);
                    let lobe_count = lobe.len() as u32;
                    let uniform = PrefilterUniform {
                        env_size: env.size,
                        env_levels: env.levels.len() as u32,
                        out_size: n,
                        samples,
                        roughness: r,
                        lobe_count,
                        hot_count: split.hot.len() as u32,
                        _pad: 0,
                    };
                    let lobe_buf = storage_buffer(device, "lobe samples", &lobe);
                    let ubuf = uniform_buffer(device, "prefilter params", &uniform);
                    sampled.dispatch(
                        device,
                        &mut encoder,
                        &[
                            ubuf.as_entire_binding(),
                            wgpu::BindingResource::TextureView(&source_view),
                            wgpu::BindingResource::TextureView(&target),
                            hot_buf.as_entire_binding(),
                            lobe_buf.as_entire_binding(),
                        ],
                        [n, n, 6],
                    );
                }
            }
        }
        queue.submit([encoder.finish()]);
        out
    })?;
    read_cubemap(device, queue, &out)
}

/// The prefiltered Charlie chain of `env` (every mip present), as
/// `backend::cpu::sheen::prefilter_sheen`: the same [`sheen_chain`], its exact sums on the GPU.
pub fn prefilter_sheen(
    device: &wgpu::Device,
    queue: &wgpu::Queue,
    env: &Cubemap,
    split: Option<&IrradianceSource>,
    chain: SpecularChain,
) -> Result<Cubemap> {
    let exact = ComputeKernel::new(device, "convolve_exact", shaders::CONVOLVE_EXACT, WORKGROUP)?;
    sheen_chain(env, split, chain, |source, n, r| {
        let texture = with_error_scope(device, "prefilter_sheen dispatch", || {
            let texture = create_cube_texture(device, "sheen level", n, 1);
            let target = cube_mip_view(&texture, 0);
            let mut encoder = device.create_command_encoder(&Default::default());
            let source = ExactSource::Sheen(source, r);
            record_exact(device, &mut encoder, &exact, &source, n, &target);
            queue.submit([encoder.finish()]);
            texture
        })?;
        Ok(read_cubemap(device, queue, &texture)?.levels.remove(0))
    })
}

/// The irradiance cube (E/π) of edge `size`, as `cpu::irradiance`.
pub fn irradiance(
    device: &wgpu::Device,
    queue: &wgpu::Queue,
    src: &IrradianceSource,
    size: u32,
) -> Result<Cubemap> {
    let exact = ComputeKernel::new(device, "convolve_exact", shaders::CONVOLVE_EXACT, WORKGROUP)?;
    let out = with_error_scope(device, "irradiance dispatch", || {
        let out = create_cube_texture(device, "irradiance", size, 1);
        let target = cube_mip_view(&out, 0);
        let mut encoder = device.create_command_encoder(&Default::default());
        let cold = moment_texels(&src.cold, irradiance_source_level(&src.cold));
        let source = ExactSource::Irradiance(&cold, &src.hot);
        record_exact(device, &mut encoder, &exact, &source, size, &target);
        queue.submit([encoder.finish()]);
        out
    })?;
    read_cubemap(device, queue, &out)
}
