//! The compute backends: one trait, a CPU implementation (the reference, usable on machines
//! without a GPU) and a GPU one (wgpu). Tests run every kernel through both.

pub mod cpu;
pub mod gpu;
mod shared_ltc;

pub use cpu::CpuBackend;
pub use gpu::{GpuBackend, SoftwareAdapterBackend};
pub use shared_ltc::{shared_ltc_table, SHARED_TABLE_SIZE};

use crate::environment::{Cubemap, EquirectIntegral, IrradianceSource};
use crate::plan::bc6h::Bc6hQuality;
use crate::plan::chain::SpecularChain;
use crate::plan::convert::EquirectToCubeParams;
use crate::plan::ltc::LtcTable;
use crate::plan::lut::{BrdfLut, LutModel};
use crate::plan::scene::{SceneUniform, SplitSumInputs, TruthInputs};
use crate::plan::shading::LightBrdf;
use crate::{Error, Result};

/// Which backend the user asked for.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum BackendChoice {
    /// A GPU adapter when one exists, the CPU otherwise; on a software adapter (lavapipe)
    /// each kernel runs where it is faster (the CPU for the bake's kernels, the adapter for
    /// the preview's ground truth).
    #[default]
    Auto,
    /// wgpu only; fails when no adapter exists.
    Gpu,
    /// The CPU reference implementation.
    Cpu,
}

/// What a backend is asked to run, for the description of where it runs: a software adapter
/// runs some jobs on the GPU and the rest on the CPU.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum BackendJob {
    /// A bake, a cube conversion or a LUT.
    Bake,
    /// A preview: a bake, its split-sum render and its ground truth.
    Preview,
    /// The LTC table's fit (`lut --ltc`).
    LtcFit,
}

/// The kernels splitsum runs; each backend implements all of them.
pub trait Backend {
    /// A human-readable description ("cpu (rayon, 2 threads)", "gpu: NVIDIA ... (Vulkan)").
    fn description(&self) -> String;

    /// [`Backend::description`] for `job`: where its kernels run.
    fn description_for(&self, job: BackendJob) -> String {
        let _ = job;
        self.description()
    }

    /// What determines the outputs, for manifests: the adapter of a GPU backend, but not
    /// the CPU backend's thread count (every texel is computed the same way however the
    /// work is split), so equal bakes on different machines give equal manifests.
    fn identity(&self) -> String {
        self.description()
    }

    /// Where [`Backend::encode_bc6h`] runs, for manifests: "cpu" or the GPU adapter.
    fn bc6h_identity(&self) -> String {
        self.identity()
    }

    /// The BRDF LUT of `model` (see [`crate::plan::lut`]).
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
    /// level m at roughness m/(M − 1), see [`cpu::specular::prefilter_specular`]. With the
    /// bake's split source (`split`), exact levels sum the hot cells at source resolution.
    fn prefilter_specular(
        &self,
        env: &Cubemap,
        split: Option<&IrradianceSource>,
        chain: SpecularChain,
        samples: u32,
    ) -> Result<Cubemap>;

    /// The prefiltered Charlie sheen chain of `env` (which has every mip) in `chain`'s
    /// layout, see [`cpu::sheen::prefilter_sheen`]; with the split source its exact sums
    /// read the hot cells at source resolution.
    fn prefilter_sheen(
        &self,
        env: &Cubemap,
        split: Option<&IrradianceSource>,
        chain: SpecularChain,
    ) -> Result<Cubemap>;

    /// The irradiance cube (E/π) of edge `size` from the split source, see
    /// [`cpu::irradiance::irradiance`] and [`crate::environment::hot`].
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

    /// The BC6H blocks of every level of `cube`, each level its six faces one after the
    /// other (see [`crate::plan::bc6h`]).
    fn encode_bc6h(&self, cube: &Cubemap, quality: Bc6hQuality) -> Result<Vec<Vec<u8>>>;

    /// The `size`² LTC table of `brdf` (see [`crate::plan::ltc`]).
    fn fit_ltc(&self, brdf: LightBrdf, size: u32) -> Result<LtcTable>;
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
