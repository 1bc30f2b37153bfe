// Seamless bilinear and trilinear lookups of a cube mip chain stored as a 2D array texture.
// Mirror of src/environment/sample.rs (same function names). Mip sizes come from the
// level-0 size, not textureDimensions (lavapipe answers it wrongly when the level differs
// across lanes). The texel fetch, `fetch_cube_texel(src, size0, m, face, x, y)` for x, y
// from -1 to n, comes from the file included before this one: cube_fetch.wgsl for a plain
// chain (layers = faces, levels = mips), cube_fetch_bordered.wgsl for a bordered one.

// Bilinear lookup of mip m at face coordinates (s, t) in [-1, 1]^2 of `face`.
fn sample_face_bilinear(src: texture_2d_array<f32>, size0: u32, m: u32, face: u32, s: f32, t: f32) -> vec3<f32> {
    let n = f32(max(size0 >> m, 1u));
    let x = (s + 1.0) * 0.5 * n - 0.5;
    let y = (t + 1.0) * 0.5 * n - 0.5;
    let x0 = floor(x);
    let y0 = floor(y);
    let fx = x - x0;
    let fy = y - y0;
    let xi = i32(x0);
    let yi = i32(y0);
    return fetch_cube_texel(src, size0, m, face, xi, yi) * ((1.0 - fx) * (1.0 - fy))
         + fetch_cube_texel(src, size0, m, face, xi + 1, yi) * (fx * (1.0 - fy))
         + fetch_cube_texel(src, size0, m, face, xi, yi + 1) * ((1.0 - fx) * fy)
         + fetch_cube_texel(src, size0, m, face, xi + 1, yi + 1) * (fx * fy);
}

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
