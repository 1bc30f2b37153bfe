//! Bevy 0.19: `EnvironmentMapLight` and `Skybox` read KTX2 cubes (rgb9e5 + zstd, as its
//! own sample files) after negating z; its own environment BRDF, no LUT and no SH.

use crate::io::PixelFormat;
use crate::math::cubemap::AxisMap;
use crate::plan::chain::{MipRoughness, DEFAULT_MIN_MIP_SIZE};
use crate::targets::generic::STANDARD;
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
    format_warnings: &[(
        PixelFormat::Rgba32f,
        "rgba32f is not filterable under WebGPU's limits: Bevy fails to bind it without the native FLOAT32_FILTERABLE feature; rgba16f or rgb9e5 render everywhere",
    )],
    format_refusals: &[],
    notes: &[
        "EnvironmentMapLight { diffuse_map: irradiance.ktx2, specular_map: specular.ktx2, intensity }",
        "Bevy samples lod = perceptual_roughness * (mip_level_count - 1) after negating z",
        "radiance is the HDRI's: at Bevy's default exposure (EV100 9.7) use intensity = brightness = 2^9.7 * 1.2 = 998 to see it as is",
        "Bevy uses its own environment BRDF, no LUT and no SH",
    ],
};
