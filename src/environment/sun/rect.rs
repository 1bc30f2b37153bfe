//! The rectangle an engine's rect area light draws for an area source at infinity
//! (three.js's and Babylon.js's `RectAreaLight`, Bevy's `RectLight`): an engine places a
//! rectangle at a finite distance d, facing the origin, so the source becomes the
//! rectangle 2 d tan α wide and 2 d tan β high about its direction, α and β its angular
//! half-sides. From the origin it subtends the source's gnomonic rectangle exactly, of
//! solid angle Ω = 4 asin(sin α sin β) (the rectangle seen from a point on its axis), and
//! its uniform radiance L = E⊥ / Ω gives a surface facing it the source's E⊥ = Σ L Ω.
//!
//! A disc (these engines have no disc light) becomes the square of its solid angle:
//! sin α = √(sin(Ω/4)). A point p away from the origin sees the rectangle turned by up to
//! |p| / d radians and its solid angle scaled by about (d / (d − p·ω))², so the irradiance
//! it gets is off by about 2 p·ω / d (2 % at |p| = d / 100): docs/targets.md, "Area lights".

use serde::{Deserialize, Serialize};

use crate::environment::sun::grid::{cross, luminance, tangent_frame};
use crate::environment::sun::source::rect_solid_angle;
use crate::environment::sun::{SourceShape, Sun};

/// An area light as the rectangle an engine draws (see the module's doc).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct RectLight {
    /// Angular half-width α along `width_axis`, in degrees: the rectangle at distance d
    /// is 2 d tan α wide.
    pub half_width_deg: f32,
    /// Angular half-height β along `height_axis`, in degrees.
    pub half_height_deg: f32,
    /// Unit vector along the width, perpendicular to the light's direction.
    pub width_axis: [f32; 3],
    /// Unit vector along the height: the light's direction × `width_axis`.
    pub height_axis: [f32; 3],
    /// Uniform radiance per channel, E⊥ / Ω, in the environment's radiance units.
    pub radiance: [f32; 3],
    /// The radiance's luminance (0.2126 R + 0.7152 G + 0.0722 B).
    pub luminance: f32,
}

impl RectLight {
    /// The rectangle of `shape` about `direction` carrying `irradiance` (E⊥ per channel).
    pub fn of(direction: [f32; 3], shape: SourceShape, irradiance: [f32; 3]) -> RectLight {
        let d = direction.map(f64::from);
        let (alpha, beta, width) = match shape {
            SourceShape::Rect {
                half_width_deg,
                half_height_deg,
                width_axis,
            } => (
                f64::from(half_width_deg).to_radians(),
                f64::from(half_height_deg).to_radians(),
                width_axis.map(f64::from),
            ),
            SourceShape::Disc { .. } => {
                let side = (shape.solid_angle_sr() / 4.0).sin().sqrt().asin();
                (side, side, tangent_frame(d).0)
            }
        };
        let height = cross(d, width);
        let omega = rect_solid_angle(alpha, beta).max(f64::MIN_POSITIVE);
        let radiance = irradiance.map(|e| (f64::from(e) / omega) as f32);
        RectLight {
            half_width_deg: alpha.to_degrees() as f32,
            half_height_deg: beta.to_degrees() as f32,
            width_axis: width.map(|c| c as f32),
            height_axis: height.map(|c| c as f32),
            luminance: luminance(radiance.map(f64::from)) as f32,
            radiance,
        }
    }

    /// The solid angle the rectangle subtends from the origin, 4 asin(sin α sin β).
    pub fn solid_angle_sr(&self) -> f64 {
        rect_solid_angle(
            f64::from(self.half_width_deg).to_radians(),
            f64::from(self.half_height_deg).to_radians(),
        )
    }

    /// This rectangle with its axes mapped by `map` (a target's frame), as its light's
    /// direction is.
    pub fn map_axes(self, map: impl Fn([f32; 3]) -> [f32; 3]) -> RectLight {
        RectLight {
            width_axis: map(self.width_axis),
            height_axis: map(self.height_axis),
            ..self
        }
    }
}

impl Sun {
    /// How its shadow's penumbra widens per unit of distance from the blocker, tan ρ of
    /// its angular radius, for an area light; 0 for a sun-sized light, whose penumbra a
    /// shadow map draws as a hard edge.
    pub fn penumbra_spread(&self) -> f32 {
        match self.shape {
            Some(_) => self.angular_radius_deg.to_radians().tan(),
            None => 0.0,
        }
    }

    /// The rectangle an engine's rect area light draws for this light, when it is an
    /// area source (`None` for a sun-sized light, a directional light).
    pub fn rect_light(&self) -> Option<RectLight> {
        self.shape
            .map(|shape| RectLight::of(self.direction, shape, self.irradiance))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn light(shape: SourceShape) -> Sun {
        Sun {
            direction: [0.0, 0.6, 0.8],
            irradiance: [3.0, 2.0, 1.0],
            solid_angle_sr: shape.solid_angle_sr() as f32,
            angular_radius_deg: shape.equivalent_radius_deg() as f32,
            share: 0.5,
            clipped: false,
            texels: 100,
            region_radius_deg: 12.0,
            shape: Some(shape),
        }
    }

    /// The rectangle carries E⊥ = L Ω, in the shape's solid angle, about the light's
    /// direction with a right-handed orthonormal frame.
    #[test]
    fn carries_the_irradiance_in_the_shapes_solid_angle() {
        for shape in [
            SourceShape::Disc { radius_deg: 6.0 },
            SourceShape::Rect {
                half_width_deg: 15.0,
                half_height_deg: 4.0,
                width_axis: [1.0, 0.0, 0.0],
            },
        ] {
            let sun = light(shape);
            let rect = sun.rect_light().unwrap();
            let omega = rect.solid_angle_sr();
            assert!((omega / shape.solid_angle_sr() - 1.0).abs() < 1e-6, "{shape:?}: {omega}");
            for c in 0..3 {
                let e = f64::from(rect.radiance[c]) * omega;
                assert!((e / f64::from(sun.irradiance[c]) - 1.0).abs() < 1e-6);
            }
            let dot = |a: [f32; 3], b: [f32; 3]| a.iter().zip(b).map(|(x, y)| x * y).sum::<f32>();
            let (w, h, d) = (rect.width_axis, rect.height_axis, sun.direction);
            assert!(dot(w, d).abs() < 1e-6 && dot(h, d).abs() < 1e-6 && dot(w, h).abs() < 1e-6);
            assert!((dot(w, w) - 1.0).abs() < 1e-6 && (dot(h, h) - 1.0).abs() < 1e-6);
            // height = direction × width.
            let cross = [
                d[1] * w[2] - d[2] * w[1],
                d[2] * w[0] - d[0] * w[2],
                d[0] * w[1] - d[1] * w[0],
            ];
            assert!(cross.iter().zip(h).all(|(a, b)| (a - b).abs() < 1e-6));
        }
        // A disc becomes a square; a rectangle keeps its sides.
        let disc = light(SourceShape::Disc { radius_deg: 6.0 }).rect_light().unwrap();
        assert_eq!(disc.half_width_deg, disc.half_height_deg);
        let rect = light(SourceShape::Rect {
            half_width_deg: 15.0,
            half_height_deg: 4.0,
            width_axis: [1.0, 0.0, 0.0],
        })
        .rect_light()
        .unwrap();
        assert_eq!((rect.half_width_deg, rect.half_height_deg), (15.0, 4.0));
    }

    #[test]
    fn a_directional_light_has_no_rectangle() {
        let mut sun = light(SourceShape::Disc { radius_deg: 1.0 });
        sun.shape = None;
        assert!(sun.rect_light().is_none());
    }
}
