//! Command-line definitions (clap derive). Parsing only; `main.rs` calls the library.

use std::path::PathBuf;

use clap::{Args, Parser, Subcommand, ValueEnum};

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
    #[arg(short, long, default_value = "out")]
    pub output: PathBuf,

    /// Specular cube edge (power of two).
    #[arg(long, default_value_t = 256)]
    pub specular_size: u32,

    /// The engine the files are for: generic (DESIGN.md's conventions), bevy (Bevy 0.19:
    /// z mirrored, rgb9e5 + zstd, no LUT or SH), three (three.js r187: x mirrored, a PMREM
    /// chain to 8×8 at r = 1 − √(1 − m/(levels − 1)), no irradiance cube or LUT), filament
    /// (cmgen's files: <stem>_ibl.ktx with the SH, <stem>_skybox.ktx and sh.txt, KTX 1
    /// rg11b10f, a quarter turn about +Y, the chain to 16×16 at three's roughness), babylon
    /// (<stem>.env: the whole chain as RGBD PNGs at Babylon's roughness per mip and the SH as
    /// its spherical polynomial, x and z swapped), gltf (the glTF Sample Viewer's
    /// glTF-IBL-Sampler folders: lambertian, ggx and a Charlie sheen chain to 16×16, and its
    /// three LUTs).
    #[arg(long, value_enum, default_value_t = TargetArg::Generic)]
    pub target: TargetArg,

    /// Edge of the smallest specular mip (power of two; 1 for the full chain to 1×1): the
    /// chain has log2(specular-size / min-mip-size) + 1 levels [default: 4; three: 8;
    /// filament and gltf: 16; babylon: 1, the only one it takes].
    #[arg(long)]
    pub min_mip_size: Option<u32>,

    /// Irradiance cube edge (power of two).
    #[arg(long, default_value_t = 32)]
    pub irradiance_size: u32,

    /// Container of the specular and irradiance cubes (generic, bevy and three; the other
    /// targets write their engine's own).
    #[arg(long, value_enum, default_value_t = ContainerArg::Ktx2)]
    pub container: ContainerArg,

    /// Pixel format of KTX2/DDS/KTX outputs [default: the target's: rgba16f; bevy: rgb9e5;
    /// filament: rg11b10f; refused for babylon, whose .env is RGBD].
    #[arg(long, value_enum)]
    pub pixel_format: Option<PixelFormatArg>,

    #[command(flatten)]
    pub zstd: ZstdArgs,

    /// Write the BRDF LUT (the target's default: generic yes as brdf_lut.png; gltf yes as
    /// lut_ggx.png, lut_charlie.png and lut_sheen_E.png; bevy, three, filament and babylon
    /// no, and three's is brdf_lut.ktx2, RG16F).
    #[arg(long, conflicts_with = "no_lut")]
    pub lut: bool,

    /// Do not write the BRDF LUT.
    #[arg(long)]
    pub no_lut: bool,

    /// Write sh.json (the target's default: generic and three yes, bevy no).
    #[arg(long, conflicts_with = "no_sh")]
    pub sh: bool,

    /// Do not write sh.json.
    #[arg(long)]
    pub no_sh: bool,

    /// GGX samples per texel for the importance-sampled (low-roughness) specular levels.
    #[arg(long, default_value_t = splitsum::cpu::prefilter_specular::DEFAULT_SAMPLES)]
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

    /// No progress bars.
    #[arg(short, long)]
    pub quiet: bool,

    #[command(flatten)]
    pub input_opts: InputArgs,

    #[command(flatten)]
    pub common: CommonArgs,
}

/// How a preview is rendered (shared by `preview` and `bake --preview`).
#[derive(Debug, Args)]
pub struct PreviewRenderArgs {
    /// Quasi-Monte Carlo points per lobe and pixel of the ground truth (its cost grows
    /// with them; 0 renders the split-sum alone, without the truth or the comparison).
    #[arg(long, default_value_t = splitsum::cpu::preview_truth::DEFAULT_TRUTH_SAMPLES)]
    pub truth_samples: u32,

    /// Edge of one sphere's cell in pixels.
    #[arg(long, default_value_t = splitsum::preview::scene::DEFAULT_CELL)]
    pub preview_cell: u32,
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

    #[command(flatten)]
    pub render: PreviewRenderArgs,

    #[command(flatten)]
    pub common: CommonArgs,
}

/// `splitsum verify`.
#[derive(Debug, Args)]
pub struct VerifyArgs {
    /// An environment to run the kernels on.
    pub input: PathBuf,
}

/// `--container` values.
#[derive(Clone, Copy, Debug, ValueEnum)]
pub enum ContainerArg {
    /// KTX 2.0.
    Ktx2,
    /// DDS with the DX10 header.
    Dds,
    /// OpenEXR crosses, one per mip.
    Exr,
}

impl From<ContainerArg> for splitsum::bake::Container {
    fn from(c: ContainerArg) -> Self {
        match c {
            ContainerArg::Ktx2 => splitsum::bake::Container::Ktx2,
            ContainerArg::Dds => splitsum::bake::Container::Dds,
            ContainerArg::Exr => splitsum::bake::Container::Exr,
        }
    }
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

    /// Width and height of the table in texels.
    #[arg(long, default_value_t = 512,
          value_parser = clap::value_parser!(u32).range(1..=splitsum::lut::MAX_LUT_SIZE as i64))]
    pub size: u32,

    /// KTX2/DDS: store 32-bit floats instead of 16-bit.
    #[arg(long = "f32")]
    pub f32: bool,

    /// What the two channels hold (README, "LUT models").
    #[arg(long, value_enum, default_value_t = LutModelArg::SchlickGgx)]
    pub model: LutModelArg,

    #[command(flatten)]
    pub common: CommonArgs,
}

/// `--model` values of `splitsum lut`.
#[derive(Clone, Copy, Debug, ValueEnum)]
pub enum LutModelArg {
    /// (A, B) scale and bias, Smith/Schlick-GGX with k = r²/2 (Karis 2013).
    SchlickGgx,
    /// (A, B) with the height-correlated Smith visibility (Heitz 2014).
    SmithCorrelated,
    /// (∫Fc·V, ∫V), Schlick-GGX: specular = mix(x, y, f0), energy compensation 1 + f0 (1/y − 1).
    MultiscatterSchlickGgx,
    /// (∫Fc·V, ∫V), height-correlated Smith: Filament's DFG (R, G).
    MultiscatterSmithCorrelated,
    /// (E, 0): the Charlie sheen albedo with the Ashikhmin visibility (Filament's cloth
    /// DFG channel, glTF-IBL-Sampler's lut_charlie); exceeds 1 near grazing: use .exr or .ktx2.
    Charlie,
    /// (E, 0): the KHR_materials_sheen albedo (Charlie D, V_Sheen), the glTF Sample
    /// Viewer's lut_sheen_E quantity.
    SheenAlbedo,
    /// Filament's three-channel DFG: R, G as multiscatter-smith-correlated, B the cloth
    /// albedo as charlie (cmgen --ibl-dfg-multiscatter --ibl-dfg-cloth).
    FilamentDfg,
}

impl From<LutModelArg> for splitsum::lut::LutModel {
    fn from(m: LutModelArg) -> Self {
        use splitsum::lut::LutModel as M;
        match m {
            LutModelArg::SchlickGgx => M::SchlickGgx,
            LutModelArg::SmithCorrelated => M::SmithCorrelated,
            LutModelArg::MultiscatterSchlickGgx => M::MultiscatterSchlickGgx,
            LutModelArg::MultiscatterSmithCorrelated => M::MultiscatterSmithCorrelated,
            LutModelArg::Charlie => M::Charlie,
            LutModelArg::SheenAlbedo => M::SheenAlbedo,
            LutModelArg::FilamentDfg => M::FilamentDfg,
        }
    }
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
    #[arg(long, value_enum, default_value_t = TargetArg::Generic)]
    pub target: TargetArg,

    /// Pixel format of KTX2/DDS/KTX outputs [default: the target's: rgba16f; bevy: rgb9e5;
    /// filament: rg11b10f].
    #[arg(long, value_enum)]
    pub pixel_format: Option<PixelFormatArg>,

    #[command(flatten)]
    pub zstd: ZstdArgs,

    /// Layout of .exr/.hdr outputs.
    #[arg(long, value_enum, default_value_t = LayoutArg::Faces)]
    pub layout: LayoutArg,

    #[command(flatten)]
    pub input_opts: InputArgs,

    #[command(flatten)]
    pub common: CommonArgs,
}

/// KTX2 supercompression, defaulting to the target's (bevy and three: zstd 10).
#[derive(Debug, Args)]
pub struct ZstdArgs {
    /// KTX2: Zstandard-supercompress each level (LEVEL 1–22, default 10).
    #[arg(long, value_name = "LEVEL", num_args = 0..=1, default_missing_value = "10",
          value_parser = clap::value_parser!(i32).range(1..=22), conflicts_with = "no_zstd")]
    pub zstd: Option<i32>,

    /// KTX2: no supercompression, whatever the target's default.
    #[arg(long)]
    pub no_zstd: bool,
}

impl ZstdArgs {
    /// The Zstandard level for `target`.
    pub fn level(&self, target: &splitsum::target::Target) -> Option<i32> {
        if self.no_zstd {
            None
        } else {
            self.zstd.or(target.zstd)
        }
    }
}

/// `--target` values.
#[derive(Clone, Copy, Debug, ValueEnum)]
pub enum TargetArg {
    /// DESIGN.md's conventions.
    Generic,
    /// Bevy 0.19.
    Bevy,
    /// three.js r187.
    Three,
    /// Filament (cmgen's KTX 1 files).
    Filament,
    /// Babylon.js (a .env file).
    Babylon,
    /// The glTF Sample Viewer (glTF-IBL-Sampler's files).
    Gltf,
}

impl From<TargetArg> for &'static splitsum::target::Target {
    fn from(t: TargetArg) -> Self {
        use splitsum::target as t_;
        match t {
            TargetArg::Generic => &t_::GENERIC,
            TargetArg::Bevy => &t_::BEVY,
            TargetArg::Three => &t_::THREE,
            TargetArg::Filament => &t_::FILAMENT,
            TargetArg::Babylon => &t_::BABYLON,
            TargetArg::Gltf => &t_::GLTF,
        }
    }
}

/// `--pixel-format` values.
#[derive(Clone, Copy, Debug, ValueEnum)]
pub enum PixelFormatArg {
    /// 4 × 16-bit float (R16G16B16A16_SFLOAT).
    Rgba16f,
    /// 4 × 32-bit float (R32G32B32A32_SFLOAT).
    Rgba32f,
    /// Shared exponent (E5B9G9R9_UFLOAT_PACK32).
    Rgb9e5,
    /// Packed unsigned floats (B10G11R11_UFLOAT_PACK32).
    Rg11b10f,
}

impl From<PixelFormatArg> for splitsum::io::PixelFormat {
    fn from(p: PixelFormatArg) -> Self {
        use splitsum::io::PixelFormat as P;
        match p {
            PixelFormatArg::Rgba16f => P::Rgba16f,
            PixelFormatArg::Rgba32f => P::Rgba32f,
            PixelFormatArg::Rgb9e5 => P::Rgb9e5,
            PixelFormatArg::Rg11b10f => P::Rg11b10f,
        }
    }
}

/// `--layout` values.
#[derive(Clone, Copy, Debug, ValueEnum)]
pub enum LayoutArg {
    /// Six files <stem>_px … <stem>_nz.
    Faces,
    /// One horizontal cross.
    Cross,
    /// One 4N×2N equirect.
    Equirect,
}

impl From<LayoutArg> for splitsum::io::cubemap::CubeLayout {
    fn from(l: LayoutArg) -> Self {
        use splitsum::io::cubemap::CubeLayout as L;
        match l {
            LayoutArg::Faces => L::Faces,
            LayoutArg::Cross => L::Cross,
            LayoutArg::Equirect => L::Equirect,
        }
    }
}

/// `--backend` values.
#[derive(Clone, Copy, Debug, ValueEnum)]
pub enum BackendArg {
    /// GPU when available, else CPU.
    Auto,
    /// GPU (wgpu) only; fails without an adapter.
    Gpu,
    /// CPU reference implementation.
    Cpu,
}

impl From<BackendArg> for splitsum::BackendChoice {
    fn from(b: BackendArg) -> Self {
        match b {
            BackendArg::Auto => splitsum::BackendChoice::Auto,
            BackendArg::Gpu => splitsum::BackendChoice::Gpu,
            BackendArg::Cpu => splitsum::BackendChoice::Cpu,
        }
    }
}
