// The texel fetch of a plain cube chain for cube_sample.wgsl: a 2D array texture whose
// layers are the faces and whose mips are the levels. Mirror of `fetch_cube_texel` in
// src/environment/sample.rs.

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
