//! The sun: the most energetic compact bright region of an environment, found on its
//! texels with the exact solid angle of each, measured as a light, and taken out of the
//! environment so that the sky can be baked without it (`docs/sun.md` says why and how
//! each threshold was chosen).
//!
//! The estimator, on an equirect or a cube's level 0, luminance Y = 0.2126 R + 0.7152 G +
//! 0.0722 B:
//!
//! 1. **Candidates.** Texels brighter than [`HOT_FACTOR`] × the mean radiance (at most
//!    [`MAX_CANDIDATE_TEXELS`], the brightest) are gathered into clusters of angular radius
//!    [`SEARCH_RADIUS_DEG`] around their brightest texel, and the clusters are tried in
//!    order of their flux Σ Y Ω.
//! 2. **Core.** Around a cluster's brightest texel (radiance peak Y_p), the texels within
//!    [`SEARCH_RADIUS_DEG`] brighter than [`CORE_FRACTION`] × Y_p are its core; their
//!    flux-weighted centre c₀ and the angle ρ_core from c₀ to the farthest of them (plus
//!    half a texel's diagonal) say how compact it is. A core wider than
//!    [`MAX_SUN_RADIUS_DEG`] is an extended source (a soft box, a bright cloud), not a sun.
//! 3. **Region and ring.** The region is the cap of radius ρ = ρ_core + [`HALO_TEXELS`]
//!    texels around c₀ (it takes in the blur and glow around the disc); the ring is the
//!    annulus [`RING_TEXELS`] texels wide outside it.
//! 4. **Fill.** Each channel of the sky under the region is the weighted least-squares
//!    plane a + b x + c y fitted to the ring's texels (x, y gnomonic coordinates about c₀,
//!    weights Ω), clamped to the ring's range and to the texel's own value (the fill never
//!    brightens a texel): exact for a sky that varies linearly across the sun, with no
//!    hole and no halo left behind.
//! 5. **The light.** Per channel E⊥ = Σ_region (L − fill) Ω: the flux taken out minus what
//!    the fill puts back, so the residual's flux plus E⊥ is the input's to rounding. Its
//!    direction is the centre of Σ Y_net Ω l, its angular radius ρ_s = √(2 ⟨γ²⟩) from the
//!    flux-weighted second moment of the angle γ to that centre (a uniform disc of radius ρ
//!    has ⟨γ²⟩ = ρ²/2) less a texel's own, (h_x² + h_y²)/12, its solid angle that of a
//!    cap of radius ρ_s. A light no wider than its texels (one lit texel) is a cap of its
//!    brightest texel's solid angle: never a light of 0 sr.
//! 6. **Dominance.** A region whose share of the environment's luminous flux is below
//!    [`MIN_SHARE`] is no sun (an overcast sky's brightest patch, a distant lamp).
//! 7. **Clipping.** [`CLIP_TEXELS`] or more core texels within [`CLIP_TOLERANCE`] of the
//!    peak, covering at least [`CLIP_AREA`] of the sun's solid angle (a plateau at one
//!    value), mean the camera saturated: E⊥ is then a lower bound.
//!
//! The sun is the first light [`split_lights`] finds; it goes on finding, on what each
//! light leaves, the further compact sources holding [`MIN_SHARE`] (an interior's
//! brightest lamps), at most [`MAX_LIGHTS`]: every one left in the IBL is a lobe-wide
//! error where the split-sum looks it up.
//!
//! Non-finite and negative texels count as black: they are never a sun, and inside the
//! region the fill replaces them.

mod fit;
pub(crate) mod grid;
mod rect;
mod source;

use serde::{Deserialize, Serialize};

use crate::environment::Environment;
use crate::math::cubemap::rotate_y;
use fit::{clusters, fit_sun, flux_stats};
use grid::{luminance, tangent_frame, Grid};
pub use rect::RectLight;
pub use source::{find_sources, take_sources_out, Source, SourceShape};
use source::take_sources_out_of;

/// A texel is a candidate when its luminance exceeds this multiple of the environment's
/// mean (the hot-texel threshold of [`crate::environment::hot`]).
pub const HOT_FACTOR: f64 = crate::environment::hot::HOT_FACTOR as f64;
/// At most this many candidate texels (the brightest) are clustered.
pub const MAX_CANDIDATE_TEXELS: usize = 4096;
/// At most this many compact lights are taken out (the sun and the brightest lamps after
/// it): the bundled interiors hold two above [`MIN_SHARE`].
pub const MAX_LIGHTS: usize = 4;
/// At most this many clusters, the most energetic first, are tried.
pub const MAX_CLUSTERS: usize = 8;
/// Radius of a cluster and of the search for its core: twice [`MAX_SUN_RADIUS_DEG`], so an
/// extended source is seen to reach beyond the bound.
pub const SEARCH_RADIUS_DEG: f64 = 2.0 * MAX_SUN_RADIUS_DEG;
/// The widest core that is still a sun. The sun's disc is 0.27° in radius; a camera's blur
/// and a 1k equirect's 0.35° texels make the cores of the bundled HDRIs' suns 0.5–0.8°
/// (quarry_01, royal_esplanade), and a lens's glare a little more, while a studio's soft
/// boxes are 6° and wider.
pub const MAX_SUN_RADIUS_DEG: f64 = 3.0;
/// A core texel is brighter than this fraction of the cluster's peak: the disc, its blur
/// and a saturated plateau, not the glow around it (which the region takes in).
pub const CORE_FRACTION: f64 = 0.01;
/// Texels of margin between the core and the region's edge: the blur and glow of a
/// camera's optics, which would otherwise be left as a halo.
pub const HALO_TEXELS: f64 = 2.0;
/// Width of the ring the fill is fitted to, in texels.
pub const RING_TEXELS: f64 = 2.0;
/// Smallest share of the environment's luminous flux a sun holds. A light with less casts
/// a shadow that darkens a surface by under 5 % (hardly visible), and the IBL renders it
/// within its own accuracy. The suns of the bundled HDRIs hold 22–49 % (quarry_01,
/// royal_esplanade, the sun through blender_studiolight_interior's window); the nearest
/// below is venice_sunset's setting sun in its unclipped EXR, 2.4 %; the brightest compact
/// patches of the overcast and sunless ones (pedestrian_overpass, venice_sunset's clipped
/// .hdr) hold under 0.1 %.
pub const MIN_SHARE: f64 = 0.05;
/// Texels at the peak's value that make a plateau (a saturated sensor): more than the 2×2
/// a peaked sun centred on a texel corner gives by symmetry.
pub const CLIP_TEXELS: usize = 5;
/// The plateau's smallest share of the sun's solid angle: a saturated sun is flat over
/// most of its disc, while a limb-darkened one is within [`CLIP_TOLERANCE`] of its peak
/// over about 1 % of it (wherever its texels are narrow, as near an equirect's poles).
pub const CLIP_AREA: f64 = 0.25;
/// Relative tolerance of "at the peak's value": one step of RGBE's 8-bit mantissa.
pub const CLIP_TOLERANCE: f64 = 1.0 / 256.0;

/// What a bake does with the sun.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum SunMode {
    /// The sun stays in the environment and is baked into the IBL like any texel (it is
    /// still found and reported).
    #[default]
    Keep,
    /// The sun is taken out: the IBL is baked from the residual, and the sun is written
    /// as a light.
    Split,
}

impl SunMode {
    /// Both modes.
    pub const ALL: [SunMode; 2] = [SunMode::Keep, SunMode::Split];

    /// Lower-case name, as `--sun` takes it.
    pub fn name(self) -> &'static str {
        match self {
            SunMode::Keep => "keep",
            SunMode::Split => "split",
        }
    }

    /// The mode called `name`.
    pub fn by_name(name: &str) -> Option<SunMode> {
        SunMode::ALL.into_iter().find(|m| m.name() == name)
    }

    /// The other mode.
    pub fn other(self) -> SunMode {
        match self {
            SunMode::Keep => SunMode::Split,
            SunMode::Split => SunMode::Keep,
        }
    }

    /// Of the lights `found` in an environment, those a bake in this mode takes out of
    /// it (and a renderer shades as lights): all with split, none with keep.
    pub fn split_out(self, found: &[Sun]) -> &[Sun] {
        match self {
            SunMode::Split => found,
            SunMode::Keep => &[],
        }
    }
}

/// The sun of an environment, as a light.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct Sun {
    /// Unit direction toward the sun's centre (the flux-weighted centre), in the frame of
    /// the environment it was found in (for a bake: the generic frame, rotation applied).
    pub direction: [f32; 3],
    /// E⊥ = Σ (L − fill) Ω per channel: the irradiance on a surface facing the sun, in the
    /// environment's radiance units.
    pub irradiance: [f32; 3],
    /// Solid angle of a disc of [`Sun::angular_radius_deg`], in steradians.
    pub solid_angle_sr: f32,
    /// Angular radius of the disc with the same second moment, in degrees (the real sun's
    /// is 0.27°; blur and texels make a measured one larger).
    pub angular_radius_deg: f32,
    /// Its share of the environment's luminous flux (0 to 1).
    pub share: f32,
    /// Whether its core is a plateau at one value (a saturated camera): its irradiance is
    /// then a lower bound.
    pub clipped: bool,
    /// How many texels the region holds (taken out and filled).
    pub texels: usize,
    /// Angular radius of the region taken out and filled (the core, its halo), in
    /// degrees, about the core's centre (within a texel of [`Sun::direction`]): the
    /// environment's texels this light was measured from. 0 when read from a file that
    /// does not give it.
    #[serde(default)]
    pub region_radius_deg: f32,
    /// An area source's shape (a soft box, a window, a lamp wider than a sun): `None` for
    /// a sun-sized light, which is shaded as a directional light. A renderer with area
    /// lights shades the shape; one without, a directional light of the same E⊥.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub shape: Option<SourceShape>,
}

impl Sun {
    /// Elevation above the horizon (the XZ plane) in degrees.
    pub fn elevation_deg(&self) -> f32 {
        elevation_deg(self.direction)
    }

    /// Azimuth in degrees, (−180, 180]: 0 along +X (an equirect's centre), 90 along +Z
    /// (u = 0.75), as the equirect's u = 0.5 + atan2(z, x)/(2π).
    pub fn azimuth_deg(&self) -> f32 {
        azimuth_deg(self.direction)
    }

    /// E⊥'s luminance.
    pub fn illuminance(&self) -> f32 {
        luminance(self.irradiance.map(f64::from)) as f32
    }

    /// This light turned about +Y as `--rotate DEG` turns the environment: its direction,
    /// and an area light's axis with it.
    pub fn rotated(mut self, rotate_degrees: f32) -> Sun {
        let turn = turn_about_y(rotate_degrees);
        self.direction = turn(self.direction);
        self.shape = self.shape.map(|s| s.map_axis(turn));
        self
    }

    /// The sun as a uniform disc of its radius split into `rings` rings of equal-area
    /// cells (1, 6, 12, … cells): (unit direction, solid angle, radiance) each, their
    /// Σ radiance × Ω equal to E⊥. What the preview's ground truth integrates and the
    /// energy checks sum.
    pub fn disc_cells(&self, rings: u32) -> Vec<([f32; 3], f32, [f32; 3])> {
        let c = self.direction.map(f64::from);
        let (t1, t2) = tangent_frame(c);
        let rho = f64::from(self.angular_radius_deg).to_radians();
        let rings = rings.max(1);
        let total = 1 + 3 * rings * (rings - 1);
        let omega = f64::from(self.solid_angle_sr) / f64::from(total);
        let radiance = self.irradiance.map(|e| e / (omega as f32 * total as f32));
        let mut cells = Vec::with_capacity(total as usize);
        for ring in 0..rings {
            let count = if ring == 0 { 1 } else { 6 * ring };
            let before = if ring == 0 {
                0
            } else {
                1 + 3 * ring * (ring - 1)
            };
            // Equal area: the cumulative count grows as the radius squared; each cell sits
            // at the radius halving its ring's area.
            let r0 = rho * (f64::from(before) / f64::from(total)).sqrt();
            let r1 = rho * (f64::from(before + count) / f64::from(total)).sqrt();
            let r = if ring == 0 {
                0.0
            } else {
                ((r0 * r0 + r1 * r1) / 2.0).sqrt()
            };
            for k in 0..count {
                let phi = 2.0 * std::f64::consts::PI * (f64::from(k) + 0.5) / f64::from(count);
                let d: [f64; 3] = std::array::from_fn(|i| {
                    c[i] * r.cos() + (t1[i] * phi.cos() + t2[i] * phi.sin()) * r.sin()
                });
                cells.push((d.map(|v| v as f32), omega as f32, radiance));
            }
        }
        cells
    }
}

/// The turn about +Y of `--rotate DEG`, as a map of directions.
pub(crate) fn turn_about_y(rotate_degrees: f32) -> impl Fn([f32; 3]) -> [f32; 3] + Copy {
    let r = rotate_degrees.to_radians();
    let (c, s) = (r.cos(), r.sin());
    move |d| rotate_y(d, c, s)
}

/// Elevation of unit `d` above the horizon (the XZ plane) in degrees.
pub(crate) fn elevation_deg(d: [f32; 3]) -> f32 {
    d[1].clamp(-1.0, 1.0).asin().to_degrees()
}

/// Azimuth of `d` in degrees, (−180, 180]: 0 along +X (an equirect's centre), 90 along
/// +Z (u = 0.75), as the equirect's u = 0.5 + atan2(z, x)/(2π).
pub(crate) fn azimuth_deg(d: [f32; 3]) -> f32 {
    d[2].atan2(d[0]).to_degrees()
}

impl std::fmt::Display for Sun {
    /// "azimuth 36.0°, elevation 10.1°, radius 0.62°, 48.3 % of the light, E 3.64 (clipped)";
    /// an area light gives its shape ("rectangle, 6.25° × 6.14°") for the radius.
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let size = match self.shape {
            Some(shape) => format!("an area light: {shape}"),
            None => format!("radius {:.2}°", self.angular_radius_deg),
        };
        write!(
            f,
            "azimuth {:.1}°, elevation {:.1}°, {size}, {:.1} % of the light, E {:.4}{}",
            self.azimuth_deg(),
            self.elevation_deg(),
            100.0 * self.share,
            self.illuminance(),
            if self.clipped {
                " (clipped: a lower bound)"
            } else {
                ""
            }
        )
    }
}

/// A sun found in an environment: the light, and where and how it was taken out.
#[derive(Clone, Debug)]
pub struct SunFit {
    /// The light.
    pub sun: Sun,
    /// The region's texel indices (an equirect's y·W + x, a cube's (face·n + j)·n + i).
    pub region: Vec<usize>,
    /// The fill of each region texel (the sky under the sun).
    pub fill: Vec<[f32; 3]>,
}

/// Finds the sun of `env` (the input's level 0 for a cube), or `None` when it has no
/// compact dominant source.
pub fn find_sun(env: &Environment) -> Option<SunFit> {
    let flux = flux_stats(&Grid::of(env)).flux;
    find_next(env, flux)
}

/// The most energetic compact source of `env` holding at least [`MIN_SHARE`] of `flux`
/// (the input's luminous flux, which `env` may be a residual of).
fn find_next(env: &Environment, flux: f64) -> Option<SunFit> {
    let grid = Grid::of(env);
    if flux.is_nan() || flux <= 0.0 {
        return None;
    }
    let mean = flux_stats(&grid).flux / (4.0 * std::f64::consts::PI);
    clusters(&grid, mean, flux)
        .into_iter()
        .find_map(|seed| fit_sun(&grid, seed, flux))
}

/// The compact dominant sources of `env`, most energetic first: the sun, then each further
/// compact source holding [`MIN_SHARE`] of the input's light (an interior's brightest
/// lamps), at most [`MAX_LIGHTS`]. Each is found on what the ones before it leave (their
/// regions filled), its share taken of the input's flux. `env` is left as it is; it is
/// copied only when it has a sun, to look for further lights on what the sun leaves.
pub fn find_lights(env: &Environment) -> Vec<Sun> {
    match take_lights_out(env) {
        Some((lights, _)) => lights,
        None => Vec::new(),
    }
}

/// [`find_lights`], taking each light out of `env` as it is found: `env` becomes the
/// residual (a cube keeps its level 0 alone, its mips being stale).
pub fn split_lights(env: &mut Environment) -> Vec<Sun> {
    match take_lights_out(env) {
        Some((lights, residual)) => {
            *env = residual;
            lights
        }
        None => Vec::new(),
    }
}

/// The lights of `env` ([`find_lights`]) and the residual they leave, or `None` when it
/// has none (and nothing is copied): what `--sun split` bakes from, with `env` kept as
/// seen for a background. The sun-sized lights first (at most [`MAX_LIGHTS`]), then the
/// area sources of what they leave ([`take_sources_out`], each with its [`Sun::shape`]),
/// every share of `env`'s flux.
pub fn take_lights_out(env: &Environment) -> Option<(Vec<Sun>, Environment)> {
    let flux = flux_stats(&Grid::of(env)).flux;
    let mut lights = Vec::new();
    let mut residual = None;
    if let Some(sun) = find_next(env, flux) {
        let mut rest = env.clone();
        apply_fill(&mut rest, &sun);
        lights.push(sun.sun);
        take_further_lights(&mut rest, flux, &mut lights);
        residual = Some(rest);
    }
    let (sources, rest) = take_sources_out_of(residual.as_ref().unwrap_or(env), flux);
    if !sources.is_empty() {
        lights.extend(sources.iter().map(Source::as_light));
        residual = Some(rest);
    }
    residual.map(|r| (lights, r))
}

/// Finds and takes out of `env` the lights after `lights`, up to [`MAX_LIGHTS`] in all.
fn take_further_lights(env: &mut Environment, flux: f64, lights: &mut Vec<Sun>) {
    while lights.len() < MAX_LIGHTS {
        let Some(fit) = find_next(env, flux) else {
            break;
        };
        apply_fill(env, &fit);
        lights.push(fit.sun);
    }
}

/// Finds the sun of `env` and replaces its region by the fill (the first of
/// [`split_lights`] alone). Returns the sun, or `None` (and `env` unchanged) when there
/// is none.
pub fn split_sun(env: &mut Environment) -> Option<Sun> {
    let fit = find_sun(env)?;
    apply_fill(env, &fit);
    Some(fit.sun)
}

/// Writes `fit`'s fill into its region of `env`.
fn apply_fill(env: &mut Environment, fit: &SunFit) {
    match env {
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

#[cfg(test)]
mod tests {
    use super::grid::{angle, dot, normalize};
    use super::*;
    use crate::environment::Equirect;

    #[test]
    fn disc_cells_hold_the_irradiance_and_stay_inside_the_disc() {
        let sun = Sun {
            direction: [0.6, 0.8, 0.0],
            irradiance: [3.0, 2.0, 1.0],
            solid_angle_sr: (2.0 * std::f64::consts::PI * (1.0 - 2f64.to_radians().cos())) as f32,
            angular_radius_deg: 2.0,
            share: 0.5,
            clipped: false,
            texels: 0,
            region_radius_deg: 2.5,
            shape: None,
        };
        let cells = sun.disc_cells(4);
        assert_eq!(cells.len(), 37);
        let e: f32 = cells.iter().map(|c| c.2[0] * c.1).sum();
        assert!((e - 3.0).abs() < 1e-4, "{e}");
        for (d, _, _) in &cells {
            let a = angle(d.map(f64::from), sun.direction.map(f64::from)).to_degrees();
            assert!(a < 2.0, "{a}");
        }
    }

    /// `--rotate` turns an area light's axis with its direction, whether the light is
    /// turned as a source or as a light of the bake.
    #[test]
    fn a_turn_turns_an_area_lights_axis() {
        let source = Source {
            direction: [1.0, 0.0, 0.0],
            irradiance: [1.0; 3],
            shape: SourceShape::Rect {
                half_width_deg: 4.0,
                half_height_deg: 2.0,
                width_axis: [0.0, 0.0, 1.0],
            },
            solid_angle_sr: 0.01,
            share: 0.5,
            shape_residual: 0.0,
            texels: 10,
            region_radius_deg: 6.0,
        };
        let light = source.as_light().rotated(90.0);
        assert_eq!(light, source.rotated(90.0).as_light());
        let turned = rotate_y([0.0, 0.0, 1.0], 0.0, 1.0);
        let Some(SourceShape::Rect { width_axis, .. }) = light.shape else {
            panic!("{light:?}")
        };
        let d = angle(width_axis.map(f64::from), turned.map(f64::from));
        assert!(d < 1e-6, "{width_axis:?} against {turned:?}");
        assert!(angle(light.direction.map(f64::from), rotate_y([1.0, 0.0, 0.0], 0.0, 1.0).map(f64::from)) < 1e-6);
    }

    #[test]
    fn equirect_cap_finds_every_texel_within_the_radius() {
        let e = Equirect {
            width: 64,
            height: 32,
            data: vec![[1.0; 3]; 64 * 32],
        };
        let grid = Grid::Equirect(&e);
        for c in [
            [1.0, 0.0, 0.0],
            [0.0, 1.0, 0.0],
            normalize([-1.0, 0.3, -0.01]),
            normalize([0.1, -0.99, 0.0]),
        ] {
            for r in [0.05f64, 0.2, 0.7] {
                let mut got = grid.cap(c, r);
                got.sort();
                let want: Vec<usize> = (0..grid.len())
                    .filter(|&k| dot(grid.direction(k), c) >= r.cos())
                    .collect();
                assert_eq!(got, want, "{c:?} {r}");
            }
        }
    }
}
