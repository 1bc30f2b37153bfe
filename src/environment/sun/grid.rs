//! The texels the sun is found on, an equirect's or a cube's level 0, with their exact
//! directions and solid angles in f64, and the small vector helpers of the search.

use crate::environment::{Cubemap, Environment, Equirect};
use crate::math::cubemap::{cube_face_coords, cube_texel_direction, cube_texel_solid_angle};

pub(crate) use crate::math::color::luminance_f64 as luminance;

/// The texels of an equirect or of a cube's level 0.
pub(crate) enum Grid<'a> {
    /// An equirect's texels, k = y·W + x.
    Equirect(&'a Equirect),
    /// A cube's level-0 texels, k = (face·n + j)·n + i.
    Cube(&'a Cubemap),
}

impl<'a> Grid<'a> {
    pub(crate) fn of(env: &'a Environment) -> Self {
        match env {
            Environment::Equirect(e) => Grid::Equirect(e),
            Environment::Cube(c) => Grid::Cube(c),
        }
    }

    pub(crate) fn len(&self) -> usize {
        match self {
            Grid::Equirect(e) => e.data.len(),
            Grid::Cube(c) => Cubemap::level_len(c.size),
        }
    }

    pub(crate) fn raw(&self, k: usize) -> [f32; 3] {
        match self {
            Grid::Equirect(e) => e.data[k],
            Grid::Cube(c) => {
                let t = c.levels[0][k];
                [t[0], t[1], t[2]]
            }
        }
    }

    /// The radiance with non-finite and negative channels as 0.
    pub(crate) fn radiance(&self, k: usize) -> [f64; 3] {
        let l = self.raw(k);
        if l.iter().any(|c| !c.is_finite()) {
            return [0.0; 3];
        }
        l.map(|c| f64::from(c.max(0.0)))
    }

    pub(crate) fn direction(&self, k: usize) -> [f64; 3] {
        match self {
            Grid::Equirect(e) => {
                let (w, h) = (e.width as usize, e.height as usize);
                let (x, y) = (k % w, k / w);
                equirect_texel_direction(x as f64, y as f64, w, h)
            }
            Grid::Cube(c) => {
                let n = c.size as usize;
                let (face, j, i) = (k / (n * n), k % (n * n) / n, k % n);
                let d = cube_texel_direction(face as u32, i as i32, j as i32, c.size);
                normalize(d.map(f64::from))
            }
        }
    }

    pub(crate) fn solid_angle(&self, k: usize) -> f64 {
        match self {
            Grid::Equirect(e) => e.row_solid_angle((k / e.width as usize) as u32),
            Grid::Cube(c) => {
                let n = c.size as usize;
                f64::from(cube_texel_solid_angle(
                    (k % n) as u32,
                    (k % (n * n) / n) as u32,
                    c.size,
                ))
            }
        }
    }

    /// The angular extent (across, along the row) of texel k, in radians: an equirect
    /// texel's row height and its width at its latitude, a cube texel's √Ω both ways.
    pub(crate) fn texel_extent(&self, k: usize) -> (f64, f64) {
        let omega = self.solid_angle(k);
        match self {
            Grid::Equirect(e) => {
                let hy = std::f64::consts::PI / f64::from(e.height);
                (omega / hy, hy)
            }
            Grid::Cube(_) => (omega.sqrt(), omega.sqrt()),
        }
    }

    /// The up to 8 texels around texel k (those sharing an edge or a corner with it), across
    /// an equirect's seam and a cube's face edges; an equirect's pole row has no texel above
    /// it (its neighbours along the row are those across the pole's point).
    pub(crate) fn neighbours(&self, k: usize) -> Vec<usize> {
        let mut out = Vec::with_capacity(8);
        match self {
            Grid::Equirect(e) => {
                let (w, h) = (e.width as isize, e.height as isize);
                let (x, y) = ((k as isize) % w, (k as isize) / w);
                for dy in -1..=1 {
                    for dx in -1..=1 {
                        let yy = y + dy;
                        if (dx, dy) == (0, 0) || yy < 0 || yy >= h {
                            continue;
                        }
                        out.push((yy * w + (x + dx).rem_euclid(w)) as usize);
                    }
                }
            }
            Grid::Cube(c) => {
                let n = c.size as i32;
                let per_face = (n * n) as usize;
                let (face, j, i) = (k / per_face, (k % per_face) as i32 / n, (k % per_face) as i32 % n);
                for dj in -1..=1 {
                    for di in -1..=1 {
                        let (ii, jj) = (i + di, j + dj);
                        if (di, dj) == (0, 0) {
                            continue;
                        }
                        let t = if (0..n).contains(&ii) && (0..n).contains(&jj) {
                            face * per_face + (jj * n + ii) as usize
                        } else {
                            // Off the face: the texel holding the direction through the
                            // extended centre (a corner's diagonal lands on either face).
                            let d = cube_texel_direction(face as u32, ii, jj, c.size);
                            let (f, s, t) = cube_face_coords(d);
                            let texel = |u: f32| (((u + 1.0) * 0.5 * n as f32) as i32).clamp(0, n - 1);
                            f as usize * per_face + (texel(t) * n + texel(s)) as usize
                        };
                        if t != k && !out.contains(&t) {
                            out.push(t);
                        }
                    }
                }
            }
        }
        out
    }

    /// The texels whose centres lie within `radius` (radians) of unit `c`.
    pub(crate) fn cap(&self, c: [f64; 3], radius: f64) -> Vec<usize> {
        let cos_r = radius.cos();
        let inside = |k: usize| dot(self.direction(k), c) >= cos_r;
        match self {
            Grid::Equirect(e) => {
                let (w, h) = (e.width as usize, e.height as usize);
                let pi = std::f64::consts::PI;
                let theta_c = c[1].clamp(-1.0, 1.0).acos();
                let phi_c = c[2].atan2(c[0]);
                let row =
                    |theta: f64| ((theta / pi * h as f64).floor().max(0.0) as usize).min(h - 1);
                let (y0, y1) = (row(theta_c - radius), row(theta_c + radius));
                let mut out = Vec::new();
                // The widest azimuth offset of a cap that holds no pole, padded by columns.
                let span = if theta_c - radius <= 0.0 || theta_c + radius >= pi {
                    w
                } else {
                    let half = (radius.sin() / theta_c.sin()).min(1.0).asin();
                    ((half / (2.0 * pi) * w as f64).ceil() as usize + 2).min(w)
                };
                for y in y0..=y1 {
                    if span * 2 + 1 >= w {
                        out.extend((y * w..(y + 1) * w).filter(|&k| inside(k)));
                        continue;
                    }
                    let xc = ((phi_c / (2.0 * pi) + 0.5) * w as f64).floor() as isize;
                    for dx in -(span as isize)..=(span as isize) {
                        let x = (xc + dx).rem_euclid(w as isize) as usize;
                        let k = y * w + x;
                        if inside(k) {
                            out.push(k);
                        }
                    }
                }
                out
            }
            Grid::Cube(_) => (0..self.len()).filter(|&k| inside(k)).collect(),
        }
    }
}

/// Direction through equirect texel (x, y)'s centre (docs/conventions.md, "Directions and
/// equirectangular maps"), in f64.
fn equirect_texel_direction(x: f64, y: f64, w: usize, h: usize) -> [f64; 3] {
    let pi = std::f64::consts::PI;
    let phi = ((x + 0.5) / w as f64 - 0.5) * 2.0 * pi;
    let theta = (y + 0.5) / h as f64 * pi;
    [
        theta.sin() * phi.cos(),
        theta.cos(),
        theta.sin() * phi.sin(),
    ]
}

pub(crate) fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

pub(crate) fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

pub(crate) fn normalize(a: [f64; 3]) -> [f64; 3] {
    let l = dot(a, a).sqrt();
    if l > 0.0 {
        a.map(|v| v / l)
    } else {
        [0.0, 1.0, 0.0]
    }
}

/// Two unit vectors completing unit `c` to an orthonormal frame.
pub(crate) fn tangent_frame(c: [f64; 3]) -> ([f64; 3], [f64; 3]) {
    let up = if c[1].abs() < 0.9 {
        [0.0, 1.0, 0.0]
    } else {
        [1.0, 0.0, 0.0]
    };
    let t1 = normalize(cross(up, c));
    (t1, cross(c, t1))
}

/// The angle between unit vectors, accurate for small angles.
pub(crate) fn angle(a: [f64; 3], b: [f64; 3]) -> f64 {
    let c = cross(a, b);
    dot(c, c).sqrt().atan2(dot(a, b))
}
