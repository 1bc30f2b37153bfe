// The lights taken out of the environment (`--sun split`) in the viewer: each a
// directional light shaded by `directional_light` (common/material.wgsl, the truth's
// BRDF, as the preview shades them), the sun (light 0) seen through its shadow map.
// The including shader declares `frame` (FrameParams), `sun_texels` (storage:
// (direction, solid angle), (radiance, light index) each; src/view/frame.rs,
// `sun_texel_table`) and `shadow_map` (r32float: distance along the sun's rays to the
// object). Mirror of src/view/shadow.rs (`visibility`) and `sun_texels_shade` in
// src/view/cpu.rs.

// The sun's visibility at surface point p with unit normal n, in [0, 1]: p moved off the
// surface along n, projected into the map, and the lit fraction of the 3 x 3 texels
// around it (lit: the object there stands further along the rays, less the bias).
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
    let cx = i32(floor((x + 1.0) * 0.5 * f32(size)));
    let cy = i32(floor((1.0 - y) * 0.5 * f32(size)));
    var lit = 0.0;
    for (var dy = -1; dy <= 1; dy++) {
        for (var dx = -1; dx <= 1; dx++) {
            let t = vec2<i32>(clamp(cx + dx, 0, size - 1), clamp(cy + dy, 0, size - 1));
            if (textureLoad(shadow_map, t, 0).r >= z) {
                lit += 1.0;
            }
        }
    }
    return lit / 9.0;
}

// The entries `first` .. first + count of `sun_texels` shading the surface a pixel sees,
// light 0's through the sun's visibility.
fn sun_texels_shade(px: PixelView, first: u32, count: u32) -> vec3<f32> {
    var sum = vec3<f32>(0.0);
    // The sun's visibility, looked up in a loop that runs once when there are entries and
    // not at all when there are none: a software rasteriser (lavapipe) runs both sides of
    // an `if` on every lane, but skips a loop no lane enters, so a frame without lights
    // pays nothing for the map's nine loads.
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
