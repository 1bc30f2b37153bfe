// The seamless bilinear lookup of one level of a bordered cube chain (the layout of
// cube_fetch_bordered.wgsl: level m's faces are layers 6m to 6m + 5, each face's n x n
// texels at (1, 1) inside its one-texel border) by the sampler's filter: one
// textureSampleLevel where cube_bilinear.wgsl fetches four texels, the same four texels
// (the border makes the face's edge seamless) at the same weights up to the hardware's
// sub-texel precision (exact floats on lavapipe; 8 bits on most GPUs, the Vulkan
// specification's `subTexelPrecisionBits`). The forward pass reads its chains through it
// (src/view/gpu/mod.rs says why); the texture must be filterable (rgba32float:
// wgpu's FLOAT32_FILTERABLE). The including shader declares `cube_linear`: a sampler with
// linear magnification and minification, clamped to the edge.

// Bilinear lookup of mip m at face coordinates (s, t) in [-1, 1]^2 of `face`: texel-centre
// coordinate x = (s + 1) n / 2 - 0.5 of the face is x + 1 of the layer, whose texels are
// w = size0 + 2 wide, so the normalised coordinate is (x + 1.5) / w.
fn sample_face_bilinear(src: texture_2d_array<f32>, size0: u32, m: u32, face: u32, s: f32, t: f32) -> vec3<f32> {
    let n = f32(max(size0 >> m, 1u));
    let w = f32(size0 + 2u);
    let uv = ((vec2<f32>(s, t) + 1.0) * (0.5 * n) + 1.0) / w;
    return textureSampleLevel(src, cube_linear, uv, i32(6u * m + face), 0.0).rgb;
}
