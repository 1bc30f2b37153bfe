// The texel fetch of a bordered cube chain for cube_sample.wgsl: level m's six faces are
// layers 6m to 6m + 5 of a 2D array texture (one mip), each face's (n + 2)^2 texels at the
// top left, its one-texel border holding what cube_fetch.wgsl's fetch returns there (the
// neighbouring faces' texels). The same texels as the plain chain's fetch, without its
// edge path. Mirror of `BorderedCube` in src/environment/sample.rs, which fills the borders.

fn fetch_cube_texel(src: texture_2d_array<f32>, size0: u32, m: u32, face: u32, x: i32, y: i32) -> vec3<f32> {
    return textureLoad(src, vec2<i32>(x + 1, y + 1), i32(6u * m + face), 0).rgb;
}
