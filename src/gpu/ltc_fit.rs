//! GPU fit of the LTC table: binds `shaders/ltc_fit.wgsl` (CPU twin: `cpu::ltc_fit`,
//! `LtcTable::fit`), in the CPU's order, a dispatch a step: the normal-incidence cells one
//! at a time, r = 1 first (each cell starts from the previous one's fit), then a cell of
//! every roughness's row along θ at a time, a workgroup a row; each workgroup's
//! invocations share every quadrature.

use bytemuck::{Pod, Zeroable};

use crate::gpu::compute::{buffer_with_data, map_read, uniform_buffer, with_error_scope, ComputeKernel};
use crate::gpu::shaders;
use crate::plan::ltc::{LtcCell, LtcTable};
use crate::plan::shading::LightBrdf;
use crate::Result;

/// Invocations of a workgroup (`FIT_THREADS` in ltc_fit.wgsl): each sums 1/64 of a
/// quadrature's points.
pub const FIT_THREADS: u32 = 64;
/// Workgroup of the kernel.
pub const WORKGROUP: [u32; 3] = [FIT_THREADS, 1, 1];

/// The kernel's uniform block (`LtcFitParams` in ltc_fit.wgsl).
#[repr(C)]
#[derive(Clone, Copy, Debug, Pod, Zeroable)]
pub struct LtcFitParams {
    /// Cells per side.
    pub size: u32,
    /// `plan::shading::Masking` as its code.
    pub masking: u32,
    /// 0: the normal-incidence cells; 1: the rows along θ.
    pub stage: u32,
    /// The cell's roughness index i (stage 0) or θ index j (stage 1).
    pub step: u32,
}

/// Fits the `size`² LTC table of `brdf` (at least 2 cells a side) on the GPU.
pub fn fit_ltc(device: &wgpu::Device, queue: &wgpu::Queue, brdf: LightBrdf, size: u32) -> Result<LtcTable> {
    let size = size.max(2);
    let kernel = ComputeKernel::new(device, "ltc_fit", shaders::LTC_FIT, WORKGROUP)?;
    let cell_bytes = u64::from(size * size) * 2 * 16;
    let staging = with_error_scope(device, "ltc_fit dispatch", || {
        let cells = buffer_with_data(
            device,
            "ltc cells",
            &vec![0u8; cell_bytes as usize],
            wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_SRC,
        );
        let starts = buffer_with_data(
            device,
            "ltc starts",
            &vec![0u8; size as usize * 16],
            wgpu::BufferUsages::STORAGE,
        );
        let mut encoder = device.create_command_encoder(&Default::default());
        let normal = (0..size).rev().map(|i| (0, i, 1));
        let rows = (1..size).map(|j| (1, j, size));
        for (stage, step, groups) in normal.chain(rows) {
            let params = LtcFitParams {
                size,
                masking: brdf.masking as u32,
                stage,
                step,
            };
            let uniform = uniform_buffer(device, "ltc fit params", &params);
            kernel.dispatch(
                device,
                &mut encoder,
                &[
                    uniform.as_entire_binding(),
                    cells.as_entire_binding(),
                    starts.as_entire_binding(),
                ],
                [groups * FIT_THREADS, 1, 1],
            );
        }
        let staging = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("ltc readback"),
            size: cell_bytes,
            usage: wgpu::BufferUsages::COPY_DST | wgpu::BufferUsages::MAP_READ,
            mapped_at_creation: false,
        });
        encoder.copy_buffer_to_buffer(&cells, 0, &staging, 0, cell_bytes);
        queue.submit([encoder.finish()]);
        staging
    })?;
    let bytes = map_read(device, &staging)?;
    // Eight floats a cell (the mapped bytes need not be aligned for f32).
    let values: Vec<f32> = bytemuck::pod_collect_to_vec(&bytes);
    let cells = values
        .chunks_exact(8)
        .map(|c| LtcCell {
            inverse: [c[0], c[1], c[2], c[3]],
            norm: c[4],
            fresnel: c[5],
        })
        .collect();
    Ok(LtcTable { size, brdf, cells })
}
