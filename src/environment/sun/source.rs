//! Every compact bright source of an environment, as an area light: a soft box, a round
//! lamp, a window, a strip light, a second sun, not only the sun-sized ones
//! [`super::find_lights`] takes out. Each is measured by its shape on the sphere (a disc,
//! or a rectangle with its orientation), direction, angular size and radiance
//! (`docs/sun.md`, "Area sources").
//!
//! The estimator, on an equirect or a cube's level 0 (luminance Y, each texel's exact
//! solid angle Ω):
//!
//! 1. **Regions.** The texels brighter than [`HOT_FACTOR`] × the mean radiance, joined
//!    with their 8 neighbours (across an equirect's seam and a cube's face edges) into
//!    connected regions. Each region takes in the texels around it (the partly covered
//!    edge and the sun's halo, [`EDGE_TEXELS`]) and holds a source when its flux Σ Y Ω is at least [`MIN_SHARE`] of the
//!    environment's and it lies within [`MAX_SOURCE_RADIUS_DEG`] of its centre: at most
//!    [`MAX_SOURCES`], the most energetic first.
//! 2. **Fill and energy**, as for the sun: the sky under a region is the weighted
//!    least-squares plane fitted to the [`RING_TEXELS`] texels around it (every region and
//!    hot texel left out), never above a texel's own value, and E⊥ = Σ (L − fill) Ω per
//!    channel: the sources and the residual hold the input's flux to rounding, and the
//!    residual is never negative.
//! 3. **Moments.** The direction is the centre c of Σ Y_net Ω l. About it, in gnomonic
//!    coordinates (x, y) = (l·t₁, l·t₂) / (l·c), the flux-weighted second moments, less a
//!    texel's own ((h_x² + h_y²)/24 per axis, a box's), give the principal axes and their
//!    variances σ₁² ≥ σ₂².
//! 4. **Shape.** A uniform disc with those moments has radius 2 √((σ₁² + σ₂²)/2) (a disc of
//!    radius ρ has σ² = ρ²/4 along any axis), a uniform rectangle half-sides √3 σ₁ and
//!    √3 σ₂ along the axes (σ² = a²/3). Each is laid over the region's texels (a texel is
//!    inside where its centre is) with the uniform radiance that carries E⊥; the one that
//!    leaves less, Σ |Y_net − Ȳ inside| Ω / Σ Y_net Ω, is the source's shape (the disc on a
//!    tie), and what it leaves is reported: a textured source (a window and its frame)
//!    leaves more than a uniform one.

use rayon::prelude::*;
use serde::{Deserialize, Serialize};

use crate::environment::sun::fit::{fill_region, fit_plane, flux_centre, flux_stats, Filled};
use crate::environment::sun::grid::{angle, dot, luminance, normalize, tangent_frame, Grid};
use crate::environment::sun::{
    azimuth_deg, elevation_deg, turn_about_y, Sun, HALO_TEXELS, HOT_FACTOR, MIN_SHARE,
    RING_TEXELS,
};
use crate::environment::Environment;

/// At most this many sources are measured, the most energetic first: a studio's lamps
/// and soft boxes, an interior's windows and brightest lamps.
pub const MAX_SOURCES: usize = 8;

/// The widest a source reaches from its centre, in degrees: a soft box close to the
/// camera or a large window is under 20° in radius; a hot region wider than this is sky
/// (a sunlit haze, an overexposed cloud bank) that the IBL carries.
pub const MAX_SOURCE_RADIUS_DEG: f64 = 30.0;

/// Texels around a region's hot texels that it takes in: its partly covered edge and the
/// sun's halo ([`HALO_TEXELS`]), the glow a camera's optics spread around a bright source.
/// On studio_small_03 the lamp's edge alone (one texel) leaves its metals at 4.5 / 5.6 % at
/// r = 0.25 / 0.5, with the halo 3.4 / 3.9 % (`examples/area_study.rs`).
const EDGE_TEXELS: u32 = 1 + HALO_TEXELS as u32;

/// The shape of a source on the sphere.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(tag = "kind", rename_all = "lowercase")]
pub enum SourceShape {
    /// A uniform disc (a round lamp, a sun, a round soft box).
    Disc {
        /// Its angular radius, in degrees.
        radius_deg: f32,
    },
    /// A uniform rectangle (a soft box, a window, a strip light): the gnomonic rectangle
    /// of these angular half-sides about the source's direction.
    Rect {
        /// Angular half-width along `width_axis`, in degrees (the longer side).
        half_width_deg: f32,
        /// Angular half-height across it, in degrees.
        half_height_deg: f32,
        /// Unit vector along the width, perpendicular to the source's direction.
        width_axis: [f32; 3],
    },
}

impl SourceShape {
    /// The solid angle of the shape, in steradians: 2π (1 − cos ρ) for a disc,
    /// 4 asin(sin α sin β) for a rectangle of half-sides α, β (the solid angle of a
    /// rectangle seen from a point on its axis).
    pub fn solid_angle_sr(&self) -> f64 {
        match *self {
            SourceShape::Disc { radius_deg } => {
                2.0 * std::f64::consts::PI * (1.0 - f64::from(radius_deg).to_radians().cos())
            }
            SourceShape::Rect {
                half_width_deg,
                half_height_deg,
                ..
            } => rect_solid_angle(
                f64::from(half_width_deg).to_radians(),
                f64::from(half_height_deg).to_radians(),
            ),
        }
    }

    /// This shape with its axis mapped by `map` (a turn, a target's frame), as its
    /// light's direction is: a disc has no axis.
    pub fn map_axis(self, map: impl Fn([f32; 3]) -> [f32; 3]) -> SourceShape {
        match self {
            SourceShape::Rect {
                half_width_deg,
                half_height_deg,
                width_axis,
            } => SourceShape::Rect {
                half_width_deg,
                half_height_deg,
                width_axis: map(width_axis),
            },
            disc => disc,
        }
    }

    /// The angular radius of the disc of the same solid angle, in degrees: one size to
    /// compare sources of either shape by.
    pub fn equivalent_radius_deg(&self) -> f64 {
        let omega = self.solid_angle_sr();
        (1.0 - omega / (2.0 * std::f64::consts::PI))
            .clamp(-1.0, 1.0)
            .acos()
            .to_degrees()
    }
}

/// The solid angle of the gnomonic rectangle of angular half-sides `alpha`, `beta`
/// (radians) about a direction, 4 asin(sin α sin β): the rectangle seen from a point on
/// its axis.
pub(crate) fn rect_solid_angle(alpha: f64, beta: f64) -> f64 {
    4.0 * (alpha.sin() * beta.sin()).asin()
}

/// A compact bright source of an environment, as an area light.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct Source {
    /// Unit direction toward its centre (the flux-weighted centre), in the frame of the
    /// environment it was found in.
    pub direction: [f32; 3],
    /// E⊥ = Σ (L − fill) Ω per channel: the irradiance it gives a surface facing it, in the
    /// environment's radiance units.
    pub irradiance: [f32; 3],
    /// Its shape and angular size.
    pub shape: SourceShape,
    /// The shape's solid angle, in steradians.
    pub solid_angle_sr: f32,
    /// Its share of the environment's luminous flux (0 to 1).
    pub share: f32,
    /// What the uniform shape leaves of its light: Σ |Y_net − Ȳ inside| Ω / Σ Y_net Ω
    /// (0 for a uniform source of that shape; its texels' own blur and, for a textured
    /// source, its texture add to it).
    pub shape_residual: f32,
    /// How many texels its region holds (taken out and filled).
    pub texels: usize,
    /// The widest angle from its direction to a texel of its region, in degrees.
    pub region_radius_deg: f32,
}

impl Source {
    /// This source as a light of the environment: its E⊥, direction and share, the disc of
    /// its solid angle for a size, its shape kept ([`Sun::shape`]): a renderer without
    /// area lights shades it as a directional light.
    pub fn as_light(&self) -> Sun {
        Sun {
            direction: self.direction,
            irradiance: self.irradiance,
            solid_angle_sr: self.solid_angle_sr,
            angular_radius_deg: self.shape.equivalent_radius_deg() as f32,
            share: self.share,
            clipped: false,
            texels: self.texels,
            region_radius_deg: self.region_radius_deg,
            shape: Some(self.shape),
        }
    }

    /// The uniform radiance of the shape that carries E⊥, per channel.
    pub fn radiance(&self) -> [f32; 3] {
        let omega = self.solid_angle_sr.max(f32::MIN_POSITIVE);
        self.irradiance.map(|e| e / omega)
    }

    /// E⊥'s luminance.
    pub fn illuminance(&self) -> f32 {
        luminance(self.irradiance.map(f64::from)) as f32
    }

    /// Elevation above the horizon in degrees ([`super::Sun::elevation_deg`]'s).
    pub fn elevation_deg(&self) -> f32 {
        elevation_deg(self.direction)
    }

    /// Azimuth in degrees ([`super::Sun::azimuth_deg`]'s).
    pub fn azimuth_deg(&self) -> f32 {
        azimuth_deg(self.direction)
    }

    /// This source turned about +Y as `--rotate DEG` turns the environment.
    pub fn rotated(mut self, rotate_degrees: f32) -> Source {
        let turn = turn_about_y(rotate_degrees);
        self.direction = turn(self.direction);
        self.shape = self.shape.map_axis(turn);
        self
    }
}

impl std::fmt::Display for SourceShape {
    /// "disc, radius 5.20°" or "rectangle, 12.0° × 4.0°" (full angular sides).
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match *self {
            SourceShape::Disc { radius_deg } => write!(f, "disc, radius {radius_deg:.2}°"),
            SourceShape::Rect {
                half_width_deg,
                half_height_deg,
                ..
            } => write!(
                f,
                "rectangle, {:.2}° × {:.2}°",
                2.0 * half_width_deg,
                2.0 * half_height_deg
            ),
        }
    }
}

/// A source with where it was found: its region's texels and their fill.
struct SourceFit {
    source: Source,
    region: Vec<usize>,
    fill: Vec<[f32; 3]>,
}

/// The compact bright sources of `env`, most energetic first (see the module's estimator).
pub fn find_sources(env: &Environment) -> Vec<Source> {
    let grid = Grid::of(env);
    fit_sources(&grid, flux_stats(&grid).flux)
        .into_iter()
        .map(|f| f.source)
        .collect()
}

/// [`find_sources`] and the residual they leave: `env` with each source's region replaced
/// by its fill (a cube keeps its level 0 alone, its mips being stale).
pub fn take_sources_out(env: &Environment) -> (Vec<Source>, Environment) {
    let grid = Grid::of(env);
    take_sources_out_of(env, flux_stats(&grid).flux)
}

/// [`take_sources_out`] of `env`, a residual of an environment of luminous flux `flux`:
/// the hot threshold and each source's share are the environment's, not the residual's.
pub(crate) fn take_sources_out_of(env: &Environment, flux: f64) -> (Vec<Source>, Environment) {
    let fits = fit_sources(&Grid::of(env), flux);
    let mut residual = env.clone();
    for fit in &fits {
        match &mut residual {
            Environment::Equirect(e) => {
                for (&k, f) in fit.region.iter().zip(&fit.fill) {
                    e.data[k] = *f;
                }
            }
            Environment::Cube(c) => {
                c.levels.truncate(1);
                for (&k, f) in fit.region.iter().zip(&fit.fill) {
                    c.levels[0][k] = [f[0], f[1], f[2], 1.0];
                }
            }
        }
    }
    (fits.into_iter().map(|f| f.source).collect(), residual)
}

/// The texels of `from` and the layers of neighbours around them, `layers` deep, none of
/// them `excluded` (which the layers do not cross) nor in `from`.
fn grow(grid: &Grid, from: &[usize], layers: u32, excluded: &[bool]) -> Vec<usize> {
    let mut seen: std::collections::HashSet<usize> = from.iter().copied().collect();
    let mut front = from.to_vec();
    let mut out = Vec::new();
    for _ in 0..layers {
        let mut next = Vec::new();
        for &k in &front {
            for t in grid.neighbours(k) {
                if !excluded[t] && seen.insert(t) {
                    next.push(t);
                }
            }
        }
        out.extend_from_slice(&next);
        front = next;
    }
    out
}

/// The connected regions of texels brighter than `threshold`, each with its flux Σ Y Ω.
fn hot_regions(grid: &Grid, threshold: f64) -> (Vec<bool>, Vec<(Vec<usize>, f64)>) {
    let hot: Vec<bool> = (0..grid.len())
        .into_par_iter()
        .map(|k| luminance(grid.radiance(k)) > threshold)
        .collect();
    let mut visited = vec![false; grid.len()];
    let mut regions = Vec::new();
    for start in 0..grid.len() {
        if !hot[start] || visited[start] {
            continue;
        }
        visited[start] = true;
        let (mut stack, mut texels, mut flux) = (vec![start], Vec::new(), 0.0);
        while let Some(k) = stack.pop() {
            texels.push(k);
            flux += luminance(grid.radiance(k)) * grid.solid_angle(k);
            for t in grid.neighbours(k) {
                if hot[t] && !visited[t] {
                    visited[t] = true;
                    stack.push(t);
                }
            }
        }
        regions.push((texels, flux));
    }
    (hot, regions)
}

/// The sources of `grid`, a residual of an environment of luminous flux `flux`.
fn fit_sources(grid: &Grid, flux: f64) -> Vec<SourceFit> {
    if flux.is_nan() || flux <= 0.0 {
        return Vec::new();
    }
    let mean = flux / (4.0 * std::f64::consts::PI);
    let (hot, mut regions) = hot_regions(grid, HOT_FACTOR * mean);
    regions.retain(|(_, f)| *f >= MIN_SHARE * flux);
    regions.sort_by(|a, b| b.1.total_cmp(&a.1).then(a.0[0].cmp(&b.0[0])));
    regions.truncate(MAX_SOURCES);
    // Each region with its edge and halo; every region and hot texel is kept out of the
    // rings.
    let regions: Vec<Vec<usize>> = regions
        .iter()
        .map(|(texels, _)| {
            let mut region = texels.clone();
            region.extend(grow(grid, texels, EDGE_TEXELS, &hot));
            region
        })
        .collect();
    let mut claimed = hot;
    for &k in regions.iter().flatten() {
        claimed[k] = true;
    }
    let mut fits: Vec<SourceFit> = regions
        .into_iter()
        .filter_map(|region| fit_source(grid, region, &claimed, flux))
        .collect();
    fits.sort_by(|a, b| b.source.share.total_cmp(&a.source.share));
    fits
}

/// The source of one region, or `None` where it reaches beyond
/// [`MAX_SOURCE_RADIUS_DEG`] or holds under [`MIN_SHARE`] of `flux` once filled.
fn fit_source(grid: &Grid, region: Vec<usize>, claimed: &[bool], flux: f64) -> Option<SourceFit> {
    let c0 = flux_centre(grid, &region);
    let reach = region
        .iter()
        .map(|&k| angle(grid.direction(k), c0))
        .fold(0.0, f64::max);
    if reach > MAX_SOURCE_RADIUS_DEG.to_radians() {
        return None;
    }
    let ring = grow(grid, &region, RING_TEXELS as u32, claimed);
    let (t1, t2) = tangent_frame(c0);
    let gnomonic = |d: [f64; 3]| {
        let z = dot(d, c0).max(1e-6);
        (dot(d, t1) / z, dot(d, t2) / z)
    };
    let plane = fit_plane(grid, &ring, &gnomonic);
    let Filled {
        fill,
        net,
        irradiance,
        moment,
    } = fill_region(grid, &region, &plane, &gnomonic);
    let e_y = luminance(irradiance);
    let share = e_y / flux;
    if share.is_nan() || share < MIN_SHARE {
        return None;
    }
    let direction = normalize(moment);
    let shape = fit_shape(grid, &region, &net, direction);
    let (shape, shape_residual) = shape;
    Some(SourceFit {
        source: Source {
            direction: direction.map(|v| v as f32),
            irradiance: irradiance.map(|v| v as f32),
            shape,
            solid_angle_sr: shape.solid_angle_sr() as f32,
            share: share as f32,
            shape_residual: shape_residual as f32,
            texels: region.len(),
            region_radius_deg: reach.to_degrees() as f32,
        },
        region,
        fill,
    })
}

/// The shape that leaves least of the net luminance `net` of `region`'s texels about
/// `c`, and what it leaves (steps 3 and 4 of the module's estimator).
fn fit_shape(grid: &Grid, region: &[usize], net: &[f64], c: [f64; 3]) -> (SourceShape, f64) {
    let (t1, t2) = tangent_frame(c);
    let at = |k: usize| {
        let d = grid.direction(k);
        let z = dot(d, c).max(1e-6);
        (dot(d, t1) / z, dot(d, t2) / z)
    };
    // Flux-weighted second moments and the texels' own (a box's, per axis).
    let (mut w, mut mxx, mut mxy, mut myy, mut own) = (0.0, 0.0, 0.0, 0.0, 0.0);
    let mut coords = Vec::with_capacity(region.len());
    for (&k, &y) in region.iter().zip(net) {
        let (x, v) = at(k);
        coords.push((x, v));
        let e = y * grid.solid_angle(k);
        let (hx, hy) = grid.texel_extent(k);
        w += e;
        mxx += e * x * x;
        mxy += e * x * v;
        myy += e * v * v;
        own += e * (hx * hx + hy * hy) / 24.0;
    }
    let w = w.max(f64::MIN_POSITIVE);
    let (mxx, mxy, myy, own) = (mxx / w, mxy / w, myy / w, own / w);
    let half = 0.5 * (mxx + myy);
    let spread = (0.25 * (mxx - myy) * (mxx - myy) + mxy * mxy).sqrt();
    // A source narrower than its texels is a texel's size: its own moment is the floor.
    let less_own = |l: f64| (l - own).max(0.25 * l).max(own);
    let (l1, l2) = (less_own(half + spread), less_own(half - spread));
    let theta = 0.5 * (2.0 * mxy).atan2(mxx - myy);
    let (ct, st) = (theta.cos(), theta.sin());
    let axis: [f64; 3] = std::array::from_fn(|i| ct * t1[i] + st * t2[i]);
    let radius = 2.0 * (0.5 * (l1 + l2)).sqrt();
    let (a, b) = ((3.0 * l1).sqrt(), (3.0 * l2).sqrt());
    let leaves = |inside: &dyn Fn(f64, f64) -> bool| {
        let covered: f64 = region
            .iter()
            .zip(&coords)
            .filter(|(_, &(x, v))| inside(x * ct + v * st, v * ct - x * st))
            .map(|(&k, _)| grid.solid_angle(k))
            .sum();
        if covered <= 0.0 {
            return 1.0;
        }
        let mean = w / covered;
        region
            .iter()
            .zip(net)
            .zip(&coords)
            .map(|((&k, &y), &(x, v))| {
                let inside = inside(x * ct + v * st, v * ct - x * st);
                (y - if inside { mean } else { 0.0 }).abs() * grid.solid_angle(k)
            })
            .sum::<f64>()
            / w
    };
    let disc = leaves(&|u, v| u * u + v * v <= radius * radius);
    let rect = leaves(&|u, v| u.abs() <= a && v.abs() <= b);
    if disc <= rect {
        let shape = SourceShape::Disc {
            radius_deg: radius.atan().to_degrees() as f32,
        };
        (shape, disc)
    } else {
        let shape = SourceShape::Rect {
            half_width_deg: a.atan().to_degrees() as f32,
            half_height_deg: b.atan().to_degrees() as f32,
            width_axis: axis.map(|v| v as f32),
        };
        (shape, rect)
    }
}
