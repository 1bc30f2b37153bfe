// The LTC table's fit (Heitz, Dupuy, Hill, Neubelt 2016, their fitLTC.cpp), one workgroup a
// cell, its FIT_THREADS invocations sharing each quadrature: mirror of
// src/cpu/ltc_fit.rs (`LtcTable::fit`, `fit_cell`, `lobe_terms`, `fit_error`,
// `nelder_mead`, `eval_brdf`, `sample_brdf`, `fit_points`) and math::ltc::Ltc (`new`,
// `density`, `sample`), whose docs say what each computes (plan::ltc: the cell's layout and
// the constants). Every invocation runs the same Nelder-Mead on the same values
// (each sum is reduced in workgroup memory and read back uniformly), in f32 where the CPU
// sums in f64.
//
// One cell a workgroup a dispatch, in the CPU's order: stage 0 (one workgroup), the
// normal-incidence cell (i, 0), i = `step`, from cell (i + 1, 0)'s parameters (r = 1 first,
// from a cosine); stage 1 (a workgroup per roughness i), cell (i, j), j = `step`, from
// (i, j - 1)'s. A dispatch a cell keeps each invocation's loop iterations under what
// llvmpipe (lavapipe) allows a shader (65 535: more, and its loops stop early), and a
// dispatch short on any GPU.

struct LtcFitParams {
    size: u32,
    masking: u32, // plan::shading::Masking (material.wgsl's MASKING_*)
    stage: u32,   // 0: normal incidence, 1: the rows along θ
    step: u32,    // the cell's i (stage 0) or j (stage 1)
}

@group(0) @binding(0) var<uniform> params: LtcFitParams;
// Two entries a cell, (i, j) at 2 (j size + i): M^-1 / M^-1_11 as (M^-1_00, M^-1_20,
// M^-1_02, M^-1_22), then (A + B, B, 0, 0).
@group(0) @binding(1) var<storage, read_write> cells: array<vec4<f32>>;
// Per roughness i, the parameters (m11, m22, m13, 0) of the last cell fitted.
@group(0) @binding(2) var<storage, read_write> starts: array<vec4<f32>>;

// Invocations of a workgroup (src/gpu/ltc_fit.rs's WORKGROUP).
const FIT_THREADS: u32 = 64u;
// plan::ltc's constants (tests/shaders.rs checks them).
const FIT_SAMPLES: u32 = 32u;
const MIN_ALPHA: f32 = 1e-3;
const SIMPLEX_STEP: f32 = 0.05;
const SIMPLEX_TOLERANCE: f32 = 1e-5;
const SIMPLEX_ITERATIONS: u32 = 100u;
const MIN_SCALE: f32 = 1e-7;
const MIN_FIT_N_DOT_V: f32 = 7.963267e-4;
// The smallest positive normal f32 (Rust's f32::MIN_POSITIVE).
const MIN_POSITIVE: f32 = 1.17549435e-38;

var<workgroup> partial: array<vec4<f32>, FIT_THREADS>;

// The sum of every invocation's `x`, the same in each (called in uniform control flow).
fn workgroup_sum(x: vec4<f32>, lid: u32) -> vec4<f32> {
    // Every invocation has read the previous sum before it is overwritten.
    workgroupBarrier();
    partial[lid] = x;
    workgroupBarrier();
    for (var s = FIT_THREADS / 2u; s > 0u; s >>= 1u) {
        if (lid < s) {
            partial[lid] += partial[lid + s];
        }
        workgroupBarrier();
    }
    return workgroupUniformLoad(&partial[0]);
}

struct FitLtc {
    m: mat3x3<f32>,
    inverse: mat3x3<f32>,
    det: f32,
}

// glam's Mat3::inverse: the adjugate's columns (cross products) over the determinant,
// transposed.
fn inverse3(m: mat3x3<f32>) -> mat3x3<f32> {
    let t0 = cross(m[1], m[2]);
    let t1 = cross(m[2], m[0]);
    let t2 = cross(m[0], m[1]);
    let inv_det = 1.0 / dot(m[2], t2);
    return transpose(mat3x3<f32>(t0 * inv_det, t1 * inv_det, t2 * inv_det));
}

// Ltc::new: M = [x y z] [[m11, 0, m13], [0, m22, 0], [0, 0, 1]].
fn fit_ltc_new(p: vec3<f32>, x: vec3<f32>, y: vec3<f32>, z: vec3<f32>) -> FitLtc {
    let shape = mat3x3<f32>(vec3<f32>(p.x, 0.0, 0.0), vec3<f32>(0.0, p.y, 0.0), vec3<f32>(p.z, 0.0, 1.0));
    let m = mat3x3<f32>(x, y, z) * shape;
    return FitLtc(m, inverse3(m), abs(determinant(m)));
}

// Ltc::density.
fn fit_ltc_density(t: FitLtc, l: vec3<f32>) -> f32 {
    let original = normalize(t.inverse * l);
    let transformed = length(t.m * original);
    return max(original.z, 0.0) / PI * (transformed * transformed * transformed) / t.det;
}

// Ltc::sample.
fn fit_ltc_sample(t: FitLtc, u: vec2<f32>) -> vec3<f32> {
    let s = sqrt(u.x);
    let c = sqrt(max(1.0 - u.x, 0.0));
    let phi = 2.0 * PI * u.y;
    return normalize(t.m * vec3<f32>(s * cos(phi), s * sin(phi), c));
}

// eval_brdf: (f (n.l) with F = 1, the pdf of fit_sample_brdf) at l for view v (n = +Z).
fn fit_eval_brdf(brdf: LightBrdf, v: vec3<f32>, l: vec3<f32>, alpha: f32) -> vec2<f32> {
    let h = normalize(v + l);
    let d = d_ggx(max(h.z, 0.0), alpha);
    let pdf = abs(d * h.z / (4.0 * dot(v, h)));
    if (l.z <= 0.0 || v.z <= 0.0) {
        return vec2<f32>(0.0, pdf);
    }
    return vec2<f32>(d * light_masking(brdf, l.z, v.z, alpha) * 0.25, pdf);
}

// sample_brdf: l reflected about a GGX normal sampled by u (Walter et al. 2007).
fn fit_sample_brdf(v: vec3<f32>, alpha: f32, u: vec2<f32>) -> vec3<f32> {
    let phi = 2.0 * PI * u.x;
    let r = alpha * sqrt(u.y / (1.0 - u.y));
    let h = normalize(vec3<f32>(r * cos(phi), r * sin(phi), 1.0));
    return 2.0 * dot(h, v) * h - v;
}

// fit_points: point k of the FIT_SAMPLES^2 grid of cell centres.
fn fit_point(k: u32) -> vec2<f32> {
    let n = f32(FIT_SAMPLES);
    return vec2<f32>((f32(k % FIT_SAMPLES) + 0.5) / n, (f32(k / FIT_SAMPLES) + 0.5) / n);
}

// lobe_terms: (magnitude, Fresnel part, the mean direction's x and z).
fn fit_lobe_terms(brdf: LightBrdf, v: vec3<f32>, alpha: f32, lid: u32) -> vec4<f32> {
    var sum = vec4<f32>(0.0);
    for (var k = lid; k < FIT_SAMPLES * FIT_SAMPLES; k += FIT_THREADS) {
        let l = fit_sample_brdf(v, alpha, fit_point(k));
        let b = fit_eval_brdf(brdf, v, l, alpha);
        if (b.y > 0.0) {
            let w = b.x / b.y;
            let h = normalize(v + l);
            let q = 1.0 - max(dot(v, h), 0.0);
            let q2 = q * q;
            sum += vec4<f32>(w, w * q2 * q2 * q, w * l.x, w * l.z);
        }
    }
    let total = workgroup_sum(sum, lid);
    let count = f32(FIT_SAMPLES * FIT_SAMPLES);
    return vec4<f32>(total.x / count, total.y / count, total.z, total.w);
}

// One term of fit_error at l.
fn fit_error_term(brdf: LightBrdf, t: FitLtc, norm: f32, v: vec3<f32>, alpha: f32, l: vec3<f32>) -> f32 {
    let b = fit_eval_brdf(brdf, v, l, alpha);
    let d = fit_ltc_density(t, l);
    let e = abs(b.x - norm * d);
    return e * e * e / max(d + b.y, MIN_POSITIVE);
}

// fit_error: the mean of |f (n.l) - norm D|^3 / (pdf_LTC + pdf_BRDF) over samples of both.
fn fit_error(brdf: LightBrdf, t: FitLtc, norm: f32, v: vec3<f32>, alpha: f32, lid: u32) -> f32 {
    var e = 0.0;
    for (var k = lid; k < FIT_SAMPLES * FIT_SAMPLES; k += FIT_THREADS) {
        let u = fit_point(k);
        e += fit_error_term(brdf, t, norm, v, alpha, fit_ltc_sample(t, u));
        e += fit_error_term(brdf, t, norm, v, alpha, fit_sample_brdf(v, alpha, u));
    }
    return workgroup_sum(vec4<f32>(e, 0.0, 0.0, 0.0), lid).x / f32(FIT_SAMPLES * FIT_SAMPLES);
}

// One cell's quadrature: its view, α, magnitude and frame.
struct FitCell {
    v: vec3<f32>,
    alpha: f32,
    norm: f32,
    fresnel: f32,
    isotropic: bool,
    x: vec3<f32>,
    z: vec3<f32>,
}

// fit_cell's `ltc_of`: the parameters (m11, m22, m13) a simplex point stands for.
fn fit_params(c: FitCell, p: vec3<f32>) -> vec3<f32> {
    let m11 = max(p.x, MIN_SCALE);
    if (c.isotropic) {
        return vec3<f32>(m11, m11, 0.0);
    }
    return vec3<f32>(m11, max(p.y, MIN_SCALE), p.z);
}

fn fit_cell_error(brdf: LightBrdf, c: FitCell, p: vec3<f32>, lid: u32) -> f32 {
    let t = fit_ltc_new(fit_params(c, p), c.x, vec3<f32>(0.0, 1.0, 0.0), c.z);
    return fit_error(brdf, t, c.norm, c.v, c.alpha, lid);
}

// nelder_mead: the best point found from `start`.
fn fit_nelder_mead(brdf: LightBrdf, c: FitCell, start: vec3<f32>, lid: u32) -> vec3<f32> {
    var s = array<vec3<f32>, 4>(start, start + vec3<f32>(SIMPLEX_STEP, 0.0, 0.0), start + vec3<f32>(0.0, SIMPLEX_STEP, 0.0), start + vec3<f32>(0.0, 0.0, SIMPLEX_STEP));
    var fs: array<f32, 4>;
    for (var k = 0u; k < 4u; k++) {
        fs[k] = fit_cell_error(brdf, c, s[k], lid);
    }
    for (var it = 0u; it < SIMPLEX_ITERATIONS; it++) {
        var lo = 0u;
        var hi = 0u;
        var nh = 0u;
        for (var i = 1u; i < 4u; i++) {
            if (fs[i] < fs[lo]) {
                lo = i;
            }
            if (fs[i] > fs[hi]) {
                nh = hi;
                hi = i;
            } else if (fs[i] > fs[nh]) {
                nh = i;
            }
        }
        let a = abs(fs[lo]);
        let b = abs(fs[hi]);
        if (2.0 * abs(a - b) < (a + b) * SIMPLEX_TOLERANCE) {
            break;
        }
        var o = vec3<f32>(0.0);
        for (var k = 0u; k < 4u; k++) {
            if (k != hi) {
                o += s[k] / 3.0;
            }
        }
        let r = o + (o - s[hi]);
        let fr = fit_cell_error(brdf, c, r, lid);
        if (fr < fs[nh]) {
            var next = r;
            var f_next = fr;
            if (fr < fs[lo]) {
                let e = o + 2.0 * (o - s[hi]);
                let fe = fit_cell_error(brdf, c, e, lid);
                if (fe < fr) {
                    next = e;
                    f_next = fe;
                }
            }
            s[hi] = next;
            fs[hi] = f_next;
            continue;
        }
        let cc = o - 0.5 * (o - s[hi]);
        let fc = fit_cell_error(brdf, c, cc, lid);
        if (fc < fs[hi]) {
            s[hi] = cc;
            fs[hi] = fc;
            continue;
        }
        for (var k = 0u; k < 4u; k++) {
            if (k != lo) {
                s[k] = s[lo] + 0.5 * (s[k] - s[lo]);
                fs[k] = fit_cell_error(brdf, c, s[k], lid);
            }
        }
    }
    var best = 0u;
    for (var k = 1u; k < 4u; k++) {
        if (fs[k] < fs[best]) {
            best = k;
        }
    }
    return s[best];
}

// fit_cell: fits cell (i, j) from `start`, stores it and returns its parameters.
fn fit_cell(brdf: LightBrdf, size: u32, i: u32, j: u32, start: vec3<f32>, lid: u32) -> vec3<f32> {
    let x = f32(j) / f32(size - 1u);
    let n_dot_v = max(1.0 - x * x, MIN_FIT_N_DOT_V);
    var c: FitCell;
    c.v = vec3<f32>(sqrt(1.0 - n_dot_v * n_dot_v), 0.0, n_dot_v);
    let r = f32(i) / f32(size - 1u);
    c.alpha = max(r * r, MIN_ALPHA);
    let lobe = fit_lobe_terms(brdf, c.v, c.alpha, lid);
    c.norm = lobe.x;
    c.fresnel = lobe.y;
    c.isotropic = j == 0u;
    var mean = vec3<f32>(0.0, 0.0, 1.0);
    let length2 = lobe.z * lobe.z + lobe.w * lobe.w;
    if (length2 > 0.0) {
        mean = normalize(vec3<f32>(lobe.z, 0.0, lobe.w));
    }
    c.x = select(vec3<f32>(mean.z, 0.0, -mean.x), vec3<f32>(1.0, 0.0, 0.0), c.isotropic);
    c.z = select(mean, vec3<f32>(0.0, 0.0, 1.0), c.isotropic);
    let p = fit_params(c, fit_nelder_mead(brdf, c, start, lid));
    let inverse = fit_ltc_new(p, c.x, vec3<f32>(0.0, 1.0, 0.0), c.z).inverse;
    let scale = inverse[1].y;
    if (lid == 0u) {
        let e = 2u * (j * size + i);
        cells[e] = vec4<f32>(inverse[0].x, inverse[0].z, inverse[2].x, inverse[2].z) / scale;
        cells[e + 1u] = vec4<f32>(c.norm, c.fresnel, 0.0, 0.0);
    }
    return p;
}

@compute @workgroup_size(WORKGROUP_X, WORKGROUP_Y, WORKGROUP_Z)
fn main(@builtin(workgroup_id) group: vec3<u32>, @builtin(local_invocation_index) lid: u32) {
    let size = params.size;
    let brdf = LightBrdf(params.masking, DIFFUSE_FRESNEL_WEIGHTED);
    var i = group.x;
    var j = params.step;
    // A cosine (m11 = m22 = 1) before the first cell, r = 1 at normal incidence.
    var start = vec3<f32>(1.0, 1.0, 0.0);
    if (params.stage == 0u) {
        i = params.step;
        j = 0u;
        if (i + 1u < size) {
            start = starts[i + 1u].xyz;
        }
    } else {
        start = starts[i].xyz;
    }
    let p = fit_cell(brdf, size, i, j, start, lid);
    if (lid == 0u) {
        starts[i] = vec4<f32>(p, 0.0);
    }
}
