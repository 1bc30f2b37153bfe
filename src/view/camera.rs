//! The viewer's camera: LearnOpenGL's first-person camera class (J. de Vries,
//! "Camera", learnopengl.com), changed so that yaw 0 looks along −z:
//!
//! front = (sin(yaw)·cos(pitch), sin(pitch), −cos(yaw)·cos(pitch)),
//! right = normalize(front × world up), up = right × front,
//!
//! with world up +y (docs/conventions.md, "The viewer"). Mouse look adds the cursor's
//! movement times a sensitivity to yaw (right turns right) and pitch (up looks up), pitch
//! clamped short of the poles; WASD moves along front and right at a fixed speed.
//!
//! A pixel (x, y) of a W × H frame (x right, y down) sees along the ray through its centre:
//! with ndc = (2(x + ½)/W − 1, 1 − 2(y + ½)/H),
//! - perspective: from the position along normalize(ndc.x·tx·right + ndc.y·ty·up + front),
//!   ty = tan(fov_y/2), tx = ty·W/H;
//! - orthographic: from position + ndc.x·hx·right + ndc.y·hy·up along front, hy the half
//!   height of the view and hx = hy·W/H.
//!
//! The raster pass's view-projection matrix ([`CameraFrame::view_projection`]) is built from the
//! same numbers, so a rasterised triangle covers the pixels whose rays hit it.

use glam::{Mat4, Vec3};

/// Degrees of yaw and pitch per pixel of cursor movement (LearnOpenGL's SENSITIVITY).
pub const MOUSE_SENSITIVITY_DEG: f32 = 0.1;
/// Movement speed in scene units per second (LearnOpenGL's SPEED).
pub const MOVE_SPEED: f32 = 2.5;
/// Largest |pitch| in degrees (LearnOpenGL's constrainPitch).
pub const MAX_PITCH_DEG: f32 = 89.0;
/// Vertical field of view in degrees (LearnOpenGL's ZOOM).
pub const FOV_Y_DEG: f32 = 45.0;
/// Near and far clipping distances of the perspective projection, scene units.
pub const NEAR: f32 = 0.05;
/// See [`NEAR`].
pub const FAR: f32 = 200.0;
/// Where the camera starts: on the +z side of the object, 3.5 units from its centre
/// (`scene::OBJECT_CENTRE`), looking at it along −z (yaw 0, pitch 0).
pub const START_POSITION: [f32; 3] = [0.0, 0.0, 5.0];

/// How the camera projects.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Projection {
    /// A pinhole with vertical field of view `fov_y_deg`.
    Perspective {
        /// Vertical field of view, degrees.
        fov_y_deg: f32,
    },
    /// Parallel rays along front; the view is 2·`half_height` units tall (the preview's
    /// distant camera).
    Orthographic {
        /// Half the view's height, scene units.
        half_height: f32,
    },
}

/// A first-person camera.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Camera {
    /// Position, scene units.
    pub position: Vec3,
    /// Yaw in degrees; 0 looks along −z, 90 along +x.
    pub yaw_deg: f32,
    /// Pitch in degrees; positive looks up.
    pub pitch_deg: f32,
    /// The projection.
    pub projection: Projection,
}

/// A camera's basis and projection, as the kernels read it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CameraFrame {
    /// Position.
    pub position: Vec3,
    /// Unit right axis.
    pub right: Vec3,
    /// Unit up axis.
    pub up: Vec3,
    /// Unit front axis.
    pub front: Vec3,
    /// tan of the half field of view (perspective) or the half extent (orthographic),
    /// horizontally.
    pub half_x: f32,
    /// The same vertically.
    pub half_y: f32,
    /// Whether the rays are parallel.
    pub orthographic: bool,
}

impl Default for Camera {
    fn default() -> Self {
        Camera {
            position: Vec3::from(START_POSITION),
            yaw_deg: 0.0,
            pitch_deg: 0.0,
            projection: Projection::Perspective {
                fov_y_deg: FOV_Y_DEG,
            },
        }
    }
}

/// The front vector of yaw and pitch in degrees (the module's formula).
pub fn front(yaw_deg: f32, pitch_deg: f32) -> Vec3 {
    let (y, p) = (yaw_deg.to_radians(), pitch_deg.to_radians());
    Vec3::new(y.sin() * p.cos(), p.sin(), -y.cos() * p.cos())
}

impl Camera {
    /// The unit front, right and up axes.
    pub fn axes(&self) -> (Vec3, Vec3, Vec3) {
        let f = front(self.yaw_deg, self.pitch_deg);
        let right = f.cross(Vec3::Y).normalize();
        let up = right.cross(f);
        (f, right, up)
    }

    /// Turns by a cursor movement of (dx, dy) pixels (y down, as window systems report it).
    pub fn look(&mut self, dx: f32, dy: f32) {
        self.yaw_deg += dx * MOUSE_SENSITIVITY_DEG;
        self.pitch_deg =
            (self.pitch_deg - dy * MOUSE_SENSITIVITY_DEG).clamp(-MAX_PITCH_DEG, MAX_PITCH_DEG);
    }

    /// Moves by `forward` and `sideways` (right positive) times [`MOVE_SPEED`]·`seconds`.
    pub fn walk(&mut self, forward: f32, sideways: f32, seconds: f32) {
        let (f, right, _) = self.axes();
        self.position += (f * forward + right * sideways) * (MOVE_SPEED * seconds);
    }

    /// The basis and projection of a `width` × `height` frame.
    pub fn frame(&self, width: u32, height: u32) -> CameraFrame {
        let (front, right, up) = self.axes();
        let aspect = width as f32 / height.max(1) as f32;
        let (half_y, orthographic) = match self.projection {
            Projection::Perspective { fov_y_deg } => ((0.5 * fov_y_deg).to_radians().tan(), false),
            Projection::Orthographic { half_height } => (half_height, true),
        };
        CameraFrame {
            position: self.position,
            right,
            up,
            front,
            half_x: half_y * aspect,
            half_y,
            orthographic,
        }
    }
}

impl CameraFrame {
    /// The ray through the centre of pixel (x, y) of a `width` × `height` frame: (origin,
    /// unit direction).
    pub fn pixel_ray(&self, x: u32, y: u32, width: u32, height: u32) -> (Vec3, Vec3) {
        let nx = 2.0 * (x as f32 + 0.5) / width as f32 - 1.0;
        let ny = 1.0 - 2.0 * (y as f32 + 0.5) / height as f32;
        if self.orthographic {
            let origin =
                self.position + (nx * self.half_x) * self.right + (ny * self.half_y) * self.up;
            (origin, self.front)
        } else {
            let dir = (nx * self.half_x) * self.right + (ny * self.half_y) * self.up + self.front;
            (self.position, dir.normalize())
        }
    }

    /// World to clip space for the raster pass, in wgpu's clip space (depth 0 at the near
    /// plane, 1 at the far one): the view matrix (rows right, up, −front, the eye at the
    /// origin) times the projection, perspective
    /// (x/tx, y/ty, (far·z + near·far)/(near − far), −z) or orthographic
    /// (x/hx, y/hy, (−z − near)/(far − near), 1) of the view-space point (x, y, z).
    pub fn view_projection(&self) -> Mat4 {
        let (r, u, f, e) = (self.right, self.up, self.front, self.position);
        let view = Mat4::from_cols_array_2d(&[
            [r.x, r.y, r.z, -r.dot(e)],
            [u.x, u.y, u.z, -u.dot(e)],
            [-f.x, -f.y, -f.z, f.dot(e)],
            [0.0, 0.0, 0.0, 1.0],
        ])
        .transpose();
        let projection = if self.orthographic {
            Mat4::from_cols_array_2d(&[
                [1.0 / self.half_x, 0.0, 0.0, 0.0],
                [0.0, 1.0 / self.half_y, 0.0, 0.0],
                [0.0, 0.0, -1.0 / (FAR - NEAR), -NEAR / (FAR - NEAR)],
                [0.0, 0.0, 0.0, 1.0],
            ])
        } else {
            Mat4::from_cols_array_2d(&[
                [1.0 / self.half_x, 0.0, 0.0, 0.0],
                [0.0, 1.0 / self.half_y, 0.0, 0.0],
                [0.0, 0.0, FAR / (NEAR - FAR), NEAR * FAR / (NEAR - FAR)],
                [0.0, 0.0, -1.0, 0.0],
            ])
        }
        .transpose();
        projection * view
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn close(a: Vec3, b: Vec3) -> bool {
        (a - b).length() < 1e-6
    }

    /// Yaw 0 looks along −z, yaw 90° along +x, pitch 90° up, as the module's formula says.
    #[test]
    fn the_front_formula() {
        assert!(close(front(0.0, 0.0), Vec3::NEG_Z));
        assert!(close(front(90.0, 0.0), Vec3::X));
        assert!(close(front(180.0, 0.0), Vec3::Z));
        assert!(close(front(0.0, 90.0), Vec3::Y));
        let c = Camera::default();
        let (f, right, up) = c.axes();
        assert!(close(f, Vec3::NEG_Z) && close(right, Vec3::X) && close(up, Vec3::Y));
    }

    /// Moving the cursor right turns right; up looks up; pitch stops short of the pole.
    #[test]
    fn mouse_look_and_walk() {
        let mut c = Camera::default();
        c.look(100.0, 0.0);
        assert!((c.yaw_deg - 10.0).abs() < 1e-5 && c.axes().0.x > 0.0);
        c.look(0.0, -10_000.0);
        assert_eq!(c.pitch_deg, MAX_PITCH_DEG);
        let mut c = Camera::default();
        c.walk(1.0, 0.0, 1.0);
        assert!(close(c.position, Vec3::new(0.0, 0.0, 5.0 - MOVE_SPEED)));
    }

    /// A point the ray of a pixel passes through projects into that pixel's centre.
    #[test]
    fn rays_and_raster_agree() {
        for projection in [
            Projection::Perspective { fov_y_deg: 45.0 },
            Projection::Orthographic { half_height: 1.3 },
        ] {
            let c = Camera {
                position: Vec3::new(0.3, 0.2, 4.0),
                yaw_deg: 12.0,
                pitch_deg: -7.0,
                projection,
            };
            let (w, h) = (64, 48);
            let f = c.frame(w, h);
            let m = f.view_projection();
            for (x, y) in [(0, 0), (63, 47), (20, 31)] {
                let (o, d) = f.pixel_ray(x, y, w, h);
                let clip = m * (o + 3.0 * d).extend(1.0);
                let ndc = clip.truncate() / clip.w;
                let px = (ndc.x + 1.0) * 0.5 * w as f32;
                let py = (1.0 - ndc.y) * 0.5 * h as f32;
                assert!(
                    (px - (x as f32 + 0.5)).abs() < 1e-3,
                    "{projection:?} x {px}"
                );
                assert!(
                    (py - (y as f32 + 0.5)).abs() < 1e-3,
                    "{projection:?} y {py}"
                );
                assert!(ndc.z > 0.0 && ndc.z < 1.0);
            }
        }
    }
}
