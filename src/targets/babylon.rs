//! Babylon.js (`CubeTexture` of a `.env`, `scene.environmentTexture`, `PBRMaterial`): the
//! whole chain in RGBD at Babylon's roughness per mip, in its left-handed frame, with the
//! irradiance as its spherical polynomial.

use crate::environment::mips::build_mips;
use crate::environment::Cubemap;
use crate::io::cubemap::Container;
use crate::io::staging::Staging;
use crate::io::{env, PixelFormat};
use crate::math::cubemap::AxisMap;
use crate::math::lookup::SpecularLookup;
use crate::plan::chain::MipRoughness;
use crate::plan::lut::LutModel;
use crate::plan::shading::{
    DiffuseLobe, IblTerms, IrradianceSource, LightBrdf, Masking, RadianceBlend, ShaderLut, Shading,
    ShadingTerms,
};
use crate::stages::light::BakedEnvironment;
use crate::targets::{engine_sh, FileContext, FileSet, Orientation, Target, BRDF_LUT_PNG};
use crate::{Error, Result};

/// Babylon.js (`CubeTexture` of a `.env`, `scene.environmentTexture`, `PBRMaterial`).
pub const BABYLON: Target = Target {
    name: "babylon",
    summary: "Babylon.js: <stem>.env, the whole chain as RGBD PNGs at Babylon's roughness per mip and the SH as its spherical polynomial, and <stem>_irradiance.env (E/π for irradianceTexture), x and z swapped",
    // Babylon's world is left-handed: its own HDRCubeTexture of an equirect holds the generic
    // direction (x, y, z) at (z, y, x) (measured texel for texel in engines/babylon), it
    // samples cubes with the world direction as it is, and evaluates the irradiance
    // polynomial in the same frame.
    orientation: Orientation {
        frame: AxisMap {
            axis: [2, 1, 0],
            sign: [1, 1, 1],
        },
        shader: AxisMap::IDENTITY,
        description: "babylon (left-handed): texel at (z, y, x) holds the light from (x, y, z)",
    },
    // Unused: a .env holds RGBD PNGs whatever the format.
    pixel_format: PixelFormat::Rgba16f,
    zstd: None,
    roughness: MipRoughness::Babylon,
    // Babylon reads a .env only with its whole chain.
    min_mip_size: 1,
    irradiance: true,
    sh: true,
    lut: false,
    luts: BRDF_LUT_PNG,
    files: FILES,
    format_warnings: &[],
    format_refusals: &[],
    notes: &[
        "<stem>.env: new CubeTexture(url, scene) (or CubeTexture.CreateFromPrefilteredData) as scene.environmentTexture; scene.createDefaultSkybox(texture) for the background",
        "<stem>_irradiance.env: new CubeTexture(url, scene) as that texture's irradianceTexture: Babylon reads the diffuse light (E / pi) from it instead of the SH",
        "with --sun split: <stem>_background.env is the sky as seen, sun included, for scene.createDefaultSkybox (the <stem>.env lacks the sun)",
        "Babylon samples lod = 0.8 * log2(size * (r^2 + 0.0005)); mip m holds GGX at alpha = 2^(m / 0.8) / size",
        "the irradiance is the header's spherical polynomial (E / pi, in the cube's frame)",
        "RGBD holds radiance up to 255: brighter texels (a sun) are clipped; scale with --exposure and scene.environmentIntensity to keep them",
    ],
    shading: BABYLON_SHADING,
};

/// How Babylon.js 9.35's `PBRMaterial` shades with its defaults (`pbrBlockReflection`,
/// `pbrBlockReflectivity`, `pbrBlockReflectance`, `pbrBlockFinalLitComponents`,
/// `pbrDirectLightingFunctions`; its `PBRBRDFConfiguration` turns on the height-correlated
/// Smith, the energy conservation, the spherical harmonics, the radiance mixed with the
/// irradiance and the legacy specular energy conservation): the chain read along R
/// (`computeReflectionCoords`); its 256² `environmentBrdfSampler` (the RGBD PNG in
/// `GetEnvironmentBRDFTexture`, (∫ Fc V, ∫ V) with the height-correlated Smith at
/// uv = (n·v, r): Filament's model, which it matches within its 8-bit steps);
/// the radiance blended toward E/π by α ([`RadianceBlend::Alpha`]) and
/// [`IblTerms::LegacyDiffuse`], E/π the irradiance cube (`<stem>_irradiance.env`, which
/// the README recipe sets as the environment's `irradianceTexture`: `USEIRRADIANCEMAP`;
/// without it Babylon evaluates the `.env`'s spherical polynomial instead); lights with
/// `smithVisibility_GGXCorrelated` times the same energy conservation, and the diffuse
/// `surfaceAlbedo` c (1 − F0)(1 − m) with its default E-Oren-Nayar at diffuse roughness 0,
/// Lambert. Left out: the 0.0005 Babylon adds
/// to α = r² (`MINIMUMVARIANCE`), 0.8 % of α at r = 0.25, and the RGBD PNGs' 8-bit steps
/// (the preview shades the bake's floats, as for every engine).
pub const BABYLON_SHADING: Shading = Shading {
    name: "Babylon.js 9.35",
    lookup: SpecularLookup::Reflect,
    min_roughness: 0.0,
    lut: ShaderLut::Table {
        model: LutModel::MultiscatterSmithCorrelated,
        size: Some(256),
    },
    terms: ShadingTerms {
        ibl: IblTerms::LegacyDiffuse,
        roughness_fresnel: false,
        radiance_blend: RadianceBlend::Alpha,
    },
    irradiance: IrradianceSource::Cube,
    light: LightBrdf {
        masking: Masking::SmithCorrelated,
        diffuse: DiffuseLobe::DielectricLambert,
        compensated: true,
    },
};

/// Babylon's prefiltered environment: `<stem>.env`, the whole chain as RGBD PNGs and the
/// irradiance as a spherical polynomial (see [`crate::io::env`]).
pub const FILES: FileSet = FileSet {
    fixed_container: Some("env (Babylon.js)"),
    has_pixel_format: false,
    carries_sh: true,
    sheen: false,
    whole_chain: true,
    cube_container: Container::Ktx2,
    write,
};

/// Writes [`FILES`]; warns when level 0 holds radiance RGBD cannot (above 255).
fn write(ctx: &FileContext, baked: BakedEnvironment, out: &mut Staging) -> Result<Vec<String>> {
    crate::targets::generic::add_sun_json(ctx, &baked, out);
    let path = ctx.dir.join(format!("{}.env", ctx.stem));
    let specular = ctx.target.orientation.apply(baked.specular);
    let enc_err = |message: String| Error::Encode {
        path: path.clone(),
        format: "Babylon .env",
        message,
    };
    let sh = baked
        .sh
        .as_ref()
        .ok_or_else(|| enc_err("a .env carries the irradiance SH".into()))?;
    let polynomial = env::SphericalPolynomial::from_prescaled(&engine_sh(sh, ctx.target));
    let bytes = env::encode(&specular, &polynomial).map_err(enc_err)?;
    let (clipped, largest) = specular.levels[0]
        .iter()
        .map(|t| t[0].max(t[1]).max(t[2]))
        .filter(|&m| m > env::RGBD_MAX)
        .fold((0usize, 0.0f32), |(n, top), m| (n + 1, top.max(m)));
    let levels = specular.levels.len() as u32;
    out.add(
        path.clone(),
        bytes,
        ("specular", "rgbd png", specular.size, levels),
    );
    // E/π as a cube for the environment's `irradianceTexture`: Babylon then reads the
    // diffuse light from it (`USEIRRADIANCEMAP`) instead of the SH9, which cannot hold a
    // kept sun.
    add_env_cube(ctx, "irradiance", baked.irradiance, &polynomial, out)?;
    // With lights split out, `<stem>_background.env`: the environment as seen, lights
    // included, for `scene.createDefaultSkybox` (a background is seen, not lit by); its
    // polynomial, the residual's, is unused by a skybox, and radiance past RGBD's 255 (the
    // sun's disc) is clipped: a skybox shows it saturated either way.
    if let Some(background) = baked.background {
        add_env_cube(ctx, "background", background, &polynomial, out)?;
    }
    Ok((clipped > 0)
        .then(|| {
            format!(
                "{}: {clipped} texels of level 0 are brighter than the {} a .env (RGBD) holds (the largest {largest:.0}) and are clipped; bake N stops darker (--exposure -N) and set scene.environmentIntensity = 2^N to keep them",
                path.display(),
                env::RGBD_MAX
            )
        })
        .into_iter()
        .collect())
}

/// `<stem>_<kind>.env`: `cube`'s level 0 as a `.env` of its own. A `.env` carries a whole
/// chain, so its mips are the solid-angle-weighted means of level 0 (what a blurred read
/// of it takes), not a prefilter; `polynomial` is the bake's.
fn add_env_cube(
    ctx: &FileContext,
    kind: &'static str,
    mut cube: Cubemap,
    polynomial: &env::SphericalPolynomial,
    out: &mut Staging,
) -> Result<()> {
    let path = ctx.dir.join(format!("{}_{kind}.env", ctx.stem));
    cube.levels.truncate(1);
    let levels = Cubemap::full_mip_count(cube.size);
    build_mips(&mut cube, levels);
    let cube = ctx.target.orientation.apply(cube);
    let bytes = env::encode(&cube, polynomial).map_err(|message| Error::Encode {
        path: path.clone(),
        format: "Babylon .env",
        message,
    })?;
    let levels = cube.levels.len() as u32;
    out.add(path, bytes, (kind, "rgbd png", cube.size, levels));
    Ok(())
}
