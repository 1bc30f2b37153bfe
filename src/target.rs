//! Engine targets: how one engine reads IBL files, as data. A bake or a cubemap for an
//! engine is the generic bake (DESIGN.md's conventions) passed through its target's
//! table: the cube orientation the engine's shader samples, the chain layout it reads
//! (levels, roughness per mip), default pixel format and supercompression, and which
//! files it uses. Writers never ask which engine they write for; they read these fields.
//!
//! Every value here was read from the engine's own code and checked by loading the
//! outputs in the engine (`engines/bevy`, `engines/three`; the README's "Engine targets").

use crate::cpu::prefilter_specular::{MipRoughness, DEFAULT_MIN_MIP_SIZE};
use crate::environment::Cubemap;
use crate::io::PixelFormat;
use crate::lut::LutModel;
use crate::math::cubemap::AxisMap;

/// The smallest mip of the Filament target's chain: cmgen's default (`--ibl-min-lod-size`).
pub const FILAMENT_MIN_MIP_SIZE: u32 = 16;

/// How an engine's shaders read directions, against DESIGN.md's (right-handed, +Y up, the
/// equirect's centre along +X).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Orientation {
    /// The engine's world direction for DESIGN.md's direction d: the identity where the
    /// engine's world is DESIGN.md's, a quarter turn about +Y for Filament (whose
    /// environments, as cmgen bakes them, face another way). SH written for the engine
    /// (Filament's KTX key, sh.txt) are expressed in this frame.
    pub frame: AxisMap,
    /// Where the engine's shader looks a world direction w up in a cube: a mirror for
    /// engines that negate an axis before every cube lookup (Bevy z, three.js x).
    pub shader: AxisMap,
    /// As written in manifests.
    pub description: &'static str,
}

impl Orientation {
    /// DESIGN.md's: `textureSample(cube, s, d)` returns the light arriving from d.
    pub const GENERIC: Orientation = Orientation {
        frame: AxisMap::IDENTITY,
        shader: AxisMap::IDENTITY,
        description: "generic: texel at d holds the light arriving from d",
    };

    /// Where the target's cube holds the light arriving from DESIGN.md's direction d: the
    /// engine's lookup of its own world direction for d.
    pub fn lookup(&self, d: [f32; 3]) -> [f32; 3] {
        self.shader.apply(self.frame.apply(d))
    }

    /// The texel permutation [`Orientation::lookup`] is.
    pub fn texel_map(&self) -> AxisMap {
        self.shader.after(self.frame)
    }

    /// `cube` (in generic orientation) stored for this orientation: every level's texels
    /// permuted so that the engine's lookup of a direction returns the light from it.
    pub fn apply(&self, cube: Cubemap) -> Cubemap {
        let map = self.texel_map();
        if map == AxisMap::IDENTITY {
            cube
        } else {
            cube.remapped(map)
        }
    }
}

/// How a LUT file holds its model's table.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum LutChannels {
    /// As the model lays it out (`splitsum lut --model`).
    Model,
    /// The model's first channel in B, R and G zero: glTF-IBL-Sampler's `lut_charlie`,
    /// which the glTF Sample Viewer reads as `.b`.
    FirstInBlue,
}

/// One LUT file a target writes when LUTs are asked for.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct LutSpec {
    /// File name in the bake folder; the extension picks the container (`io::lut`).
    pub file: &'static str,
    /// The model integrated.
    pub model: LutModel,
    /// How the file holds it.
    pub channels: LutChannels,
}

impl LutSpec {
    /// The format as written in manifests.
    pub fn format(&self) -> &'static str {
        match (
            crate::io::extension_of(std::path::Path::new(self.file)).as_str(),
            self.channels,
        ) {
            ("ktx2", _) => "ktx2 rg16f",
            (_, LutChannels::FirstInBlue) => "png rgb16 (the model in B)",
            _ => "png rgb16",
        }
    }
}

/// `brdf_lut.png`: the default model, 16-bit RGB (B = 0).
const BRDF_LUT_PNG: &[LutSpec] = &[LutSpec {
    file: "brdf_lut.png",
    model: LutModel::SchlickGgx,
    channels: LutChannels::Model,
}];

/// Which files a bake writes for the engine, each in the container the engine loads.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum FileSet {
    /// DESIGN.md's: `specular.<ext>` and `irradiance.<ext>` (when [`Target::irradiance`])
    /// in the bake's container (KTX2, DDS or EXR crosses), `sh.json` and the LUT.
    Standard,
    /// cmgen's deploy set (`cmgen -x DIR --format=ktx`), which Filament loads:
    /// `<stem>_ibl.ktx` (KTX 1: the specular chain, with the SH pre-scaled for Filament's
    /// shader as text under the key `sh`), `<stem>_skybox.ktx` (the environment, level 0
    /// alone) and `sh.txt`.
    FilamentKtx1,
    /// Babylon.js's prefiltered environment: `<stem>.env` (the whole chain as RGBD PNGs and
    /// the irradiance as a spherical polynomial, see [`crate::io::env`]).
    BabylonEnv,
    /// glTF-IBL-Sampler's folders, which the glTF Sample Viewer reads:
    /// `lambertian/diffuse.ktx2`, `ggx/specular.ktx2`, `charlie/sheen.ktx2`, with the LUTs
    /// `lut_ggx.png`, `lut_charlie.png` and `lut_sheen_E.png` beside them.
    GltfSampleViewer,
}

impl FileSet {
    /// Whether `--pixel-format` chooses how the cubes are stored (a `.env` is always RGBD).
    pub fn has_pixel_format(self) -> bool {
        self != FileSet::BabylonEnv
    }

    /// Whether the irradiance SH are part of the engine's own file (Filament's IBL,
    /// Babylon's .env), so they cannot be left out.
    pub fn carries_sh(self) -> bool {
        matches!(self, FileSet::FilamentKtx1 | FileSet::BabylonEnv)
    }

    /// Whether the set holds a Charlie sheen chain (glTF's `charlie/sheen.ktx2`, for
    /// KHR_materials_sheen), so the bake prefilters one.
    pub fn has_sheen(self) -> bool {
        self == FileSet::GltfSampleViewer
    }

    /// The extension of `splitsum cubemap`'s default output: the engine's cube container.
    pub fn cube_extension(self) -> &'static str {
        match self {
            FileSet::FilamentKtx1 => "ktx",
            _ => "ktx2",
        }
    }
}

/// One engine's conventions.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Target {
    /// Name on the command line and in manifests.
    pub name: &'static str,
    /// Where the engine reads each direction.
    pub orientation: Orientation,
    /// Default pixel format of cube outputs.
    pub pixel_format: PixelFormat,
    /// Default KTX2 Zstandard level (None: not supercompressed).
    pub zstd: Option<i32>,
    /// Roughness of each specular mip, as the engine's shader picks the lod.
    pub roughness: MipRoughness,
    /// Default edge of the smallest specular mip.
    pub min_mip_size: u32,
    /// Whether the irradiance cube is written (the engine has a diffuse cube input).
    pub irradiance: bool,
    /// Whether sh.json is written by default.
    pub sh: bool,
    /// Whether the LUTs are written by default.
    pub lut: bool,
    /// The LUT files, when they are written.
    pub luts: &'static [LutSpec],
    /// The files written and their containers.
    pub files: FileSet,
    /// Pixel formats the engine cannot use everywhere, with the reason (a warning).
    pub format_warnings: &'static [(PixelFormat, &'static str)],
    /// How the engine reads the files, for the manifest.
    pub notes: &'static [&'static str],
}

/// DESIGN.md's conventions: right-handed, +Y up, lod = r·(M − 1), irradiance E/π.
pub const GENERIC: Target = Target {
    name: "generic",
    orientation: Orientation::GENERIC,
    pixel_format: PixelFormat::Rgba16f,
    zstd: None,
    roughness: MipRoughness::Linear,
    min_mip_size: DEFAULT_MIN_MIP_SIZE,
    irradiance: true,
    sh: true,
    lut: true,
    luts: BRDF_LUT_PNG,
    files: FileSet::Standard,
    format_warnings: &[],
    notes: &[
        "sample specular at lod = roughness * (levels - 1), seamless trilinear",
        "irradiance holds E / pi: multiply by the diffuse albedo",
    ],
};

/// Bevy 0.19 (`EnvironmentMapLight`, `Skybox`).
pub const BEVY: Target = Target {
    name: "bevy",
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
    files: FileSet::Standard,
    format_warnings: &[(
        PixelFormat::Rgba32f,
        "rgba32f is not filterable under WebGPU's limits: Bevy fails to bind it without the native FLOAT32_FILTERABLE feature; rgba16f or rgb9e5 render everywhere",
    )],
    notes: &[
        "EnvironmentMapLight { diffuse_map: irradiance.ktx2, specular_map: specular.ktx2, intensity }",
        "Bevy samples lod = perceptual_roughness * (mip_level_count - 1) after negating z",
        "radiance is the HDRI's: at Bevy's default exposure (EV100 9.7) use intensity = brightness = 2^9.7 * 1.2 = 998 to see it as is",
        "Bevy uses its own environment BRDF, no LUT and no SH",
    ],
};

/// three.js r187 (`MeshStandardMaterial`, `MeshPhysicalMaterial`, `scene.background`).
pub const THREE: Target = Target {
    name: "three",
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
    files: FileSet::Standard,
    format_warnings: &[(
        PixelFormat::Rgba32f,
        "rgba32f cubes are filtered only where WebGL has OES_texture_float_linear; rgba16f is filterable everywhere",
    )],
    notes: &[
        "load with js/splitsum-three.js: a cube with isPMREMTexture = true, used by MeshStandardMaterial as it is (no run-time PMREM)",
        "three samples lod = maxLod * r * (2 - r) (roughnessToMip), mips down to 8x8 as r187's PMREMGenerator (LOD_MIN = 3)",
        "the last level holds E / pi: three reads diffuse as PI * textureLod(envMap, N, maxLod)",
        "sh.json radiance_sh9 is the SphericalHarmonics3 of a THREE.LightProbe as is (world space, not mirrored)",
    ],
};

/// Filament (`IndirectLight`, `Skybox`; the web build's `Engine.createIblFromKtx1` and
/// `createSkyFromKtx1`), as cmgen deploys an environment for it.
pub const FILAMENT: Target = Target {
    name: "filament",
    // cmgen's faces: DESIGN.md's direction d is stored at (−z, y, x), a quarter turn about
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
    files: FileSet::FilamentKtx1,
    format_warnings: &[
        (
            PixelFormat::Rgba16f,
            "Filament's web loader (createIblFromKtx1) warns about any IBL format but R11F_G11F_B10F and RGB32F; the native engine loads rgba16f",
        ),
        (
            PixelFormat::Rgba32f,
            "Filament's web loader (createIblFromKtx1) warns about any IBL format but R11F_G11F_B10F and RGB32F; the native engine loads rgba32f",
        ),
    ],
    notes: &[
        "<stem>_ibl.ktx: IndirectLight reflections (web: engine.createIblFromKtx1), its key 'sh' the irradiance SH pre-scaled for Filament's shader (IndirectLight::Builder::irradiance(3, sh); web: ibl.shfloats)",
        "<stem>_skybox.ktx: Skybox environment (web: engine.createSkyFromKtx1)",
        "Filament samples lod = (levels - 1) * r * (2 - r) (perceptualRoughnessToLod); without SH it reads diffuse from the last level, which holds E / pi",
        "sh.txt: the same SH as cmgen --sh-shader writes them",
    ],
};

/// Babylon.js (`CubeTexture` of a `.env`, `scene.environmentTexture`, `PBRMaterial`).
pub const BABYLON: Target = Target {
    name: "babylon",
    // Babylon's world is left-handed: its own HDRCubeTexture of an equirect holds DESIGN.md's
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
    irradiance: false,
    sh: true,
    lut: false,
    luts: BRDF_LUT_PNG,
    files: FileSet::BabylonEnv,
    format_warnings: &[],
    notes: &[
        "<stem>.env: new CubeTexture(url, scene) (or CubeTexture.CreateFromPrefilteredData) as scene.environmentTexture; scene.createDefaultSkybox(texture) for the background",
        "Babylon samples lod = 0.8 * log2(size * (r^2 + 0.0005)); mip m holds GGX at alpha = 2^(m / 0.8) / size",
        "the irradiance is the header's spherical polynomial (E / pi, in the cube's frame)",
        "RGBD holds radiance up to 255: brighter texels (a sun) are clipped; scale with --exposure and scene.environmentIntensity to keep them",
    ],
};

/// The glTF Sample Viewer (npm `@khronosgroup/gltf-viewer` 1.1), with glTF-IBL-Sampler's
/// file set and its own chain layout.
pub const GLTF: Target = Target {
    name: "gltf",
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
    files: FileSet::GltfSampleViewer,
    format_warnings: &[],
    notes: &[
        "lambertian/diffuse.ktx2 (E / pi), ggx/specular.ktx2 and charlie/sheen.ktx2 as the environment's u_LambertianEnvSampler, u_GGXEnvSampler and u_CharlieEnvSampler, u_MipCount = the specular levels",
        "the viewer samples lod = roughness * (u_MipCount - 1), GGX and sheen alike, at u_EnvRotation * direction",
        "lut_ggx.png (height-correlated Smith scale and bias), lut_charlie.png (the Charlie albedo in B) and lut_sheen_E.png (the sheen albedo in R) at uv = (n.v, roughness)",
    ],
};

/// Every target, for the command line.
pub const TARGETS: [&Target; 6] = [&GENERIC, &BEVY, &THREE, &FILAMENT, &BABYLON, &GLTF];

impl Target {
    /// The target called `name`.
    pub fn by_name(name: &str) -> Option<&'static Target> {
        TARGETS.iter().copied().find(|t| t.name == name)
    }

    /// The warning for writing `format` for this target, if any.
    pub fn format_warning(&self, format: PixelFormat) -> Option<&'static str> {
        self.format_warnings
            .iter()
            .find(|(f, _)| *f == format)
            .map(|(_, w)| *w)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::math::cubemap::{cube_face_coords, cube_texel_direction};

    /// A cube whose texels hold their own direction.
    fn direction_cube(n: u32) -> Cubemap {
        let levels = (0..Cubemap::full_mip_count(n))
            .map(|m| {
                let s = (n >> m).max(1);
                let mut v = Vec::new();
                for f in 0..6 {
                    for j in 0..s {
                        for i in 0..s {
                            let d = cube_texel_direction(f, i as i32, j as i32, s);
                            v.push([d[0], d[1], d[2], 1.0]);
                        }
                    }
                }
                v
            })
            .collect();
        Cubemap { size: n, levels }
    }

    #[test]
    fn a_mirrored_cube_returns_the_light_from_d_where_the_engine_looks() {
        for orientation in TARGETS.map(|t| t.orientation) {
            let cube = orientation.apply(direction_cube(8));
            for m in 0..cube.levels.len() {
                let n = cube.level_size(m);
                for f in 0..6 {
                    for j in 0..n {
                        for i in 0..n {
                            // The engine looks world direction d up at lookup(d).
                            let d = cube_texel_direction(f, i as i32, j as i32, n);
                            let (face, s, t) = cube_face_coords(orientation.lookup(d));
                            let idx = |c: f32| ((c + 1.0) * 0.5 * n as f32).floor() as u32;
                            let got = cube.texel(m, face, idx(s).min(n - 1), idx(t).min(n - 1));
                            for k in 0..3 {
                                assert!(
                                    (got[k] - d[k]).abs() < 1e-6,
                                    "{} {m} {f} {i} {j}",
                                    orientation.description
                                );
                            }
                        }
                    }
                }
            }
        }
    }

    #[test]
    fn every_target_is_found_by_its_name() {
        for t in TARGETS {
            assert_eq!(Target::by_name(t.name), Some(t));
        }
        assert_eq!(Target::by_name("unity"), None);
    }

    #[test]
    fn a_mirror_twice_is_the_identity() {
        let cube = direction_cube(16);
        for axis in [0, 2] {
            assert_eq!(cube.mirrored(axis).mirrored(axis), cube);
        }
    }
}
