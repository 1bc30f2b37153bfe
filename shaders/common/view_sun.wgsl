// The lights taken out of the environment (`--sun split`) in the viewer: each a
// directional light shaded by `directional_light` (common/material.wgsl, the truth's
// BRDF, as the preview shades them), the sun (light 0) seen through its shadow map.
// The including shader declares `frame` (FrameParams), `sun_texels` (storage:
// (direction, solid angle), (radiance, light index) each; src/view/frame.rs,
// `sun_texel_table`) and `shadow_map` (r32float: distance along the sun's rays to the
// object). Mirror of src/view/shadow.rs (`visibility`) and `sun_texels_shade` in
// src/view/cpu.rs.

// The sun's visibility at surface point p with unit normal n, in [0, 1]: p moved off the
// surface along n, projected into the map, and the 2 x 2 texels around it, each lit (1)
// where the object there stands further along the rays, less the bias, else 0,
// interpolated bilinearly at the point (percentage-closer filtering).
fn sun_visibility(p: vec3<f32>, n: vec3<f32>) -> f32 {
    if (frame.sun.z == 0u) {
        return 1.0;
    }
    let half = frame.shadow[0].w;
    let d = p + n * frame.shadow[2].w - frame.shadow[0].xyz;
    let x = dot(d, frame.shadow[1].xyz) / half;
    let y = dot(d, frame.shadow[2].xyz) / half;
    if (abs(x) >= 1.0 || abs(y) >= 1.0) {
        return 1.0;
    }
    let z = dot(d, frame.shadow[3].xyz) - frame.shadow[1].w;
    let size = i32(frame.sun.w);
    // Texel-centre coordinates (texel i's centre at i), the four around, clamped.
    let u = (x + 1.0) * 0.5 * f32(size) - 0.5;
    let w = (1.0 - y) * 0.5 * f32(size) - 0.5;
    let u0 = floor(u);
    let w0 = floor(w);
    let fx = u - u0;
    let fy = w - w0;
    let i0 = clamp(i32(u0), 0, size - 1);
    let i1 = clamp(i32(u0) + 1, 0, size - 1);
    let j0 = clamp(i32(w0), 0, size - 1);
    let j1 = clamp(i32(w0) + 1, 0, size - 1);
    let l00 = select(0.0, 1.0, textureLoad(shadow_map, vec2<i32>(i0, j0), 0).r >= z);
    let l10 = select(0.0, 1.0, textureLoad(shadow_map, vec2<i32>(i1, j0), 0).r >= z);
    let l01 = select(0.0, 1.0, textureLoad(shadow_map, vec2<i32>(i0, j1), 0).r >= z);
    let l11 = select(0.0, 1.0, textureLoad(shadow_map, vec2<i32>(i1, j1), 0).r >= z);
    return (l00 * (1.0 - fx) + l10 * fx) * (1.0 - fy) + (l01 * (1.0 - fx) + l11 * fx) * fy;
}

// The entries `first` .. first + count of `sun_texels` shading the surface a pixel sees,
// light 0's through the sun's visibility.
fn sun_texels_shade(px: PixelView, first: u32, count: u32) -> vec3<f32> {
    var sum = vec3<f32>(0.0);
    // The sun's visibility, looked up in a loop that runs once when there are entries and
    // not at all when there are none: a software rasteriser (lavapipe) runs both sides of
    // an `if` on every lane, but skips a loop no lane enters, so a frame without lights
    // does not pay for the map's four loads (with `count` a constant, as in the forward
    // pass, the compiler removes the loop).
    var visibility = 1.0;
    for (var once = 0u; once < min(count, 1u); once++) {
        visibility = sun_visibility(px.s.p, px.s.n);
    }
    let alpha = alpha_from_roughness(px.m.roughness);
    for (var i = first; i < first + count; i++) {
        let t = sun_texels[2u * i];
        let r = sun_texels[2u * i + 1u];
        let s = directional_light(px.s.n, px.v, px.n_dot_v, alpha, px.m.f0, px.m.metallic, t.xyz, r.rgb * t.w, generic_light_brdf());
        var c = s.spec + s.diff * px.m.albedo;
        if (r.w < 0.5) {
            c *= visibility;
        }
        sum += c;
    }
    return sum;
}
