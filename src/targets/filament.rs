//! Filament (`IndirectLight`, `Skybox`; the web build's `Engine.createIblFromKtx1` and
//! `createSkyFromKtx1`), as cmgen deploys an environment for it: KTX 1 files in cmgen's
//! frame (a quarter turn about +Y), the chain to 16² at Filament's roughness per mip.

use std::path::Path;

use crate::environment::Cubemap;
use crate::io::cubemap::{encode_texture, Container};
use crate::io::staging::Staging;
use crate::io::{ktx1, sh_text, PixelFormat};
use crate::math::cubemap::AxisMap;
use crate::plan::chain::MipRoughness;
use crate::stages::light::BakedEnvironment;
use crate::targets::{engine_sh, FileContext, FileSet, Orientation, Target, BRDF_LUT_PNG};
use crate::{Error, Result};
use crate::math::lookup::SpecularLookup;
use crate::plan::lut::LutModel;
use crate::plan::shading::{
    DiffuseLobe, IblTerms, IrradianceSource, RadianceBlend, LightBrdf, Masking, Shading, ShaderLut,
    ShadingTerms,
};

/// The smallest mip of the Filament target's chain: cmgen's default (`--ibl-min-lod-size`).
pub const FILAMENT_MIN_MIP_SIZE: u32 = 16;

/// Filament (`IndirectLight`, `Skybox`; the web build's `Engine.createIblFromKtx1` and
/// `createSkyFromKtx1`), as cmgen deploys an environment for it.
pub const FILAMENT: Target = Target {
    name: "filament",
    summary: "Filament (cmgen's files): <stem>_ibl.ktx with the SH, <stem>_skybox.ktx and sh.txt, KTX 1 rg11b10f, a quarter turn about +Y, the chain to 16×16",
    // cmgen's faces: the generic direction d is stored at (−z, y, x), a quarter turn about
    // +Y (measured against cmgen 1.9's output in tests/targets.rs). Filament samples its
    // cubes with the world direction as it is, and evaluates the SH in the same frame.
    orientation: Orientation {
        frame: AxisMap {
            axis: [2, 1, 0],
            sign: [-1, 1, 1],
        },
        shader: AxisMap::IDENTITY,
        description: "filament (cmgen's faces): texel at (-z, y, x) holds the light from (x, y, z), a quarter turn about +y",
    },
    // cmgen's KTX format; Filament's web loader warns about any other but RGB32F.
    pixel_format: PixelFormat::Rg11b10f,
    zstd: None,
    // Filament's perceptualRoughnessToLod: lod = iblRoughnessOneLevel · r (2 − r), with
    // iblRoughnessOneLevel = the reflections texture's level count − 1.
    roughness: MipRoughness::Quadratic,
    min_mip_size: FILAMENT_MIN_MIP_SIZE,
    irradiance: false,
    sh: true,
    lut: false,
    luts: BRDF_LUT_PNG,
    files: FILES,
    format_warnings: &[
        (
            PixelFormat::Bc6h,
            "Filament reads BC6H (RGB_BPTC_UNSIGNED_FLOAT) on desktop GL, Vulkan and Metal and in WebGL with EXT_texture_compression_bptc, not on mobile GPUs, whose HDR compression is ASTC",
        ),
        (
            PixelFormat::Rgba16f,
            "Filament's web loader (createIblFromKtx1) warns about any IBL format but R11F_G11F_B10F and RGB32F; the native engine loads rgba16f",
        ),
        (
            PixelFormat::Rgba32f,
            "Filament's web loader (createIblFromKtx1) warns about any IBL format but R11F_G11F_B10F and RGB32F; the native engine loads rgba32f",
        ),
    ],
    format_refusals: &[],
    notes: &[
        "<stem>_ibl.ktx: IndirectLight reflections (web: engine.createIblFromKtx1), its key 'sh' the irradiance SH pre-scaled for Filament's shader (IndirectLight::Builder::irradiance(3, sh); web: ibl.shfloats)",
        "<stem>_skybox.ktx: Skybox environment (web: engine.createSkyFromKtx1)",
        "Filament samples lod = (levels - 1) * r * (2 - r) (perceptualRoughnessToLod); without SH it reads diffuse from the last level, which holds E / pi",
        "sh.txt: the same SH as cmgen --sh-shader writes them",
    ],
    shading: FILAMENT_SHADING,
};

/// How Filament 1.53's standard lit model shades (`light_indirect.fs` `evaluateIBL`,
/// `shading_model_standard.fs`): roughness at least 0.045 (`MIN_PERCEPTUAL_ROUGHNESS` on
/// desktop; 0.089 where materials are built for mobile, which changes only r = 0); the
/// chain read along mix(R, n, α²) (`getSpecularDominantDirection` with α = r²); its
/// 128² DFG of (∫ Fc V, ∫ V) with the height-correlated Smith; E = mix(dfg.x, dfg.y, F0)
/// (= FssEss), the specular S E times `energyCompensation` 1 + F0 (1/dfg.y − 1), the
/// diffuse c E/π (1 − E) from the last level (`createIblFromKtx1` gives no SH, the README's
/// recipe); lights with `V_SmithGGXCorrelated` times the same compensation and
/// `Fd_Lambert` unweighted by F.
pub const FILAMENT_SHADING: Shading = Shading {
    name: "Filament 1.53",
    lookup: SpecularLookup::AlphaSquared,
    min_roughness: 0.045,
    lut: ShaderLut::Table {
        model: LutModel::MultiscatterSmithCorrelated,
        size: Some(128),
    },
    terms: ShadingTerms {
        ibl: IblTerms::EnergyCompensated,
        roughness_fresnel: false,
        radiance_blend: RadianceBlend::None,
    },
    irradiance: IrradianceSource::LastLevel,
    light: LightBrdf {
        masking: Masking::SmithCorrelated,
        diffuse: DiffuseLobe::Lambert,
        compensated: true,
    },
};

/// cmgen's deploy set: `<stem>_ibl.ktx` (KTX 1: the specular chain, with the SH
/// pre-scaled for Filament's shader as text under the key `sh`), `<stem>_skybox.ktx`
/// (the environment, level 0 alone) and `sh.txt`.
pub const FILES: FileSet = FileSet {
    fixed_container: Some("ktx (KTX 1)"),
    has_pixel_format: true,
    carries_sh: true,
    sheen: false,
    whole_chain: false,
    cube_container: Container::Ktx1,
    write,
};

/// Writes [`FILES`].
fn write(ctx: &FileContext, baked: BakedEnvironment, out: &mut Staging) -> Result<Vec<String>> {
    crate::targets::generic::add_sun_json(ctx, &baked, out);
    let (dir, stem, format) = (ctx.dir, ctx.stem, ctx.encoding.format);
    let specular = ctx.target.orientation.apply(baked.specular);
    let sh = baked.sh.as_ref().map(|sh| engine_sh(sh, ctx.target));
    let fmt = format.name();
    let ktx = |path: &Path, cube: &Cubemap, key_values: &[(&str, &[u8])]| -> Result<Vec<u8>> {
        let texture = encode_texture(cube, format, &ctx.encoding.blocks)?;
        ktx1::encode(&texture, key_values).map_err(|message| Error::Encode {
            path: path.to_path_buf(),
            format: "KTX 1",
            message,
        })
    };
    let ibl = dir.join(format!("{stem}_ibl.ktx"));
    let sh_value = sh.as_ref().map(sh_text::ktx_value);
    let key_values: Vec<(&str, &[u8])> = sh_value.iter().map(|v| ("sh", v.as_slice())).collect();
    let bytes = ktx(&ibl, &specular, &key_values)?;
    let levels = specular.levels.len() as u32;
    out.add(ibl, bytes, ("specular", fmt, specular.size, levels));
    // The skybox is seen, not lit by: it keeps the lights a split bake took out.
    let skybox_cube = match baked.background {
        Some(background) => ctx.target.orientation.apply(background),
        None => Cubemap {
            size: specular.size,
            levels: vec![specular.levels[0].clone()],
        },
    };
    let skybox = dir.join(format!("{stem}_skybox.ktx"));
    let bytes = ktx(&skybox, &skybox_cube, &[])?;
    out.add(skybox, bytes, ("skybox", fmt, specular.size, 1));
    if let Some(sh) = &sh {
        out.add(
            dir.join("sh.txt"),
            sh_text::sh_txt(sh).into_bytes(),
            ("sh", "text (cmgen --sh-shader)", 0, 0),
        );
    }
    Ok(Vec::new())
}
