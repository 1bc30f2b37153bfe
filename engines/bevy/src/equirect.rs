//! The HDRI itself, as the check compares Bevy's renders with it.

use std::f32::consts::PI;
use std::path::Path;

use bevy::prelude::*;

/// An equirect in splitsum's convention (u = 0.5 + atan2(z, x)/2π, v = acos(y)/π).
#[derive(Clone)]
pub struct Equirect {
    width: usize,
    height: usize,
    data: Vec<[f32; 3]>,
}

impl Equirect {
    pub fn load(path: &Path) -> Equirect {
        let img = image::open(path)
            .unwrap_or_else(|e| panic!("{}: {e}", path.display()))
            .into_rgb32f();
        Equirect {
            width: img.width() as usize,
            height: img.height() as usize,
            data: img.pixels().map(|p| p.0).collect(),
        }
    }

    /// Bilinear lookup (wrapping in u, clamped in v) of direction `d`.
    pub fn lookup(&self, d: Vec3) -> [f32; 3] {
        let u = 0.5 + d.z.atan2(d.x) / (2.0 * PI);
        let v = d.y.clamp(-1.0, 1.0).acos() / PI;
        let x = u * self.width as f32 - 0.5;
        let y = (v * self.height as f32 - 0.5).clamp(0.0, (self.height - 1) as f32);
        let (x0, y0) = (x.floor(), y.floor());
        let (fx, fy) = (x - x0, y - y0);
        let at = |xi: i64, yi: usize| {
            let xi = xi.rem_euclid(self.width as i64) as usize;
            self.data[yi.min(self.height - 1) * self.width + xi]
        };
        let (xi, yi) = (x0 as i64, y0 as usize);
        let mut out = [0.0; 3];
        for c in 0..3 {
            let top = at(xi, yi)[c] * (1.0 - fx) + at(xi + 1, yi)[c] * fx;
            let bottom = at(xi, yi + 1)[c] * (1.0 - fx) + at(xi + 1, yi + 1)[c] * fx;
            out[c] = top * (1.0 - fy) + bottom * fy;
        }
        out
    }

    /// Direction and solid angle of texel (x, y).
    pub fn texel(&self, x: usize, y: usize) -> (Vec3, f32) {
        let (t0, t1) = (
            PI * y as f32 / self.height as f32,
            PI * (y + 1) as f32 / self.height as f32,
        );
        let theta = 0.5 * (t0 + t1);
        let phi = 2.0 * PI * ((x as f32 + 0.5) / self.width as f32 - 0.5);
        let omega = 2.0 * PI / self.width as f32 * (t0.cos() - t1.cos());
        (
            Vec3::new(
                theta.sin() * phi.cos(),
                theta.cos(),
                theta.sin() * phi.sin(),
            ),
            omega,
        )
    }

    /// The sun: luminance-weighted mean direction of the texels above half the maximum.
    pub fn sun(&self) -> Vec3 {
        let max = self.data.iter().map(|&p| luminance(p)).fold(0.0, f32::max);
        let mut d = Vec3::ZERO;
        for y in 0..self.height {
            for x in 0..self.width {
                let l = luminance(self.data[y * self.width + x]);
                if l >= 0.5 * max {
                    let (dir, omega) = self.texel(x, y);
                    d += dir * l * omega;
                }
            }
        }
        d.normalize()
    }

    /// The solid-angle-weighted box reduction by `k` in each axis (energy kept).
    pub fn reduce(&self, k: usize) -> Equirect {
        let (w, h) = (self.width / k, self.height / k);
        let mut data = vec![[0.0; 3]; w * h];
        for y in 0..h {
            for x in 0..w {
                let (mut sum, mut weight) = ([0.0f32; 3], 0.0);
                for yy in y * k..(y + 1) * k {
                    let omega = self.texel(0, yy).1;
                    for xx in x * k..(x + 1) * k {
                        let p = self.data[yy * self.width + xx];
                        for c in 0..3 {
                            sum[c] += p[c] * omega;
                        }
                        weight += omega;
                    }
                }
                data[y * w + x] = sum.map(|s| s / weight);
            }
        }
        Equirect {
            width: w,
            height: h,
            data,
        }
    }

    /// E(n)/π, the cosine-weighted sum over every texel.
    pub fn irradiance_over_pi(&self, n: Vec3) -> [f32; 3] {
        let mut e = [0.0f32; 3];
        for y in 0..self.height {
            for x in 0..self.width {
                let (d, omega) = self.texel(x, y);
                let c = n.dot(d);
                if c > 0.0 {
                    let p = self.data[y * self.width + x];
                    for k in 0..3 {
                        e[k] += p[k] * c * omega;
                    }
                }
            }
        }
        e.map(|v| v / PI)
    }
}

pub fn luminance(p: [f32; 3]) -> f32 {
    0.2126 * p[0] + 0.7152 * p[1] + 0.0722 * p[2]
}
