//! The generic target: the conventions of `docs/conventions.md` (right-handed, +Y up, the
//! texel at d holds the light arriving from d, the chain's levels geometric in α,
//! irradiance E/π), and the standard file set it writes, which the Bevy and three.js
//! targets share: `specular` and `irradiance` cubes in the bake's container, `sh.json` and
//! the LUTs.

use serde::Serialize;

use crate::environment::sun::Sun;
use crate::io::cubemap::Container;
use crate::io::staging::Staging;
use crate::io::{to_json, PixelFormat};
use crate::math::sh::{sinc_window, SH_ORDER};
use crate::plan::chain::MipRoughness;
use crate::stages::light::BakedEnvironment;
use crate::stages::sh::ShCoefficients;
use crate::targets::{FileContext, FileSet, Orientation, Target, BRDF_LUT_PNG};
use crate::{Error, Result};
use crate::plan::shading::Shading;

/// The standard file set ([`write_standard`]), in the bake's container.
pub const STANDARD: FileSet = FileSet {
    fixed_container: None,
    has_pixel_format: true,
    carries_sh: false,
    sheen: false,
    whole_chain: false,
    cube_container: Container::Ktx2,
    write: write_standard,
};

/// The conventions of `docs/conventions.md`: right-handed, +Y up, the chain down to 1×1 with
/// mip m > 0 at α = 2^(m/0.8 − (M − 1)) (the layout Babylon.js's `HDRFiltering` writes;
/// chosen by what a user sees: docs/accuracy.md, "The chain's layout and the blend toward
/// E/π"), irradiance E/π.
pub const GENERIC: Target = Target {
    name: "generic",
    summary: "the conventions of docs/conventions.md: right-handed, +Y up, lod = 0.8 (levels - 1 + log2(r² + 0.0005)), irradiance E/π",
    orientation: Orientation::GENERIC,
    pixel_format: PixelFormat::Rgba16f,
    zstd: None,
    // Levels geometric in α, down to 1×1: the recipe's figures against the truth drop at
    // r = 0.25 on every bundled HDRI, and with its blend toward E/π they are at or below
    // the previous layout's at every r but 0.5 on two HDRIs (docs/accuracy.md).
    roughness: MipRoughness::Babylon,
    min_mip_size: 1,
    irradiance: true,
    sh: true,
    lut: true,
    luts: BRDF_LUT_PNG,
    files: STANDARD,
    format_warnings: &[
        (PixelFormat::Astc4x4Hdr, super::ASTC_HDR_WHERE),
        (PixelFormat::Astc6x6Hdr, super::ASTC_HDR_WHERE),
    ],
    format_refusals: &[],
    notes: &[
        "sample specular at lod = clamp(0.8 * (levels - 1 + log2(roughness^2 + 0.0005)), 0, levels - 1), seamless trilinear; blend it toward the irradiance by roughness^4 (the README's recipe)",
        "irradiance holds E / pi: multiply by the diffuse albedo",
    ],
    shading: Shading::GENERIC,
};

/// The standard file set: `specular.<ext>` and (when [`Target::irradiance`]) `irradiance.<ext>`
/// in the bake's container (KTX2, DDS, or OpenEXR crosses, one per level), `sh.json`
/// when the SH were asked for, and with lights split out `sun.json` and
/// `background.<ext>` (the environment as seen, lights included, one level: for a skybox).
pub fn write_standard(
    ctx: &FileContext,
    baked: BakedEnvironment,
    out: &mut Staging,
) -> Result<Vec<String>> {
    add_sun_json(ctx, &baked, out);
    let enc = &ctx.encoding;
    let fmt = match enc.container {
        Container::Exr => "rgb32f (OpenEXR cross)",
        _ => enc.format.name(),
    };
    let ext = enc.container.extension();
    let path = |name: &str| ctx.dir.join(format!("{name}.{ext}"));
    ctx.add_cube(out, &path("specular"), "specular", fmt, baked.specular)?;
    if let Some(background) = baked.background {
        ctx.add_cube(out, &path("background"), "background", fmt, background)?;
    }
    if ctx.target.irradiance {
        ctx.add_cube(out, &path("irradiance"), "irradiance", fmt, baked.irradiance)?;
    }
    if let Some(sh) = &baked.sh {
        out.add(
            ctx.dir.join("sh.json"),
            sh_json(sh).into_bytes(),
            ("sh", "json", 0, 0),
        );
    }
    Ok(Vec::new())
}

/// `sh.json`: the coefficient order, the radiance projection and the E/π coefficients a
/// renderer uses (deringed), the exact projection, the window, and ZH3.
#[derive(Serialize)]
struct ShJson<'a> {
    order: &'a str,
    radiance_sh9: &'a [[f32; 3]; 9],
    irradiance_sh9: &'a [[f32; 3]; 9],
    deringing: Deringing,
    exact_radiance_sh9: &'a [[f32; 3]; 9],
    exact_irradiance_sh9: &'a [[f32; 3]; 9],
    zh3_irradiance: Zh3Json,
}

/// How `radiance_sh9` and `irradiance_sh9` were deringed.
#[derive(Serialize)]
struct Deringing {
    about: &'static str,
    /// The cutoff in bands; `None` when the exact projection did not ring.
    cutoff: Option<f32>,
    /// The factor of each band.
    band_factors: [f32; 3],
}

/// ZH3 as `sh.json` writes it.
#[derive(Serialize)]
struct Zh3Json {
    about: &'static str,
    axis: [f32; 3],
    linear: [[f32; 3]; 4],
    zonal: [f32; 3],
}

/// `sh.json` of `sh` (world space, generic orientation, whatever the target).
pub fn sh_json(sh: &ShCoefficients) -> String {
    let band_factors = std::array::from_fn(|l| sh.window_cutoff.map_or(1.0, |w| sinc_window(l, w)));
    let z = &sh.zh3_irradiance;
    to_json(&ShJson {
        order: SH_ORDER,
        radiance_sh9: &sh.radiance,
        irradiance_sh9: &sh.irradiance,
        deringing: Deringing {
            about: "radiance_sh9 and irradiance_sh9 are the exact projection with each band l multiplied by sinc(pi l / cutoff)^4 (0 from l = cutoff on): the weakest such window that leaves irradiance_sh9 non-negative in every direction (Sloan, Deringing Spherical Harmonics; Filament's windowSH); the mean (band 0) is unchanged; cutoff null: no window was needed",
            cutoff: sh.window_cutoff,
            band_factors,
        },
        exact_radiance_sh9: &sh.exact_radiance,
        exact_irradiance_sh9: &sh.exact_irradiance,
        zh3_irradiance: Zh3Json {
            about: "ZH3 (Roughton et al., i3D 2024) of exact_irradiance_sh9, E / pi: linear holds l0m0, l1m-1, l1m0, l1m1 per channel as in the SH9 order; E / pi (d) = sum of linear[k] Y_k(d) + zonal * 0.25 sqrt(5 / pi) (3 (axis . d)^2 - 1)",
            axis: z.axis,
            linear: z.linear,
            zonal: z.zonal,
        },
    })
}

/// One light of `sun.json`.
#[derive(serde::Serialize, serde::Deserialize)]
struct LightJson {
    direction: [f32; 3],
    irradiance: [f32; 3],
    illuminance: f32,
    angular_radius_deg: f32,
    solid_angle_sr: f32,
    /// The cap taken out of the environment for it (absent from older files).
    #[serde(default)]
    region_radius_deg: f32,
    /// An area source's shape (absent for a directional light).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    shape: Option<crate::environment::sun::SourceShape>,
    /// The rectangle an engine's rect area light draws for an area source (derived from
    /// `shape`; not read back).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    rect_light: Option<crate::environment::sun::RectLight>,
    share: f32,
    clipped: bool,
    azimuth_deg: f32,
    elevation_deg: f32,
}

/// `sun.json`: the lights taken out of the IBL (`--sun split`): the sun at the top level,
/// further compact lights (an interior's brightest lamps) in `additional_lights`.
#[derive(serde::Serialize, serde::Deserialize)]
struct SunJson {
    /// What the numbers mean.
    about: String,
    /// The frame `direction` is in.
    frame: String,
    #[serde(flatten)]
    sun: LightJson,
    additional_lights: Vec<LightJson>,
}

/// What `sun.json`'s figures mean.
const SUN_JSON_ABOUT: &str = "the sun, taken out of the IBL, as a directional light (cast its shadows); additional_lights: further compact lights taken out, in the same terms. direction: unit vector toward the light in the frame below; irradiance: E on a surface facing it per channel (the sum of L dw over it, in the HDRI's radiance units); illuminance: its luminance (0.2126 R + 0.7152 G + 0.0722 B); angular_radius_deg and solid_angle_sr: the uniform disc of the same second moment, never narrower than one of the HDRI's texels; region_radius_deg: the cap taken out of the HDRI for it; shape (an area light: a soft box, a window, a lamp wider than a sun): kind disc with radius_deg, or kind rect with half_width_deg and half_height_deg along width_axis (a unit vector in the frame below), the gnomonic rectangle about direction, of uniform radiance irradiance / solid_angle_sr, which a renderer without area lights shades as a directional light; rect_light (with shape): the rectangle a rect area light draws for it, facing the origin from distance d along direction, 2 d tan(half_width_deg) along width_axis by 2 d tan(half_height_deg) along height_axis (perpendicular to both), of uniform radiance (per channel, luminance its luminance) so that it gives a surface facing it irradiance from the origin, a disc being the square of its solid angle; share: of the HDRI's luminous flux; azimuth and elevation in the generic frame (azimuth 0 along +X, 90 along +Z); clipped: its core is a plateau (a saturated camera), so its irradiance is a lower bound";

/// Stages `sun.json` when lights were taken out of `baked` (their directions in the
/// target's world frame). Every target's writer calls it: the IBL of a split bake lacks
/// them, so the lights must reach the engine.
pub fn add_sun_json(ctx: &FileContext, baked: &BakedEnvironment, out: &mut Staging) {
    if let Some(json) = sun_json(baked.split_lights(), ctx.target) {
        out.add(ctx.dir.join("sun.json"), json.into_bytes(), ("sun", "json", 0, 0));
    }
}

/// `sun.json` of `lights` (generic frame, the sun first) for `target`; `None` for none.
pub fn sun_json(lights: &[Sun], target: &Target) -> Option<String> {
    let light = |sun: &Sun| LightJson {
        direction: target.orientation.frame.apply(sun.direction),
        irradiance: sun.irradiance,
        illuminance: sun.illuminance(),
        angular_radius_deg: sun.angular_radius_deg,
        solid_angle_sr: sun.solid_angle_sr,
        region_radius_deg: sun.region_radius_deg,
        shape: sun.shape.map(|s| s.map_axis(|d| target.orientation.frame.apply(d))),
        rect_light: sun
            .rect_light()
            .map(|r| r.map_axes(|d| target.orientation.frame.apply(d))),
        share: sun.share,
        clipped: sun.clipped,
        azimuth_deg: sun.azimuth_deg(),
        elevation_deg: sun.elevation_deg(),
    };
    let (sun, rest) = lights.split_first()?;
    Some(to_json(&SunJson {
        about: SUN_JSON_ABOUT.into(),
        frame: format!("target {}: {}", target.name, target.orientation.description),
        sun: light(sun),
        additional_lights: rest.iter().map(light).collect(),
    }))
}

/// Reads a generic target's `sun.json` back: its lights, the sun first.
pub fn read_sun_json(path: &std::path::Path) -> Result<Vec<Sun>> {
    let text = std::fs::read_to_string(path).map_err(|e| Error::io(path, e))?;
    let j: SunJson = serde_json::from_str(&text).map_err(|e| Error::Decode {
        path: path.to_path_buf(),
        format: "JSON",
        message: format!("{e} (not a sun.json splitsum bake wrote?)"),
    })?;
    let sun = |l: &LightJson| Sun {
        direction: l.direction,
        irradiance: l.irradiance,
        solid_angle_sr: l.solid_angle_sr,
        angular_radius_deg: l.angular_radius_deg,
        share: l.share,
        clipped: l.clipped,
        texels: 0,
        region_radius_deg: l.region_radius_deg,
        shape: l.shape,
    };
    Ok(std::iter::once(&j.sun)
        .chain(&j.additional_lights)
        .map(sun)
        .collect())
}
