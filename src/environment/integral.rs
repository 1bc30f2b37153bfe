//! An equirect prepared for exact footprint integrals (what `equirect_to_cube` reads).
//!
//! The equirect is piecewise constant: texel (x, r) covers φ ∈ [φ_x, φ_{x+1}] and
//! θ ∈ [θ_r, θ_{r+1}], with φ_x = 2π(x/W − ½) and θ_r = πr/H. In the coordinates
//! (φ, y = cos θ) the solid angle is dω = dφ dy, so the radiance's integral over any region
//! follows from Green's theorem once the radiance is integrated along each meridian: this
//! module holds, per texel, the cumulative sums of L·(cos θ_r − cos θ_{r+1}) from the north
//! pole down to the texel's top edge and from the south pole up to its bottom edge (two
//! sums so that either pole's neighbourhood is computed from small numbers, which keeps a
//! polar texel's integral accurate in f32), plus the row and column boundary tables. All
//! of it is accumulated in f64 and stored in f32 for both backends.

use super::Equirect;

/// The source texels of one equirect level and their per-column cumulative sums.
#[derive(Clone, Debug)]
pub struct EquirectIntegral {
    /// Width W in texels.
    pub width: u32,
    /// Height H in texels.
    pub height: u32,
    /// Radiance, row-major.
    pub radiance: Vec<[f32; 3]>,
    /// ∫ L dy from the north pole down to the top edge of each texel's row (exclusive).
    pub from_north: Vec<[f32; 3]>,
    /// ∫ L dy from the south pole up to the bottom edge of each texel's row (exclusive).
    pub from_south: Vec<[f32; 3]>,
    /// Per row boundary r = 0..=H: (cos θ_r, sin θ_r, 1 − cos θ_r, 1 + cos θ_r), the last
    /// two computed without cancellation near the poles.
    pub rows: Vec<[f32; 4]>,
    /// Per column boundary x = 0..=W: (−sin φ_x, cos φ_x), the x and z components of the
    /// normal of the meridian plane at φ_x.
    pub columns: Vec<[f32; 2]>,
}

impl EquirectIntegral {
    /// Prepares `image` (consumed: its texels become [`EquirectIntegral::radiance`]).
    pub fn new(image: Equirect) -> Self {
        let (w, h) = (image.width as usize, image.height as usize);
        let pi = std::f64::consts::PI;
        let rows: Vec<[f64; 4]> = (0..=h)
            .map(|r| {
                let theta = pi * r as f64 / h as f64;
                let half = (0.5 * theta).sin();
                let half_c = (0.5 * theta).cos();
                [
                    theta.cos(),
                    theta.sin(),
                    2.0 * half * half,
                    2.0 * half_c * half_c,
                ]
            })
            .collect();
        // Height of row r in y, cos θ_r − cos θ_{r+1} = 2 sin(θ_mid) sin(Δθ/2).
        let band: Vec<f64> = (0..h)
            .map(|r| {
                let mid = pi * (r as f64 + 0.5) / h as f64;
                2.0 * mid.sin() * (0.5 * pi / h as f64).sin()
            })
            .collect();
        // Running f64 sums down (and up) every column at once, one row at a time.
        let data = &image.data;
        let mut from_north = vec![[0.0f32; 3]; w * h];
        let mut from_south = vec![[0.0f32; 3]; w * h];
        let mut acc = vec![[0.0f64; 3]; w];
        for r in 0..h {
            for (x, a) in acc.iter_mut().enumerate() {
                from_north[r * w + x] = a.map(|v| v as f32);
                let t = data[r * w + x];
                (0..3).for_each(|c| a[c] += t[c] as f64 * band[r]);
            }
        }
        acc.iter_mut().for_each(|a| *a = [0.0; 3]);
        for r in (0..h).rev() {
            for (x, a) in acc.iter_mut().enumerate() {
                from_south[r * w + x] = a.map(|v| v as f32);
                let t = data[r * w + x];
                (0..3).for_each(|c| a[c] += t[c] as f64 * band[r]);
            }
        }
        let columns = (0..=w)
            .map(|x| {
                let phi = 2.0 * pi * (x as f64 / w as f64 - 0.5);
                [-phi.sin() as f32, phi.cos() as f32]
            })
            .collect();
        EquirectIntegral {
            width: image.width,
            height: image.height,
            radiance: image.data,
            from_north,
            from_south,
            rows: rows.iter().map(|r| r.map(|v| v as f32)).collect(),
            columns,
        }
    }

    /// Texel index of column `x`, row `r`.
    pub fn index(&self, x: u32, r: u32) -> usize {
        (r * self.width + x) as usize
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn cumulative_sums_add_up_to_each_column_total() {
        let (w, h) = (8u32, 5u32);
        let data = (0..w * h)
            .map(|i| [i as f32, 1.0, (i % 3) as f32])
            .collect();
        let src = EquirectIntegral::new(Equirect {
            width: w,
            height: h,
            data,
        });
        for x in 0..w {
            let total_north = {
                let i = src.index(x, h - 1);
                let band = src.rows[(h - 1) as usize][0] - src.rows[h as usize][0];
                src.from_north[i][1] + src.radiance[i][1] * band
            };
            // A constant column integrates to the height of the sphere in y, 2.
            assert!((total_north - 2.0).abs() < 1e-6, "{total_north}");
            for r in 0..h {
                let i = src.index(x, r);
                let band = src.rows[r as usize][0] - src.rows[r as usize + 1][0];
                let sum = src.from_north[i][0] + src.radiance[i][0] * band + src.from_south[i][0];
                let whole = src.from_south[src.index(x, 0)][0]
                    + src.radiance[src.index(x, 0)][0] * (1.0 - src.rows[1][0]);
                assert!((sum - whole).abs() < 1e-4 * whole.max(1.0), "{sum} {whole}");
            }
        }
        assert!((src.rows[0][2]).abs() < 1e-9 && (src.rows[h as usize][3]).abs() < 1e-9);
    }
}
