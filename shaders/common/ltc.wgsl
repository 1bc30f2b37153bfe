// Area lights shaded with linearly transformed cosines (Heitz, Dupuy, Hill, Neubelt,
// SIGGRAPH 2016) in real-time form: a quadrilateral light of uniform radiance at infinity
// (the rectangle an engine's rect light draws), its LTC from a table cell, the LTC as a
// control variate at the light's centre, each edge's integral from a rational fit and the
// horizon clipping the polygon's vector form factor as a sphere (Hill and Heitz, SIGGRAPH
// 2016 course, as three.js's RectAreaLight). Mirror of `shade_quad_light` in
// src/plan/ltc.rs and `edge_vector_form_factor`, `horizon_form_factor`, `inverse_density`
// in src/math/ltc.rs, step for step in f32. The including shader includes material.wgsl,
// brdf.wgsl and sampling.wgsl, and defines `fn ltc_vertex(i: u32) -> vec3<f32>`: the
// light's unit corners, world space, counter-clockwise seen from the origin, from a first
// index on. The corners are read one by one, never held in an array: a software
// rasteriser (lavapipe) gives every invocation of a shader the scratch memory of its
// function-local arrays.
// One cell of an LTC table (`plan::ltc::LtcCell`): M^-1 / M^-1[1][1] as (m00, m20, m02,
// m22), the lobe's magnitude A + B with F = 1 and its Fresnel part B.
struct LtcCell {
    inverse: vec4<f32>,
    norm: f32,
    fresnel: f32,
}

fn ltc_inverse_matrix(c: LtcCell) -> mat3x3<f32> {
    return mat3x3<f32>(vec3<f32>(c.inverse.x, 0.0, c.inverse.y), vec3<f32>(0.0, 1.0, 0.0), vec3<f32>(c.inverse.z, 0.0, c.inverse.w));
}

// The rational fit of theta / (2 pi sin theta), (c0 + (c1 + c2 y) y) / (c3 + (c4 + y) y)
// with y = |cos theta| (EDGE_FIT in src/math/ltc.rs).
const EDGE_FIT_C0: f32 = 0.8543985;
const EDGE_FIT_C1: f32 = 0.4965155;
const EDGE_FIT_C2: f32 = 0.0145206;
const EDGE_FIT_C3: f32 = 3.417594;
const EDGE_FIT_C4: f32 = 4.1616724;
// The floor of sin^2 theta of an arc of nearly opposite ends (MIN_SIN_SQUARED).
const MIN_SIN_SQUARED: f32 = 1e-7;

// The vector form factor of the arc from unit a to unit b: (a x b) theta / (2 pi sin theta).
fn ltc_edge_vector(a: vec3<f32>, b: vec3<f32>) -> vec3<f32> {
    let x = dot(a, b);
    let y = abs(x);
    let fit = (EDGE_FIT_C0 + (EDGE_FIT_C1 + EDGE_FIT_C2 * y) * y) / (EDGE_FIT_C3 + (EDGE_FIT_C4 + y) * y);
    let theta_over_sin = select(0.5 / sqrt(max(1.0 - x * x, MIN_SIN_SQUARED)) - fit, fit, x > 0.0);
    return cross(a, b) * theta_over_sin;
}

// The form factor above the horizon z = 0 of a polygon of vector form factor f: f.z where
// the whole polygon is above, else the horizon-clipped sphere of the same vector form
// factor.
fn ltc_horizon_form_factor(f: vec3<f32>, above: bool) -> f32 {
    let l = length(f);
    return select(max((l * l + f.z) / (l + 1.0), 0.0), max(f.z, 0.0), above);
}

// The LTC's density at unit l in its local frame: D_o(M^-1 l / |M^-1 l|) |det M^-1| /
// |M^-1 l|^3.
fn ltc_density(inverse: mat3x3<f32>, l: vec3<f32>) -> f32 {
    let o = inverse * l;
    let len = length(o);
    return max(o.z / len, 0.0) / PI * abs(determinant(inverse)) / (len * len * len);
}

// What a shaded point's area lights share (`LtcPoint` in src/plan/ltc.rs): its LTC's
// inverse matrix, the world-to-shading frame, world to the LTC's cosine space, whether the LTC reflects
// (-1) or not (1), its alpha and the lobe's scale F0 (A + B - B) + B.
struct LtcPoint {
    inverse: mat3x3<f32>,
    to_local: mat3x3<f32>,
    to_cosine: mat3x3<f32>,
    orientation: f32,
    alpha: f32,
    scale: vec3<f32>,
}

// The shaded point of normal n, view v, Fresnel f0 and roughness `roughness`, its LTC
// `cell` looked up at (n.v, roughness).
fn ltc_point(cell: LtcCell, n: vec3<f32>, v: vec3<f32>, f0: vec3<f32>, roughness: f32) -> LtcPoint {
    var t1 = v - n * dot(n, v);
    if (length(t1) > 1e-6) {
        t1 = normalize(t1);
    } else {
        t1 = tangent_frame(n)[0];
    }
    let t2 = cross(n, t1);
    var out: LtcPoint;
    out.inverse = ltc_inverse_matrix(cell);
    // World to the shading frame (rows t1, t2, n).
    out.to_local = transpose(mat3x3<f32>(t1, t2, n));
    out.to_cosine = out.inverse * out.to_local;
    out.orientation = sign(determinant(out.inverse));
    out.alpha = alpha_from_roughness(roughness);
    out.scale = f0 * (cell.norm - cell.fresnel) + vec3<f32>(cell.fresnel);
    return out;
}

// What the quadrilateral light of corners ltc_vertex(first ..), centre `centre`, solid
// angle `omega`, world-space vector form factor `light_f` and uniform `radiance` sends
// towards v off the point `q` (normal n, material f0 and metallic): (specular, diffuse per
// unit albedo), as `LightShade`.
fn ltc_shade_quad(q: LtcPoint, n: vec3<f32>, v: vec3<f32>, n_dot_v: f32, f0: vec3<f32>, metallic: f32, first: u32, centre: vec3<f32>, omega: f32, light_f: vec3<f32>, radiance: vec3<f32>, brdf: LightBrdf) -> LightShade {
    // The corners in the LTC's cosine space; a reflection reverses the winding.
    var f = vec3<f32>(0.0);
    var above = true;
    var above_n = true;
    var a = normalize(q.to_cosine * ltc_vertex(first + 3u));
    for (var i = 0u; i < 4u; i++) {
        let corner = ltc_vertex(first + i);
        let b = normalize(q.to_cosine * corner);
        f += ltc_edge_vector(a, b);
        above = above && b.z >= 0.0;
        above_n = above_n && dot(corner, n) >= 0.0;
        a = b;
    }
    let polygon_lobe = radiance * q.scale * ltc_horizon_form_factor(f * q.orientation, above);
    let point = directional_light(n, v, n_dot_v, q.alpha, f0, 1.0, centre, radiance * omega, brdf).spec;
    let point_ltc = radiance * q.scale * (omega * ltc_density(q.inverse, q.to_local * centre));
    let lobe = 4.0 * PI * q.alpha * q.alpha;
    let beta = lobe / (lobe + omega);
    var out: LightShade;
    out.spec = max(polygon_lobe + beta * (point - point_ltc), vec3<f32>(0.0));
    out.diff = vec3<f32>(0.0);
    if (metallic < 1.0) {
        let h = normalize(centre + v);
        let weight = diffuse_weight(brdf, f0, max(dot(n, centre), 0.0), n_dot_v, max(dot(v, h), 0.0), q.alpha);
        out.diff = radiance * weight * ((1.0 - metallic) * ltc_horizon_form_factor(q.to_local * light_f, above_n));
    }
    return out;
}
