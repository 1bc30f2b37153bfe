// GGX half-vector sampling and low-discrepancy points. Mirror of src/math/sampling.rs.
// pdf(h) = D(h) (n.h); its theta marginal has CDF u = sin^2 / (sin^2 + alpha^2 cos^2)
// (Walter et al. 2007, eq. 35). We use q = 1 - u, which keeps precision for small alpha.

// q(theta) = alpha^2 cos^2 / (sin^2 + alpha^2 cos^2).
fn ggx_q_from_theta(cos2_theta: f32, sin2_theta: f32, alpha2: f32) -> f32 {
    let ac = alpha2 * cos2_theta;
    return ac / (sin2_theta + ac);
}

// (cos^2 theta, sin^2 theta) for a given q, without cancellation.
fn ggx_theta_from_q(q: f32, alpha2: f32) -> vec2<f32> {
    let s = alpha2 * (1.0 - q);
    let den = q + s;
    return vec2<f32>(q / den, s / den);
}

// Van der Corput radical inverse in base 2.
fn radical_inverse_vdc(bits: u32) -> f32 {
    return f32(reverseBits(bits)) * (1.0 / 4294967296.0);
}

// i-th of n Hammersley points in [0, 1)^2.
fn hammersley(i: u32, n: u32) -> vec2<f32> {
    return vec2<f32>(f32(i) / f32(n), radical_inverse_vdc(i));
}

// GGX half vector in tangent space (z = n).
// pdf(h) = D(h) (n.h) with respect to solid angle (Walter et al. 2007, eq. 35-36).
fn importance_sample_ggx(xi: vec2<f32>, alpha: f32) -> vec3<f32> {
    let phi = 2.0 * PI * xi.y;
    let cs2 = ggx_theta_from_q(1.0 - xi.x, alpha * alpha);
    let c = sqrt(cs2.x);
    let s = sqrt(cs2.y);
    return vec3<f32>(s * cos(phi), s * sin(phi), c);
}
