//! The CPU backend: the twins in [`crate::cpu`] driven over every texel with rayon, with
//! faster sums of the same terms where a kernel's loop dominates (lanes for the exact
//! sums, runs for the irradiance, interpolation where the LUT is smooth), each checked
//! against the texel-by-texel twin in its tests.

pub mod astc;
pub mod bc6h;
pub mod irradiance;
pub mod lanes;
pub mod lut_interpolation;
pub mod sheen;
pub mod specular;

use crate::backend::Backend;
use crate::cpu;
use crate::environment::{Cubemap, EquirectIntegral, IrradianceSource};
use crate::plan::bc6h::Bc6hQuality;
use crate::plan::chain::SpecularChain;
use crate::plan::convert::EquirectToCubeParams;
use crate::plan::ltc::LtcTable;
use crate::plan::lut::{validate_lut_size, BrdfLut, LutModel, LutQuadrature};
use crate::plan::scene::{SceneUniform, SplitSumInputs, TruthInputs};
use crate::plan::shading::LightBrdf;
use crate::Result;

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
            Ok(lut_interpolation::brdf_lut(
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
        crate::environment::mips::build_mips(&mut cube, mips);
        Ok(cube)
    }

    fn prefilter_specular(
        &self,
        env: &Cubemap,
        split: Option<&IrradianceSource>,
        chain: SpecularChain,
        samples: u32,
    ) -> Result<Cubemap> {
        Ok(specular::prefilter_specular(
            env, split, chain, samples,
        ))
    }

    fn prefilter_sheen(
        &self,
        env: &Cubemap,
        split: Option<&IrradianceSource>,
        chain: SpecularChain,
    ) -> Result<Cubemap> {
        Ok(sheen::prefilter_sheen(env, split, chain))
    }

    fn irradiance(&self, source: &IrradianceSource, size: u32) -> Result<Cubemap> {
        Ok(irradiance::irradiance(source, size))
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

    fn encode_bc6h(&self, cube: &Cubemap, quality: Bc6hQuality) -> Result<Vec<Vec<u8>>> {
        Ok(bc6h::encode_bc6h(cube, quality))
    }

    fn fit_ltc(&self, brdf: LightBrdf, size: u32) -> Result<LtcTable> {
        Ok(LtcTable::fit(brdf, size))
    }
}
