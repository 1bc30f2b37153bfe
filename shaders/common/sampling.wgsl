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

// ln(1 + x) to about 1e-7 relative: 2 atanh(x / (2 + x)) by its series for |x| < 1/2
// (Vulkan bounds log only to 2^-21 absolute near 1).
fn log1p_accurate(x: f32) -> f32 {
    if (abs(x) >= 0.5) {
        return log(1.0 + x);
    }
    let s = x / (2.0 + x);
    let s2 = s * s;
    var p = 1.0 / 15.0;
    p = p * s2 + 1.0 / 13.0;
    p = p * s2 + 1.0 / 11.0;
    p = p * s2 + 1.0 / 9.0;
    p = p * s2 + 1.0 / 7.0;
    p = p * s2 + 1.0 / 5.0;
    p = p * s2 + 1.0 / 3.0;
    p = p * s2 + 1.0;
    return 2.0 * s * p;
}

// e^x - 1 to about 1e-7 relative: its Taylor series to x^10/10! for |x| < 1/2.
fn expm1_accurate(x: f32) -> f32 {
    if (abs(x) >= 0.5) {
        return exp(x) - 1.0;
    }
    var p = 1.0;
    p = 1.0 + x / 10.0 * p;
    p = 1.0 + x / 9.0 * p;
    p = 1.0 + x / 8.0 * p;
    p = 1.0 + x / 7.0 * p;
    p = 1.0 + x / 6.0 * p;
    p = 1.0 + x / 5.0 * p;
    p = 1.0 + x / 4.0 * p;
    p = 1.0 + x / 3.0 * p;
    p = 1.0 + x / 2.0 * p;
    return x * p;
}

// Charlie sheen distribution (Estevez & Kulla 2017): q = 1 - u, u = sin^(2 + 1/a) theta
// = (1 - cos^2)^e, e = 1 + 1/(2a).
fn charlie_q_from_theta(cos2_theta: f32, alpha: f32) -> f32 {
    let e = 1.0 + 0.5 / alpha;
    return -expm1_accurate(e * log1p_accurate(-cos2_theta));
}

// (cos^2 theta, sin^2 theta) for a given q.
fn charlie_theta_from_q(q: f32, alpha: f32) -> vec2<f32> {
    let e = 1.0 + 0.5 / alpha;
    let l = log1p_accurate(-q) / e;
    return vec2<f32>(-expm1_accurate(l), exp(l));
}
