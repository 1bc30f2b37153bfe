//! Seamless bilinear and trilinear lookups of a cube mip chain. Mirror of
//! `shaders/common/cube_bilinear.wgsl` and `cube_sample.wgsl` (same function names).
//!
//! A bilinear tap that falls off a face is fetched from the neighbouring face: the missing
//! texel's centre is extended on the face plane, turned into a direction and re-projected,
//! so filtering is continuous across edges (no seams at small mips).

use crate::environment::Cubemap;
use crate::math::cubemap::{cube_face_coords, cube_face_jacobian, cube_texel_direction};

/// ⌊x⌋ for |x| < 2³¹, exactly as WGSL's `floor` then a conversion: truncation, one less
/// where that rounded a negative x up. `f32::floor` is a libm call on x86-64 without
/// SSE4.1, and these lookups call it three times a tap (6 % of a default bake's time).
#[inline]
pub fn floor_i32(x: f32) -> i32 {
    let t = x as i32;
    t - ((t as f32) > x) as i32
}

/// Texel (x, y) of `face` at mip `m`, where x or y may be −1 or n (one texel off the face):
/// those are fetched from the face the extended texel centre points into.
pub fn fetch_cube_texel(cube: &Cubemap, m: usize, face: u32, x: i32, y: i32) -> [f32; 3] {
    let n = cube.level_size(m) as i32;
    let (mut f, mut xi, mut yi) = (face, x, y);
    if x < 0 || y < 0 || x >= n || y >= n {
        let (f2, s2, t2) = cube_face_coords(cube_texel_direction(face, x, y, n as u32));
        f = f2;
        xi = floor_i32((s2 + 1.0) * 0.5 * n as f32).clamp(0, n - 1);
        yi = floor_i32((t2 + 1.0) * 0.5 * n as f32).clamp(0, n - 1);
    }
    let t = cube.texel(m, f, xi as u32, yi as u32);
    [t[0], t[1], t[2]]
}

/// Seamless bilinear lookup of mip `m` at face coordinates (s, t) ∈ [−1, 1]² of `face`.
/// When the 2×2 footprint lies inside the face (nearly always at large mips) the four
/// texels are read directly; otherwise each tap goes through [`fetch_cube_texel`]. Both
/// paths sum the taps in the same order, so the result does not depend on the path.
pub fn sample_face_bilinear(cube: &Cubemap, m: usize, face: u32, s: f32, t: f32) -> [f32; 3] {
    let n = cube.level_size(m);
    let (xi, yi, weights) = bilinear_footprint(n, s, t);
    let inside = xi >= 0 && yi >= 0 && xi + 1 < n as i32 && yi + 1 < n as i32;
    if inside {
        let base = ((face * n + yi as u32) * n + xi as u32) as usize;
        let n = n as usize;
        let level = &cube.levels[m];
        return weighted_taps(
            [base, base + 1, base + n, base + n + 1].map(|k| level[k]),
            weights,
        );
    }
    let taps = [(0, 0), (1, 0), (0, 1), (1, 1)].map(|(dx, dy)| {
        let [r, g, b] = fetch_cube_texel(cube, m, face, xi + dx, yi + dy);
        [r, g, b, 1.0]
    });
    weighted_taps(taps, weights)
}

/// The 2×2 footprint of a bilinear lookup at face coordinates (s, t) of an n² face: the
/// texel (xi, yi) of its lower corner (−1 … n − 1) and the weights of the taps (0, 0),
/// (1, 0), (0, 1), (1, 1).
#[inline(always)]
fn bilinear_footprint(n: u32, s: f32, t: f32) -> (i32, i32, [f32; 4]) {
    let x = (s + 1.0) * 0.5 * n as f32 - 0.5;
    let y = (t + 1.0) * 0.5 * n as f32 - 0.5;
    let (xi, yi) = (floor_i32(x), floor_i32(y));
    let (fx, fy) = (x - xi as f32, y - yi as f32);
    let weights = [
        (1.0 - fx) * (1.0 - fy),
        fx * (1.0 - fy),
        (1.0 - fx) * fy,
        fx * fy,
    ];
    (xi, yi, weights)
}

/// Σ wₖ tapₖ over rgb, in tap order (so every path that reads the same four texels gives
/// the same bits).
#[inline(always)]
fn weighted_taps(taps: [[f32; 4]; 4], weights: [f32; 4]) -> [f32; 3] {
    let mut out = [0.0f32; 3];
    for (v, w) in taps.into_iter().zip(weights) {
        for c in 0..3 {
            out[c] += w * v[c];
        }
    }
    out
}

/// The trilinear blend of a chain of `levels` at `lod` (clamped to it) around `d`, with
/// `bilinear(m, face, s, t)` reading one level; an integral lod reads one level only.
#[inline(always)]
fn trilinear(
    levels: usize,
    d: [f32; 3],
    lod: f32,
    bilinear: impl Fn(usize, u32, f32, f32) -> [f32; 3],
) -> [f32; 3] {
    let last = (levels - 1) as f32;
    let lod = lod.clamp(0.0, last);
    let l0 = floor_i32(lod) as f32;
    let f = lod - l0;
    let (face, s, t) = cube_face_coords(d);
    let a = bilinear(l0 as usize, face, s, t);
    if f == 0.0 {
        return a;
    }
    let b = bilinear((l0 + 1.0).min(last) as usize, face, s, t);
    [0, 1, 2].map(|c| a[c] + f * (b[c] - a[c]))
}

/// Trilinear lookup at fractional mip `lod` (clamped to the chain). The face coordinates
/// are found once for both levels, and an integral lod reads one level only.
pub fn sample_cube_lod(cube: &Cubemap, d: [f32; 3], lod: f32) -> [f32; 3] {
    trilinear(cube.levels.len(), d, lod, |m, face, s, t| {
        sample_face_bilinear(cube, m, face, s, t)
    })
}

/// A cube chain with a one-texel border around every face of every level, holding what
/// [`fetch_cube_texel`] returns there (the neighbouring faces' texels), so that no
/// bilinear tap leaves its face: [`BorderedCube::sample_lod`] returns exactly what
/// [`sample_cube_lod`] returns for the same cube, bit for bit, without the per-tap edge
/// path that the lobe tails' reads of small mips take nearly every time. The prefilter's
/// sampled levels read it on the CPU, and the viewer's GPU kernels read its levels as a
/// texture (`shaders/common/cube_fetch_bordered.wgsl`); the bake's GPU kernels sample the
/// plain chain.
#[derive(Clone, Debug)]
pub struct BorderedCube {
    /// Edge of level 0 (without the border).
    size: u32,
    /// Per level: six faces of (n + 2)² texels, row-major, texel (x, y) of the face (x, y
    /// from −1 to n) at ((face · (n + 2) + y + 1) · (n + 2) + x + 1).
    levels: Vec<Vec<[f32; 4]>>,
}

impl BorderedCube {
    /// Adds the borders to every level of `cube`.
    pub fn new(cube: &Cubemap) -> Self {
        let levels = (0..cube.levels.len())
            .map(|m| {
                let n = cube.level_size(m) as i32;
                let p = n + 2;
                let mut out = Vec::with_capacity((6 * p * p) as usize);
                for face in 0..6u32 {
                    for y in -1..=n {
                        for x in -1..=n {
                            let inside = x >= 0 && y >= 0 && x < n && y < n;
                            out.push(if inside {
                                cube.texel(m, face, x as u32, y as u32)
                            } else {
                                let [r, g, b] = fetch_cube_texel(cube, m, face, x, y);
                                [r, g, b, 1.0]
                            });
                        }
                    }
                }
                out
            })
            .collect();
        BorderedCube {
            size: cube.size,
            levels,
        }
    }

    /// Edge of level 0, without the border.
    #[cfg_attr(not(feature = "view"), allow(dead_code))]
    pub fn size(&self) -> u32 {
        self.size
    }

    /// Level `m`: six faces of (n + 2)² texels, layout as in the struct's documentation.
    #[cfg_attr(not(feature = "view"), allow(dead_code))]
    pub fn level(&self, m: usize) -> &[[f32; 4]] {
        &self.levels[m]
    }

    /// Number of levels.
    #[cfg_attr(not(feature = "view"), allow(dead_code))]
    pub fn level_count(&self) -> usize {
        self.levels.len()
    }

    /// [`sample_face_bilinear`] on the bordered level `m`.
    fn face_bilinear(&self, m: usize, face: u32, s: f32, t: f32) -> [f32; 3] {
        let n = (self.size >> m).max(1);
        let (xi, yi, weights) = bilinear_footprint(n, s, t);
        // |s|, |t| ≤ 1, so xi, yi ∈ [−1, n − 1] and the 2×2 footprint lies in the border.
        let p = n as usize + 2;
        let base = (face as usize * p + (yi + 1) as usize) * p + (xi + 1) as usize;
        let level = &self.levels[m];
        weighted_taps(
            [base, base + 1, base + p, base + p + 1].map(|k| level[k]),
            weights,
        )
    }

    /// [`sample_cube_lod`] on this chain.
    pub fn sample_lod(&self, d: [f32; 3], lod: f32) -> [f32; 3] {
        trilinear(self.levels.len(), d, lod, |m, face, s, t| {
            self.face_bilinear(m, face, s, t)
        })
    }
}

/// Solid angle of a level-0 texel of `cube` at direction `d` ((2/n)² times the face's
/// solid-angle density there).
pub fn cube_texel_solid_angle_at(cube: &Cubemap, d: [f32; 3]) -> f32 {
    let (_, s, t) = cube_face_coords(d);
    let n = cube.size as f32;
    (2.0 / n) * (2.0 / n) * cube_face_jacobian(s, t)
}

/// A 16² … chain with `mips` levels whose texels follow three incommensurate patterns
/// (no two neighbours alike, so a wrong tap shows), for the lookup and prefilter tests.
#[cfg(any(test, feature = "internals"))]
pub fn patterned_chain(size: u32, mips: u32) -> Cubemap {
    let mut cube = Cubemap {
        size,
        levels: vec![(0..Cubemap::level_len(size))
            .map(|i| {
                [
                    (i % 17) as f32 * 0.37,
                    (i % 5) as f32,
                    1.0 + (i % 3) as f32,
                    1.0,
                ]
            })
            .collect()],
    };
    crate::environment::mips::build_mips(&mut cube, mips);
    cube
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The direct read of an inside footprint gives exactly what four `fetch_cube_texel`
    /// taps give, and edge footprints still reach the neighbouring faces.
    /// `floor_i32` is `floor` on every kind of value a lookup gives it.
    #[test]
    fn floor_i32_is_floor() {
        for x in [
            -1.5f32,
            -1.0,
            -0.5,
            -1e-7,
            -0.0,
            0.0,
            1e-7,
            0.5,
            0.999_999_9,
            1.0,
            255.5,
            4095.9,
        ] {
            assert_eq!(floor_i32(x), x.floor() as i32, "{x}");
        }
        for k in -2000..2000 {
            let x = k as f32 * 0.013_7;
            assert_eq!(floor_i32(x), x.floor() as i32, "{x}");
        }
    }

    /// The bordered chain returns `sample_cube_lod`'s values bit for bit, at face
    /// edges and corners, fractional and integral lods, on every level down to 1×1.
    #[test]
    fn bordered_cube_equals_seamless_lookups() {
        let cube = patterned_chain(16, 5);
        let bordered = BorderedCube::new(&cube);
        let mut edge = 0;
        for k in 0..20_000 {
            let d = crate::math::cubemap::normalize([
                (k as f32 * 0.7311).sin(),
                (k as f32 * 0.3137).cos(),
                (k as f32 * 0.1713).sin() * 1.3,
            ]);
            let lod = [0.0, 0.5, 1.0, 2.25, 3.7, 4.0, 9.0][k % 7];
            let want = sample_cube_lod(&cube, d, lod);
            assert_eq!(
                bordered.sample_lod(d, lod).map(f32::to_bits),
                want.map(f32::to_bits),
                "{d:?} lod {lod}"
            );
            let (_, s, t) = cube_face_coords(d);
            edge += (s.abs().max(t.abs()) > 0.9) as u32;
        }
        assert!(edge > 1000, "{edge}");
    }

    #[test]
    fn fast_path_equals_per_tap_fetches() {
        let cube = patterned_chain(16, 5);
        let mut checked = 0;
        for m in 0..5usize {
            let n = cube.level_size(m) as f32;
            for face in 0..6u32 {
                for k in 0..97 {
                    let s = -1.0 + 2.0 * ((k * 37 % 97) as f32 + 0.5) / 97.0;
                    let t = -1.0 + 2.0 * ((k * 59 % 97) as f32 + 0.5) / 97.0;
                    let x = (s + 1.0) * 0.5 * n - 0.5;
                    let y = (t + 1.0) * 0.5 * n - 0.5;
                    let (fx, fy) = (x - x.floor(), y - y.floor());
                    let (xi, yi) = (x.floor() as i32, y.floor() as i32);
                    let mut want = [0.0f32; 3];
                    for (dx, dy, w) in [
                        (0, 0, (1.0 - fx) * (1.0 - fy)),
                        (1, 0, fx * (1.0 - fy)),
                        (0, 1, (1.0 - fx) * fy),
                        (1, 1, fx * fy),
                    ] {
                        let v = fetch_cube_texel(&cube, m, face, xi + dx, yi + dy);
                        (0..3).for_each(|c| want[c] += w * v[c]);
                    }
                    let got = sample_face_bilinear(&cube, m, face, s, t);
                    assert_eq!(
                        got.map(f32::to_bits),
                        want.map(f32::to_bits),
                        "m {m} face {face} ({s}, {t})"
                    );
                    checked += 1;
                }
            }
        }
        assert_eq!(checked, 5 * 6 * 97);
    }
}
