//! The wgpu backend, and what `--backend auto` runs on a software adapter.

use crate::backend::cpu::CpuBackend;
use crate::backend::{Backend, BackendJob};
use crate::environment::{Cubemap, EquirectIntegral, IrradianceSource};
use crate::gpu::{self, GpuContext};
use crate::plan::bc6h::Bc6hQuality;
use crate::plan::chain::SpecularChain;
use crate::plan::convert::EquirectToCubeParams;
use crate::plan::ltc::LtcTable;
use crate::plan::lut::{validate_lut_size, BrdfLut, LutModel, LutQuadrature};
use crate::plan::scene::{SceneUniform, SplitSumInputs, TruthInputs};
use crate::plan::shading::LightBrdf;
use crate::Result;

/// The wgpu backend.
#[derive(Debug)]
pub struct GpuBackend {
    /// The device every kernel runs on.
    pub ctx: GpuContext,
}

impl GpuBackend {
    /// Opens the default adapter.
    pub fn new() -> Result<Self> {
        Ok(GpuBackend {
            ctx: GpuContext::new()?,
        })
    }
}

impl Backend for GpuBackend {
    fn description(&self) -> String {
        format!("gpu: {}", self.ctx.adapter_description())
    }

    fn brdf_lut_model(&self, width: u32, height: u32, model: LutModel) -> Result<BrdfLut> {
        validate_lut_size(width, height)?;
        BrdfLut::assemble(model, |m| {
            self.ctx.run_kernel("brdf_lut", |device, queue| {
                let quad = LutQuadrature::for_model(m);
                gpu::brdf_lut::brdf_lut(device, queue, width, height, &quad, m)
            })
        })
    }

    fn equirect_to_cube(
        &self,
        source: &EquirectIntegral,
        params: &EquirectToCubeParams,
        mips: u32,
    ) -> Result<Cubemap> {
        self.ctx.run_kernel("equirect_to_cube", |device, queue| {
            gpu::equirect_to_cube::equirect_to_cube(device, queue, source, params, mips)
        })
    }

    fn prefilter_specular(
        &self,
        env: &Cubemap,
        split: Option<&IrradianceSource>,
        chain: SpecularChain,
        samples: u32,
    ) -> Result<Cubemap> {
        self.ctx.run_kernel("prefilter_specular", |device, queue| {
            gpu::prefilter::prefilter_specular(device, queue, env, split, chain, samples)
        })
    }

    fn prefilter_sheen(
        &self,
        env: &Cubemap,
        split: Option<&IrradianceSource>,
        chain: SpecularChain,
    ) -> Result<Cubemap> {
        self.ctx.run_kernel("prefilter_sheen", |device, queue| {
            gpu::prefilter::prefilter_sheen(device, queue, env, split, chain)
        })
    }

    fn irradiance(&self, source: &IrradianceSource, size: u32) -> Result<Cubemap> {
        self.ctx.run_kernel("irradiance", |device, queue| {
            gpu::prefilter::irradiance(device, queue, source, size)
        })
    }

    fn preview_split_sum(
        &self,
        scene: &SceneUniform,
        inputs: &SplitSumInputs,
    ) -> Result<Vec<[f32; 3]>> {
        self.ctx.run_kernel("preview_split_sum", |device, queue| {
            gpu::preview::preview_split_sum(device, queue, scene, inputs)
        })
    }

    fn preview_truth(&self, scene: &SceneUniform, inputs: &TruthInputs) -> Result<Vec<[f32; 3]>> {
        self.ctx.run_kernel("preview_truth", |device, queue| {
            gpu::preview::preview_truth(device, queue, scene, inputs)
        })
    }

    fn encode_bc6h(&self, cube: &Cubemap, quality: Bc6hQuality) -> Result<Vec<Vec<u8>>> {
        self.ctx.run_kernel("bc6h", |device, queue| {
            gpu::bc6h::encode_bc6h(device, queue, &self.ctx.bc6h, cube, quality)
        })
    }

    fn fit_ltc(&self, brdf: LightBrdf, size: u32) -> Result<LtcTable> {
        self.ctx.run_kernel("ltc_fit", |device, queue| {
            gpu::ltc_fit::fit_ltc(device, queue, brdf, size)
        })
    }
}

/// What `--backend auto` uses on a software adapter (Mesa's lavapipe and the like): the
/// GPU for the kernels lavapipe runs faster than the CPU backend (the preview's ground
/// truth, the LTC fit: docs/accuracy.md, "The LTC fit on either backend") and the CPU
/// reference for the others (the LUT, cube conversion, prefilter,
/// irradiance, the preview's split-sum), as measured by `cargo bench` on a 2-core machine
/// (LUT 512: 2.0 CPU-s on lavapipe integrating every texel, 0.24 on the CPU interpolating
/// most of them; prefilter 256: 2.1 on lavapipe, 1.3 on the CPU; irradiance 32: 1.9 and
/// 0.4; preview truth at 2048 points: 22.9 and 41.2; preview split-sum: 0.12 and 0.02 s
/// wall). On a hardware adapter every kernel runs on the GPU.
#[derive(Debug)]
pub struct SoftwareAdapterBackend {
    /// The software adapter.
    pub gpu: GpuBackend,
}

impl Backend for SoftwareAdapterBackend {
    fn description(&self) -> String {
        format!(
            "{} for the preview's truth and the LTC fit, {} for the LUT, conversion, prefilter, irradiance and the preview's split-sum (software adapter)",
            self.gpu.description(),
            CpuBackend.description()
        )
    }

    fn description_for(&self, job: BackendJob) -> String {
        match job {
            BackendJob::Preview => self.description(),
            BackendJob::LtcFit => format!("{} (software adapter: faster here than the CPU)", self.gpu.description()),
            BackendJob::Bake => format!("{} (software adapter: the CPU is faster here)", CpuBackend.description()),
        }
    }

    fn identity(&self) -> String {
        format!(
            "{} for the preview's truth and the LTC fit, cpu for the LUT, conversion, prefilter, irradiance and the preview's split-sum",
            self.gpu.identity()
        )
    }

    fn bc6h_identity(&self) -> String {
        CpuBackend.identity()
    }

    fn brdf_lut_model(&self, width: u32, height: u32, model: LutModel) -> Result<BrdfLut> {
        CpuBackend.brdf_lut_model(width, height, model)
    }

    fn equirect_to_cube(
        &self,
        source: &EquirectIntegral,
        params: &EquirectToCubeParams,
        mips: u32,
    ) -> Result<Cubemap> {
        CpuBackend.equirect_to_cube(source, params, mips)
    }

    fn prefilter_specular(
        &self,
        env: &Cubemap,
        split: Option<&IrradianceSource>,
        chain: SpecularChain,
        samples: u32,
    ) -> Result<Cubemap> {
        CpuBackend.prefilter_specular(env, split, chain, samples)
    }

    fn prefilter_sheen(
        &self,
        env: &Cubemap,
        split: Option<&IrradianceSource>,
        chain: SpecularChain,
    ) -> Result<Cubemap> {
        CpuBackend.prefilter_sheen(env, split, chain)
    }

    fn irradiance(&self, source: &IrradianceSource, size: u32) -> Result<Cubemap> {
        CpuBackend.irradiance(source, size)
    }

    fn preview_split_sum(
        &self,
        scene: &SceneUniform,
        inputs: &SplitSumInputs,
    ) -> Result<Vec<[f32; 3]>> {
        CpuBackend.preview_split_sum(scene, inputs)
    }

    fn preview_truth(&self, scene: &SceneUniform, inputs: &TruthInputs) -> Result<Vec<[f32; 3]>> {
        self.gpu.preview_truth(scene, inputs)
    }

    fn encode_bc6h(&self, cube: &Cubemap, quality: Bc6hQuality) -> Result<Vec<Vec<u8>>> {
        CpuBackend.encode_bc6h(cube, quality)
    }

    fn fit_ltc(&self, brdf: LightBrdf, size: u32) -> Result<LtcTable> {
        self.gpu.fit_ltc(brdf, size)
    }
}
