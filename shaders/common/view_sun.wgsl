// The lights taken out of the environment (`--sun split`) in the viewer: each a
// directional light shaded by `directional_light` (common/material.wgsl, the truth's
// BRDF, as the preview shades them), or an area light (a studio's lamp) shaded from the
// LTC table (common/ltc.wgsl, as the preview shades it), the sun (light 0) seen through its
// shadow map. The including shader declares `frame` (FrameParams), `sun_texels` (storage,
// src/view/frame.rs, `sun_texel_table`: per light split out (direction, 1), (E⊥, light
// index), (0, 0, LTC table entry, LTC table size), a zero entry, or for an area light (centre, solid angle), (radiance, light
// index), (first corner entry, 4, LTC table entry, LTC table size), (vector form factor,
// 0); then the truth's texels, (direction, solid angle), (radiance, light index) each;
// then the area lights' corners and the LTC table, two entries a cell)
// and `shadow_map` (r32float array: distance along each light's rays to the object).
// Mirror of src/view/shadow.rs (`visibility`) and `split_lights_shade`,
// `truth_texels_shade` in src/view/cpu.rs.

// Texels per side of the soft shadow's blocker search and of its filter (src/view/shadow.rs).
const BLOCKER_TAPS: u32 = 3u;
const FILTER_TAPS: u32 = 4u;

// Map `layer`'s depth at texel (i, j), clamped to the map.
fn shadow_depth(i: i32, j: i32, size: i32, layer: u32) -> f32 {
    return textureLoad(shadow_map, vec2<i32>(clamp(i, 0, size - 1), clamp(j, 0, size - 1)), layer, 0).r;
}

// The texel nearest texel-centre coordinate c.
fn nearest_texel(c: f32) -> i32 {
    return i32(floor(c + 0.5));
}

// Tap k of a taps x taps grid across +-radius texels about (u, w).
fn shadow_grid(u: f32, w: f32, taps: u32, radius: f32, k: u32) -> vec2<i32> {
    let step = 2.0 * radius / f32(taps);
    return vec2<i32>(nearest_texel(u - radius + (f32(k % taps) + 0.5) * step), nearest_texel(w - radius + (f32(k / taps) + 0.5) * step));
}

// An area light's visibility at texel-centre coordinates (u, w) of map `layer` of a
// receiver at depth z (less the bias), `spread` its penumbra's growth in texels per unit
// of depth: percentage-closer soft shadows (src/view/shadow.rs says how).
fn soft_visibility(u: f32, w: f32, z: f32, spread: f32, size: i32, layer: u32) -> f32 {
    let search = spread * z;
    var sum = 0.0;
    var count = 0.0;
    for (var k = 0u; k < BLOCKER_TAPS * BLOCKER_TAPS; k++) {
        let t = shadow_grid(u, w, BLOCKER_TAPS, search, k);
        let d = shadow_depth(t.x, t.y, size, layer);
        if (d < z) {
            sum += d;
            count += 1.0;
        }
    }
    if (count == 0.0) {
        return 1.0;
    }
    let radius = max(spread * (z - sum / count), 1.0);
    var lit = 0.0;
    for (var k = 0u; k < FILTER_TAPS * FILTER_TAPS; k++) {
        let t = shadow_grid(u, w, FILTER_TAPS, radius, k);
        lit += select(0.0, 1.0, shadow_depth(t.x, t.y, size, layer) >= z);
    }
    return lit / f32(FILTER_TAPS * FILTER_TAPS);
}

// Light k's visibility at surface point p with unit normal n, in [0, 1], from its map (block
// `frame.shadow[4k ..]`, layer k): p moved off the surface along n, projected into the map;
// for a directional light the 2 x 2 texels around it, each lit (1) where the object there
// stands further along the rays, less the bias, else 0, interpolated bilinearly at the
// point (percentage-closer filtering); for an area light (the block's spread above 0) its
// soft shadow.
fn light_visibility(p: vec3<f32>, n: vec3<f32>, k: u32) -> f32 {
    let b = 4u * k;
    let half = frame.shadow[b].w;
    let d = p + n * frame.shadow[b + 2u].w - frame.shadow[b].xyz;
    let x = dot(d, frame.shadow[b + 1u].xyz) / half;
    let y = dot(d, frame.shadow[b + 2u].xyz) / half;
    if (abs(x) >= 1.0 || abs(y) >= 1.0) {
        return 1.0;
    }
    let z = dot(d, frame.shadow[b + 3u].xyz) - frame.shadow[b + 1u].w;
    let size = i32(frame.sun.w);
    // Texel-centre coordinates (texel i's centre at i).
    let u = (x + 1.0) * 0.5 * f32(size) - 0.5;
    let w = (1.0 - y) * 0.5 * f32(size) - 0.5;
    let u0 = floor(u);
    let w0 = floor(w);
    let fx = u - u0;
    let fy = w - w0;
    let i = i32(u0);
    let j = i32(w0);
    let l00 = select(0.0, 1.0, shadow_depth(i, j, size, k) >= z);
    let l10 = select(0.0, 1.0, shadow_depth(i + 1, j, size, k) >= z);
    let l01 = select(0.0, 1.0, shadow_depth(i, j + 1, size, k) >= z);
    let l11 = select(0.0, 1.0, shadow_depth(i + 1, j + 1, size, k) >= z);
    var visibility = (l00 * (1.0 - fx) + l10 * fx) * (1.0 - fy) + (l01 * (1.0 - fx) + l11 * fx) * fy;
    // The soft shadow in a loop that runs once or not at all: lavapipe runs both sides of
    // an `if`, and a sun's frame should not pay for the area light's 25 loads.
    let spread = frame.shadow[b + 3u].w;
    for (var once = 0u; once < min(select(0u, 1u, spread > 0.0), AREA_LIGHTS); once++) {
        visibility = soft_visibility(u, w, z, spread / (2.0 * half / f32(size)), size, k);
    }
    return visibility;
}

// Entries of a split-out light's record in `sun_texels`.
const SPLIT_RECORD: u32 = 4u;

// 1 when an area light is split out (its LTC shading and the soft shadow are compiled in),
// else 0: a constant of the pipeline (src/view/gpu, `area_lights`), since lavapipe's code
// for a light's LTC, run or not, costs a frame of directional lights twice its time.
override AREA_LIGHTS: u32 = 0u;

// Each light's visibility by light: from its map for the first `count` lights that have one
// (`frame.sun.z`), 1 for the rest. The loop runs not at all when `count` is 0: a software
// rasteriser (lavapipe) runs both sides of an `if` on every lane, but skips a loop no lane
// enters, so a frame without lights does not pay for the maps' loads (with `count` a
// constant, as in the forward pass, the compiler removes the loop).
fn lights_visibility(px: PixelView, count: u32) -> vec4<f32> {
    var visibility = vec4<f32>(1.0);
    for (var k = 0u; k < min(count, frame.sun.z); k++) {
        visibility[k] = light_visibility(px.s.p, px.s.n, k);
    }
    return visibility;
}

// Light `index`'s (a record's w) share of `visibility`: 1 past the maps.
fn shadowed(visibility: vec4<f32>, index: f32) -> f32 {
    let k = u32(index);
    return select(1.0, visibility[min(k, MAX_SHADOW_MAPS - 1u)], k < MAX_SHADOW_MAPS);
}

// The LTC table's cell at (n.v, roughness), bilinear between cells, clamped (mirror of
// `LtcTable::lookup`): cell (i, j) at entries base + 2 (j size + i), + 1.
fn ltc_table_lookup(base: u32, size: u32, n_dot_v: f32, roughness: f32) -> LtcCell {
    let last = f32(size - 1u);
    let u = clamp(roughness, 0.0, 1.0) * last;
    let w = sqrt(1.0 - clamp(n_dot_v, 0.0, 1.0)) * last;
    let i0 = min(floor(u), last - 1.0);
    let j0 = min(floor(w), last - 1.0);
    let fu = u - i0;
    let fw = w - j0;
    var inverse = vec4<f32>(0.0);
    var magnitude = vec2<f32>(0.0);
    for (var k = 0u; k < 4u; k++) {
        let di = k & 1u;
        let dj = k >> 1u;
        let weight = select(1.0 - fu, fu, di == 1u) * select(1.0 - fw, fw, dj == 1u);
        let e = base + 2u * ((u32(j0) + dj) * size + u32(i0) + di);
        inverse += weight * sun_texels[e];
        magnitude += weight * sun_texels[e + 1u].xy;
    }
    var c: LtcCell;
    c.inverse = inverse;
    c.norm = magnitude.x;
    c.fresnel = magnitude.y;
    return c;
}

// The area lights' corners, for common/ltc.wgsl.
fn ltc_vertex(i: u32) -> vec3<f32> {
    return sun_texels[i].xyz;
}

// The shaded point of a pixel as its area lights share it, from the table whose first
// light's record has third entry `a` (every area light reads the one table).
fn area_light_point(px: PixelView, a: vec4<f32>) -> LtcPoint {
    let cell = ltc_table_lookup(u32(a.z), u32(a.w), px.n_dot_v, px.m.roughness);
    return ltc_point(cell, px.s.n, px.v, px.m.f0, px.m.roughness);
}

// An area light whose record's entries are `t`, `r`, `a`, `f` (its centre and solid
// angle, radiance, corners and table, vector form factor) shading the surface a pixel sees
// at `q` (specular plus diffuse times the albedo).
fn area_light_shade(px: PixelView, q: LtcPoint, t: vec4<f32>, r: vec4<f32>, a: vec4<f32>, f: vec4<f32>) -> vec3<f32> {
    let s = ltc_shade_quad(q, px.s.n, px.v, px.n_dot_v, px.m.f0, px.m.metallic, u32(a.x), t.xyz, t.w, f.xyz, r.rgb, generic_light_brdf());
    return s.spec + s.diff * px.m.albedo;
}

// The `count` lights split out shading the surface a pixel sees, each through its
// visibility: a directional light of E⊥, or an area light from the LTC table. Each light
// takes one of the two paths in a loop that runs once or not at all (as in
// `lights_visibility`), so a frame of directional lights does not pay for the LTC.
fn split_lights_shade(px: PixelView, count: u32) -> vec3<f32> {
    let visibility = lights_visibility(px, count);
    let alpha = alpha_from_roughness(px.m.roughness);
    // The point's LTC, once for every area light, in a loop that runs once or not at all;
    // every record's third entry names the table, light 0's too.
    var q: LtcPoint;
    for (var k = 0u; k < min(min(count, 1u), AREA_LIGHTS); k++) {
        q = area_light_point(px, sun_texels[2u]);
    }
    var sum = vec3<f32>(0.0);
    for (var i = 0u; i < count; i++) {
        let t = sun_texels[SPLIT_RECORD * i];
        let r = sun_texels[SPLIT_RECORD * i + 1u];
        let a = sun_texels[SPLIT_RECORD * i + 2u];
        let area = min(min(u32(a.y), 1u), AREA_LIGHTS);
        var c = vec3<f32>(0.0);
        for (var k = 0u; k < 1u - area; k++) {
            let s = directional_light(px.s.n, px.v, px.n_dot_v, alpha, px.m.f0, px.m.metallic, t.xyz, r.rgb * t.w, generic_light_brdf());
            c = s.spec + s.diff * px.m.albedo;
        }
        for (var k = 0u; k < area; k++) {
            c = area_light_shade(px, q, t, r, a, sun_texels[SPLIT_RECORD * i + 3u]);
        }
        sum += c * shadowed(visibility, r.w);
    }
    return sum;
}

// The truth's `count` texels of the lights' regions, from entry `first` on (two entries
// each), shading the surface a pixel sees, each through its light's visibility.
fn truth_texels_shade(px: PixelView, first: u32, count: u32) -> vec3<f32> {
    // The lights' visibilities, when there is a texel to shade (the floor's from its grids,
    // common/view_floor_shadow.wgsl).
    let visibility = surface_visibility(px, min(count, 1u) * frame.sun.x);
    let alpha = alpha_from_roughness(px.m.roughness);
    var sum = vec3<f32>(0.0);
    for (var i = 0u; i < count; i++) {
        let t = sun_texels[first + 2u * i];
        let r = sun_texels[first + 2u * i + 1u];
        let s = directional_light(px.s.n, px.v, px.n_dot_v, alpha, px.m.f0, px.m.metallic, t.xyz, r.rgb * t.w, generic_light_brdf());
        var c = s.spec + s.diff * px.m.albedo;
        sum += c * shadowed(visibility, r.w);
    }
    return sum;
}
