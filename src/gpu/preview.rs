//! GPU preview renders: binds `shaders/preview_split_sum.wgsl` and
//! `shaders/preview_truth.wgsl` (CPU mirrors in `cpu/preview_split_sum.rs` and
//! `cpu/preview_truth.rs`). Each writes one panel into an `Rgba32Float` 2D texture that is
//! read back as row-major RGB.

use crate::plan::scene::{SplitSumInputs, SplitSumLight, TruthInputs, TruthLight};
use crate::gpu::compute::{
    read_texture_level, storage_buffer, uniform_buffer, with_error_scope, ComputeKernel,
};
use crate::gpu::prefilter::upload_cube;
use crate::gpu::shaders;
use crate::gpu::texture::{create_storage_texture_2d, cube_array_view, upload_lut_pairs};
use crate::plan::scene::SceneUniform;
use crate::Result;

/// Workgroup of both kernels (x, y over the panel).
pub const WORKGROUP: [u32; 3] = [8, 8, 1];

/// Uniform block of `preview_split_sum.wgsl` (layout checked in tests/shaders.rs).
#[repr(C)]
#[derive(Clone, Copy, Debug, bytemuck::Pod, bytemuck::Zeroable)]
pub struct SplitSumUniform {
    /// Specular chain level-0 edge.
    pub specular_size: u32,
    /// Specular chain levels.
    pub specular_levels: u32,
    /// Irradiance cube edge.
    pub irradiance_size: u32,
    /// LUT width (n·v).
    pub lut_width: u32,
    /// LUT height (roughness).
    pub lut_height: u32,
    /// How the reads combine (`IblTerms` as u32).
    pub ibl_terms: u32,
    /// 1 where kS is the roughness-aware Fresnel.
    pub roughness_fresnel: u32,
    /// How far S leans toward E/π (`RadianceBlend` as u32).
    pub radiance_blend: u32,
    /// 1 for the recipe's taps at grazing views (`plan::filtered`).
    pub filtered: u32,
    /// How the chain's levels map to roughness (`MipRoughness::code`), for the grazing
    /// taps' levels.
    pub mip_roughness: u32,
    /// Padding to 16 bytes.
    pub pad: [u32; 2],
}

impl SplitSumUniform {
    /// The block for `light`, its chain of `specular_levels` levels.
    pub fn new(light: &SplitSumLight, specular_levels: u32) -> Self {
        SplitSumUniform {
            specular_size: light.specular.size,
            specular_levels,
            irradiance_size: light.irradiance.size,
            lut_width: light.lut.width,
            lut_height: light.lut.height,
            ibl_terms: light.terms.ibl as u32,
            roughness_fresnel: light.terms.roughness_fresnel as u32,
            radiance_blend: light.terms.radiance_blend as u32,
            filtered: light.filtered.is_some() as u32,
            mip_roughness: light.filtered.map_or(0, |m| m.code()),
            pad: [0; 2],
        }
    }
}

/// Uniform block of `preview_truth.wgsl` (layout checked in tests/shaders.rs).
#[repr(C)]
#[derive(Clone, Copy, Debug, bytemuck::Pod, bytemuck::Zeroable)]
pub struct TruthUniform {
    /// Environment level-0 edge.
    pub env_size: u32,
    /// Number of hot texels.
    pub hot_count: u32,
    /// Number of quadrature points.
    pub point_count: u32,
    /// The BRDF's masking (`Masking` as u32).
    pub masking: u32,
    /// The BRDF's diffuse weighting (`DiffuseLobe` as u32).
    pub diffuse: u32,
    /// 1 where the preview scales the specular by the LUT's compensation.
    pub compensated: u32,
    /// The compensation's LUT width (n·v; 0 without one).
    pub lut_width: u32,
    /// Its height (roughness).
    pub lut_height: u32,
}

impl TruthUniform {
    /// The block for `light` (whose BRDF's compensation reads a `lut` of `lut_size`, when
    /// the kernel binds one).
    pub fn new(light: &TruthLight, lut_size: [u32; 2]) -> Self {
        TruthUniform {
            env_size: light.env.size,
            hot_count: light.hot.len() as u32,
            point_count: light.points.len() as u32,
            masking: light.brdf.masking as u32,
            diffuse: light.brdf.diffuse as u32,
            compensated: light.brdf.compensated as u32,
            lut_width: lut_size[0],
            lut_height: lut_size[1],
        }
    }
}

/// Runs `kernel` over the panel with `resources` followed by the output, and reads it back.
fn run_panel(
    device: &wgpu::Device,
    queue: &wgpu::Queue,
    kernel: &ComputeKernel,
    scene: &SceneUniform,
    resources: &[wgpu::BindingResource<'_>],
    stage: &str,
) -> Result<Vec<[f32; 3]>> {
    let out = with_error_scope(device, stage, || {
        let out = create_storage_texture_2d(device, "preview panel", scene.width, scene.height);
        let view = out.create_view(&Default::default());
        let mut all = resources.to_vec();
        all.push(wgpu::BindingResource::TextureView(&view));
        let mut encoder = device.create_command_encoder(&Default::default());
        kernel.dispatch(device, &mut encoder, &all, [scene.width, scene.height, 1]);
        queue.submit([encoder.finish()]);
        out
    })?;
    let flat = read_texture_level(device, queue, &out, 0)?;
    Ok(flat.chunks_exact(4).map(|t| [t[0], t[1], t[2]]).collect())
}

/// The split-sum panel, as `cpu::preview_split_sum::render_split_sum`.
pub fn preview_split_sum(
    device: &wgpu::Device,
    queue: &wgpu::Queue,
    scene: &SceneUniform,
    inputs: &SplitSumInputs,
) -> Result<Vec<[f32; 3]>> {
    let kernel = ComputeKernel::new(
        device,
        "preview_split_sum",
        shaders::PREVIEW_SPLIT_SUM,
        WORKGROUP,
    )?;
    let (spec, irr, lut) = (inputs.light.specular, inputs.light.irradiance, inputs.light.lut);
    let params = SplitSumUniform::new(&inputs.light, spec.levels.len() as u32);
    let lut_tex = upload_lut_pairs(device, queue, "preview lut", lut)?;
    let (spec_tex, irr_tex, buffers) =
        with_error_scope(device, "preview_split_sum upload", || {
            (
                upload_cube(device, queue, spec, spec.levels.len() as u32),
                upload_cube(device, queue, irr, 1),
                [
                    uniform_buffer(device, "preview scene", scene),
                    uniform_buffer(device, "preview split-sum params", &params),
                    storage_buffer(device, "preview spheres", inputs.spheres),
                    storage_buffer(device, "preview materials", inputs.materials),
                ],
            )
        })?;
    let (spec_view, irr_view) = (cube_array_view(&spec_tex), cube_array_view(&irr_tex));
    let lut_view = lut_tex.create_view(&Default::default());
    run_panel(
        device,
        queue,
        &kernel,
        scene,
        &[
            buffers[0].as_entire_binding(),
            buffers[1].as_entire_binding(),
            wgpu::BindingResource::TextureView(&spec_view),
            wgpu::BindingResource::TextureView(&irr_view),
            wgpu::BindingResource::TextureView(&lut_view),
            buffers[2].as_entire_binding(),
            buffers[3].as_entire_binding(),
        ],
        "preview_split_sum dispatch",
    )
}

/// The ground-truth panel, as `cpu::preview_truth::render_truth`.
pub fn preview_truth(
    device: &wgpu::Device,
    queue: &wgpu::Queue,
    scene: &SceneUniform,
    inputs: &TruthInputs,
) -> Result<Vec<[f32; 3]>> {
    let kernel = ComputeKernel::new(device, "preview_truth", shaders::PREVIEW_TRUTH, WORKGROUP)?;
    let params = TruthUniform::new(&inputs.light, [inputs.lut.width, inputs.lut.height]);
    let lut_tex = upload_lut_pairs(device, queue, "preview truth lut", inputs.lut)?;
    let (env_tex, cold_tex, buffers) = with_error_scope(device, "preview_truth upload", || {
        (
            upload_cube(device, queue, inputs.light.env, 1),
            upload_cube(device, queue, inputs.light.cold, 1),
            [
                uniform_buffer(device, "preview scene", scene),
                uniform_buffer(device, "preview truth params", &params),
                storage_buffer(device, "preview hot texels", inputs.light.hot),
                storage_buffer(device, "preview spheres", inputs.spheres),
                storage_buffer(device, "preview materials", inputs.materials),
                storage_buffer(device, "preview points", inputs.light.points),
            ],
        )
    })?;
    let (env_view, cold_view) = (cube_array_view(&env_tex), cube_array_view(&cold_tex));
    let lut_view = lut_tex.create_view(&Default::default());
    run_panel(
        device,
        queue,
        &kernel,
        scene,
        &[
            buffers[0].as_entire_binding(),
            buffers[1].as_entire_binding(),
            wgpu::BindingResource::TextureView(&env_view),
            wgpu::BindingResource::TextureView(&cold_view),
            buffers[2].as_entire_binding(),
            buffers[3].as_entire_binding(),
            buffers[4].as_entire_binding(),
            buffers[5].as_entire_binding(),
            wgpu::BindingResource::TextureView(&lut_view),
        ],
        "preview_truth dispatch",
    )
}
