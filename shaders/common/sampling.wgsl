// Sampling shared by the kernels: the GGX theta mapping of the LUT quadrature, tangent
// frames, the cosine and GGX visible-normal samplers and an integer hash. Mirror of
// src/math/sampling.rs. The Hammersley points, the half-vector sampler and the unit-disk
// points live only there (GPU sin/cos are too coarse): kernels read tables built by them
// (prefilter_sampled.wgsl's lobe samples, preview_truth.wgsl's disk points).
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

// Orthonormal tangent frame around unit n (columns t, b): t = normalize(up x n), up = +Z
// or +X near the poles; b = n x t.
fn tangent_frame(n: vec3<f32>) -> mat2x3<f32> {
    var up = vec3<f32>(1.0, 0.0, 0.0);
    if (abs(n.z) < 0.999) {
        up = vec3<f32>(0.0, 0.0, 1.0);
    }
    let t = normalize(cross(up, n));
    return mat2x3<f32>(t, cross(n, t));
}

// Cosine-weighted direction (tangent space, z = n) from a unit-disk point (Malley's method).
// pdf(l) = (n.l) / pi.
fn cosine_hemisphere_from_disk(p: vec2<f32>) -> vec3<f32> {
    return vec3<f32>(p.x, p.y, sqrt(max(1.0 - p.x * p.x - p.y * p.y, 0.0)));
}

// GGX visible normal for tangent-space view v from a unit-disk point (Heitz 2018, listing 1).
// pdf(h) = G1(v) max(0, v.h) D(h) / (n.v); for l = reflect(-v, h), pdf(l) = pdf(h) / (4 v.h).
fn sample_ggx_vndf(v: vec3<f32>, alpha: f32, p: vec2<f32>) -> vec3<f32> {
    let vh = normalize(vec3<f32>(alpha * v.x, alpha * v.y, v.z));
    let lensq = vh.x * vh.x + vh.y * vh.y;
    var t1 = vec3<f32>(1.0, 0.0, 0.0);
    if (lensq > 0.0) {
        let inv = 1.0 / sqrt(lensq);
        t1 = vec3<f32>(-vh.y * inv, vh.x * inv, 0.0);
    }
    let t2 = cross(vh, t1);
    let s = 0.5 * (1.0 + vh.z);
    let d1 = p.x;
    let d2 = (1.0 - s) * sqrt(max(1.0 - d1 * d1, 0.0)) + s * p.y;
    let dz = sqrt(max(1.0 - d1 * d1 - d2 * d2, 0.0));
    let nh = d1 * t1 + d2 * t2 + dz * vh;
    return normalize(vec3<f32>(alpha * nh.x, alpha * nh.y, max(nh.z, 0.0)));
}

// PCG hash (Jarzynski & Olano 2020): integer-only, so both backends draw the same points.
fn pcg_hash(x: u32) -> u32 {
    let state = x * 747796405u + 2891336453u;
    let word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
    return (word >> 22u) ^ word;
}

// A 32-bit integer as a float in [0, 1) (its top 24 bits).
fn unit_float(bits: u32) -> f32 {
    return f32(bits >> 8u) * (1.0 / 16777216.0);
}
