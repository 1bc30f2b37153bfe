//! Bevy 0.19: `EnvironmentMapLight` and `Skybox` read KTX2 cubes (rgb9e5 + zstd, as its
//! own sample files) after negating z; its own environment BRDF, no LUT and no SH.

use crate::io::PixelFormat;
use crate::math::cubemap::AxisMap;
use crate::plan::chain::{MipRoughness, DEFAULT_MIN_MIP_SIZE};
use crate::targets::generic::STANDARD;
use crate::math::lookup::SpecularLookup;
use crate::plan::shading::{
    DiffuseLobe, IblTerms, IrradianceSource, RadianceBlend, LightBrdf, Masking, ShaderLut, Shading,
    ShadingTerms,
};
use crate::targets::{Orientation, Target, BRDF_LUT_PNG};

/// Bevy 0.19 (`EnvironmentMapLight`, `Skybox`).
pub const BEVY: Target = Target {
    name: "bevy",
    summary: "Bevy 0.19: z mirrored, rgb9e5 + zstd, no LUT or SH",
    // bevy_pbr's environment_map.wgsl: `sample_dir.z = -sample_dir.z` ("cube maps are
    // left-handed"); the skybox shader: `ray_direction * vec3(1.0, 1.0, -1.0)`.
    orientation: Orientation {
        frame: AxisMap::IDENTITY,
        shader: AxisMap::mirror(2),
        description: "mirror z: texel at (x, y, -z) holds the light from (x, y, z)",
    },
    pixel_format: PixelFormat::Rgb9e5,
    zstd: Some(10),
    roughness: MipRoughness::Linear,
    min_mip_size: DEFAULT_MIN_MIP_SIZE,
    irradiance: true,
    sh: false,
    lut: false,
    luts: BRDF_LUT_PNG,
    files: STANDARD,
    format_warnings: &[
        (
            PixelFormat::Rgba32f,
            "rgba32f is not filterable under WebGPU's limits: Bevy fails to bind it without the native FLOAT32_FILTERABLE feature; rgba16f or rgb9e5 render everywhere",
        ),
        (PixelFormat::Astc4x4Hdr, super::ASTC_HDR_WHERE),
        (PixelFormat::Astc6x6Hdr, super::ASTC_HDR_WHERE),
    ],
    format_refusals: &[],
    notes: &[
        "EnvironmentMapLight { diffuse_map: irradiance.ktx2, specular_map: specular.ktx2, intensity }",
        "Bevy samples lod = perceptual_roughness * (mip_level_count - 1) after negating z",
        "radiance is the HDRI's: at Bevy's default exposure (EV100 9.7) use intensity = brightness = 2^9.7 * 1.2 = 998 to see it as is",
        "Bevy uses its own environment BRDF, no LUT and no SH",
    ],
    shading: BEVY_SHADING,
};

/// How bevy_pbr 0.19's `StandardMaterial` shades with an `EnvironmentMapLight` and its
/// default features (`environment_map.wgsl`'s `environment_map_light`, `pbr_lighting.wgsl`):
/// α = max(r, 0.089)² (`perceptualRoughnessToRoughness`; the lod and the LUT read r
/// unclamped, which differs at r = 0 alone); the chain read along Frostbite's dominant
/// direction (`radiance_sample_direction`); (A, B) from `F_AB`, Karis's analytic fit (the
/// `dfg_lut` feature, off by default, reads a 64² height-correlated table instead);
/// `compute_multiscatter`'s FssEss and FmsEms, the multiple scattering lit by the
/// irradiance cube, the diffuse by `Edss` = 1 − FssEss − FmsEms of the dielectric
/// (`specular_occlusion` is 1 for F0 ≥ 0.02); lights with `V_SmithGGXCorrelated`, Fresnel
/// with f90 = 1 for F0 ≥ 0.02, `specular_multiscatter`'s 1 + F0 (1/(A + B) − 1), and
/// `Fd_Burley` unweighted by F.
pub const BEVY_SHADING: Shading = Shading {
    name: "Bevy 0.19",
    lookup: SpecularLookup::Frostbite,
    min_roughness: 0.089,
    lut: ShaderLut::EnvBrdfApprox,
    terms: ShadingTerms {
        ibl: IblTerms::MultiscatterIrradiance,
        roughness_fresnel: false,
        radiance_blend: RadianceBlend::None,
    },
    irradiance: IrradianceSource::Cube,
    light: LightBrdf {
        masking: Masking::SmithCorrelated,
        diffuse: DiffuseLobe::Burley,
        compensated: true,
    },
};
