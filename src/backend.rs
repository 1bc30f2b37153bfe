//! The compute backends: one trait, a CPU implementation (the reference, usable on machines
//! without a GPU) and a GPU one (wgpu). Tests run every kernel through both.

use crate::cpu::equirect_to_cube::EquirectToCubeParams;
use crate::cpu::prefilter_specular::SpecularChain;
use crate::cpu::preview_split_sum::SplitSumInputs;
use crate::cpu::preview_truth::TruthInputs;
use crate::environment::{Cubemap, EquirectIntegral, IrradianceSource};
use crate::gpu::GpuContext;
use crate::lut::{validate_lut_size, BrdfLut, LutModel, LutQuadrature};
use crate::preview::scene::SceneUniform;
use crate::{cpu, gpu, Error, Result};

/// Which backend the user asked for.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum BackendChoice {
    /// A GPU adapter when one exists, the CPU otherwise; on a software adapter (lavapipe)
    /// each kernel runs where it is faster (see [`SoftwareAdapterBackend`]).
    #[default]
    Auto,
    /// wgpu only; fails when no adapter exists.
    Gpu,
    /// The CPU reference implementation.
    Cpu,
}

/// The kernels splitsum runs; each backend implements all of them.
pub trait Backend {
    /// A human-readable description ("cpu (rayon, 2 threads)", "gpu: NVIDIA ... (Vulkan)").
    fn description(&self) -> String;

    /// What determines the outputs, for manifests: the adapter of a GPU backend, but not
    /// the CPU backend's thread count (every texel is computed the same way however the
    /// work is split), so equal bakes on different machines give equal manifests.
    fn identity(&self) -> String {
        self.description()
    }

    /// The BRDF LUT of `model` (see [`crate::lut`]).
    fn brdf_lut_model(&self, width: u32, height: u32, model: LutModel) -> Result<BrdfLut>;

    /// The split-sum BRDF LUT of the default model (Schlick-GGX scale and bias).
    fn brdf_lut(&self, width: u32, height: u32) -> Result<BrdfLut> {
        self.brdf_lut_model(width, height, LutModel::default())
    }

    /// An equirect (one pyramid level, prepared for exact integrals) to a cube of
    /// `params.face_size` with `mips` levels (level 0: each texel the exact footprint mean,
    /// see [`crate::cpu::equirect_to_cube`]; the rest by the 2×2 solid-angle reduction).
    fn equirect_to_cube(
        &self,
        source: &EquirectIntegral,
        params: &EquirectToCubeParams,
        mips: u32,
    ) -> Result<Cubemap>;

    /// The prefiltered specular chain of `env` (which has every mip) in `chain`'s layout:
    /// level m at roughness m/(M − 1), see [`crate::cpu::prefilter_specular`]. With the
    /// bake's split source (`split`), exact levels sum the hot cells at source resolution.
    fn prefilter_specular(
        &self,
        env: &Cubemap,
        split: Option<&IrradianceSource>,
        chain: SpecularChain,
        samples: u32,
    ) -> Result<Cubemap>;

    /// The prefiltered Charlie sheen chain of `env` (which has every mip) in `chain`'s
    /// layout, see [`crate::cpu::prefilter_sheen`]; with the split source its exact sums
    /// read the hot cells at source resolution.
    fn prefilter_sheen(
        &self,
        env: &Cubemap,
        split: Option<&IrradianceSource>,
        chain: SpecularChain,
    ) -> Result<Cubemap>;

    /// The irradiance cube (E/π) of edge `size` from the split source, see
    /// [`crate::cpu::irradiance`] and [`crate::environment::hot`].
    fn irradiance(&self, source: &IrradianceSource, size: u32) -> Result<Cubemap>;

    /// The preview's split-sum panel (row-major linear RGB), see
    /// [`crate::cpu::preview_split_sum`].
    fn preview_split_sum(
        &self,
        scene: &SceneUniform,
        inputs: &SplitSumInputs,
    ) -> Result<Vec<[f32; 3]>>;

    /// The preview's ground-truth panel, see [`crate::cpu::preview_truth`].
    fn preview_truth(&self, scene: &SceneUniform, inputs: &TruthInputs) -> Result<Vec<[f32; 3]>>;
}

/// The CPU reference backend.
#[derive(Debug, Default)]
pub struct CpuBackend;

impl Backend for CpuBackend {
    fn description(&self) -> String {
        format!("cpu (rayon, {} threads)", rayon::current_num_threads())
    }

    fn identity(&self) -> String {
        "cpu".into()
    }

    fn brdf_lut_model(&self, width: u32, height: u32, model: LutModel) -> Result<BrdfLut> {
        validate_lut_size(width, height)?;
        BrdfLut::assemble(model, |m| {
            Ok(cpu::lut_interpolation::brdf_lut(
                width,
                height,
                &LutQuadrature::for_model(m),
                m,
            ))
        })
    }

    fn equirect_to_cube(
        &self,
        source: &EquirectIntegral,
        params: &EquirectToCubeParams,
        mips: u32,
    ) -> Result<Cubemap> {
        let mut cube = cpu::equirect_to_cube::equirect_to_cube(source, params);
        cpu::cube_downsample::build_mips(&mut cube, mips);
        Ok(cube)
    }

    fn prefilter_specular(
        &self,
        env: &Cubemap,
        split: Option<&IrradianceSource>,
        chain: SpecularChain,
        samples: u32,
    ) -> Result<Cubemap> {
        Ok(cpu::prefilter_specular::prefilter_specular(
            env, split, chain, samples,
        ))
    }

    fn prefilter_sheen(
        &self,
        env: &Cubemap,
        split: Option<&IrradianceSource>,
        chain: SpecularChain,
    ) -> Result<Cubemap> {
        Ok(cpu::prefilter_sheen::prefilter_sheen(env, split, chain))
    }

    fn irradiance(&self, source: &IrradianceSource, size: u32) -> Result<Cubemap> {
        Ok(cpu::irradiance::irradiance(source, size))
    }

    fn preview_split_sum(
        &self,
        scene: &SceneUniform,
        inputs: &SplitSumInputs,
    ) -> Result<Vec<[f32; 3]>> {
        Ok(cpu::preview_split_sum::render_split_sum(scene, inputs))
    }

    fn preview_truth(&self, scene: &SceneUniform, inputs: &TruthInputs) -> Result<Vec<[f32; 3]>> {
        Ok(cpu::preview_truth::render_truth(scene, inputs))
    }
}

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
}

/// What `--backend auto` uses on a software adapter (Mesa's lavapipe and the like): the
/// GPU for the kernel lavapipe runs faster than the CPU backend (the preview's ground
/// truth) and the CPU reference for the others (the LUT, cube conversion, prefilter,
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
            "{} for the preview's truth, {} for the LUT, conversion, prefilter, irradiance and the preview's split-sum (software adapter)",
            self.gpu.description(),
            CpuBackend.description()
        )
    }

    fn identity(&self) -> String {
        format!(
            "{} for the preview's truth, cpu for the LUT, conversion, prefilter, irradiance and the preview's split-sum",
            self.gpu.identity()
        )
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
}

/// A backend picked by `choice`, and a note for the user when `Auto` fell back to the CPU.
pub fn create_backend(choice: BackendChoice) -> Result<(Box<dyn Backend>, Option<String>)> {
    match choice {
        BackendChoice::Cpu => Ok((Box::new(CpuBackend), None)),
        BackendChoice::Gpu => Ok((Box::new(GpuBackend::new()?), None)),
        BackendChoice::Auto => match GpuBackend::new() {
            Ok(gpu) if gpu.ctx.adapter_info.device_type == wgpu::DeviceType::Cpu => {
                Ok((Box::new(SoftwareAdapterBackend { gpu }), None))
            }
            Ok(gpu) => Ok((Box::new(gpu), None)),
            Err(e @ (Error::NoAdapter { .. } | Error::Gpu { .. })) => Ok((
                Box::new(CpuBackend),
                Some(format!("using the CPU backend: {e}")),
            )),
            Err(e) => Err(e),
        },
    }
}
