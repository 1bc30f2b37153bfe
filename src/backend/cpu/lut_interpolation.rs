//! The whole BRDF LUT on the CPU with far fewer integrals than texels: exact quadrature
//! ([`brdf_lut_texel`]) on a coarse grid, tensor-product cubic Lagrange interpolation
//! between its nodes, and a check of that interpolation in every coarse cell.
//!
//! # Estimator and error control
//! The coarse grid takes every 4th column and 8th row ([`LUT_COARSE_STEP`]) plus the last
//! ones, so no texel is extrapolated. A texel between nodes is the tensor product of 4-point
//! Lagrange interpolants through the nearest coarse nodes (the stencil shifts inward at the
//! edges). Its error is ω(x) f⁽⁴⁾/4! per axis with ω(x) = Π (x − xₖ), largest near the
//! middle of the cell (A&S 25.2.2; |ω| is 0.56 h⁴ there and 0.41 h⁴ a quarter cell off), so
//! every cell integrates its middle texel exactly and compares: where the interpolant is
//! off by more than [`LUT_INTERPOLATION_TOLERANCE`] · max(1, |value|) in either channel
//! (near grazing n·v at small roughness, where the horizon makes the table steep), every
//! texel of the cell and of its eight neighbours, edges included, is integrated exactly
//! instead. The neighbours are included because their stencils reach into the failed
//! cell: without them the Charlie table kept interpolated texels 1.8e-4 off beside steep
//! cells whose own checks passed. Interpolated values are clamped at 0, as every channel
//! integrates a non-negative integrand.
//!
//! The result differs from integrating every texel ([`brdf_lut_exact`], which the GPU
//! kernel mirrors) by at most a few times the tolerance; tests/lut_accuracy.rs measures the
//! difference at every texel of every model and the total error against a converged
//! reference. The GPU integrates every texel: there a texel costs less than a readback.

use rayon::prelude::*;

use crate::cpu::brdf_lut::{brdf_lut_exact, brdf_lut_texel};
use crate::plan::lut::{lut_texel_coords, BrdfLut, LutModel, LutQuadrature, LUT_COARSE_STEP, LUT_INTERPOLATION_TOLERANCE};

/// The coarse nodes of one axis of `n` texels and, for every texel, its cell and
/// interpolation stencil.
struct Axis {
    /// Texel indices of the coarse nodes, increasing, the last one n − 1.
    nodes: Vec<u32>,
    /// Per texel: the index (into `nodes`) of its stencil's first node and the four
    /// Lagrange weights.
    stencil: Vec<(usize, [f32; 4])>,
}

impl Axis {
    /// `None` when the axis has fewer than four nodes (a table that small is integrated
    /// texel by texel).
    fn new(n: u32, step: u32) -> Option<Axis> {
        let mut nodes: Vec<u32> = (0..n).step_by(step as usize).collect();
        if *nodes.last()? != n - 1 {
            nodes.push(n - 1);
        }
        if nodes.len() < 4 {
            return None;
        }
        let mut cell = 0;
        let stencil = (0..n)
            .map(|i| {
                while cell + 2 < nodes.len() && nodes[cell + 1] <= i {
                    cell += 1;
                }
                let start = cell.saturating_sub(1).min(nodes.len() - 4);
                let x = |k: usize| nodes[start + k] as f64;
                let mut w = [0.0f32; 4];
                for (k, wk) in w.iter_mut().enumerate() {
                    // Lagrange basis ℓₖ(i) = Π_{m≠k} (i − xₘ) / (xₖ − xₘ)
                    let mut l = 1.0f64;
                    for m in (0..4).filter(|&m| m != k) {
                        l *= (i as f64 - x(m)) / (x(k) - x(m));
                    }
                    *wk = l as f32;
                }
                (start, w)
            })
            .collect();
        Some(Axis { nodes, stencil })
    }

    /// Number of cells (gaps between consecutive nodes).
    fn cells(&self) -> usize {
        self.nodes.len() - 1
    }

    /// The middle texel of cell `c`.
    fn middle(&self, c: usize) -> u32 {
        (self.nodes[c] + self.nodes[c + 1]) / 2
    }
}

/// The LUT of `model`, integrated exactly at the coarse nodes, at each cell's check texel
/// and in the cells whose check failed, and interpolated elsewhere (see the module doc).
/// Tables too small for a 4×4 coarse grid are integrated at every texel.
pub fn brdf_lut(width: u32, height: u32, quad: &LutQuadrature, model: LutModel) -> BrdfLut {
    interpolated_lut(width, height, quad, model).lut
}

/// A LUT from [`interpolated_lut`] and how many of its texels were integrated.
#[derive(Clone, Debug)]
pub struct InterpolatedLut {
    /// The table.
    pub lut: BrdfLut,
    /// Texels integrated exactly (nodes, checks and failed cells); the rest were
    /// interpolated. (Reported by the tests and benchmarks.)
    #[cfg_attr(not(feature = "internals"), allow(dead_code))]
    pub integrated: usize,
}

/// [`brdf_lut`] with the count of integrated texels (for tests and benchmarks).
pub fn interpolated_lut(
    width: u32,
    height: u32,
    quad: &LutQuadrature,
    model: LutModel,
) -> InterpolatedLut {
    let (Some(ax), Some(ay)) = (
        Axis::new(width, LUT_COARSE_STEP[0]),
        Axis::new(height, LUT_COARSE_STEP[1]),
    ) else {
        return InterpolatedLut {
            lut: brdf_lut_exact(width, height, quad, model),
            integrated: (width * height) as usize,
        };
    };
    let exact = |i: u32, j: u32| {
        let (n_dot_v, roughness) = lut_texel_coords(i, j, width, height);
        brdf_lut_texel(n_dot_v, roughness, quad, model)
    };
    let (nx, ny) = (ax.nodes.len(), ay.nodes.len());
    // Coarse values, row-major over (node y, node x).
    let coarse: Vec<[f32; 2]> = (0..nx * ny)
        .into_par_iter()
        .map(|k| exact(ax.nodes[k % nx], ay.nodes[k / nx]))
        .collect();
    let interpolate = |i: u32, j: u32| {
        let (sx, wx) = ax.stencil[i as usize];
        let (sy, wy) = ay.stencil[j as usize];
        let mut v = [0.0f32; 2];
        for (b, wb) in wy.iter().enumerate() {
            let row = &coarse[(sy + b) * nx + sx..(sy + b) * nx + sx + 4];
            for (c, wa) in row.iter().zip(wx) {
                let w = wa * wb;
                v[0] += w * c[0];
                v[1] += w * c[1];
            }
        }
        // Every channel integrates a non-negative integrand; a cubic through values near
        // 0 (B where Fc vanishes) can overshoot below it by the tolerance.
        [v[0].max(0.0), v[1].max(0.0)]
    };
    // Check every cell at its middle texel.
    let cells = ax.cells() * ay.cells();
    let checks: Vec<((u32, u32), [f32; 2], bool)> = (0..cells)
        .into_par_iter()
        .map(|c| {
            let (i, j) = (ax.middle(c % ax.cells()), ay.middle(c / ax.cells()));
            let (e, p) = (exact(i, j), interpolate(i, j));
            let ok = (0..2)
                .all(|k| (e[k] - p[k]).abs() <= LUT_INTERPOLATION_TOLERANCE * e[k].abs().max(1.0));
            ((i, j), e, ok)
        })
        .collect();
    // Texels already known (nodes and checks) are stored; a failed cell's other texels,
    // its edges included, are integrated; the rest are interpolated.
    const INTERPOLATE: u8 = 0;
    const KNOWN: u8 = 1;
    const INTEGRATE: u8 = 2;
    let at = |i: u32, j: u32| (j * width + i) as usize;
    let mut data = vec![[0.0f32; 2]; (width * height) as usize];
    let mut state = vec![INTERPOLATE; data.len()];
    for (k, v) in coarse.iter().enumerate() {
        let t = at(ax.nodes[k % nx], ay.nodes[k / nx]);
        data[t] = *v;
        state[t] = KNOWN;
    }
    for &((i, j), e, _) in &checks {
        data[at(i, j)] = e;
        state[at(i, j)] = KNOWN;
    }
    for (c, _) in checks.iter().enumerate().filter(|(_, check)| !check.2) {
        let (cx, cy) = (c % ax.cells(), c / ax.cells());
        let (x0, x1) = (cx.saturating_sub(1), (cx + 2).min(ax.cells()));
        let (y0, y1) = (cy.saturating_sub(1), (cy + 2).min(ay.cells()));
        for j in ay.nodes[y0]..=ay.nodes[y1] {
            for i in ax.nodes[x0]..=ax.nodes[x1] {
                if state[at(i, j)] != KNOWN {
                    state[at(i, j)] = INTEGRATE;
                }
            }
        }
    }
    data.par_chunks_mut(width as usize)
        .zip(state.par_chunks(width as usize))
        .enumerate()
        .for_each(|(j, (row, states))| {
            let j = j as u32;
            for (i, (texel, &s)) in row.iter_mut().zip(states).enumerate() {
                let i = i as u32;
                match s {
                    INTEGRATE => *texel = exact(i, j),
                    INTERPOLATE => *texel = interpolate(i, j),
                    _ => {}
                }
            }
        });
    InterpolatedLut {
        integrated: state.iter().filter(|&&s| s != INTERPOLATE).count(),
        lut: BrdfLut::new(width, height, data),
    }
}
