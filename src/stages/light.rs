//! The light of one environment, baked in memory: cube conversion, the prefiltered
//! specular chain (its roughest level fitted for bilinear lookups), the irradiance cube,
//! the Charlie sheen chain where a target reads one, and the SH. Each step is a
//! [`Stage`], reported to a progress callback and timed.

use std::time::Instant;

use crate::backend::Backend;
use crate::environment::sun::{find_lights, take_lights_out, Sun, SunMode};
use crate::environment::{Cubemap, Environment};
use crate::plan::chain::SpecularChain;
use crate::plan::fit::fit_roughest_level;
use crate::stages::convert::{environment_into_cube, environment_into_cube_with_irradiance};
use crate::stages::sh::{sh_project, ShCoefficients};
use crate::Result;

/// A stage of a bake, reported to the progress callback before it starts.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Stage {
    /// Reading and validating the input.
    Load,
    /// Finding the sun (and taking it out with `--sun split`).
    Sun,
    /// Converting to the environment cubemap with mips.
    Cubemap,
    /// Converting the environment as seen, lights included, for a background (only when
    /// `--sun split` took lights out).
    Background,
    /// Converting the environment as read, lights included, at its own resolution for a
    /// ground truth (only for a preview or the viewer, and only when that resolution is
    /// not the specular chain's).
    Truth,
    /// Prefiltering the specular chain.
    Specular,
    /// Convolving the irradiance cube.
    Irradiance,
    /// Prefiltering the Charlie sheen chain (targets that read one).
    Sheen,
    /// Projecting onto spherical harmonics.
    Sh,
    /// Rendering the preview.
    Preview,
    /// Encoding and writing the outputs.
    Write,
}

impl Stage {
    /// Lower-case name.
    pub fn name(self) -> &'static str {
        match self {
            Stage::Load => "load",
            Stage::Sun => "sun",
            Stage::Cubemap => "cubemap",
            Stage::Background => "background",
            Stage::Truth => "truth",
            Stage::Specular => "specular",
            Stage::Irradiance => "irradiance",
            Stage::Sheen => "sheen",
            Stage::Sh => "sh",
            Stage::Preview => "preview",
            Stage::Write => "write",
        }
    }

    /// All stages in order.
    pub const ALL: [Stage; 11] = [
        Stage::Load,
        Stage::Sun,
        Stage::Cubemap,
        Stage::Background,
        Stage::Truth,
        Stage::Specular,
        Stage::Irradiance,
        Stage::Sheen,
        Stage::Sh,
        Stage::Preview,
        Stage::Write,
    ];
}

/// Wall seconds per stage, in the order they ran.
pub type Timings = Vec<(Stage, f64)>;

/// Runs `f` as `stage`: reports it to `progress` and records its wall time.
pub fn timed_stage<T>(
    stage: Stage,
    progress: &mut dyn FnMut(Stage),
    timings: &mut Timings,
    f: impl FnOnce() -> Result<T>,
) -> Result<T> {
    progress(stage);
    let t = Instant::now();
    let out = f()?;
    timings.push((stage, t.elapsed().as_secs_f64()));
    Ok(out)
}

/// What the in-memory bake computes (already validated by the caller).
#[derive(Clone, Copy, Debug)]
pub struct LightOptions {
    /// Specular cube edge.
    pub specular_size: u32,
    /// The specular chain's layout.
    pub chain: SpecularChain,
    /// Irradiance cube edge.
    pub irradiance_size: u32,
    /// GGX samples per texel of the importance-sampled levels.
    pub samples: u32,
    /// Rotation about +Y in degrees.
    pub rotate_degrees: f32,
    /// Prefilter the Charlie sheen chain.
    pub sheen: bool,
    /// Project onto SH.
    pub sh: bool,
    /// Whether the sun is taken out and baked as a light.
    pub sun: SunMode,
    /// Keep the environment as read at its own resolution ([`BakedEnvironment::truth`])
    /// for a ground truth: a preview's or the viewer's.
    pub truth: bool,
}

/// The finest cube the ground truth reads an environment at: a 4k equirect's own
/// resolution (texels 0.088° across at the equator); a finer input is read at this.
pub const MAX_TRUTH_SIZE: u32 = 1024;

/// The cube edge at which `env` is read at its own resolution, at most
/// [`MAX_TRUTH_SIZE`]: a cube's own edge; an equirect's width / 4, where a face's central
/// texel, π/(2n) across, is the equirect's 2π/W at the equator (and finer elsewhere, where
/// the equirect's texels narrow in azimuth only).
pub fn native_cube_size(env: &Environment) -> u32 {
    let n = match env {
        Environment::Equirect(e) => e.width.div_ceil(4),
        Environment::Cube(c) => c.size,
    };
    n.clamp(1, MAX_TRUTH_SIZE)
}

/// The light of one environment baked in memory, in the generic orientation (before a
/// target's): what a bake writes and a preview renders.
#[derive(Clone, Debug)]
pub struct BakedEnvironment {
    /// The prefiltered specular chain (level 0 is the environment cube).
    pub specular: Cubemap,
    /// Its layout.
    pub chain: SpecularChain,
    /// The irradiance cube (E/π).
    pub irradiance: Cubemap,
    /// The SH projection, when asked for.
    pub sh: Option<ShCoefficients>,
    /// The prefiltered Charlie sheen chain, in the specular chain's layout, when asked for.
    pub sheen: Option<Cubemap>,
    /// The compact lights found in the environment, the sun first (see
    /// [`find_lights`]), in the output frame (rotation applied), whatever the mode; empty
    /// when it has none.
    pub lights: Vec<Sun>,
    /// [`SunMode::Split`]: the chain, irradiance, SH and sheen are the residual's (the
    /// environment without its lights), and the lights are lights of their own.
    pub sun_mode: SunMode,
    /// With [`SunMode::Split`] and lights taken out: the environment as seen, lights
    /// included, at the specular chain's level-0 size (one level): what a target's skybox
    /// or background shows, since a background is seen, not lit by. `None` otherwise
    /// (level 0 of `specular` is the environment as seen then), and for a bake read back
    /// from its folder, which reads its `background.ktx2` where it has one.
    pub background: Option<Cubemap>,
    /// With `LightOptions::truth`: the environment as read, lights included, at its own
    /// resolution (`native_cube_size`, one level), where that is not the chain's level-0
    /// size; `None` otherwise (then [`BakedEnvironment::seen`] is `background` or level 0
    /// of `specular`, at the same resolution).
    pub truth: Option<Cubemap>,
}

impl BakedEnvironment {
    /// The sun: the most energetic compact light, if any.
    pub fn sun(&self) -> Option<&Sun> {
        self.lights.first()
    }

    /// The lights to shade beside the IBL: those taken out of it (none with
    /// [`SunMode::Keep`]).
    pub fn split_lights(&self) -> &[Sun] {
        self.sun_mode.split_out(&self.lights)
    }

    /// The environment as read, lights included, in its level 0 (the finest kept):
    /// [`BakedEnvironment::truth`], else the background, else the chain (whose level 0 is
    /// the environment as read when nothing was taken out of it). What a ground truth
    /// integrates and an exposure is chosen from, whatever the sun mode: the lights
    /// taken out change what the split-sum shades, never what it is measured against.
    pub fn seen(&self) -> &Cubemap {
        self.truth
            .as_ref()
            .or(self.background.as_ref())
            .unwrap_or(&self.specular)
    }
}

/// Bakes `source` in memory as `opts` say on `backend`. `progress` is called as each stage
/// starts, and each stage's wall time is pushed onto `timings`.
pub fn bake_light(
    backend: &dyn Backend,
    source: Environment,
    opts: &LightOptions,
    progress: &mut dyn FnMut(Stage),
    timings: &mut Timings,
) -> Result<BakedEnvironment> {
    // The ground truth's resolution, where it is not the chain's (a copy is converted).
    let truth_size = Some(native_cube_size(&source))
        .filter(|&n| opts.truth && n != opts.specular_size);
    // With lights taken out, the environment as seen is kept for the background (a
    // background is seen, not lit by) and the residual is baked; a copy is made only then.
    let (lights, source, seen) = timed_stage(Stage::Sun, progress, timings, || {
        let (lights, source, seen) = match opts.sun {
            SunMode::Keep => (find_lights(&source), source, None),
            SunMode::Split => match take_lights_out(&source) {
                Some((lights, residual)) => (lights, residual, Some(source)),
                None => (Vec::new(), source, None),
            },
        };
        let lights = lights
            .into_iter()
            .map(|s| s.rotated(opts.rotate_degrees))
            .collect::<Vec<_>>();
        Ok((lights, source, seen))
    })?;
    let truth = match truth_size {
        Some(n) => Some(timed_stage(Stage::Truth, progress, timings, || {
            let read = seen.as_ref().unwrap_or(&source).clone();
            environment_into_cube(backend, read, n, false, opts.rotate_degrees)
        })?),
        None => None,
    };
    let background = match seen {
        Some(seen) => Some(timed_stage(Stage::Background, progress, timings, || {
            environment_into_cube(backend, seen, opts.specular_size, false, opts.rotate_degrees)
        })?),
        None => None,
    };
    let (env, irradiance_source) = timed_stage(Stage::Cubemap, progress, timings, || {
        environment_into_cube_with_irradiance(
            backend,
            source,
            opts.specular_size,
            true,
            opts.rotate_degrees,
        )
    })?;
    let chain = opts.chain;
    let mut specular = timed_stage(Stage::Specular, progress, timings, || {
        backend.prefilter_specular(&env, Some(&irradiance_source), chain, opts.samples)
    })?;
    let irradiance = timed_stage(Stage::Irradiance, progress, timings, || {
        let irradiance = backend.irradiance(&irradiance_source, opts.irradiance_size)?;
        // The r = 1 level is E/π; its texels are fitted to the finer irradiance cube for
        // the bilinear lookup a shader makes (see `plan::fit`).
        fit_roughest_level(&mut specular, &irradiance);
        Ok(irradiance)
    })?;
    let sheen = match opts.sheen {
        false => None,
        true => Some(timed_stage(Stage::Sheen, progress, timings, || {
            backend.prefilter_sheen(&env, Some(&irradiance_source), chain)
        })?),
    };
    let sh = timed_stage(Stage::Sh, progress, timings, || {
        Ok(opts.sh.then(|| sh_project(&irradiance_source)))
    })?;
    Ok(BakedEnvironment {
        specular,
        chain,
        irradiance,
        sh,
        sheen,
        lights,
        sun_mode: opts.sun,
        background,
        truth,
    })
}
