//! CPU reference for `shaders/equirect_to_cube.wgsl`: every cube texel is the exact
//! solid-angle mean of the piecewise-constant equirect over the texel's footprint, so each
//! channel's ∫ L dω is kept at every cube size and a lamp's energy lands in the texels that
//! its source texel overlaps, in proportion to the overlap.
//!
//! Estimator (Green's theorem on the sphere). In (φ, y = cos θ), dω = dφ dy. With Φ(φ, y)
//! the radiance integrated along the meridian from a pole (∂Φ/∂y = L; kept per texel by
//! [`EquirectIntegral`]), the integral over a texel T is a boundary integral,
//! ∫_T L dω = −∮_∂T Φ dφ (counter-clockwise in the (φ, y) plane; the orientation cancels
//! in the ratio below). A texel's edges are great-circle arcs; each arc is split where it
//! crosses a source column's meridian, since Φ jumps between columns, and each piece is
//! integrated with a 3-point Gauss–Legendre rule in the arc parameter λ (d = a + λ(b − a),
//! dφ = (a_x b_z − a_z b_x)/(x² + z²) dλ). Φ is continuous in λ (only its slope changes
//! where the arc crosses a row), so the rule is accurate and, above all, the edge a texel
//! shares with its neighbour is computed bit for bit the same on both sides (edges are
//! integrated in one canonical direction): the texels partition each source texel's
//! energy exactly. Texels in the north use Φ from the north pole, those in the south from
//! the south pole (small numbers near either pole, so polar texels stay accurate in f32;
//! a pole at a texel's corner then adds no term). The value is ∫ L dω / ∫ dω with both
//! integrals taken by the same rule, so a constant environment is reproduced exactly.

use rayon::prelude::*;

use crate::environment::{Cubemap, EquirectIntegral};
use crate::plan::convert::EquirectToCubeParams;
use crate::math::cubemap::{cube_face_direction, rotate_y};
use crate::math::trig::atan2_precise;

/// Gauss–Legendre nodes on [−1, 1] used along each piece of an edge (the WGSL twin
/// `GAUSS_NODE` in `shaders/equirect_to_cube.wgsl` must equal it; tests/shaders.rs checks).
pub const GAUSS_NODE: f32 = 0.774_596_7;
/// Weights of the outer and centre Gauss–Legendre nodes (5/9 and 8/9).
pub const GAUSS_WEIGHTS: [f32; 2] = [0.555_555_6, 0.888_888_9];

/// ca − cb for two angles given by their cosines and sines, without the cancellation of
/// the plain difference near a pole: (sb² − sa²)/(ca + cb) when ca + cb is not small.
pub fn cos_difference(ca: f32, sa: f32, cb: f32, sb: f32) -> f32 {
    let sum = ca + cb;
    if sum.abs() >= 0.5 {
        (sb - sa) * (sb + sa) / sum
    } else {
        ca - cb
    }
}

/// Column of the (unnormalised) direction `d` in a `width`-column equirect.
pub fn column_of(width: u32, d: [f32; 3]) -> u32 {
    let u = 0.5 + atan2_precise(d[2], d[0]) / (2.0 * std::f32::consts::PI);
    ((u * width as f32).floor().max(0.0) as u32).min(width - 1)
}

/// Φ at the (unnormalised) direction `d`, which lies in column `col`: the radiance
/// integrated along the meridian from the north pole (negated, so that ∂Φ/∂y = L) or from
/// the south pole, and the same for a radiance of 1 (the solid-angle integrand).
pub fn meridian_cumulative(
    src: &EquirectIntegral,
    col: u32,
    d: [f32; 3],
    north: bool,
) -> ([f32; 3], f32) {
    let h2 = d[0] * d[0] + d[2] * d[2];
    let h = h2.sqrt();
    let rho = (h2 + d[1] * d[1]).sqrt();
    let (c, s) = (d[1] / rho, h / rho);
    let theta = atan2_precise(h, d[1]);
    let row = ((theta * src.height as f32 / std::f32::consts::PI) as u32).min(src.height - 1);
    let i = src.index(col, row);
    let l = src.radiance[i];
    if north {
        let [cr, sr, one_minus_cr, _] = src.rows[row as usize];
        let dc = cos_difference(cr, sr, c, s);
        let n = src.from_north[i];
        ([0, 1, 2].map(|k| -(n[k] + l[k] * dc)), -(one_minus_cr + dc))
    } else {
        let [cr, sr, _, one_plus_cr] = src.rows[row as usize + 1];
        let dc = cos_difference(c, s, cr, sr);
        let n = src.from_south[i];
        ([0, 1, 2].map(|k| n[k] + l[k] * dc), one_plus_cr + dc)
    }
}

/// ∫ Φ dφ along the great-circle arc from `a` to `b` (unnormalised directions less than
/// a half-turn apart in φ): radiance and solid-angle parts.
pub fn edge_integral(src: &EquirectIntegral, a: [f32; 3], b: [f32; 3], north: bool) -> [f32; 4] {
    let mut acc = [0.0f32; 4];
    let cross = a[0] * b[2] - a[2] * b[0];
    if cross == 0.0 {
        return acc; // a meridian (or a point): dφ = 0 along it
    }
    let dir = [b[0] - a[0], b[1] - a[1], b[2] - a[2]];
    let w = src.width;
    let (ka, kb) = (column_of(w, a), column_of(w, b));
    let up = cross > 0.0;
    let mut count = if up {
        (kb + w - ka) % w
    } else {
        (ka + w - kb) % w
    };
    if count > w / 2 {
        count = 0; // a and b in one column, rounded onto either side of its boundary
    }
    let mut lam0 = 0.0f32;
    let mut col = ka;
    for step in 0..=count {
        let (lam1, next) = if step < count {
            let m = src.columns[(if up { col + 1 } else { col }) as usize];
            let am = a[0] * m[0] + a[2] * m[1];
            let dm = dir[0] * m[0] + dir[2] * m[1];
            let lam = if dm != 0.0 {
                (-am / dm).clamp(lam0, 1.0)
            } else {
                lam0
            };
            (lam, if up { (col + 1) % w } else { (col + w - 1) % w })
        } else {
            (1.0, col)
        };
        let half = 0.5 * (lam1 - lam0);
        if half > 0.0 {
            let mid = lam0 + half;
            for (offset, weight) in [
                (-GAUSS_NODE, GAUSS_WEIGHTS[0]),
                (0.0, GAUSS_WEIGHTS[1]),
                (GAUSS_NODE, GAUSS_WEIGHTS[0]),
            ] {
                let lam = mid + offset * half;
                let d = [
                    a[0] + lam * dir[0],
                    a[1] + lam * dir[1],
                    a[2] + lam * dir[2],
                ];
                let dphi = cross / (d[0] * d[0] + d[2] * d[2]);
                let (phi, area) = meridian_cumulative(src, col, d, north);
                let wgt = weight * half * dphi;
                for k in 0..3 {
                    acc[k] += wgt * phi[k];
                }
                acc[3] += wgt * area;
            }
        }
        lam0 = lam1;
        col = next;
    }
    acc
}

/// [`edge_integral`] computed in one canonical direction (from the lexicographically
/// smaller end), so the two texels sharing an edge get the same numbers, negated.
pub fn oriented_edge_integral(
    src: &EquirectIntegral,
    a: [f32; 3],
    b: [f32; 3],
    north: bool,
) -> [f32; 4] {
    let less = a[0] < b[0] || (a[0] == b[0] && (a[1] < b[1] || (a[1] == b[1] && a[2] < b[2])));
    if less {
        edge_integral(src, a, b, north)
    } else {
        edge_integral(src, b, a, north).map(|v| -v)
    }
}

/// Corner (i, j) of the texel grid of `face` (i, j ∈ 0..=n), unnormalised, in the
/// source's frame: the environment rotated by +angle shows, in direction d, what the
/// source shows in direction R(−angle)·d.
fn texel_corner(p: &EquirectToCubeParams, face: u32, i: u32, j: u32) -> [f32; 3] {
    let inv = 2.0 / p.face_size as f32;
    let (s, t) = (i as f32 * inv - 1.0, j as f32 * inv - 1.0);
    rotate_y(
        cube_face_direction(face, s, t),
        p.rotation[0],
        -p.rotation[1],
    )
}

/// Whether texel row `j` of `face` integrates Φ from the north pole: its centre is in the
/// northern hemisphere (on every face y depends on the row alone).
fn row_is_north(p: &EquirectToCubeParams, face: u32, j: u32) -> bool {
    let inv = 2.0 / p.face_size as f32;
    let t = (j as f32 + 0.5) * inv - 1.0;
    cube_face_direction(face, 0.0, t)[1] >= 0.0
}

/// A texel's value from its four oriented edge integrals (top, right, bottom, left, each
/// in the direction of the texel's boundary v00 → v10 → v11 → v01 → v00): ∫ L dω / ∫ dω.
fn texel_from_edges(edges: [[f32; 4]; 4]) -> [f32; 4] {
    let mut sum = [0.0f32; 4];
    for e in edges {
        for c in 0..4 {
            sum[c] += e[c];
        }
    }
    [sum[0] / sum[3], sum[1] / sum[3], sum[2] / sum[3], 1.0]
}

#[cfg(any(test, feature = "internals"))]
/// One output texel: the exact footprint mean of the source.
pub fn equirect_to_cube_texel(
    src: &EquirectIntegral,
    p: &EquirectToCubeParams,
    face: u32,
    i: u32,
    j: u32,
) -> [f32; 4] {
    let v = [
        texel_corner(p, face, i, j),
        texel_corner(p, face, i + 1, j),
        texel_corner(p, face, i + 1, j + 1),
        texel_corner(p, face, i, j + 1),
    ];
    let north = row_is_north(p, face, j);
    texel_from_edges([0, 1, 2, 3].map(|k| oriented_edge_integral(src, v[k], v[(k + 1) % 4], north)))
}


/// Level 0 of the cube (one level; see `cube_downsample` for the chain). Equal, bit for
/// bit, to [`equirect_to_cube_texel`] at every texel (what the GPU kernel computes), but
/// each edge is integrated once for the two texel rows or columns that share it.
pub fn equirect_to_cube(src: &EquirectIntegral, p: &EquirectToCubeParams) -> Cubemap {
    let n = p.face_size;
    let band = n.min(8) as usize; // texel rows per task (a power of two dividing n)
    let mut level = vec![[0.0f32; 4]; Cubemap::level_len(n)];
    level
        .par_chunks_mut(band * n as usize)
        .enumerate()
        .for_each(|(chunk, out)| {
            let first = (chunk * band) as u32;
            let (face, j0) = (first / n, first % n);
            let corner = |i: u32, j: u32| texel_corner(p, face, i, j);
            let row_edges = |j: u32, north: bool| -> Vec<[f32; 4]> {
                (0..n)
                    .map(|i| oriented_edge_integral(src, corner(i, j), corner(i + 1, j), north))
                    .collect()
            };
            let mut top: Option<(bool, Vec<[f32; 4]>)> = None;
            for (r, row) in out.chunks_mut(n as usize).enumerate() {
                let j = j0 + r as u32;
                let north = row_is_north(p, face, j);
                let upper = match top.take() {
                    Some((variant, edges)) if variant == north => edges,
                    _ => row_edges(j, north),
                };
                let lower = row_edges(j + 1, north);
                let sides: Vec<[f32; 4]> = (0..=n)
                    .map(|i| oriented_edge_integral(src, corner(i, j), corner(i, j + 1), north))
                    .collect();
                for (i, t) in row.iter_mut().enumerate() {
                    *t = texel_from_edges([
                        upper[i],
                        sides[i + 1],
                        lower[i].map(|v| -v),
                        sides[i].map(|v| -v),
                    ]);
                }
                top = Some((north, lower));
            }
        });
    Cubemap {
        size: p.face_size,
        levels: vec![level],
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::environment::Equirect;

    /// The shared-edge level equals, bit for bit, the per-texel function (the GPU's).
    #[test]
    fn shared_edges_equal_the_per_texel_kernel() {
        let (w, h) = (64u32, 32u32);
        let data = (0..w * h)
            .map(|k| {
                let v = (k.wrapping_mul(2_654_435_761) % 1000) as f32;
                [v, 0.5 * v + 1.0, (k % 7) as f32]
            })
            .collect();
        let src = EquirectIntegral::new(Equirect {
            width: w,
            height: h,
            data,
        });
        for (n, rotate) in [(8u32, 0.0f32), (4, 37.0), (1, 0.0)] {
            let p = EquirectToCubeParams::new(n, w, h, rotate);
            let cube = equirect_to_cube(&src, &p);
            for face in 0..6 {
                for j in 0..n {
                    for i in 0..n {
                        assert_eq!(
                            cube.texel(0, face, i, j),
                            equirect_to_cube_texel(&src, &p, face, i, j),
                            "{n} rotated {rotate}: face {face} ({i}, {j})"
                        );
                    }
                }
            }
        }
    }
}
