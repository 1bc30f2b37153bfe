//! The search itself: candidate clusters, the core, region and ring of one, the fill
//! fitted to the ring and the light measured from what the fill leaves (see the module
//! above for the estimator).

use rayon::prelude::*;

use crate::environment::sun::grid::{angle, dot, luminance, normalize, tangent_frame, Grid};
use crate::environment::sun::{
    Sun, SunFit, CLIP_AREA, CLIP_TEXELS, CLIP_TOLERANCE, CORE_FRACTION, HALO_TEXELS, HOT_FACTOR,
    MAX_CANDIDATE_TEXELS, MAX_CLUSTERS, MAX_SUN_RADIUS_DEG, MIN_SHARE, RING_TEXELS,
    SEARCH_RADIUS_DEG,
};

pub(crate) struct FluxStats {
    /// Σ Y Ω over the finite texels.
    pub(crate) flux: f64,
}

/// Texels a parallel pass gives each task; the partial sums are added in order, so the
/// result does not depend on the thread count.
const CHUNK: usize = 1 << 16;

/// The texel ranges of the parallel passes, in order.
fn chunks(grid: &Grid) -> impl IndexedParallelIterator<Item = std::ops::Range<usize>> {
    let n = grid.len();
    (0..n.div_ceil(CHUNK))
        .into_par_iter()
        .map(move |c| c * CHUNK..((c + 1) * CHUNK).min(n))
}

pub(crate) fn flux_stats(grid: &Grid) -> FluxStats {
    let partial: Vec<f64> = chunks(grid)
        .map(|r| {
            r.map(|k| luminance(grid.radiance(k)) * grid.solid_angle(k))
                .sum()
        })
        .collect();
    FluxStats {
        flux: partial.iter().sum(),
    }
}

/// The candidate clusters' brightest texels, the most energetic cluster first (those
/// holding at least [`MIN_SHARE`] of `flux`, at most [`MAX_CLUSTERS`]).
pub(crate) fn clusters(grid: &Grid, mean: f64, flux: f64) -> Vec<usize> {
    let threshold = HOT_FACTOR * mean;
    let mut hot: Vec<(usize, f64)> = chunks(grid)
        .flat_map_iter(|r| {
            r.filter_map(|k| {
                let y = luminance(grid.radiance(k));
                (y > threshold).then_some((k, y))
            })
        })
        .collect();
    let by_brightness =
        |a: &(usize, f64), b: &(usize, f64)| b.1.total_cmp(&a.1).then(a.0.cmp(&b.0));
    if hot.len() > MAX_CANDIDATE_TEXELS {
        hot.select_nth_unstable_by(MAX_CANDIDATE_TEXELS, by_brightness);
        hot.truncate(MAX_CANDIDATE_TEXELS);
    }
    hot.sort_by(by_brightness);
    let cos_search = SEARCH_RADIUS_DEG.to_radians().cos();
    // (seed texel, its direction, the cluster's flux)
    let mut seeds: Vec<(usize, [f64; 3], f64)> = Vec::new();
    for (k, y) in hot {
        let d = grid.direction(k);
        let e = y * grid.solid_angle(k);
        match seeds.iter_mut().find(|s| dot(s.1, d) >= cos_search) {
            Some(s) => s.2 += e,
            None => seeds.push((k, d, e)),
        }
    }
    seeds.sort_by(|a, b| b.2.total_cmp(&a.2).then(a.0.cmp(&b.0)));
    seeds
        .into_iter()
        .filter(|s| s.2 >= MIN_SHARE * flux)
        .take(MAX_CLUSTERS)
        .map(|s| s.0)
        .collect()
}

/// The sun around candidate texel `seed`, if its core is compact and it holds enough of
/// `flux`.
pub(crate) fn fit_sun(grid: &Grid, seed: usize, flux: f64) -> Option<SunFit> {
    let seed_dir = grid.direction(seed);
    let search = grid.cap(seed_dir, SEARCH_RADIUS_DEG.to_radians());
    let peak = search
        .iter()
        .map(|&k| luminance(grid.radiance(k)))
        .fold(0.0, f64::max);
    if peak <= 0.0 {
        return None;
    }
    let core: Vec<usize> = search
        .iter()
        .copied()
        .filter(|&k| luminance(grid.radiance(k)) >= CORE_FRACTION * peak)
        .collect();
    let centre = flux_centre(grid, &core);
    // A texel's angular size where the sun is: √Ω of its brightest texel.
    let texel = grid.solid_angle(seed).sqrt();
    let core_radius = core
        .iter()
        .map(|&k| angle(grid.direction(k), centre))
        .fold(0.0, f64::max)
        + texel * std::f64::consts::FRAC_1_SQRT_2;
    if core_radius > MAX_SUN_RADIUS_DEG.to_radians() {
        return None;
    }
    let plateau: Vec<usize> = core
        .iter()
        .copied()
        .filter(|&k| luminance(grid.radiance(k)) >= (1.0 - CLIP_TOLERANCE) * peak)
        .collect();

    let region_radius = core_radius + HALO_TEXELS * texel;
    let outer = region_radius + RING_TEXELS * texel;
    let (t1, t2) = tangent_frame(centre);
    let gnomonic = |d: [f64; 3]| {
        let z = dot(d, centre).max(1e-6);
        (dot(d, t1) / z, dot(d, t2) / z)
    };
    let mut region = Vec::new();
    let mut ring = Vec::new();
    for k in grid.cap(centre, outer) {
        if angle(grid.direction(k), centre) <= region_radius {
            region.push(k);
        } else {
            ring.push(k);
        }
    }
    let plane = fit_plane(grid, &ring, &gnomonic);

    let Filled {
        fill,
        irradiance,
        moment,
        ..
    } = fill_region(grid, &region, &plane, &gnomonic);
    let share = luminance(irradiance) / flux;
    if share.is_nan() || share < MIN_SHARE {
        return None;
    }
    let direction = normalize(moment);
    let (mut m2, mut weight) = (0.0, 0.0);
    for (&k, f) in region.iter().zip(&fill) {
        let d = grid.direction(k);
        let l = grid.radiance(k);
        let net: [f64; 3] = std::array::from_fn(|c| l[c] - f64::from(f[c]));
        let w = luminance(net) * grid.solid_angle(k);
        let g = angle(d, direction);
        m2 += w * g * g;
        weight += w;
    }
    // The moment of texel centres is the disc's plus a texel's own, (h_x² + h_y²)/12
    // (sampling the disc convolved with the texel's box): taken off, so a disc narrower
    // than a texel is measured as itself.
    let (hx, hy) = grid.texel_extent(seed);
    let texel_moment = (hx * hx + hy * hy) / 12.0;
    let m2 = m2 / weight.max(f64::MIN_POSITIVE);
    // A light no wider than its texels (one lit texel: m2 = 0) is a disc of its brightest
    // texel's solid angle, never one of 0 sr (its radiance E⊥/Ω would be infinite).
    let texel_cap = cap_radius(grid.solid_angle(seed));
    let radius = (2.0 * (m2 - texel_moment).max(0.25 * m2))
        .sqrt()
        .max(texel_cap);
    let solid_angle = 2.0 * std::f64::consts::PI * (1.0 - radius.cos());
    let plateau_omega: f64 = plateau.iter().map(|&k| grid.solid_angle(k)).sum();
    let clipped = plateau.len() >= CLIP_TEXELS && plateau_omega >= CLIP_AREA * solid_angle;
    Some(SunFit {
        sun: Sun {
            direction: direction.map(|v| v as f32),
            irradiance: irradiance.map(|v| v as f32),
            solid_angle_sr: solid_angle as f32,
            angular_radius_deg: radius.to_degrees() as f32,
            share: share as f32,
            clipped,
            texels: region.len(),
            region_radius_deg: region_radius.to_degrees() as f32,
            shape: None,
        },
        region,
        fill,
    })
}

/// The angular radius of a spherical cap of solid angle `omega` (Ω = 2π (1 − cos ρ)).
fn cap_radius(omega: f64) -> f64 {
    (1.0 - omega / (2.0 * std::f64::consts::PI))
        .clamp(-1.0, 1.0)
        .acos()
}

/// A region filled: per texel the fill and the net luminance Y(L − fill) it leaves, and
/// over the region E⊥ = Σ (L − fill) Ω per channel and the first moment Σ Y_net Ω l.
pub(super) struct Filled {
    pub(super) fill: Vec<[f32; 3]>,
    pub(super) net: Vec<f64>,
    pub(super) irradiance: [f64; 3],
    pub(super) moment: [f64; 3],
}

/// `region` filled from `plane` (in the `gnomonic` coordinates it was fitted in).
pub(super) fn fill_region(
    grid: &Grid,
    region: &[usize],
    plane: &Plane,
    gnomonic: &dyn Fn([f64; 3]) -> (f64, f64),
) -> Filled {
    let mut out = Filled {
        fill: Vec::with_capacity(region.len()),
        net: Vec::with_capacity(region.len()),
        irradiance: [0.0; 3],
        moment: [0.0; 3],
    };
    for &k in region {
        let (d, l, omega) = (grid.direction(k), grid.radiance(k), grid.solid_angle(k));
        // The fill never brightens a texel: the residual is nowhere above the input, and
        // the light is non-negative in every channel.
        let f = plane.at(gnomonic(d));
        let f: [f64; 3] = std::array::from_fn(|c| f[c].min(l[c]));
        let net: [f64; 3] = std::array::from_fn(|c| l[c] - f[c]);
        let y = luminance(net);
        for (e, n) in out.irradiance.iter_mut().zip(net) {
            *e += n * omega;
        }
        for (m, di) in out.moment.iter_mut().zip(d) {
            *m += y * omega * di;
        }
        out.fill.push(f.map(|v| v as f32));
        out.net.push(y);
    }
    out
}

/// The flux-weighted centre of `texels` (their radiance as it is).
pub(super) fn flux_centre(grid: &Grid, texels: &[usize]) -> [f64; 3] {
    let mut c = [0.0; 3];
    for &k in texels {
        let w = luminance(grid.radiance(k)) * grid.solid_angle(k);
        let d = grid.direction(k);
        for i in 0..3 {
            c[i] += w * d[i];
        }
    }
    normalize(c)
}

/// A per-channel plane a + b x + c y over gnomonic coordinates, clamped to a range.
pub(super) struct Plane {
    coef: [[f64; 3]; 3],
    low: [f64; 3],
    high: [f64; 3],
}

impl Plane {
    pub(super) fn at(&self, (x, y): (f64, f64)) -> [f64; 3] {
        std::array::from_fn(|c| {
            let [a, b, d] = self.coef[c];
            (a + b * x + d * y).clamp(self.low[c], self.high[c])
        })
    }
}

/// The weighted (Ω) least-squares plane through the ring's texels per channel; their mean
/// when the ring is too small or degenerate for a plane.
pub(super) fn fit_plane(grid: &Grid, ring: &[usize], gnomonic: &dyn Fn([f64; 3]) -> (f64, f64)) -> Plane {
    let mut m = [[0.0f64; 3]; 3];
    let mut rhs = [[0.0f64; 3]; 3];
    let (mut low, mut high) = ([f64::INFINITY; 3], [0.0f64; 3]);
    for &k in ring {
        let (x, y) = gnomonic(grid.direction(k));
        let w = grid.solid_angle(k);
        let basis = [1.0, x, y];
        let l = grid.radiance(k);
        for i in 0..3 {
            for j in 0..3 {
                m[i][j] += w * basis[i] * basis[j];
            }
            for c in 0..3 {
                rhs[c][i] += w * basis[i] * l[c];
            }
        }
        for c in 0..3 {
            low[c] = low[c].min(l[c]);
            high[c] = high[c].max(l[c]);
        }
    }
    if ring.is_empty() {
        return Plane {
            coef: [[0.0; 3]; 3],
            low: [0.0; 3],
            high: [0.0; 3],
        };
    }
    let mean = |c: usize| rhs[c][0] / m[0][0];
    let coef = match (ring.len() >= 6).then(|| solve3(m, rhs)).flatten() {
        Some(coef) => coef,
        None => std::array::from_fn(|c| [mean(c), 0.0, 0.0]),
    };
    Plane { coef, low, high }
}

/// Solves m · x = `rhs[c]` for each channel c by Cramer's rule; `None` when m is singular.
fn solve3(m: [[f64; 3]; 3], rhs: [[f64; 3]; 3]) -> Option<[[f64; 3]; 3]> {
    let det = |a: [[f64; 3]; 3]| {
        a[0][0] * (a[1][1] * a[2][2] - a[1][2] * a[2][1])
            - a[0][1] * (a[1][0] * a[2][2] - a[1][2] * a[2][0])
            + a[0][2] * (a[1][0] * a[2][1] - a[1][1] * a[2][0])
    };
    let d = det(m);
    let scale = m[0][0] * m[1][1] * m[2][2];
    if d.is_nan() || d.abs() <= 1e-12 * scale.abs() {
        return None;
    }
    Some(std::array::from_fn(|c| {
        std::array::from_fn(|col| {
            let mut a = m;
            for row in 0..3 {
                a[row][col] = rhs[c][row];
            }
            det(a) / d
        })
    }))
}
