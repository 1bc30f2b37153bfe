//! `splitsum verify`: every kernel on the GPU and on the CPU reference, on a reduced
//! problem, with the tolerances the tests state (and their reasons, in `tests/`).

use crate::stages::convert::environment_to_cube;
use crate::plan::chain::SpecularChain;
use crate::environment::{Cubemap, Environment, IrradianceSource};
use crate::backend::{Backend, CpuBackend, GpuBackend};
use crate::Result;

/// LUT: |gpu − cpu| ≤ 5e-5 (tests/gpu_vs_cpu.rs).
pub const LUT_TOLERANCE: f32 = 5e-5;
/// Cube conversion: relative 1e-4 of the texel + 1e-6 of the image maximum
/// (tests/cubemap.rs).
pub const CUBEMAP_TOLERANCE: f32 = 1e-4;
/// Prefilter and irradiance: relative 1e-3 of the texel + 1e-5 of the level maximum
/// (tests/specular.rs).
pub const CONVOLUTION_TOLERANCE: f32 = 1e-3;

/// One row of the verify table.
#[derive(Clone, Debug)]
pub struct VerifyRow {
    /// Kernel name.
    pub kernel: &'static str,
    /// Largest absolute difference.
    pub max_abs: f32,
    /// Largest difference relative to the texel.
    pub max_rel: f32,
    /// The relative tolerance.
    pub tolerance: f32,
    /// Whether every texel is within tolerance.
    pub pass: bool,
}

/// Compares two cubes texel by texel: |a − b| ≤ tol·|b| + floor·max(level).
pub fn compare(kernel: &'static str, a: &Cubemap, b: &Cubemap, tol: f32, floor: f32) -> VerifyRow {
    let (mut max_abs, mut max_rel, mut pass) = (0.0f32, 0.0f32, a.levels.len() == b.levels.len());
    for (la, lb) in a.levels.iter().zip(&b.levels) {
        let max = lb
            .iter()
            .flat_map(|t| t[..3].to_vec())
            .fold(0.0f32, f32::max);
        for (ta, tb) in la.iter().zip(lb) {
            for c in 0..3 {
                let d = (ta[c] - tb[c]).abs();
                max_abs = max_abs.max(d);
                max_rel = max_rel.max(d / tb[c].abs().max(1e-6));
                pass &= d <= tol * tb[c].abs() + floor * max;
            }
        }
    }
    VerifyRow {
        kernel,
        max_abs,
        max_rel,
        tolerance: tol,
        pass,
    }
}

/// Runs the kernels on `gpu` and the CPU for `env` reduced to a 64² cube.
pub fn verify(gpu: &GpuBackend, env: &Environment) -> Result<Vec<VerifyRow>> {
    let cpu = CpuBackend;
    let mut rows = Vec::new();
    // The GPU integrates every texel; so does this CPU table (the CPU backend's own
    // interpolates most of them, which tests/lut_accuracy.rs checks separately).
    let quad = crate::plan::lut::LutQuadrature::default();
    let b = crate::cpu::brdf_lut::brdf_lut_exact(64, 64, &quad, Default::default());
    let a = gpu.brdf_lut(64, 64)?;
    let max_abs = a
        .data
        .iter()
        .zip(&b.data)
        .map(|(x, y)| (x[0] - y[0]).abs().max((x[1] - y[1]).abs()))
        .fold(0.0f32, f32::max);
    rows.push(VerifyRow {
        kernel: "brdf_lut 64",
        max_abs,
        max_rel: max_abs,
        tolerance: LUT_TOLERANCE,
        pass: max_abs <= LUT_TOLERANCE,
    });
    let ga = environment_to_cube(gpu, env, 64, true, 0.0)?;
    let gb = environment_to_cube(&cpu, env, 64, true, 0.0)?;
    rows.push(compare(
        "equirect_to_cube 64",
        &ga,
        &gb,
        CUBEMAP_TOLERANCE,
        1e-6,
    ));
    let (sa, sb) = (
        gpu.prefilter_specular(
            &gb,
            None,
            SpecularChain::linear(Cubemap::full_mip_count(gb.size)),
            32,
        )?,
        cpu.prefilter_specular(
            &gb,
            None,
            SpecularChain::linear(Cubemap::full_mip_count(gb.size)),
            32,
        )?,
    );
    rows.push(compare(
        "prefilter_specular 64",
        &sa,
        &sb,
        CONVOLUTION_TOLERANCE,
        1e-5,
    ));
    let source = IrradianceSource::from_cube(&gb);
    let (ia, ib) = (gpu.irradiance(&source, 16)?, cpu.irradiance(&source, 16)?);
    rows.push(compare(
        "irradiance 16",
        &ia,
        &ib,
        CONVOLUTION_TOLERANCE,
        1e-5,
    ));
    Ok(rows)
}

/// What [`verify_input`] found: the adapter and one row per kernel.
#[derive(Clone, Debug)]
pub struct Verification {
    /// The GPU adapter, in words.
    pub adapter: String,
    /// One row per kernel.
    pub rows: Vec<VerifyRow>,
}

impl Verification {
    /// Whether every kernel is within its tolerance.
    pub fn passed(&self) -> bool {
        self.rows.iter().all(|r| r.pass)
    }
}

/// Reads `input` and runs every kernel on the default GPU adapter and on the CPU
/// reference, on a reduced problem (a 64² cube), with the tolerances the tests state.
pub fn verify_input(input: &std::path::Path) -> Result<Verification> {
    let loaded = crate::io::input::load_environment(input, &Default::default())?;
    let gpu = GpuBackend::new()?;
    let rows = verify(&gpu, &loaded.env)?;
    Ok(Verification {
        adapter: gpu.ctx.adapter_description(),
        rows,
    })
}
