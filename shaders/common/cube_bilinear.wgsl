// The seamless bilinear lookup of one level of a cube chain, four texels fetched and
// weighted here (exact in f32, as its CPU mirror `sample_face_bilinear` in
// src/environment/sample.rs). The texel fetch, `fetch_cube_texel(src, size0, m, face, x,
// y)` for x, y from -1 to n, comes from the file included before this one (cube_fetch.wgsl
// or cube_fetch_bordered.wgsl).

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
