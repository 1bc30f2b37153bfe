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

/// Where a target's cube texel for world direction d lies.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Orientation {
    /// At d: `textureSample(cube, s, d)` returns the light arriving from d (DESIGN.md).
    Generic,
    /// At (−x, y, z): the engine mirrors x before sampling (three.js: `flipEnvMap`, the
    /// (−1, 1, 1) matrix WebGLMaterials and WebGLBackground premultiply for cube textures
    /// that are not render targets).
    MirrorX,
    /// At (x, y, −z): the engine mirrors z before sampling (Bevy:
    /// `sample_dir.z = -sample_dir.z` in bevy_pbr's environment_map.wgsl, the skybox's
    /// `ray_direction * vec3(1.0, 1.0, -1.0)`).
    MirrorZ,
}

impl Orientation {
    /// The world axis the engine negates, if any.
    pub fn mirror_axis(self) -> Option<usize> {
        match self {
            Orientation::Generic => None,
            Orientation::MirrorX => Some(0),
            Orientation::MirrorZ => Some(2),
        }
    }

    /// The texture coordinate direction at which the engine reads world direction `d`.
    pub fn lookup(self, d: [f32; 3]) -> [f32; 3] {
        let mut d = d;
        if let Some(axis) = self.mirror_axis() {
            d[axis] = -d[axis];
        }
        d
    }

    /// `cube` (in generic orientation) stored for this orientation: every level's texels
    /// permuted so that the engine's lookup of d returns the light from d.
    pub fn apply(self, cube: Cubemap) -> Cubemap {
        match self.mirror_axis() {
            None => cube,
            Some(axis) => cube.mirrored(axis),
        }
    }

    /// The orientation as written in manifests.
    pub fn description(self) -> &'static str {
        match self {
            Orientation::Generic => "generic: texel at d holds the light arriving from d",
            Orientation::MirrorX => "mirror x: texel at (-x, y, z) holds the light from (x, y, z)",
            Orientation::MirrorZ => "mirror z: texel at (x, y, -z) holds the light from (x, y, z)",
        }
    }
}

/// The LUT file a target writes when a LUT is asked for.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum LutFile {
    /// `brdf_lut.png`, 16-bit RGB (B = 0).
    Png,
    /// `brdf_lut.ktx2`, R16G16_SFLOAT: browsers decode 16-bit PNGs to 8 bits and three's
    /// TextureLoader flips PNGs.
    Ktx2,
}

impl LutFile {
    /// File name in the bake folder.
    pub fn file_name(self) -> &'static str {
        match self {
            LutFile::Png => "brdf_lut.png",
            LutFile::Ktx2 => "brdf_lut.ktx2",
        }
    }

    /// Format as written in manifests.
    pub fn format(self) -> &'static str {
        match self {
            LutFile::Png => "png rgb16",
            LutFile::Ktx2 => "ktx2 rg16f",
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
    /// Whether a LUT is written by default.
    pub lut: bool,
    /// The LUT file, when one is written.
    pub lut_file: LutFile,
    /// Pixel formats the engine cannot use everywhere, with the reason (a warning).
    pub format_warnings: &'static [(PixelFormat, &'static str)],
    /// How the engine reads the files, for the manifest.
    pub notes: &'static [&'static str],
}

/// DESIGN.md's conventions: right-handed, +Y up, lod = r·(M − 1), irradiance E/π.
pub const GENERIC: Target = Target {
    name: "generic",
    orientation: Orientation::Generic,
    pixel_format: PixelFormat::Rgba16f,
    zstd: None,
    roughness: MipRoughness::Linear,
    min_mip_size: DEFAULT_MIN_MIP_SIZE,
    irradiance: true,
    sh: true,
    lut: true,
    lut_file: LutFile::Png,
    format_warnings: &[],
    notes: &[
        "sample specular at lod = roughness * (levels - 1), seamless trilinear",
        "irradiance holds E / pi: multiply by the diffuse albedo",
    ],
};

/// Bevy 0.19 (`EnvironmentMapLight`, `Skybox`).
pub const BEVY: Target = Target {
    name: "bevy",
    orientation: Orientation::MirrorZ,
    pixel_format: PixelFormat::Rgb9e5,
    zstd: Some(10),
    roughness: MipRoughness::Linear,
    min_mip_size: DEFAULT_MIN_MIP_SIZE,
    irradiance: true,
    sh: false,
    lut: false,
    lut_file: LutFile::Png,
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
    orientation: Orientation::MirrorX,
    pixel_format: PixelFormat::Rgba16f,
    zstd: Some(10),
    roughness: MipRoughness::Quadratic,
    min_mip_size: 8,
    irradiance: false,
    sh: true,
    lut: false,
    lut_file: LutFile::Ktx2,
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

/// Every target, for the command line.
pub const TARGETS: [&Target; 3] = [&GENERIC, &BEVY, &THREE];

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
        for orientation in [Orientation::MirrorX, Orientation::MirrorZ] {
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
                                    "{orientation:?} {m} {f} {i} {j}"
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
