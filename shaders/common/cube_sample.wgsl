// Seamless bilinear and trilinear lookups of a cube mip chain stored as a 2D array texture
// (layers = faces). Mirror of src/cpu/cube_sample.rs (same function names). Mip sizes
// come from the level-0 size, not textureDimensions (lavapipe answers it wrongly when the
// level differs across lanes).

// Texel (x, y) of `face` at mip m; one texel off the face is fetched from the neighbour.
fn fetch_cube_texel(src: texture_2d_array<f32>, size0: u32, m: u32, face: u32, x: i32, y: i32) -> vec3<f32> {
    let n = i32(max(size0 >> m, 1u));
    var f = face;
    var xi = x;
    var yi = y;
    if (x < 0 || y < 0 || x >= n || y >= n) {
        let c = cube_face_coords(cube_texel_direction(face, x, y, u32(n)));
        f = u32(c.x);
        xi = clamp(i32(floor((c.y + 1.0) * 0.5 * f32(n))), 0, n - 1);
        yi = clamp(i32(floor((c.z + 1.0) * 0.5 * f32(n))), 0, n - 1);
    }
    return textureLoad(src, vec2<i32>(xi, yi), i32(f), i32(m)).rgb;
}

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
