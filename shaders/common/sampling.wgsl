// The GGX theta mapping shared by the LUT quadrature. Mirror of src/math/sampling.rs (the
// Hammersley points and half-vector sampler live only there: the prefilter kernel reads a
// table of lobe samples built by them, see prefilter_sampled.wgsl).
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
