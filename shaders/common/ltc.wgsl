// Area lights shaded with linearly transformed cosines (Heitz, Dupuy, Hill, Neubelt,
// SIGGRAPH 2016): a polygonal light of uniform radiance at infinity, its LTC from a table
// cell, the LTC as a control variate at the polygon's centre. Mirror of src/math/ltc.rs
// (`Ltc::density`, `Ltc::integrate_polygon`, `polygon_form_factor`,
// `polygon_solid_angle`) and `shade_polygon` in src/plan/ltc.rs, in f32 where the CPU
// sums in f64. The including shader includes material.wgsl, brdf.wgsl and sampling.wgsl,
// and defines `fn ltc_vertex(i: u32) -> vec3<f32>`: the polygon's unit vertices, world
// space, i from a first index on. The polygon is streamed, never held in an array: a
// software rasteriser (lavapipe) gives every invocation of a shader the scratch memory of
// its function-local arrays, which cost the viewer's frames several times over even where
// no area light is drawn.

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

// Lambert's term of the arc from unit a to unit b.
fn ltc_edge(a: vec3<f32>, b: vec3<f32>) -> f32 {
    let c = cross(a, b);
    let s = length(c);
    return select(0.0, atan2(s, dot(a, b)) * c.z / s, s > 0.0);
}

// The irradiance form factor of the polygon of vertices normalize(m ltc_vertex(i)),
// i = first .. first + count: the integral of max(0, z) / pi over its part above z = 0,
// clipped to the horizon (Sutherland-Hodgman on the arcs) edge by edge as it streams, then
// Lambert's closed form over the clipped polygon's edges.
fn ltc_form_factor(m: mat3x3<f32>, first: u32, count: u32) -> f32 {
    var sum = 0.0;
    var emitted = 0u;
    var head = vec3<f32>(0.0);
    var last = vec3<f32>(0.0);
    var a = normalize(m * ltc_vertex(first + count - 1u));
    for (var i = 0u; i < count; i++) {
        let b = normalize(m * ltc_vertex(first + i));
        // The clipped polygon's points from the edge a -> b: its crossing of the horizon,
        // then b where b is above.
        for (var k = 0u; k < 2u; k++) {
            var p = b;
            var keep = b.z >= 0.0;
            if (k == 0u) {
                keep = (a.z >= 0.0) != (b.z >= 0.0);
                p = normalize(a + (a.z / (a.z - b.z)) * (b - a));
            }
            if (keep) {
                if (emitted == 0u) {
                    head = p;
                } else {
                    sum += ltc_edge(last, p);
                }
                last = p;
                emitted += 1u;
            }
        }
        a = b;
    }
    if (emitted < 3u) {
        return 0.0;
    }
    sum += ltc_edge(last, head);
    return abs(sum) / (2.0 * PI);
}

// The LTC's density at unit l in its local frame: D_o(M^-1 l / |M^-1 l|) |det M^-1| /
// |M^-1 l|^3.
fn ltc_density(inverse: mat3x3<f32>, l: vec3<f32>) -> f32 {
    let o = inverse * l;
    let len = length(o);
    return max(o.z / len, 0.0) / PI * abs(determinant(inverse)) / (len * len * len);
}

// The solid angle of the convex spherical polygon of vertices ltc_vertex(first ..): its
// fan of triangles from the first vertex, each by Van Oosterom and Strackee.
fn ltc_solid_angle(first: u32, count: u32) -> f32 {
    var sum = 0.0;
    let a = ltc_vertex(first);
    for (var i = 1u; i + 1u < count; i++) {
        let b = ltc_vertex(first + i);
        let c = ltc_vertex(first + i + 1u);
        sum += 2.0 * atan2(abs(dot(a, cross(b, c))), 1.0 + dot(a, b) + dot(b, c) + dot(c, a));
    }
    return sum;
}

// What the polygonal light of vertices ltc_vertex(first ..) and uniform `radiance` sends
// towards v off a point with normal n and material (f0, metallic, roughness), its LTC
// `cell` looked up at (n.v, roughness): (specular, diffuse per unit albedo), as
// `LightShade`.
fn ltc_shade_polygon(cell: LtcCell, n: vec3<f32>, v: vec3<f32>, n_dot_v: f32, f0: vec3<f32>, metallic: f32, roughness: f32, first: u32, count: u32, radiance: vec3<f32>, brdf: LightBrdf) -> LightShade {
    var t1 = v - n * dot(n, v);
    if (length(t1) > 1e-6) {
        t1 = normalize(t1);
    } else {
        t1 = tangent_frame(n)[0];
    }
    let t2 = cross(n, t1);
    // World to the shading frame (rows t1, t2, n).
    let to_local = transpose(mat3x3<f32>(t1, t2, n));
    var centre = vec3<f32>(0.0);
    for (var i = 0u; i < count; i++) {
        centre += ltc_vertex(first + i);
    }
    centre = normalize(centre);
    let inverse = ltc_inverse_matrix(cell);
    let omega = ltc_solid_angle(first, count);
    let alpha = alpha_from_roughness(roughness);
    let scale = f0 * (cell.norm - cell.fresnel) + vec3<f32>(cell.fresnel);
    let polygon_lobe = radiance * scale * ltc_form_factor(inverse * to_local, first, count);
    let point = directional_light(n, v, n_dot_v, alpha, f0, 1.0, centre, radiance * omega, brdf).spec;
    let point_ltc = radiance * scale * (omega * ltc_density(inverse, to_local * centre));
    let lobe = 4.0 * PI * alpha * alpha;
    let beta = lobe / (lobe + omega);
    var out: LightShade;
    out.spec = max(polygon_lobe + beta * (point - point_ltc), vec3<f32>(0.0));
    out.diff = vec3<f32>(0.0);
    if (metallic < 1.0) {
        let h = normalize(centre + v);
        let weight = diffuse_weight(brdf, f0, max(dot(n, centre), 0.0), n_dot_v, max(dot(v, h), 0.0), alpha);
        out.diff = radiance * weight * ((1.0 - metallic) * ltc_form_factor(to_local, first, count));
    }
    return out;
}
