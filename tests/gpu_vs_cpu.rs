//! The LUT kernel on the GPU against its CPU twin, every model. (The other kernels are
//! compared with their CPU twins beside their accuracy tests: conversion in
//! `tests/cubemap.rs`, prefilter and irradiance in `tests/specular.rs`, the sheen chain in
//! `tests/sheen.rs`, the preview's renders in `tests/preview.rs`.)
mod common;

use splitsum::plan::lut::{LutModel, LutQuadrature};

/// GPU vs CPU tolerance for the LUT. Both sides run the same quadrature, with the same f32
/// node tables and the same polynomial acos (`math::trig`), in f32; they differ through
/// the GPU's cos, sin and sqrt (Vulkan allows cos/sin 2⁻¹¹ absolute in the worst case;
/// real GPUs and lavapipe are within ~1e-6) and fused multiply-adds. Measured: ~1e-6 on
/// lavapipe. 5e-5 is half the LUT's accuracy budget, so a GPU within it still meets the
/// 1e-4 quality bar.
const LUT_GPU_TOLERANCE: f32 = 5e-5;

#[test]
fn brdf_lut_gpu_matches_cpu() {
    let Some(ctx) = common::gpu() else { return };
    let quad = LutQuadrature::default();
    let sizes = [(64u32, 32u32), (128, 128)];
    for (model, (w, h)) in LutModel::singles().flat_map(|m| sizes.map(|s| (m, s))) {
        let gpu =
            splitsum::gpu::brdf_lut::brdf_lut(&ctx.device, &ctx.queue, w, h, &quad, model).unwrap();
        let cpu = splitsum::cpu::brdf_lut::brdf_lut_exact(w, h, &quad, model);
        assert_eq!((gpu.width, gpu.height), (w, h));
        let max = gpu
            .data
            .iter()
            .zip(&cpu.data)
            .map(|(g, c)| (g[0] - c[0]).abs().max((g[1] - c[1]).abs()))
            .fold(0.0f32, f32::max);
        println!(
            "{} {w}x{h} on {}: max |gpu - cpu| = {max:.2e}",
            model.name(),
            ctx.adapter_description()
        );
        assert!(max <= LUT_GPU_TOLERANCE, "{} {w}x{h}: {max}", model.name());
    }
}
