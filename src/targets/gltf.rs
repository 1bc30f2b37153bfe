//! The glTF Sample Viewer (npm `@khronosgroup/gltf-viewer` 1.1) with glTF-IBL-Sampler's
//! file set: Lambertian, GGX and Charlie sheen cubes in folders, and its three LUTs; with
//! lights split out, `sun.gltf`, the lights as `KHR_lights_punctual` directional lights.

use crate::environment::sun::Sun;
use crate::io::cubemap::Container;
use crate::math::cubemap::rotate_y;
use crate::io::staging::Staging;
use crate::io::PixelFormat;
use crate::plan::chain::MipRoughness;
use crate::plan::lut::LutModel;
use crate::stages::light::BakedEnvironment;
use crate::targets::{FileContext, FileSet, LutChannels, LutSpec, Orientation, Target};
use crate::Result;
use serde_json::json;
use crate::math::lookup::SpecularLookup;
use crate::plan::shading::{
    DiffuseLobe, IblTerms, IrradianceSource, RadianceBlend, LightBrdf, Masking, Shading, ShaderLut,
    ShadingTerms,
};

/// Why the glTF target refuses block formats.
const GLTF_UNCOMPRESSED: &str =
    "the glTF Sample Viewer reads its environment cubes as uncompressed KTX2 (rgba16f, rgba32f)";

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
    format_refusals: &[
        (PixelFormat::Bc6h, GLTF_UNCOMPRESSED),
        (PixelFormat::Astc4x4Hdr, GLTF_UNCOMPRESSED),
        (PixelFormat::Astc6x6Hdr, GLTF_UNCOMPRESSED),
    ],
    notes: &[
        "lambertian/diffuse.ktx2 (E / pi), ggx/specular.ktx2 and charlie/sheen.ktx2 as the environment's u_LambertianEnvSampler, u_GGXEnvSampler and u_CharlieEnvSampler, u_MipCount = the specular levels",
        "the viewer samples lod = roughness * (u_MipCount - 1), GGX and sheen alike, at u_EnvRotation * direction",
        "lut_ggx.png (height-correlated Smith scale and bias), lut_charlie.png (the Charlie albedo in B) and lut_sheen_E.png (the sheen albedo in R) at uv = (n.v, roughness)",
    ],
    shading: GLTF_SHADING,
};

/// How the glTF Sample Viewer 1.1 shades a metallic-roughness material (its `ibl.glsl`
/// and `pbr.frag`, read in `@khronosgroup/gltf-viewer`'s bundle): no minimum roughness;
/// the chain read along R; `lut_ggx` (A, B) with the height-correlated Smith (the bake's
/// file); `getIBLGGXFresnel`'s roughness-aware kS, FssEss + FmsEms all lit by the
/// prefiltered radiance, the Lambertian cube's E/π mixed in by 1 − that (`mix(f_diffuse,
/// f_specular, fresnel)`); lights with `V_GGX` (correlated Smith), no compensation, and
/// the dielectric's Lambert mixed by F(v·h).
pub const GLTF_SHADING: Shading = Shading {
    name: "glTF Sample Viewer 1.1",
    lookup: SpecularLookup::Reflect,
    min_roughness: 0.0,
    lut: ShaderLut::Table {
        model: LutModel::SmithCorrelated,
        size: None,
    },
    terms: ShadingTerms {
        ibl: IblTerms::MultiscatterRadiance,
        roughness_fresnel: true,
        radiance_blend: RadianceBlend::None,
    },
    irradiance: IrradianceSource::Cube,
    light: LightBrdf {
        masking: Masking::SmithCorrelated,
        diffuse: DiffuseLobe::FresnelWeighted,
        compensated: false,
    },
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
    if let Some(gltf) = sun_gltf(baked.split_lights(), ctx.target) {
        out.add(ctx.dir.join("sun.gltf"), gltf.into_bytes(), ("sun", "gltf", 0, 0));
    }
    let fmt = ctx.encoding.format.name();
    let path = |folder: &str, name: &str| ctx.dir.join(folder).join(format!("{name}.ktx2"));
    let irradiance = path("lambertian", "diffuse");
    ctx.add_cube(out, &irradiance, "irradiance", fmt, baked.irradiance)?;
    ctx.add_cube(out, &path("ggx", "specular"), "specular", fmt, baked.specular)?;
    if let Some(sheen) = baked.sheen {
        ctx.add_cube(out, &path("charlie", "sheen"), "sheen", fmt, sheen)?;
    }
    Ok(Vec::new())
}

/// The Sample Viewer's default `environmentRotation`, degrees about +Y: it samples every
/// environment cube at `u_EnvRotation · d`, so the cube's direction c is seen from the
/// world direction [cos t c_x − sin t c_z, c_y, sin t c_x + cos t c_z].
pub const VIEWER_ENVIRONMENT_ROTATION_DEG: f32 = 90.0;

/// The world direction from which the Sample Viewer, at its default environment rotation,
/// shows the cube's direction `c`: `c` turned by −t with the environment's turn about +Y.
fn viewer_world(c: [f32; 3]) -> [f32; 3] {
    let (sin, cos) = VIEWER_ENVIRONMENT_ROTATION_DEG.to_radians().sin_cos();
    rotate_y(c, cos, -sin)
}

/// `sun.gltf` of `lights` (generic frame, the sun first) for `target`: a glTF 2.0 scene of
/// one node per light, each a `KHR_lights_punctual` directional light, for a user to merge
/// into their scene, in the viewer's world at its default environment rotation
/// ([`VIEWER_ENVIRONMENT_ROTATION_DEG`]: the lights shine from where it shows the sun; turn
/// the nodes with the environment at another). A directional light shines along its node's local −Z (the extension's
/// specification), so each node's rotation takes +Z to the direction toward the light;
/// the extension's `color` lies in [0, 1], so it is E / max(E) and `intensity` max(E),
/// colour × intensity = E in the HDRI's radiance units (the specification's lux, at the
/// environment's scale). `None` for none.
pub fn sun_gltf(lights: &[Sun], target: &Target) -> Option<String> {
    if lights.is_empty() {
        return None;
    }
    let name = |k: usize| match k {
        0 => "sun".to_string(),
        k => format!("light {k}"),
    };
    let punctual: Vec<_> = lights
        .iter()
        .enumerate()
        .map(|(k, l)| {
            let peak = l.irradiance.iter().fold(0.0f32, |m, &c| m.max(c));
            let color = match peak > 0.0 {
                true => l.irradiance.map(|c| c / peak),
                false => [1.0; 3],
            };
            json!({ "type": "directional", "name": name(k), "color": color, "intensity": peak })
        })
        .collect();
    let nodes: Vec<_> = lights
        .iter()
        .enumerate()
        .map(|(k, l)| {
            let toward = viewer_world(target.orientation.frame.apply(l.direction));
            json!({
                "name": name(k),
                "rotation": rotation_from_z(toward),
                "extensions": { "KHR_lights_punctual": { "light": k } },
            })
        })
        .collect();
    let gltf = json!({
        "asset": { "version": "2.0", "generator": "splitsum" },
        "extensionsUsed": ["KHR_lights_punctual"],
        "extensions": { "KHR_lights_punctual": { "lights": punctual } },
        "scene": 0,
        "scenes": [{ "name": "splitsum lights", "nodes": (0..lights.len()).collect::<Vec<_>>() }],
        "nodes": nodes,
    });
    Some(crate::io::to_json(&gltf))
}

/// The unit quaternion [x, y, z, w] (glTF's order) of the shortest rotation taking +Z to
/// the unit vector `d`: axis +Z × d, angle acos(d_z), as (+Z × d, 1 + d_z) normalised;
/// for d = −Z, half a turn about +X.
fn rotation_from_z(d: [f32; 3]) -> [f32; 4] {
    let q = [-d[1], d[0], 0.0, 1.0 + d[2]];
    let len = q.iter().map(|c| c * c).sum::<f32>().sqrt();
    match len > 1e-6 {
        true => q.map(|c| c / len),
        false => [1.0, 0.0, 0.0, 0.0],
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Rotates `v` by the unit quaternion `q` ([x, y, z, w]).
    fn rotate(q: [f32; 4], v: [f32; 3]) -> [f32; 3] {
        let (u, w) = ([q[0], q[1], q[2]], q[3]);
        let cross = |a: [f32; 3], b: [f32; 3]| {
            [
                a[1] * b[2] - a[2] * b[1],
                a[2] * b[0] - a[0] * b[2],
                a[0] * b[1] - a[1] * b[0],
            ]
        };
        let t = cross(u, v).map(|c| 2.0 * c);
        let ut = cross(u, t);
        [0, 1, 2].map(|i| v[i] + w * t[i] + ut[i])
    }

    /// The node's −Z, where the light shines, is −(the direction toward the light), for
    /// directions all round, the poles and −Z included.
    #[test]
    fn a_node_shines_away_from_its_light() {
        let dirs = [
            [0.0, 0.0, 1.0],
            [0.0, 0.0, -1.0],
            [0.0, 1.0, 0.0],
            [0.79666, 0.17492, 0.57857],
            [-0.0964, 0.99362, -0.05851],
            [0.3, -0.4, -0.866],
        ];
        for d in dirs {
            let len = d.iter().map(|c: &f32| c * c).sum::<f32>().sqrt();
            let d = d.map(|c| c / len);
            let shines = rotate(rotation_from_z(d), [0.0, 0.0, -1.0]);
            for i in 0..3 {
                // 1e-5: single-precision rounding of a unit quaternion's product.
                assert!((shines[i] + d[i]).abs() < 1e-5, "{d:?} shines along {shines:?}");
            }
        }
    }
}
