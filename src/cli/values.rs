//! What the flags take: the value parsers drawn from the library's tables (targets, pixel
//! formats, LUT models, sun modes, BC6H presets), the value enums of the container, the
//! layout and the backend, and the help texts that list each target's default.

use clap::builder::{PossibleValue, PossibleValuesParser, TypedValueParser};
use clap::ValueEnum;
use splitsum::{
    AstcQuality, Bc6hQuality, LutModel, PixelFormat, SpecularLookup, Target, CUBE_PIXEL_FORMATS,
    TARGETS,
};

/// `--target`'s values: the names of [`TARGETS`], each with its summary.
pub(super) fn target_parser() -> impl TypedValueParser<Value = &'static Target> {
    PossibleValuesParser::new(
        TARGETS
            .iter()
            .map(|t| PossibleValue::new(t.name).help(t.summary)),
    )
    .map(|name| Target::by_name(&name).unwrap_or(&splitsum::GENERIC))
}

/// `--pixel-format`'s values.
pub(super) fn pixel_format_parser() -> impl TypedValueParser<Value = PixelFormat> {
    PossibleValuesParser::new(
        CUBE_PIXEL_FORMATS
            .iter()
            .map(|(name, f)| PossibleValue::new(*name).help(f.description())),
    )
    .map(|name| {
        CUBE_PIXEL_FORMATS
            .iter()
            .find(|(n, _)| *n == name)
            .map_or(PixelFormat::Rgba16f, |(_, f)| *f)
    })
}

/// `--model`'s values.
pub(super) fn lut_model_parser() -> impl TypedValueParser<Value = LutModel> {
    PossibleValuesParser::new(
        LutModel::ALL
            .iter()
            .map(|m| PossibleValue::new(m.name()).help(m.description())),
    )
    .map(|name| LutModel::by_name(&name).unwrap_or_default())
}

/// `--lookup`'s values.
pub(super) fn lookup_parser() -> impl TypedValueParser<Value = SpecularLookup> {
    PossibleValuesParser::new(
        SpecularLookup::ALL
            .iter()
            .chain(&[SpecularLookup::Filtered])
            .map(|l| PossibleValue::new(l.id()).help(l.description())),
    )
    .map(|id| SpecularLookup::by_id(&id).unwrap_or(SpecularLookup::GENERIC))
}

/// `target: value` for every target, joined.
fn per_target(value: impl Fn(&Target) -> String) -> String {
    TARGETS
        .iter()
        .map(|t| format!("{} {}", t.name, value(t)))
        .collect::<Vec<_>>()
        .join(", ")
}

/// `--target`'s help.
pub(super) fn target_help() -> String {
    "The engine the files are for: its orientation, chain layout, default formats and file set (README, \"Engine targets\")".into()
}

/// `--min-mip-size`'s help, with each target's default.
pub(super) fn min_mip_size_help() -> String {
    format!(
        "Edge of the smallest specular mip (power of two; 1 for the full chain to 1×1): the chain has log2(specular-size / min-mip-size) + 1 levels [default: the target's: {}]",
        per_target(|t| t.min_mip_size.to_string())
    )
}

/// `--pixel-format`'s help, with each target's default.
pub(super) fn pixel_format_help() -> String {
    format!(
        "Pixel format of KTX2/DDS/KTX outputs [default: the target's: {}; refused where the target's file has none: {}]",
        per_target_where(|t| t.files.has_pixel_format, |t| t.pixel_format.name().into()),
        names_where(|t| !t.files.has_pixel_format)
    )
}

/// `--lut`'s help, with each target's default.
pub(super) fn lut_help() -> String {
    format!(
        "Write the target's BRDF LUT files [default: yes for {}; no for {}]. Files: {}",
        names_where(|t| t.lut),
        names_where(|t| !t.lut),
        per_target(|t| t
            .luts
            .iter()
            .map(|l| l.file)
            .collect::<Vec<_>>()
            .join(" + "))
    )
}

/// `--sh`'s help, with each target's default.
pub(super) fn sh_help() -> String {
    format!(
        "Write the SH (sh.json; Filament and Babylon carry them in their own file) [default: yes for {}; no for {}]",
        names_where(|t| t.sh),
        names_where(|t| !t.sh)
    )
}

/// `--zstd`'s help, with each target's default.
pub(super) fn zstd_help() -> String {
    format!(
        "KTX2: Zstandard-supercompress each level (LEVEL 1–22, default 10) [default: the target's: {}]",
        per_target(|t| t.zstd.map_or("none".into(), |l| format!("zstd {l}")))
    )
}

/// The names of the targets where `pick` holds.
fn names_where(pick: impl Fn(&Target) -> bool) -> String {
    let names: Vec<&str> = TARGETS.iter().filter(|t| pick(t)).map(|t| t.name).collect();
    if names.is_empty() {
        "none".into()
    } else {
        names.join(", ")
    }
}

/// [`per_target`] for the targets where `pick` holds.
fn per_target_where(pick: impl Fn(&Target) -> bool, value: impl Fn(&Target) -> String) -> String {
    TARGETS
        .iter()
        .filter(|t| pick(t))
        .map(|t| format!("{} {}", t.name, value(t)))
        .collect::<Vec<_>>()
        .join(", ")
}
/// `--sun`'s values.
pub(super) fn sun_mode_parser() -> impl TypedValueParser<Value = splitsum::SunMode> {
    PossibleValuesParser::new(
        splitsum::SunMode::ALL
            .iter()
            .map(|m| PossibleValue::new(m.name())),
    )
    .map(|name| splitsum::SunMode::by_name(&name).unwrap_or_default())
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

impl From<ContainerArg> for splitsum::Container {
    fn from(c: ContainerArg) -> Self {
        match c {
            ContainerArg::Ktx2 => splitsum::Container::Ktx2,
            ContainerArg::Dds => splitsum::Container::Dds,
            ContainerArg::Exr => splitsum::Container::Exr,
        }
    }
}
/// `--bc6h-quality`'s values.
pub(super) fn bc6h_parser() -> impl TypedValueParser<Value = Bc6hQuality> {
    PossibleValuesParser::new(Bc6hQuality::ALL.map(|q| q.name()))
        .map(|name| Bc6hQuality::by_name(&name).unwrap_or_default())
}
/// `--astc-quality`'s values.
pub(super) fn astc_parser() -> impl TypedValueParser<Value = AstcQuality> {
    PossibleValuesParser::new(AstcQuality::ALL.map(|q| q.name()))
        .map(|name| AstcQuality::by_name(&name).unwrap_or_default())
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

impl From<LayoutArg> for splitsum::CubeLayout {
    fn from(l: LayoutArg) -> Self {
        use splitsum::CubeLayout as L;
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
