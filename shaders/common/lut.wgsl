// Reading a split-sum LUT (scale A, bias B) and the light BRDF's multiple-scattering
// compensation it gives. CPU mirrors: cpu::preview_split_sum::sample_lut and
// plan::shading's compensation (cpu::preview_split_sum::specular_compensation).
//
// The including kernel declares the LUT as a module global: lut: texture_2d<f32>.

// Bilinear lookup of a width x height LUT at uv = (n.v, r), clamp-to-edge, texel centres
// at (i + 0.5) / W. The texture holds each texel's (A, B) in .xy and its right
// neighbour's (clamped to the last column) in .zw (gpu::texture::upload_lut_pairs), so the
// four taps a, b, c, d of the CPU twin are two loads.
fn lut_bilinear(w: u32, h: u32, n_dot_v: f32, roughness: f32) -> vec2<f32> {
    let x = clamp(n_dot_v * f32(w) - 0.5, 0.0, f32(w - 1u));
    let y = clamp(roughness * f32(h) - 0.5, 0.0, f32(h - 1u));
    let x0 = floor(x);
    let y0 = floor(y);
    let fx = x - x0;
    let fy = y - y0;
    let i0 = u32(x0);
    let j0 = u32(y0);
    let j1 = min(j0 + 1u, h - 1u);
    let row0 = textureLoad(lut, vec2<u32>(i0, j0), 0);
    let row1 = textureLoad(lut, vec2<u32>(i0, j1), 0);
    let a = row0.xy;
    let b = row0.zw;
    let c = row1.xy;
    let d = row1.zw;
    return (a * (1.0 - fx) + b * fx) * (1.0 - fy) + (c * (1.0 - fx) + d * fx) * fy;
}

// The factor 1 + F0 (1/Ess - 1), Ess = A + B, by which a compensated light BRDF scales
// its specular (plan::shading::LightBrdf::compensated; Turquin 2019).
fn specular_compensation(ab: vec2<f32>, f0: vec3<f32>) -> vec3<f32> {
    return vec3<f32>(1.0) + f0 * (1.0 / (ab.x + ab.y) - 1.0);
}
