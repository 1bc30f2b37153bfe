//! The generic target: the conventions of `docs/conventions.md` (right-handed, +Y up, the
//! texel at d holds the light arriving from d, lod = r·(M − 1), irradiance E/π), and the
//! standard file set it writes, which the Bevy and three.js targets share: `specular` and
//! `irradiance` cubes in the bake's container, `sh.json` and the LUTs.

use serde::Serialize;

use crate::io::cubemap::{encode_cube, Container};
use crate::io::staging::Staging;
use crate::io::{to_json, PixelFormat};
use crate::math::sh::SH_ORDER;
use crate::plan::chain::{MipRoughness, DEFAULT_MIN_MIP_SIZE};
use crate::stages::light::BakedEnvironment;
use crate::stages::sh::ShCoefficients;
use crate::targets::{FileContext, FileSet, Orientation, Target, BRDF_LUT_PNG};
use crate::Result;

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

/// The conventions of `docs/conventions.md`: right-handed, +Y up, lod = r·(M − 1), irradiance E/π.
pub const GENERIC: Target = Target {
    name: "generic",
    summary: "the conventions of docs/conventions.md: right-handed, +Y up, lod = r·(levels − 1)",
    orientation: Orientation::GENERIC,
    pixel_format: PixelFormat::Rgba16f,
    zstd: None,
    roughness: MipRoughness::Linear,
    min_mip_size: DEFAULT_MIN_MIP_SIZE,
    irradiance: true,
    sh: true,
    lut: true,
    luts: BRDF_LUT_PNG,
    files: STANDARD,
    format_warnings: &[],
    format_refusals: &[],
    notes: &[
        "sample specular at lod = roughness * (levels - 1), seamless trilinear",
        "irradiance holds E / pi: multiply by the diffuse albedo",
    ],
};

/// The standard file set: `specular.<ext>` and (when [`Target::irradiance`]) `irradiance.<ext>`
/// in the bake's container (KTX2, DDS, or OpenEXR crosses, one per level), and `sh.json`
/// when the SH were asked for.
pub fn write_standard(
    ctx: &FileContext,
    baked: BakedEnvironment,
    out: &mut Staging,
) -> Result<Vec<String>> {
    let target = ctx.target;
    let enc = &ctx.encoding;
    let fmt = match enc.container {
        Container::Exr => "rgb32f (OpenEXR cross)",
        _ => enc.format.name(),
    };
    let ext = enc.container.extension();
    let specular = target.orientation.apply(baked.specular);
    let path = ctx.dir.join(format!("specular.{ext}"));
    out.add_cube(encode_cube(&path, &specular, enc)?, "specular", fmt, &specular);
    if target.irradiance {
        let irradiance = target.orientation.apply(baked.irradiance);
        let path = ctx.dir.join(format!("irradiance.{ext}"));
        out.add_cube(
            encode_cube(&path, &irradiance, enc)?,
            "irradiance",
            fmt,
            &irradiance,
        );
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

/// `sh.json`: the coefficient order, the radiance projection and the E/π coefficients.
#[derive(Serialize)]
struct ShJson<'a> {
    order: &'a str,
    radiance_sh9: &'a [[f32; 3]; 9],
    irradiance_sh9: &'a [[f32; 3]; 9],
}

/// `sh.json` of `sh` (world space, generic orientation, whatever the target).
pub fn sh_json(sh: &ShCoefficients) -> String {
    to_json(&ShJson {
        order: SH_ORDER,
        radiance_sh9: &sh.radiance,
        irradiance_sh9: &sh.irradiance,
    })
}
