//! Command-line definitions (clap derive). Parsing only; the commands call the library.
//! The target, pixel format and LUT model values and each target's defaults in `--help`
//! come from the library's tables.

use std::path::PathBuf;

use clap::{Args, Parser, Subcommand};
use splitsum::{AstcQuality, Bc6hQuality, LutModel, PixelFormat, Target};

use super::values::{
    astc_parser, bc6h_parser, lookup_parser, lut_help, lut_model_parser, min_mip_size_help,
    pixel_format_help, pixel_format_parser, sh_help, sun_mode_parser, target_help, target_parser,
    zstd_help,
};
pub use super::values::{BackendArg, ContainerArg, LayoutArg};

/// Bakes image-based lighting for physically based renderers.
///
/// Conventions: perceptual roughness r with GGX α = r², Smith/Schlick-GGX k = r²/2 for IBL,
/// Fresnel-Schlick. LUT texel (i, j) of a W×H table holds n·v = (i+½)/W and r = (j+½)/H;
/// row 0 (r ≈ 0) is the first row of every file (top of a PNG), so a shader samples it at
/// uv = (n·v, r). R = scale A and G = bias B: specular ≈ prefiltered · (F0·A + B).
#[derive(Debug, Parser)]
#[command(
    name = "splitsum",
    version,
    about,
    long_about,
    propagate_version = true
)]
#[command(after_help = "Exit codes: 0 success, 1 a job failed, 2 usage error, 130 interrupted.")]
pub struct Cli {
    /// What to bake.
    #[command(subcommand)]
    pub command: Command,
}

/// The subcommands.
#[derive(Debug, Subcommand)]
pub enum Command {
    /// Writes a BRDF lookup table (by default the split-sum scale A in R, bias B in G).
    ///
    /// Texel (i, j) of an N×N table holds n·v = (i+½)/N and roughness r = (j+½)/N; row 0
    /// (r ≈ 0) is the first row stored (top of a PNG), so a shader samples it at
    /// uv = (n·v, r) and computes specular ≈ prefiltered · (F0·A + B). GGX with α = r²,
    /// Smith/Schlick-GGX with k = r²/2, Fresnel-Schlick.
    ///
    /// Format from the extension: .png (16-bit RGB, B = 0), .exr (float32 R, G),
    /// .ktx2 (R16G16_SFLOAT, or R32G32_SFLOAT with --f32), .dds (DXGI R16G16_FLOAT or
    /// R32G32_FLOAT with --f32).
    Lut(LutArgs),

    /// Converts an HDR environment (equirect, cross, faces, KTX2/DDS/KTX cube) to a cubemap.
    ///
    /// Faces +X, −X, +Y, −Y, +Z, −Z in the Vulkan/D3D/OpenGL face orientation: a shader
    /// sampling the result with a world-space direction d gets the radiance arriving from d
    /// (right-handed, +Y up; the equirect's centre looks along +X, u = 0.75 along +Z).
    /// Each texel is the solid-angle-weighted mean of the environment over its footprint;
    /// mips (--mips) keep the energy of the level above. Format from the extension: .ktx2,
    /// .dds and .ktx (KTX 1, as Filament loads it) with every mip in --pixel-format; .exr
    /// and .hdr (level 0, for inspection) as six files <stem>_px … <stem>_nz, or one image
    /// with --layout cross|equirect.
    Cubemap(CubemapArgs),

    /// Bakes everything a PBR renderer needs for image-based lighting from each input.
    ///
    /// Writes <out>/<stem>/specular.<ext> (prefiltered GGX, mip m at roughness
    /// m/(levels−1), down to --min-mip-size), irradiance.<ext> (E/π: multiply by the
    /// diffuse albedo), sh.json (9 SH coefficients, radiance and E/π), brdf_lut.png and
    /// manifest.json (version, target, parameters, every output with its SHA-256).
    /// --target bevy|three|filament|babylon|gltf write what that engine reads, as it samples
    /// it (see the README's "Engine targets"). Every input is baked even when another fails; the
    /// exit code is 1 if any failed.
    Bake(BakeArgs),

    /// Renders the seed materials under a bake: split-sum against ground truth.
    ///
    /// A grid of spheres (rows gold, copper, aluminium, titanium, silver and a dielectric
    /// with F0 0.04 and albedo 0.8; columns roughness 0, 0.25, 0.5, 0.75, 1) over the
    /// environment, twice: split-sum (prefiltered specular at the documented lod, the LUT,
    /// irradiance × albedo × kD, as the README tells engines to) and ground truth (the full
    /// reflectance integral of the same BRDF over the same environment per pixel), with a
    /// heat map of |split-sum − truth| / truth. Tone-mapped with Khronos PBR Neutral, 8-bit
    /// sRGB PNG. Prints per material and roughness the mean and worst relative difference.
    /// INPUT is an environment (baked in memory with the bake defaults) or a folder that
    /// `bake` wrote (--target generic, KTX2).
    Preview(PreviewArgs),

    /// Runs every kernel on the GPU and on the CPU reference on a reduced problem and
    /// prints their differences; exits 1 when one is out of tolerance.
    Verify(VerifyArgs),

    /// Says what is in an environment: size, mean and peak radiance, dynamic range, bad
    /// texels, and its sun.
    ///
    /// The sun is the most energetic compact bright region (docs/sun.md): its direction
    /// (azimuth 0 along +X, the equirect's centre, 90 along +Z; elevation above the XZ
    /// plane), its irradiance E on a surface facing it (Σ L dω per channel, the sky under
    /// it taken off), its angular radius and solid angle, its share of the luminous flux,
    /// and whether it looks clipped. An environment with no compact dominant source has no
    /// sun. --json writes the same as JSON on stdout.
    Inspect(InspectArgs),

    /// Opens a window on a bake: an object above a floor under the baked light.
    ///
    /// Walk around it (WASD, the mouse while the cursor is captured), switch materials and
    /// models, turn the roughness; G shows the ground truth of the same view (the full
    /// reflectance integral per pixel, accumulated while the view is still), H the heat
    /// map of |split-sum − truth| / truth. INPUT is an HDRI (baked in memory with the bake
    /// defaults; drop another on the window) or a folder `bake` wrote. With --screenshot,
    /// renders offscreen into a PNG instead (no display needed).
    View(ViewArgs),
}

/// The viewer's keys, for `view --help`.
fn view_keys_help() -> String {
    let mut s = String::from("Keys (window) and --keys tokens:\n");
    for (key, token, what, _) in splitsum::VIEW_KEYS {
        let token = if token.is_empty() {
            String::new()
        } else {
            format!(" [{token}]")
        };
        s.push_str(&format!("  {key}{token}: {what}\n"));
    }
    s
}

/// `WxH` as (width, height).
fn parse_size(s: &str) -> Result<(u32, u32), String> {
    let (w, h) = s
        .split_once(['x', 'X', '×'])
        .ok_or_else(|| format!("'{s}' is not WIDTHxHEIGHT (for example 1280x720)"))?;
    let parse = |v: &str| {
        v.trim()
            .parse::<u32>()
            .map_err(|_| format!("'{s}' is not WIDTHxHEIGHT (for example 1280x720)"))
    };
    Ok((parse(w)?, parse(h)?))
}

/// `splitsum view`.
#[derive(Debug, Args)]
#[command(after_long_help = view_keys_help())]
pub struct ViewArgs {
    /// An HDRI or a folder `bake` wrote [default: the bundled venice_sunset_1k.hdr].
    pub input: Option<PathBuf>,

    /// A model (.obj, .gltf, .glb) shown first, after Spot, the sphere and the torus on
    /// keys 7, 8, 9 (key 0).
    #[arg(long, value_name = "FILE")]
    pub model: Option<PathBuf>,

    /// Window or picture size.
    #[arg(long, value_name = "WxH", default_value = "1280x720", value_parser = parse_size)]
    pub size: (u32, u32),

    /// Render offscreen into this PNG and exit (no window; works without a display).
    #[arg(long, value_name = "PNG")]
    pub screenshot: Option<PathBuf>,

    /// Actions before the first frame, as tokens: for example "2 r+ r+ m2 g" (copper, two
    /// steps rougher, the sphere, the ground truth); see the key table below.
    #[arg(long, value_name = "TOKENS", allow_hyphen_values = true)]
    pub keys: Option<String>,

    /// Frames rendered with --screenshot (the ground truth adds 64 samples a frame).
    #[arg(long, default_value_t = 1)]
    pub frames: u32,

    /// An HDRI's lights (its sun, a studio's lamps) at start: split out as lights with
    /// their shadows, or kept in the IBL (U swaps; an HDRI with lights is baked both ways).
    /// --lights is the same option.
    #[arg(long, visible_alias = "lights", value_name = "MODE", default_value = "split", value_parser = sun_mode_parser())]
    pub sun: splitsum::SunMode,

    #[command(flatten)]
    pub common: CommonArgs,
}

/// `splitsum bake`.
#[derive(Debug, Args)]
#[command(
    after_help = "Exit codes: 0 every input baked, 1 an input failed (the others are still baked), 2 usage error, 130 interrupted (Ctrl-C or SIGTERM: files being written are removed, finished inputs stay)."
)]
pub struct BakeArgs {
    /// Input environments (equirects, crosses, KTX2/DDS/KTX cubemaps, face patterns).
    #[arg(required = true)]
    pub inputs: Vec<PathBuf>,

    /// Output folder; each input gets a folder named after its stem.
    #[arg(
        short,
        long,
        default_value = "out",
        alias = "outdir",
        alias = "out-dir"
    )]
    pub output: PathBuf,

    /// Specular cube edge (power of two).
    #[arg(long, default_value_t = 256)]
    pub specular_size: u32,

    #[arg(long, default_value = "generic", value_parser = target_parser(), help = target_help())]
    pub target: &'static Target,

    #[arg(long, help = min_mip_size_help())]
    pub min_mip_size: Option<u32>,

    /// Irradiance cube edge (power of two).
    #[arg(long, default_value_t = 32)]
    pub irradiance_size: u32,

    /// Container of the specular and irradiance cubes (generic, bevy and three; the other
    /// targets write their engine's own).
    #[arg(long, value_enum, default_value_t = ContainerArg::Ktx2)]
    pub container: ContainerArg,

    #[arg(long, value_parser = pixel_format_parser(), help = pixel_format_help())]
    pub pixel_format: Option<PixelFormat>,

    #[command(flatten)]
    pub zstd: ZstdArgs,

    #[command(flatten)]
    pub blocks: BlockArgs,

    #[arg(long, conflicts_with = "no_lut", help = lut_help())]
    pub lut: bool,

    /// Do not write the BRDF LUT.
    #[arg(long)]
    pub no_lut: bool,

    #[arg(long, conflicts_with = "no_sh", help = sh_help())]
    pub sh: bool,

    /// Do not write sh.json.
    #[arg(long)]
    pub no_sh: bool,

    /// GGX samples per texel for the importance-sampled (low-roughness) specular levels.
    #[arg(long, default_value_t = splitsum::BakeOptions::default().samples)]
    pub samples: u32,

    /// Also render preview.png into each output folder (see `splitsum preview`).
    #[arg(long)]
    pub preview: bool,

    /// The preview's exposure in stops [default: from the environment].
    #[arg(
        long,
        value_name = "EV",
        allow_hyphen_values = true,
        requires = "preview"
    )]
    pub preview_exposure: Option<f32>,

    #[command(flatten)]
    pub preview_render: PreviewRenderArgs,

    /// Print nothing on success (no progress bar, no summary line); warnings and errors
    /// are still printed.
    #[arg(short, long)]
    pub quiet: bool,

    #[command(flatten)]
    pub input_opts: InputArgs,

    #[command(flatten)]
    pub sun: SunArgs,

    #[command(flatten)]
    pub common: CommonArgs,
}

/// How a preview is rendered (shared by `preview` and `bake --preview`).
#[derive(Debug, Args)]
pub struct PreviewRenderArgs {
    /// Quasi-Monte Carlo points per lobe and pixel of the ground truth (its cost grows
    /// with them; 0 renders the split-sum alone, without the truth or the comparison).
    #[arg(long, default_value_t = splitsum::PreviewOptions::default().truth_samples)]
    pub truth_samples: u32,

    /// Edge of one sphere's cell in pixels.
    #[arg(long, default_value_t = splitsum::PreviewOptions::default().cell)]
    pub preview_cell: u32,

    /// Where the split-sum reads the specular chain [default: the shading's own: for the
    /// generic target the README's recipe, which bends R toward the normal, reads two
    /// sharper taps toward grazing views, blends the read toward the irradiance by r⁴ and
    /// takes four taps of the lobe at grazing views of glossy points (filtered); the
    /// others are the lookups engines make, read plainly].
    #[arg(long, value_parser = lookup_parser())]
    pub lookup: Option<splitsum::SpecularLookup>,
}

/// `splitsum preview`.
#[derive(Debug, Args)]
pub struct PreviewArgs {
    /// An environment (as `bake` reads) or a folder `bake` wrote.
    pub input: PathBuf,

    /// Output PNG [default: <folder>/preview.png for a bake folder, out/<stem>_preview.png
    /// for an environment].
    #[arg(short, long)]
    pub output: Option<PathBuf>,

    /// Exposure in stops [default: the environment's log-average luminance maps to 0.18].
    #[arg(long, value_name = "EV", allow_hyphen_values = true)]
    pub exposure: Option<f32>,

    /// Specular cube edge when INPUT is an environment (power of two).
    #[arg(long, default_value_t = 256)]
    pub specular_size: u32,

    /// Also write the figures as JSON: the mode, the sun, and per sphere the material,
    /// roughness, mean and worst relative difference.
    #[arg(long, value_name = "FILE")]
    pub json: Option<PathBuf>,

    /// With an environment: keep the lights (the sun, a studio's lamps) in the IBL, or
    /// split them out and shade them as lights with the BRDF, area lights from the LTC
    /// table [default: keep]. A bake folder is shown as it was baked. --lights is the same
    /// option.
    #[arg(long, visible_alias = "lights", value_name = "MODE", value_parser = sun_mode_parser())]
    pub sun: Option<splitsum::SunMode>,

    /// With an environment: bake it for this engine (its chain layout, its lookup's
    /// files) and shade the spheres as its shader does, its ground truth the integral of
    /// its own BRDF; generic is the README's recipe.
    #[arg(long, default_value = "generic", value_parser = target_parser())]
    pub target: &'static Target,

    #[command(flatten)]
    pub render: PreviewRenderArgs,

    #[command(flatten)]
    pub common: CommonArgs,
}

/// `splitsum inspect`.
#[derive(Debug, Args)]
pub struct InspectArgs {
    /// An environment (as `bake` reads it).
    pub input: PathBuf,

    /// Print JSON on stdout instead of text.
    #[arg(long)]
    pub json: bool,

    #[command(flatten)]
    pub input_opts: InputArgs,
}

/// What to do with the sun (`--sun`), shared by `bake`, `cubemap` and `preview`.
#[derive(Debug, Args)]
pub struct SunArgs {
    /// keep: the lights (the sun, a studio's lamps and soft boxes) stay in the environment
    /// (those found are reported); split: they are taken out, their texels filled from the
    /// sky around them, and written as lights (bake: sun.json beside an IBL baked from the
    /// rest; cubemap: the rest as the cube and <output stem>_sun.json). --lights is the
    /// same option.
    #[arg(long, visible_alias = "lights", value_name = "MODE", default_value = "keep", value_parser = sun_mode_parser())]
    pub sun: splitsum::SunMode,
}

/// `splitsum verify`.
#[derive(Debug, Args)]
pub struct VerifyArgs {
    /// An environment to run the kernels on.
    pub input: PathBuf,
}

/// Options shared by every command.
#[derive(Debug, Args)]
pub struct CommonArgs {
    /// Compute backend: auto picks a GPU adapter when there is one (Mesa's lavapipe counts)
    /// and the CPU otherwise.
    #[arg(long, value_enum, default_value_t = BackendArg::Auto)]
    pub backend: BackendArg,

    /// Print the adapter used and timings to stderr.
    #[arg(short, long)]
    pub verbose: bool,
}

/// `splitsum lut`.
#[derive(Debug, Args)]
pub struct LutArgs {
    /// Output file; the extension picks the format.
    #[arg(short, long, default_value = "out/brdf_lut.png")]
    pub output: PathBuf,

    /// Width and height of the table in texels [default: 512; 64 with --ltc].
    #[arg(long)]
    pub size: Option<u32>,

    /// KTX2/DDS: store 32-bit floats instead of 16-bit.
    #[arg(long = "f32")]
    pub f32: bool,

    /// What the channels hold (docs/conventions.md, "BRDF LUT").
    #[arg(long, default_value = "schlick-ggx", value_parser = lut_model_parser())]
    pub model: LutModel,

    /// Write the LTC table that area lights are shaded from instead (.json, in three.js's
    /// LTC_1/LTC_2 layout; docs/targets.md, "Area lights"), fitted to the GGX lobe with
    /// --model's masking (schlick-ggx or smith-correlated and their multiscatter models).
    #[arg(long)]
    pub ltc: bool,

    #[command(flatten)]
    pub common: CommonArgs,
}

/// Options that read an environment.
#[derive(Debug, Args)]
pub struct InputArgs {
    /// Rotate the environment about +Y by DEG degrees before anything else (right-handed:
    /// a positive angle turns +X towards −Z).
    #[arg(
        long,
        value_name = "DEG",
        default_value_t = 0.0,
        allow_hyphen_values = true
    )]
    pub rotate: f32,

    /// Multiply the input radiance by 2^EV.
    #[arg(
        long,
        value_name = "EV",
        default_value_t = 0.0,
        allow_hyphen_values = true
    )]
    pub exposure: f32,
}

/// `splitsum cubemap`.
#[derive(Debug, Args)]
pub struct CubemapArgs {
    /// Input: a 2:1 equirect, a 4:3 or 3:4 cross (.hdr, .exr, .png, .jpg), a KTX2/DDS
    /// cubemap, or a face-file pattern such as 'sky_{face}.hdr' ({face} = px nx py ny pz nz).
    #[arg(required_unless_present = "faces")]
    pub input: Option<PathBuf>,

    /// Six square face images instead of INPUT, in the order +X −X +Y −Y +Z −Z.
    #[arg(long, num_args = 6, value_names = ["PX", "NX", "PY", "NY", "PZ", "NZ"], conflicts_with = "input")]
    pub faces: Vec<PathBuf>,

    /// Output file [default: out/<stem>_cubemap.ktx2].
    #[arg(short, long)]
    pub output: Option<PathBuf>,

    /// Face edge in texels, a power of two [default: the largest power of two ≤ input
    /// width / 4].
    #[arg(long)]
    pub size: Option<u32>,

    /// Write the full mip chain (down to 1×1).
    #[arg(long)]
    pub mips: bool,

    /// The engine the cube is for: its orientation and default pixel format (see bake).
    #[arg(long, default_value = "generic", value_parser = target_parser())]
    pub target: &'static Target,

    #[arg(long, value_parser = pixel_format_parser(), help = pixel_format_help())]
    pub pixel_format: Option<PixelFormat>,

    #[command(flatten)]
    pub zstd: ZstdArgs,

    #[command(flatten)]
    pub blocks: BlockArgs,

    /// Layout of .exr/.hdr outputs.
    #[arg(long, value_enum, default_value_t = LayoutArg::Faces)]
    pub layout: LayoutArg,

    #[command(flatten)]
    pub input_opts: InputArgs,

    #[command(flatten)]
    pub sun: SunArgs,

    #[command(flatten)]
    pub common: CommonArgs,
}

/// The block encoders' presets.
#[derive(Debug, Args)]
pub struct BlockArgs {
    /// With --pixel-format bc6h: how hard the encoder searches (fast, basic, slow; see
    /// docs/accuracy.md, "BC6H").
    #[arg(long, value_name = "PRESET", default_value = "fast", value_parser = bc6h_parser())]
    pub bc6h_quality: Bc6hQuality,

    /// With --pixel-format astc-4x4-hdr or astc-6x6-hdr: astc-encoder's preset (fast,
    /// medium, thorough; see docs/astc.md).
    #[arg(long, value_name = "PRESET", default_value = "medium", value_parser = astc_parser())]
    pub astc_quality: AstcQuality,
}

/// KTX2 supercompression, defaulting to the target's.
#[derive(Debug, Args)]
pub struct ZstdArgs {
    #[arg(long, value_name = "LEVEL", num_args = 0..=1, default_missing_value = "10",
          value_parser = clap::value_parser!(i32).range(1..=22), conflicts_with = "no_zstd",
          help = zstd_help())]
    pub zstd: Option<i32>,

    /// KTX2: no supercompression, whatever the target's default.
    #[arg(long)]
    pub no_zstd: bool,
}

impl ZstdArgs {
    /// The Zstandard level for `target`.
    pub fn level(&self, target: &Target) -> Option<i32> {
        if self.no_zstd {
            None
        } else {
            self.zstd.or(target.zstd)
        }
    }
}
