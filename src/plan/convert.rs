//! The HDRI → cube conversion's parameters, shared by both backends: which level of the
//! equirect pyramid a cube of a given size is integrated from, and the rotation.

use crate::environment::pyramid_level_count;
use crate::math::cubemap::cube_texel_solid_angle;

/// The converted level's rows are at most this fraction of the smallest target texel
/// (a face corner's), so a lamp's energy is placed to 1/64 of a texel. The cost of the
/// integral grows with the cube's perimeter times the source's resolution, so a small cube
/// reads a fine level cheaply: a 1k input is read at full resolution for cubes of 4² and up.
pub const SOURCE_ROWS_PER_TEXEL: f32 = 32.0;

/// Largest source level the conversion reads (texels): a 4096×2048 level. Inputs larger
/// than that are reduced on load (exact area filter) whatever the cube size, which bounds
/// memory; at the default 256² the corner texels still span about two such rows.
pub const MAX_SOURCE_TEXELS: u64 = 1 << 23;

/// Parameters shared by both backends.
#[derive(Clone, Copy, Debug)]
pub struct EquirectToCubeParams {
    /// Edge of the output cube face.
    pub face_size: u32,
    /// The equirect pyramid level the conversion reads (see [`source_level`]).
    pub base_level: u32,
    /// cos and sin of the environment's rotation about +Y.
    pub rotation: [f32; 2],
}

impl EquirectToCubeParams {
    /// Parameters for a `face_size` cube from a `source_width`×`source_height` equirect,
    /// rotated by `rotate_degrees`.
    pub fn new(face_size: u32, source_width: u32, source_height: u32, rotate_degrees: f32) -> Self {
        let r = rotate_degrees.to_radians();
        EquirectToCubeParams {
            face_size,
            base_level: source_level(face_size, source_width, source_height),
            rotation: [r.cos(), r.sin()],
        }
    }
}

/// The pyramid level a `face_size` cube is integrated from: the coarsest whose rows are
/// at most 1/[`SOURCE_ROWS_PER_TEXEL`] of the smallest target texel's angular size, and
/// no finer than [`MAX_SOURCE_TEXELS`] allows. Levels halve with floor, as the pyramid's.
pub fn source_level(face_size: u32, width: u32, height: u32) -> u32 {
    let texel = cube_texel_solid_angle(0, 0, face_size.max(1)).sqrt();
    let levels = pyramid_level_count(height);
    let rows = |l: u32| (height >> l).max(1);
    let texels = |l: u32| (width >> l).max(1) as u64 * rows(l) as u64;
    let mut l = 0;
    while l + 1 < levels
        && std::f32::consts::PI / rows(l + 1) as f32 <= texel / SOURCE_ROWS_PER_TEXEL
    {
        l += 1;
    }
    while l + 1 < levels && texels(l) > MAX_SOURCE_TEXELS {
        l += 1;
    }
    l
}
