//! The glTF Sample Viewer (npm `@khronosgroup/gltf-viewer` 1.1) with glTF-IBL-Sampler's
//! file set: Lambertian, GGX and Charlie sheen cubes in folders, and its three LUTs.

use crate::environment::Cubemap;
use crate::io::cubemap::{encode_cube, Container};
use crate::io::staging::Staging;
use crate::io::PixelFormat;
use crate::plan::chain::MipRoughness;
use crate::plan::lut::LutModel;
use crate::stages::light::BakedEnvironment;
use crate::targets::{FileContext, FileSet, LutChannels, LutSpec, Orientation, Target};
use crate::Result;

/// The glTF Sample Viewer (npm `@khronosgroup/gltf-viewer` 1.1), with glTF-IBL-Sampler's
/// file set and its own chain layout.
pub const GLTF: Target = Target {
    name: "gltf",
    summary: "the glTF Sample Viewer: glTF-IBL-Sampler's folders (lambertian, ggx, a Charlie sheen chain to 16×16) and its three LUTs",
    orientation: Orientation::GENERIC,
    pixel_format: PixelFormat::Rgba16f,
    zstd: None,
    // The viewer reads lod = r * (u_MipCount - 1) for GGX and sheen alike.
    roughness: MipRoughness::Linear,
    // The viewer's own filtering (iblSampler): 256² with lowestMipLevel 4, five levels to
    // 16², which also holds the Charlie lobe (its r = 1 level at 4² misses a sun by 3.5 %).
    min_mip_size: 16,
    irradiance: true,
    sh: false,
    lut: true,
    luts: &[
        LutSpec {
            file: "lut_ggx.png",
            model: LutModel::SmithCorrelated,
            channels: LutChannels::Model,
        },
        LutSpec {
            file: "lut_charlie.png",
            model: LutModel::Charlie,
            channels: LutChannels::FirstInBlue,
        },
        LutSpec {
            file: "lut_sheen_E.png",
            model: LutModel::SheenAlbedo,
            channels: LutChannels::Model,
        },
    ],
    files: FILES,
    format_warnings: &[],
    // The viewer's KTX2 path (libktx in the page) uploads uncompressed cubes; a BC6H cube
    // would need its transcoder's BC6H output, which the viewer does not ask for.
    format_refusals: &[(
        PixelFormat::Bc6h,
        "the glTF Sample Viewer reads its environment cubes as uncompressed KTX2 (rgba16f, rgba32f)",
    )],
    notes: &[
        "lambertian/diffuse.ktx2 (E / pi), ggx/specular.ktx2 and charlie/sheen.ktx2 as the environment's u_LambertianEnvSampler, u_GGXEnvSampler and u_CharlieEnvSampler, u_MipCount = the specular levels",
        "the viewer samples lod = roughness * (u_MipCount - 1), GGX and sheen alike, at u_EnvRotation * direction",
        "lut_ggx.png (height-correlated Smith scale and bias), lut_charlie.png (the Charlie albedo in B) and lut_sheen_E.png (the sheen albedo in R) at uv = (n.v, roughness)",
    ],
};

/// glTF-IBL-Sampler's folders: `lambertian/diffuse.ktx2` (E/π), `ggx/specular.ktx2` and
/// `charlie/sheen.ktx2` (the Charlie chain, in the GGX chain's layout), with the LUTs
/// `lut_ggx.png`, `lut_charlie.png` and `lut_sheen_E.png` beside them.
pub const FILES: FileSet = FileSet {
    fixed_container: Some("ktx2 (glTF-IBL-Sampler's folders)"),
    has_pixel_format: true,
    carries_sh: false,
    sheen: true,
    whole_chain: false,
    cube_container: Container::Ktx2,
    write,
};

/// Writes [`FILES`].
fn write(ctx: &FileContext, baked: BakedEnvironment, out: &mut Staging) -> Result<Vec<String>> {
    crate::targets::generic::add_sun_json(ctx, &baked, out);
    let orientation = ctx.target.orientation;
    let fmt = ctx.encoding.format.name();
    let mut cube = |folder: &str, name: &str, kind: &'static str, cube: Cubemap| -> Result<()> {
        let cube = orientation.apply(cube);
        let path = ctx.dir.join(folder).join(format!("{name}.ktx2"));
        out.add_cube(encode_cube(&path, &cube, &ctx.encoding)?, kind, fmt, &cube);
        Ok(())
    };
    let specular = baked.specular;
    cube("lambertian", "diffuse", "irradiance", baked.irradiance)?;
    cube("ggx", "specular", "specular", specular)?;
    if let Some(sheen) = baked.sheen {
        cube("charlie", "sheen", "sheen", sheen)?;
    }
    Ok(Vec::new())
}
