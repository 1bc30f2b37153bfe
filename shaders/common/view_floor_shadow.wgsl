// The lights' shadows on the floor from a grid laid on the floor per light (src/view/
// floor_shadow.rs says why and how), and a surface's visibilities by what it is. Mirror of
// `FloorShadows::visibility` in src/view/floor_shadow.rs and `lights_visibility` in
// src/view/cpu.rs. The including shader declares `floor_shadow` (storage, f32: a header
// (nodes along, nodes across, lights, 0), eight parameters a light from entry 4: (a.x,
// a.z, sigma0, sigma1), (T, L, c.x, c.z); then light k's node (i, j) at
// FLOOR_SHADOW_HEADER + (k across + j) along + i).

// A light's parameters, and the entries before the grids: 4, then the parameters of
// each light (the same names in floor_shadow.rs).
const FLOOR_SHADOW_PARAMS: u32 = 8u;
const FLOOR_SHADOW_HEADER: u32 = 4u + FLOOR_SHADOW_PARAMS * MAX_SHADOW_MAPS;

// Light k's visibility at floor point p, bilinear between its grid's nodes, 1 outside
// the grid.
fn floor_visibility(p: vec3<f32>, k: u32) -> f32 {
    let along = floor_shadow[0];
    let across = floor_shadow[1];
    let q = 4u + FLOOR_SHADOW_PARAMS * k;
    let dx = p.x - floor_shadow[q + 6u];
    let dz = p.z - floor_shadow[q + 7u];
    let ax = floor_shadow[q];
    let az = floor_shadow[q + 1u];
    let s = dx * ax + dz * az;
    let t = -dx * az + dz * ax;
    let sigma = sign(s) * log(1.0 + abs(s) / floor_shadow[q + 5u]);
    let x = (sigma - floor_shadow[q + 2u]) / (floor_shadow[q + 3u] - floor_shadow[q + 2u]) * (along - 1.0);
    let y = (t + floor_shadow[q + 4u]) / (2.0 * floor_shadow[q + 4u]) * (across - 1.0);
    let inside = x >= 0.0 && x <= along - 1.0 && y >= 0.0 && y <= across - 1.0;
    let i = clamp(min(floor(x), along - 2.0), 0.0, along - 2.0);
    let j = clamp(min(floor(y), across - 2.0), 0.0, across - 2.0);
    let fx = x - i;
    let fy = y - j;
    let w = u32(along);
    let base = FLOOR_SHADOW_HEADER + k * u32(along * across) + u32(j) * w + u32(i);
    let a = mix(floor_shadow[base], floor_shadow[base + 1u], fx);
    let b = mix(floor_shadow[base + w], floor_shadow[base + w + 1u], fx);
    return select(1.0, mix(a, b, fy), inside);
}

// The floor's visibility by light: from its grid for the first `count` lights that have a
// map (`frame.sun.z`), 1 for the rest.
fn floor_lights_visibility(px: PixelView, count: u32) -> vec4<f32> {
    var visibility = vec4<f32>(1.0);
    for (var k = 0u; k < min(count, frame.sun.z); k++) {
        visibility[k] = floor_visibility(px.s.p, k);
    }
    return visibility;
}

// A surface's visibility by light: the floor's from its grids, the object's from the maps.
fn surface_visibility(px: PixelView, count: u32) -> vec4<f32> {
    if (px.s.id == 2u) {
        return floor_lights_visibility(px, count);
    }
    return lights_visibility(px, count);
}
