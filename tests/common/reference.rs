//! Independent f64 references the tests measure splitsum against, written from the papers
//! and not from splitsum's code: a converged adaptive Gauss-Kronrod integral of the BRDF
//! LUT models, luminance, and an equirect as exact terms (solid angle, direction,
//! radiance) for brute-force integrals at full source resolution.

use std::f64::consts::PI;

/// One Gauss-Kronrod (7, 15) step on [a, b]: (K15 estimate, |K15 − G7|). The node and
/// weight tables are the published 33-digit values (QUADPACK), kept as printed.
#[allow(clippy::excessive_precision)]
fn gk15(f: &mut dyn FnMut(f64) -> f64, a: f64, b: f64) -> (f64, f64) {
    const XGK: [f64; 8] = [
        0.991455371120812639206854697526329,
        0.949107912342758524526189684047851,
        0.864864423359769072789712788640926,
        0.741531185599394439863864773280788,
        0.586087235467691130294144845693013,
        0.405845151377397166906606412076961,
        0.207784955007898467600689403773245,
        0.0,
    ];
    const WGK: [f64; 8] = [
        0.022935322010529224963732008058970,
        0.063092092629978553290700663189204,
        0.104790010322250183839876322541518,
        0.140653259715525918745189590510238,
        0.169004726639267902826583426598550,
        0.190350578064785409913256402421014,
        0.204432940075298892414161999234649,
        0.209482141084727828012999174891714,
    ];
    const WG: [f64; 4] = [
        0.129484966168869693270611432679082,
        0.279705391489276667901467771423780,
        0.381830050505118944950369775488975,
        0.417959183673469387755102040816327,
    ];
    let c = 0.5 * (a + b);
    let h = 0.5 * (b - a);
    let fc = f(c);
    let mut rk = fc * WGK[7];
    let mut rg = fc * WG[3];
    for j in 0..7 {
        let x = h * XGK[j];
        let s = f(c - x) + f(c + x);
        rk += WGK[j] * s;
        if j % 2 == 1 {
            rg += WG[j / 2] * s;
        }
    }
    (rk * h, ((rk - rg) * h).abs())
}

/// Adaptive Gauss-Kronrod quadrature with absolute tolerance `tol`.
pub fn adaptive(f: &mut dyn FnMut(f64) -> f64, a: f64, b: f64, tol: f64) -> f64 {
    fn rec(f: &mut dyn FnMut(f64) -> f64, a: f64, b: f64, tol: f64, depth: u32) -> f64 {
        let (r, e) = gk15(f, a, b);
        if e <= tol.max(1e-16) || depth >= 40 {
            return r;
        }
        let m = 0.5 * (a + b);
        rec(f, a, m, 0.5 * tol, depth + 1) + rec(f, m, b, 0.5 * tol, depth + 1)
    }
    rec(f, a, b, tol, 0)
}

/// The converged split-sum integrals (A, B) at (n·v, roughness), in f64, written from the
/// textbook formula independently of the library: f = D G F / (4 (n·l)(n·v)) with
/// GGX D (α = r²), Smith/Schlick-GGX G (k = r²/2) and Schlick F, integrated as
/// E_h[f (n·l) / pdf(l)] with pdf(l) = D (n·h) / (4 v·h), by nested adaptive
/// Gauss-Kronrod over the GGX CDF variable u of θh and over φ ∈ [0, π]. The φ range is cut
/// where n·l reaches 0 (located by bisection), and the u range at θh = (π/2 ∓ θv)/2, so the
/// adaptive rule never straddles the horizon kink.
pub fn reference_lut(n_dot_v: f64, roughness: f64) -> (f64, f64) {
    reference_integrals(
        n_dot_v,
        roughness,
        splitsum::plan::lut::Visibility::SchlickGgx,
    )
}

/// [`reference_lut`] for `model`, in the model's channel layout: (A, B), or (B, A + B) for
/// the multiscatter layout (Filament's `DFV_Multiscatter`). The height-correlated
/// visibility is V = 0.5 / (n·l √(n·v² (1 − α²) + α²) + n·v √(n·l² (1 − α²) + α²))
/// (Heitz 2014, eq. 99), written here from the paper.
pub fn reference_lut_model(
    n_dot_v: f64,
    roughness: f64,
    model: splitsum::plan::lut::LutModel,
) -> (f64, f64) {
    if model.distribution() == splitsum::plan::lut::LutDistribution::Charlie {
        return (
            reference_charlie(n_dot_v, roughness, model.visibility()),
            0.0,
        );
    }
    let (a, b) = reference_integrals(n_dot_v, roughness, model.visibility());
    match model.layout() {
        splitsum::plan::lut::LutLayout::ScaleBias => (a, b),
        splitsum::plan::lut::LutLayout::Multiscatter => (b, a + b),
        splitsum::plan::lut::LutLayout::Albedo => (a + b, 0.0),
    }
}

/// The Charlie sheen albedo E = ∫ D V (n·l) dl with D = (2 + 1/α) sin^(1/α)θh / (2π)
/// (Estevez & Kulla 2017), α = r², and V either Ashikhmin's 1 / (4 (n·l + n·v − n·l n·v))
/// (Neubelt & Pettineo 2013) or KHR_materials_sheen's clamp(1 / ((1 + Λ(v) + Λ(l))
/// 4 n·v n·l), 0, 1) with the spec's fitted Λ, in f64: over h, dl = 4 (v·h) dh, written as ∫ du dφ/(2π) · 4 V (n·l)
/// (v·h)/(n·h) in the CDF variable u = sin^(2 + 1/α)θh of D (n·h), by nested adaptive
/// Gauss-Kronrod with the φ range cut at the horizon (bisection), the u range at the
/// horizon breakpoints θh = (π/2 ∓ θv)/2.
pub fn reference_charlie(
    n_dot_v: f64,
    roughness: f64,
    visibility: splitsum::plan::lut::Visibility,
) -> f64 {
    let alpha = (roughness * roughness).max(1e-12);
    // The KHR_materials_sheen Λ (spec, "Sheen BRDF"), in f64.
    let helper = |x: f64| {
        let t = (1.0 - alpha) * (1.0 - alpha);
        let lerp = |p: f64, q: f64| p * (1.0 - t) + q * t;
        lerp(21.5473, 25.3245) / (1.0 + lerp(3.82987, 3.32435) * x.powf(lerp(0.19823, 0.16801)))
            + lerp(-1.97760, -1.27393) * x
            + lerp(-4.32054, -4.85967)
    };
    let lambda = |c: f64| {
        if c < 0.5 {
            helper(c).exp()
        } else {
            (2.0 * helper(0.5) - helper(1.0 - c)).exp()
        }
    };
    let vis = |n_dot_l: f64| match visibility {
        splitsum::plan::lut::Visibility::Sheen => (1.0
            / ((1.0 + lambda(n_dot_v) + lambda(n_dot_l)) * 4.0 * n_dot_v * n_dot_l))
            .clamp(0.0, 1.0),
        _ => 1.0 / (4.0 * (n_dot_l + n_dot_v - n_dot_l * n_dot_v)),
    };
    let e = 2.0 + 1.0 / alpha; // u = sin^e θ
    let v = [(1.0 - n_dot_v * n_dot_v).sqrt(), 0.0, n_dot_v];
    // (cos θ, sin θ) at u, with cos² = 1 − u^(2/e) computed without cancellation.
    let theta = |u: f64| {
        let l = u.ln() * 2.0 / e;
        let cos2 = -l.exp_m1();
        (cos2.max(0.0).sqrt(), l.exp().sqrt())
    };
    let n_dot_l_at = |u: f64, phi: f64| {
        let (ct, st) = theta(u);
        2.0 * (v[0] * st * phi.cos() + v[2] * ct) * ct - v[2]
    };
    let integrand = |u: f64, phi: f64| {
        let (ct, st) = theta(u);
        let v_dot_h = v[0] * st * phi.cos() + v[2] * ct;
        let n_dot_l = 2.0 * v_dot_h * ct - v[2];
        if n_dot_l <= 0.0 || v_dot_h <= 0.0 || ct <= 0.0 {
            return 0.0;
        }
        4.0 * vis(n_dot_l) * n_dot_l * v_dot_h / ct
    };
    let phi_limit = |u: f64| horizon_phi(|phi| n_dot_l_at(u, phi));
    let theta_v = n_dot_v.acos();
    let u_of = |th: f64| th.sin().powf(e);
    let b1 = u_of(0.5 * (PI / 2.0 - theta_v));
    let b2 = u_of(0.5 * (PI / 2.0 + theta_v));
    let mut outer = |u: f64| {
        if u <= 0.0 {
            return 0.0;
        }
        let pm = phi_limit(u);
        let mut inner = |phi: f64| integrand(u, phi);
        adaptive(&mut inner, 0.0, pm, 1e-11) / PI
    };
    adaptive(&mut outer, 0.0, b1, 1e-10) + adaptive(&mut outer, b1, b2, 1e-10)
}

/// The largest φ ∈ [0, π] with n·l(φ) ≥ 0, by bisection (n·l decreases with φ on [0, π]
/// for a fixed half-vector polar angle): π when the whole range is above the horizon, 0 when
/// none of it is.
fn horizon_phi(n_dot_l: impl Fn(f64) -> f64) -> f64 {
    if n_dot_l(PI) >= 0.0 {
        return PI;
    }
    if n_dot_l(0.0) <= 0.0 {
        return 0.0;
    }
    let (mut lo, mut hi) = (0.0, PI);
    for _ in 0..80 {
        let mid = 0.5 * (lo + hi);
        if n_dot_l(mid) >= 0.0 {
            lo = mid
        } else {
            hi = mid
        }
    }
    lo
}

/// A = ∫ f/F (1 − Fc)(n·l) dl and B = ∫ f/F Fc (n·l) dl with `visibility`.
fn reference_integrals(
    n_dot_v: f64,
    roughness: f64,
    visibility: splitsum::plan::lut::Visibility,
) -> (f64, f64) {
    let alpha = roughness * roughness;
    let a2 = alpha * alpha;
    let k = alpha / 2.0;
    let v = [(1.0 - n_dot_v * n_dot_v).sqrt(), 0.0, n_dot_v];
    let g1 = |x: f64| x / (x * (1.0 - k) + k);
    // G = 4 V (n·l)(n·v), so that f = D G F / (4 (n·l)(n·v)) for both forms.
    let g2 = |n_dot_l: f64| match visibility {
        splitsum::plan::lut::Visibility::SchlickGgx => g1(n_dot_l) * g1(n_dot_v),
        splitsum::plan::lut::Visibility::SmithCorrelated => {
            let lv = (n_dot_v * n_dot_v * (1.0 - a2) + a2).sqrt();
            let ll = (n_dot_l * n_dot_l * (1.0 - a2) + a2).sqrt();
            let vis = 0.5 / (n_dot_l * lv + n_dot_v * ll);
            4.0 * vis * n_dot_l * n_dot_v
        }
        splitsum::plan::lut::Visibility::Ashikhmin | splitsum::plan::lut::Visibility::Sheen => {
            unreachable!("the sheen visibilities go with the Charlie distribution")
        }
    };
    let integrand = |u: f64, phi: f64| -> (f64, f64) {
        let den = (1.0 - u) + a2 * u;
        let ct = ((1.0 - u) / den).sqrt();
        let st = (a2 * u / den).sqrt();
        let h = [st * phi.cos(), st * phi.sin(), ct];
        let v_dot_h = v[0] * h[0] + v[2] * h[2];
        let n_dot_l = 2.0 * v_dot_h * h[2] - v[2];
        if n_dot_l <= 0.0 || v_dot_h <= 0.0 {
            return (0.0, 0.0);
        }
        let d = a2 / (PI * (ct * ct * (a2 - 1.0) + 1.0).powi(2));
        let g = g2(n_dot_l);
        let f_no_fresnel = d * g / (4.0 * n_dot_l * n_dot_v);
        let pdf_l = d * ct / (4.0 * v_dot_h);
        let val = f_no_fresnel * n_dot_l / pdf_l;
        let fc = (1.0 - v_dot_h).powi(5);
        (val * (1.0 - fc), val * fc)
    };
    let n_dot_l_at = |u: f64, phi: f64| {
        let den = (1.0 - u) + a2 * u;
        let ct = ((1.0 - u) / den).sqrt();
        let st = (a2 * u / den).sqrt();
        2.0 * (v[0] * st * phi.cos() + v[2] * ct) * ct - v[2]
    };
    let phi_limit = |u: f64| horizon_phi(|phi| n_dot_l_at(u, phi));
    let theta_v = n_dot_v.acos();
    let u_of = |th: f64| {
        let (s2, c2) = (th.sin().powi(2), th.cos().powi(2));
        s2 / (s2 + a2 * c2)
    };
    let b1 = u_of(0.5 * (PI / 2.0 - theta_v));
    let b2 = u_of(0.5 * (PI / 2.0 + theta_v));
    let mut result = [0.0; 2];
    for (ch, out) in result.iter_mut().enumerate() {
        let mut outer = |u: f64| {
            let pm = phi_limit(u);
            let mut inner = |phi: f64| {
                let (a, b) = integrand(u, phi);
                if ch == 0 {
                    a
                } else {
                    b
                }
            };
            adaptive(&mut inner, 0.0, pm, 1e-11) / PI
        };
        *out = adaptive(&mut outer, 0.0, b1, 1e-10) + adaptive(&mut outer, b1, b2, 1e-10);
    }
    (result[0], result[1])
}

/// Worst |error| (relative to max(1, |reference|)) of `lut_texel(n·v, r)` against
/// [`reference_lut`] over `texels` of a W×H table, with the worst texel.
pub fn worst_lut_error(
    width: u32,
    height: u32,
    texels: &[(u32, u32)],
    lut_texel: impl Fn(f32, f32) -> [f32; 2] + Sync,
) -> (f64, (u32, u32)) {
    worst_model_error(
        width,
        height,
        texels,
        splitsum::plan::lut::LutModel::SchlickGgx,
        lut_texel,
    )
}

/// [`worst_lut_error`] against [`reference_lut_model`] for `model`.
pub fn worst_model_error(
    width: u32,
    height: u32,
    texels: &[(u32, u32)],
    model: splitsum::plan::lut::LutModel,
    lut_texel: impl Fn(f32, f32) -> [f32; 2] + Sync,
) -> (f64, (u32, u32)) {
    let by_index = |i, j| {
        let (nv, r) = splitsum::plan::lut::lut_texel_coords(i, j, width, height);
        lut_texel(nv, r)
    };
    worst_model_errors(width, height, texels, model, &[&by_index])[0]
}

/// The worst error of each candidate (a function of the texel index) against one
/// evaluation of [`reference_lut_model`] per texel, and where it is.
pub fn worst_model_errors(
    width: u32,
    height: u32,
    texels: &[(u32, u32)],
    model: splitsum::plan::lut::LutModel,
    candidates: &[&(dyn Fn(u32, u32) -> [f32; 2] + Sync)],
) -> Vec<(f64, (u32, u32))> {
    use rayon::prelude::*;
    let start = vec![(0.0f64, (0, 0)); candidates.len()];
    texels
        .par_iter()
        .map(|&(i, j)| {
            let (nv, r) = splitsum::plan::lut::lut_texel_coords(i, j, width, height);
            let (ra, rb) = reference_lut_model(nv as f64, r as f64, model);
            // Relative to max(1, |reference|): every GGX model stays within [0, 1]; the
            // Charlie sheen albedo exceeds 1 near grazing n·v (22 at the 128² corner),
            // where f32 keeps about 1e-7 of the value, not of 1.
            let rel = |g: f32, r: f64| (g as f64 - r).abs() / r.abs().max(1.0);
            candidates
                .iter()
                .map(|c| {
                    let got = c(i, j);
                    (rel(got[0], ra).max(rel(got[1], rb)), (i, j))
                })
                .collect::<Vec<_>>()
        })
        .reduce(
            || start.clone(),
            |a, b| {
                a.into_iter()
                    .zip(b)
                    .map(|(a, b)| if b.0 > a.0 { b } else { a })
                    .collect()
            },
        )
}

/// Rec. 709 luminance.
pub fn luminance(c: [f64; 3]) -> f64 {
    0.2126 * c[0] + 0.7152 * c[1] + 0.0722 * c[2]
}

/// One source texel of a brute-force sum: centre direction, solid angle Ω and Y·Ω.
pub struct Term {
    pub d: [f64; 3],
    pub omega: f64,
    pub y_omega: f64,
}

/// The stride through a cube level's texel indices (face-major, row-major) at which a
/// brute-force check compares it with the full-resolution truth: every texel up to 32²,
/// every third from 64² (each truth texel is a sum over the 524 288 texels of a 1k source,
/// and a 64² level holds three times as many texels as all the smaller ones together; a
/// stride of three crosses every row and column of every face).
pub fn truth_texel_stride(n: u32) -> usize {
    if n >= 64 {
        3
    } else {
        1
    }
}

/// Every texel of an equirect at full resolution, for brute-force integrals.
pub fn equirect_terms(e: &splitsum::Equirect) -> Vec<Term> {
    use std::f64::consts::PI;
    let (w, h) = (e.width as f64, e.height as f64);
    let mut out = Vec::with_capacity(e.data.len());
    for y in 0..e.height {
        let (t0, t1) = (PI * y as f64 / h, PI * (y + 1) as f64 / h);
        let omega = 2.0 * PI / w * (t0.cos() - t1.cos());
        let theta = 0.5 * (t0 + t1);
        for x in 0..e.width {
            let phi = 2.0 * PI * ((x as f64 + 0.5) / w - 0.5);
            let l = e.get(x, y);
            out.push(Term {
                d: [
                    theta.sin() * phi.cos(),
                    theta.cos(),
                    theta.sin() * phi.sin(),
                ],
                omega,
                y_omega: luminance([0, 1, 2].map(|c| l[c] as f64)) * omega,
            });
        }
    }
    out
}

/// Σ L Ω max(0, n·l) of every texel of `e`, per channel, at each of `normals`.
pub fn brute_force_irradiance(e: &splitsum::Equirect, normals: &[[f64; 3]]) -> Vec<[f64; 3]> {
    use rayon::prelude::*;
    let terms: Vec<([f64; 3], [f64; 3])> = (0..e.data.len())
        .map(|k| {
            let (w, h) = (e.width as usize, e.height as usize);
            let (x, y) = (k % w, k / w);
            let (t0, t1) = (PI * y as f64 / h as f64, PI * (y + 1) as f64 / h as f64);
            let omega = 2.0 * PI / w as f64 * (t0.cos() - t1.cos());
            let theta = 0.5 * (t0 + t1);
            let phi = 2.0 * PI * ((x as f64 + 0.5) / w as f64 - 0.5);
            let l = e.data[k];
            (
                [
                    theta.sin() * phi.cos(),
                    theta.cos(),
                    theta.sin() * phi.sin(),
                ],
                [0, 1, 2].map(|c| l[c] as f64 * omega),
            )
        })
        .collect();
    normals
        .par_iter()
        .map(|n| {
            let mut s = [0.0; 3];
            for (d, lo) in &terms {
                let c = n[0] * d[0] + n[1] * d[1] + n[2] * d[2];
                if c > 0.0 {
                    for i in 0..3 {
                        s[i] += lo[i] * c;
                    }
                }
            }
            s
        })
        .collect()
}

/// A light's irradiance at `n`: the disc (a fine grid of cells) clipped by n's horizon.
pub fn light_irradiance(sun: &splitsum::Sun, n: [f64; 3]) -> [f64; 3] {
    let mut s = [0.0; 3];
    for (d, omega, l) in sun.disc_cells(24) {
        let c = n[0] * f64::from(d[0]) + n[1] * f64::from(d[1]) + n[2] * f64::from(d[2]);
        if c > 0.0 {
            for i in 0..3 {
                s[i] += f64::from(l[i]) * f64::from(omega) * c;
            }
        }
    }
    s
}

/// Exact solid angle of texel (i, j) of an n×n face, in f64.
pub fn texel_solid_angle(i: u32, j: u32, n: u32) -> f64 {
    let e = |x: f64, y: f64| (x * y).atan2((x * x + y * y + 1.0).sqrt());
    let inv = 2.0 / n as f64;
    let (x0, y0) = (i as f64 * inv - 1.0, j as f64 * inv - 1.0);
    let (x1, y1) = (x0 + inv, y0 + inv);
    e(x0, y0) - e(x0, y1) - e(x1, y0) + e(x1, y1)
}

/// Flux Σ L·Ω of level 0 of `cube` per channel, each texel's exact solid angle.
pub fn cube_flux(cube: &splitsum::Cubemap) -> [f64; 3] {
    let n = cube.size;
    let mut f = [0.0; 3];
    for (face, i, j, _) in splitsum::environment::walk::texel_centres(n) {
        let t = cube.texel(0, face, i, j);
        let o = texel_solid_angle(i, j, n);
        (0..3).for_each(|c| f[c] += t[c] as f64 * o);
    }
    f
}
