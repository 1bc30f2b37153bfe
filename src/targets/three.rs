//! three.js r187: a cube with `isPMREMTexture = true` (assembled by `js/splitsum-three.js`)
//! after mirroring x, at three's PMREM roughness per mip, with the SH as a `LightProbe`.

use crate::io::PixelFormat;
use crate::math::cubemap::AxisMap;
use crate::plan::chain::MipRoughness;
use crate::plan::lut::LutModel;
use crate::targets::generic::STANDARD;
use crate::targets::{LutChannels, LutSpec, Orientation, Target};
use crate::math::lookup::SpecularLookup;
use crate::plan::shading::{
    DiffuseLobe, IblTerms, IrradianceSource, RadianceBlend, LightBrdf, Masking, Shading, ShaderLut,
    ShadingTerms,
};

/// three.js r187 (`MeshStandardMaterial`, `MeshPhysicalMaterial`, `scene.background`).
pub const THREE: Target = Target {
    name: "three",
    summary: "three.js r187: x mirrored, a PMREM chain to 8×8 at r = 1 − √(1 − m/(levels − 1)), no irradiance cube or LUT",
    // `flipEnvMap`: WebGLMaterials and WebGLBackground premultiply (-1, 1, 1) for cube
    // textures that are not render targets.
    orientation: Orientation {
        frame: AxisMap::IDENTITY,
        shader: AxisMap::mirror(0),
        description: "mirror x: texel at (-x, y, z) holds the light from (x, y, z)",
    },
    pixel_format: PixelFormat::Rgba16f,
    zstd: Some(10),
    roughness: MipRoughness::Quadratic,
    min_mip_size: 8,
    irradiance: false,
    sh: true,
    lut: false,
    // Browsers decode 16-bit PNGs to 8 bits and three's TextureLoader flips PNGs.
    luts: &[LutSpec {
        file: "brdf_lut.ktx2",
        model: LutModel::SchlickGgx,
        channels: LutChannels::Model,
    }],
    files: STANDARD,
    format_warnings: &[
        (
            PixelFormat::Bc6h,
            "three.js needs EXT_texture_compression_bptc for bc6h (desktop browsers; not most phones); js/splitsum-three.js throws a clear error without it",
        ),
        (PixelFormat::Astc4x4Hdr, THREE_ASTC),
        (PixelFormat::Astc6x6Hdr, THREE_ASTC),
        (
        PixelFormat::Rgba32f,
        "rgba32f cubes are filtered only where WebGL has OES_texture_float_linear; rgba16f is filterable everywhere",
    )],
    format_refusals: &[],
    notes: &[
        "load with js/splitsum-three.js: a cube with isPMREMTexture = true, used by MeshStandardMaterial as it is (no run-time PMREM)",
        "three samples lod = maxLod * r * (2 - r) (roughnessToMip), mips down to 8x8 as r187's PMREMGenerator (LOD_MIN = 3)",
        "the last level holds E / pi: three reads diffuse as PI * textureLod(envMap, N, maxLod)",
        "sh.json radiance_sh9 is the SphericalHarmonics3 of a THREE.LightProbe as is (world space, not mirrored)",
    ],
    shading: THREE_SHADING,
};

/// The three target's warning for ASTC HDR: where three samples it.
const THREE_ASTC: &str = "three.js samples ASTC HDR where WEBGL_compressed_texture_astc lists the \"hdr\" profile (phones, Apple GPUs; not desktop GPUs); js/splitsum-three.js throws a clear error elsewhere, and pickSplitsumBake chooses among bakes in several formats";

/// How three.js r187's `MeshStandardMaterial` shades (`lights_physical_fragment`,
/// `lights_fragment_begin`, `lights_physical_pars_fragment`,
/// `envmap_physical_pars_fragment`): roughness at least 0.045 (plus `geometryRoughness`,
/// the screen-space normal variation, which the preview's resolution-free spheres leave
/// out); the chain read along normalize(mix(R, n, r⁴)); its own 16² DFG (`DFGLUTData`,
/// (A, B) with the height-correlated Smith, at uv = (r, n·v)); `computeMultiscattering`'s
/// FssEss and FmsEms, the multiple scattering lit by `iblIrradiance`, the last level
/// (`textureLod(envMap, n, ENVMAP_MAX_LOD)`), the diffuse by 1 − FssEss − FmsEms of the
/// dielectric; lights with `BRDF_GGX` (correlated Smith) times
/// `multiScatteringCompensation` = 1 + F0 (1/(A + B) − 1), Lambert times 1 − F(v·h).
pub const THREE_SHADING: Shading = Shading {
    name: "three.js r187",
    lookup: SpecularLookup::AlphaSquared,
    min_roughness: 0.045,
    lut: ShaderLut::Table {
        model: LutModel::SmithCorrelated,
        size: Some(16),
    },
    terms: ShadingTerms {
        ibl: IblTerms::MultiscatterIrradiance,
        roughness_fresnel: false,
        radiance_blend: RadianceBlend::None,
    },
    irradiance: IrradianceSource::LastLevel,
    light: LightBrdf {
        masking: Masking::SmithCorrelated,
        diffuse: DiffuseLobe::FresnelWeighted,
        compensated: true,
    },
};
