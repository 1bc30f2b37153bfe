// The lights' shadows on the floor from a grid laid on the floor (src/view/floor_shadow.rs
// says why and how), and a surface's visibilities by what it is. Mirror of
// `FloorShadows::visibilities` in src/view/floor_shadow.rs and `lights_visibility` in
// src/view/cpu.rs. The including shader declares `floor_shadow` (storage: (nodes, L,
// sigma_max, 0), (c.x, c.z, 0, 0), then node (i along x, j along z) at
// FLOOR_SHADOW_HEADER + j nodes + i, each light's visibility by light).

// Entries before the grid (the same name in floor_shadow.rs).
const FLOOR_SHADOW_HEADER: u32 = 2u;

// Node coordinate of a floor offset d from the object's centre: warped by
// sign(d) ln(1 + |d| / L), clamped to the grid.
fn floor_shadow_coordinate(d: f32) -> f32 {
    let n = floor_shadow[0].x;
    let sigma_max = floor_shadow[0].z;
    let sigma = sign(d) * log(1.0 + abs(d) / floor_shadow[0].y);
    return clamp((sigma + sigma_max) / (2.0 * sigma_max) * (n - 1.0), 0.0, n - 1.0);
}

// Floor point p's node coordinates (i along x, j along z).
fn floor_shadow_position(p: vec3<f32>) -> vec2<f32> {
    return vec2<f32>(floor_shadow_coordinate(p.x - floor_shadow[1].x), floor_shadow_coordinate(p.z - floor_shadow[1].y));
}

// Each light's visibility at floor point p, bilinear between the grid's nodes.
fn floor_visibilities(p: vec3<f32>) -> vec4<f32> {
    let n = floor_shadow[0].x;
    let position = floor_shadow_position(p);
    let x = position.x;
    let y = position.y;
    let i = min(floor(x), n - 2.0);
    let j = min(floor(y), n - 2.0);
    let w = u32(n);
    let base = FLOOR_SHADOW_HEADER + u32(j) * w + u32(i);
    let a = mix(floor_shadow[base], floor_shadow[base + 1u], x - i);
    let b = mix(floor_shadow[base + w], floor_shadow[base + w + 1u], x - i);
    return mix(a, b, y - j);
}

// The floor's visibility by light: from the grid for the first `count` lights that have
// a map (`frame.sun.z`), 1 for the rest.
fn floor_lights_visibility(px: PixelView, count: u32) -> vec4<f32> {
    return floor_lit(floor_visibilities(px.s.p), count);
}

// The grid's `visibilities` for the first `count` lights that have a map, 1 for the rest.
fn floor_lit(visibilities: vec4<f32>, count: u32) -> vec4<f32> {
    let lit = min(count, frame.sun.z);
    return select(vec4<f32>(1.0), visibilities, vec4<u32>(0u, 1u, 2u, 3u) < vec4<u32>(lit));
}

// A surface's visibility by light: the floor's from its grid, the object's from the maps.
fn surface_visibility(px: PixelView, count: u32) -> vec4<f32> {
    if (px.s.id == 2u) {
        return floor_lights_visibility(px, count);
    }
    return lights_visibility(px, count);
}
