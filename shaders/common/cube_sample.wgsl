// Seamless trilinear lookups of a cube mip chain stored as a 2D array texture. Mirror of
// src/environment/sample.rs (same function names). Mip sizes come from the level-0 size,
// not textureDimensions (lavapipe answers it wrongly when the level differs across
// lanes). The bilinear lookup of one level, `sample_face_bilinear(src, size0, m, face, s,
// t)`, comes from the files included before this one: cube_bilinear.wgsl over a texel
// fetch (cube_fetch.wgsl for a plain chain, layers = faces and levels = mips;
// cube_fetch_bordered.wgsl for a bordered one), or cube_filter_bordered.wgsl, the
// sampler's filter on a bordered chain.

// Trilinear lookup at fractional lod (clamped to the chain); face coordinates are found
// once, and an integral lod reads one level only.
fn sample_cube_lod(src: texture_2d_array<f32>, size0: u32, levels: u32, d: vec3<f32>, lod_in: f32) -> vec3<f32> {
    let last = f32(levels - 1u);
    let lod = clamp(lod_in, 0.0, last);
    let l0 = floor(lod);
    let f = lod - l0;
    let c = cube_face_coords(d);
    let face = u32(c.x);
    let a = sample_face_bilinear(src, size0, u32(l0), face, c.y, c.z);
    if (f == 0.0) {
        return a;
    }
    let b = sample_face_bilinear(src, size0, u32(min(l0 + 1.0, last)), face, c.y, c.z);
    return a + f * (b - a);
}
