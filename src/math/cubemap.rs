//! Directions, equirectangular and cube-face mappings, texel solid angles. Mirror of
//! `shaders/common/cubemap.wgsl` (same function names).
//!
//! Conventions (docs/conventions.md, "Directions and equirectangular maps" and "Cube faces"): right-handed,
//! +Y up. Equirect: u = 0.5 + atan2(d.z, d.x)/(2π), v = acos(d.y)/π, v = 0 the top row.
//! Cube faces +X, −X, +Y, −Y, +Z, −Z oriented as in the Vulkan/OpenGL/D3D cube-map face
//! selection table (Vulkan spec, "Cube Map Face Selection"), rows top to bottom.

use std::f32::consts::PI;

use super::trig::atan2_precise;

/// Number of cube faces.
pub const FACES: usize = 6;

/// The direction through face coordinates (s, t) ∈ [−1, 1]² of `face` (not normalised):
/// s grows to the right, t downwards, per the face selection table.
pub fn cube_face_direction(face: u32, s: f32, t: f32) -> [f32; 3] {
    match face {
        0 => [1.0, -t, -s],  // +X: sc = −z, tc = −y
        1 => [-1.0, -t, s],  // −X: sc = +z, tc = −y
        2 => [s, 1.0, t],    // +Y: sc = +x, tc = +z
        3 => [s, -1.0, -t],  // −Y: sc = +x, tc = −z
        4 => [s, -t, 1.0],   // +Z: sc = +x, tc = −y
        _ => [-s, -t, -1.0], // −Z: sc = −x, tc = −y
    }
}

/// Unit direction through the centre of texel (i, j) of `face` of an n×n face (texel
/// coordinates may lie one texel off the face: the direction then points into a
/// neighbouring face's area, extended on this face's plane).
pub fn cube_texel_direction(face: u32, i: i32, j: i32, n: u32) -> [f32; 3] {
    let s = (i as f32 + 0.5) * 2.0 / n as f32 - 1.0;
    let t = (j as f32 + 0.5) * 2.0 / n as f32 - 1.0;
    normalize(cube_face_direction(face, s, t))
}

/// Face and face coordinates (s, t) ∈ [−1, 1]² that direction `d` lands on (inverse of
/// [`cube_face_direction`]); ties go to X, then Y, then Z.
pub fn cube_face_coords(d: [f32; 3]) -> (u32, f32, f32) {
    let [x, y, z] = d;
    let (ax, ay, az) = (x.abs(), y.abs(), z.abs());
    if ax >= ay && ax >= az {
        if x >= 0.0 {
            (0, -z / ax, -y / ax)
        } else {
            (1, z / ax, -y / ax)
        }
    } else if ay >= az {
        if y >= 0.0 {
            (2, x / ay, z / ay)
        } else {
            (3, x / ay, -z / ay)
        }
    } else if z >= 0.0 {
        (4, x / az, -y / az)
    } else {
        (5, -x / az, -y / az)
    }
}

/// A signed permutation of the world axes: `apply(d)[i] = sign[i] · d[axis[i]]` (a mirror,
/// a quarter turn, or a product of them). It maps the cube's texel centres onto texel
/// centres, so a cube re-expressed through one is an exact permutation of its texels
/// ([`crate::environment::Cubemap::remapped`]); engines that read cubes in another frame
/// than the generic one differ from it by one of these (`crate::targets`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct AxisMap {
    /// Which input axis each output component takes (a permutation of 0, 1, 2).
    pub axis: [usize; 3],
    /// The sign each output component gets (±1).
    pub sign: [i8; 3],
}

impl AxisMap {
    /// d ↦ d.
    pub const IDENTITY: AxisMap = AxisMap {
        axis: [0, 1, 2],
        sign: [1, 1, 1],
    };

    /// d with component `axis` negated.
    pub const fn mirror(axis: usize) -> AxisMap {
        let mut sign = [1, 1, 1];
        sign[axis] = -1;
        AxisMap {
            axis: [0, 1, 2],
            sign,
        }
    }

    /// The image of `d`.
    pub fn apply(&self, d: [f32; 3]) -> [f32; 3] {
        std::array::from_fn(|i| f32::from(self.sign[i]) * d[self.axis[i]])
    }

    /// This map applied after `first`: d ↦ self(first(d)).
    pub fn after(&self, first: AxisMap) -> AxisMap {
        AxisMap {
            axis: std::array::from_fn(|i| first.axis[self.axis[i]]),
            sign: std::array::from_fn(|i| self.sign[i] * first.sign[self.axis[i]]),
        }
    }

    /// The inverse map (the transpose of its matrix).
    pub fn inverse(&self) -> AxisMap {
        let mut inv = AxisMap::IDENTITY;
        for i in 0..3 {
            inv.axis[self.axis[i]] = i;
            inv.sign[self.axis[i]] = self.sign[i];
        }
        inv
    }

    /// Its 3×3 matrix, rows: `apply(d) = m · d`.
    pub fn matrix(&self) -> [[f32; 3]; 3] {
        let mut m = [[0.0; 3]; 3];
        for i in 0..3 {
            m[i][self.axis[i]] = f32::from(self.sign[i]);
        }
        m
    }
}

/// Normalises a vector.
pub fn normalize(v: [f32; 3]) -> [f32; 3] {
    let l = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
    [v[0] / l, v[1] / l, v[2] / l]
}

#[cfg(any(test, feature = "internals"))]
/// Equirect (u, v) ∈ [0, 1]² of unit direction `d`: u from atan2(z, x), v from
/// acos(y) = atan2(√(x² + z²), y) (both with [`atan2_precise`]).
pub fn equirect_uv(d: [f32; 3]) -> (f32, f32) {
    let u = 0.5 + atan2_precise(d[2], d[0]) / (2.0 * PI);
    let v = atan2_precise((d[0] * d[0] + d[2] * d[2]).sqrt(), d[1]) / PI;
    (u, v)
}

/// Unit direction at equirect (u, v) (inverse of [`equirect_uv`]).
pub fn equirect_direction(u: f32, v: f32) -> [f32; 3] {
    let phi = (u - 0.5) * 2.0 * PI;
    let theta = v * PI;
    let st = theta.sin();
    [st * phi.cos(), theta.cos(), st * phi.sin()]
}

/// Rotates `d` about +Y by the angle whose cosine and sine are given (right-handed:
/// +X turns towards −Z for a positive angle).
pub fn rotate_y(d: [f32; 3], cos_a: f32, sin_a: f32) -> [f32; 3] {
    [
        cos_a * d[0] + sin_a * d[2],
        d[1],
        -sin_a * d[0] + cos_a * d[2],
    ]
}

/// ∫ of the cube-face solid-angle density from the face centre to (x, y):
/// atan2(x y, √(x² + y² + 1)) (the standard closed form; e.g. Driscoll, "Cubemap texel
/// solid angle", 2012).
fn area_element(x: f32, y: f32) -> f32 {
    atan2_precise(x * y, (x * x + y * y + 1.0).sqrt())
}

/// Solid angle of texel (i, j) of an n×n cube face (exact).
pub fn cube_texel_solid_angle(i: u32, j: u32, n: u32) -> f32 {
    let inv = 2.0 / n as f32;
    let x0 = i as f32 * inv - 1.0;
    let y0 = j as f32 * inv - 1.0;
    let x1 = x0 + inv;
    let y1 = y0 + inv;
    area_element(x0, y0) - area_element(x0, y1) - area_element(x1, y0) + area_element(x1, y1)
}

/// Solid-angle density of the cube face parametrisation at (s, t): dω = dA / (1+s²+t²)^{3/2}.
pub fn cube_face_jacobian(s: f32, t: f32) -> f32 {
    let r2 = 1.0 + s * s + t * t;
    1.0 / (r2 * r2.sqrt())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn face_selection_matches_the_conventions_example() {
        // (1, 0.5, 0) lands on +X at the column centre, a quarter of the way down.
        let (face, s, t) = cube_face_coords([1.0, 0.5, 0.0]);
        assert_eq!(face, 0);
        assert!((s - 0.0).abs() < 1e-6 && (t + 0.5).abs() < 1e-6);
        for face in 0..6 {
            for &(s, t) in &[(0.3f32, -0.7f32), (-0.9, 0.2), (0.0, 0.0)] {
                let d = cube_face_direction(face, s, t);
                let (f2, s2, t2) = cube_face_coords(d);
                assert_eq!(f2, face);
                assert!((s - s2).abs() < 1e-6 && (t - t2).abs() < 1e-6);
            }
        }
    }

    #[test]
    fn equirect_mapping_follows_the_convention() {
        let (u, v) = equirect_uv([1.0, 0.0, 0.0]);
        assert!((u - 0.5).abs() < 1e-6 && (v - 0.5).abs() < 1e-6);
        let (u, _) = equirect_uv([0.0, 0.0, 1.0]);
        assert!((u - 0.75).abs() < 1e-6);
        let (_, v) = equirect_uv([0.0, 1.0, 0.0]);
        assert!(v.abs() < 1e-6);
        let d = equirect_direction(0.3, 0.6);
        let (u, v) = equirect_uv(d);
        assert!((u - 0.3).abs() < 1e-5 && (v - 0.6).abs() < 1e-5);
    }

    #[test]
    fn texel_solid_angles_sum_to_the_sphere() {
        for n in [1u32, 2, 7, 32] {
            let mut total = 0.0f64;
            for j in 0..n {
                for i in 0..n {
                    total += cube_texel_solid_angle(i, j, n) as f64;
                }
            }
            assert!(
                (total * 6.0 - 4.0 * std::f64::consts::PI).abs() < 1e-4,
                "{n}: {total}"
            );
        }
    }
}
