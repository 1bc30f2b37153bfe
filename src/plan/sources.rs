//! What the prefilter kernels read, prepared once per chain and shared by both backends:
//! the split source of the importance-sampled levels ([`SampledSource`]: the environment
//! without its hot texels, and those texels), the GGX sample table of a sampled level
//! ([`ggx_lobe_samples`]) and the texels an exact level sums ([`exact_source_texels`]).
//!
//! Filtered importance sampling (Colbert & Křivánek 2007): each sample reads the
//! environment's solid-angle-correct mip chain at lod = ½ log₂(Ωs/Ωp) + bias, Ωs =
//! 1/(N pdf) the sample's solid angle, pdf(l) = D(n·h)/4 for n = v, Ωp the solid angle of a
//! level-0 texel. A tiny bright sun is thus read from a mip where it is spread over the
//! lobe: smooth lobes, no fireflies.

use std::f32::consts::PI;

use crate::environment::hot::hottest_texels;
use crate::environment::sample::BorderedCube;
use crate::environment::texels::{source_texels, SourceTexel};
use crate::environment::{Cubemap, IrradianceSource};
use crate::math::brdf::{alpha_from_roughness, d_ggx};
use crate::math::color::luminance;
use crate::math::sampling::{hammersley, importance_sample_ggx};
use crate::plan::chain::EXACT_MAX_SOURCE;

/// Lod bias of filtered importance sampling. Colbert & Křivánek add +1 (one level blurrier
/// than the pdf suggests) to hide sample structure; against a brute-force convolution of
/// quarry_01_1k.hdr at r = 1/7, 128 samples, +1 gives 7.3 % energy-weighted error and 0
/// gives 4.7 % with no visible structure (tests/specular.rs checks for fireflies), so 0.
pub const LOD_BIAS: f32 = 0.0;

/// The environment for the importance-sampled levels, split in two: `rest`, the
/// environment with its hot texels (a sun, bright lamps) blacked out and its mips
/// rebuilt, which filtered importance sampling handles well because its dynamic range is
/// low; and `hot`, those texels (of the ≤ 64² mip, with their radiance centroids), which
/// are summed exactly. Sampling a tiny sun through filtered lookups either misses it or
/// smears it over a coarse mip; summing it exactly does neither.
#[derive(Clone, Debug)]
pub struct SampledSource {
    /// The environment without its hot texels, with every mip.
    pub rest: Cubemap,
    /// `rest` with a border around each face, which the CPU's lookups read
    /// ([`BorderedCube`]: the same values, faster).
    pub bordered: BorderedCube,
    /// The hot texels.
    pub hot: Vec<SourceTexel>,
}

/// Splits `env` (with every mip) into [`SampledSource`].
pub fn split_hot_texels(env: &Cubemap) -> SampledSource {
    let m = (0..env.levels.len())
        .find(|&m| env.level_size(m) <= EXACT_MAX_SOURCE)
        .unwrap_or(env.levels.len() - 1);
    let n = env.level_size(m);
    let texels = source_texels(env, m);
    let lum = |t: &SourceTexel| luminance([t.radiance[0], t.radiance[1], t.radiance[2]]);
    let mean = texels
        .iter()
        .map(|t| (lum(t) * t.dir_omega[3]) as f64)
        .sum::<f64>()
        / (4.0 * std::f64::consts::PI);
    let hot = hottest_texels(
        (0..texels.len()).map(|k| {
            let y = lum(&texels[k]);
            (k, y as f64, (y * texels[k].dir_omega[3]) as f64)
        }),
        mean,
    );
    let mut level0 = env.levels[0].clone();
    let (n0, k) = (env.size, env.size / n);
    for &idx in &hot {
        let (face, j, i) = (
            (idx as u32) / (n * n),
            (idx as u32 % (n * n)) / n,
            idx as u32 % n,
        );
        for cj in j * k..(j + 1) * k {
            for ci in i * k..(i + 1) * k {
                level0[((face * n0 + cj) * n0 + ci) as usize] = [0.0, 0.0, 0.0, 1.0];
            }
        }
    }
    let mut rest = Cubemap {
        size: env.size,
        levels: vec![level0],
    };
    crate::environment::mips::build_mips(&mut rest, env.levels.len() as u32);
    SampledSource {
        bordered: BorderedCube::new(&rest),
        rest,
        hot: hot.into_iter().map(|k| texels[k]).collect(),
    }
}

/// The filtered-importance samples of the GGX lobe at `roughness` around n = v, in the
/// tangent frame of n (z along n), each `[l.x, l.y, l.z = n·l, lod]`: l = reflect(−n, h)
/// for the i-th of `samples` Hammersley half vectors h, read at
/// lod = ½ log₂(Ωs / Ωp) + [`LOD_BIAS`], where Ωs = 1 / (N pdf(l)) is the sample's solid
/// angle and Ωp = 4π / (6 n²) a level-0 texel's (n = `env_size`). Samples below the
/// horizon (n·l ≤ 0) are left out. They depend on nothing else, so a level computes them
/// once and every texel only rotates them; the GPU kernel reads the same table.
pub fn ggx_lobe_samples(samples: u32, roughness: f32, env_size: u32) -> Vec<[f32; 4]> {
    let alpha = alpha_from_roughness(roughness);
    let omega_p = 4.0 * PI / (6.0 * (env_size * env_size) as f32);
    (0..samples)
        .filter_map(|i| {
            let h = importance_sample_ggx(hammersley(i, samples), alpha);
            let n_dot_h = h[2];
            // l = 2 (n·h) h − n, with n = (0, 0, 1).
            let l = [
                2.0 * n_dot_h * h[0],
                2.0 * n_dot_h * h[1],
                2.0 * n_dot_h * n_dot_h - 1.0,
            ];
            // pdf(l) = D(n·h) (n·h) / (4 v·h) = D / 4 for v = n.
            let pdf = d_ggx(n_dot_h, alpha) * 0.25;
            let omega_s = 1.0 / (samples as f32 * pdf);
            let lod = 0.5 * (omega_s / omega_p).log2() + LOD_BIAS;
            (l[2] > 0.0).then_some([l[0], l[1], l[2], lod])
        })
        .collect()
}

/// The texels an exact-sum level reads: every texel of mip `source_mip` of `env` or, with
/// the split source of the bake (`split`: the cold cube and the hot cells at the source's
/// resolution, see [`crate::environment::hot`]), the cold cube's mip of that size and the
/// hot cells, which add to the numerator only (the cold texels already count their solid
/// angle). A sun then keeps its true position inside a lobe that a small mip's texels
/// would blur (quarry_01 in a 64² chain at r = 1/4: 1.38 % → see `tests/lookup.rs`).
pub fn exact_source_texels(
    env: &Cubemap,
    split: Option<&IrradianceSource>,
    source_mip: usize,
) -> Vec<SourceTexel> {
    let n = env.level_size(source_mip);
    let Some(split) = split.filter(|s| s.cold.size >= n) else {
        return source_texels(env, source_mip);
    };
    let m = (split.cold.size / n).trailing_zeros() as usize;
    let mut texels = source_texels(&split.cold, m);
    texels.extend(split.hot.iter().map(|c| {
        let omega = c.radiance_omega[3];
        let d = c.dir_sin2;
        SourceTexel {
            dir_omega: [d[0], d[1], d[2], omega],
            radiance: [
                c.radiance_omega[0] / omega,
                c.radiance_omega[1] / omega,
                c.radiance_omega[2] / omega,
                0.0,
            ],
        }
    }));
    texels
}
