//! CPU reference for `shaders/prefilter_specular.wgsl`: the split-sum prefiltered radiance
//! (Karis 2013), with n = v = r, for mip m of M at the roughness its [`MipRoughness`] maps
//! it to (r = m/(M − 1) for generic and Bevy bakes).
//!
//! Estimator: P(n) = Σ L(lᵢ) (n·lᵢ) / Σ (n·lᵢ), lᵢ = reflect(−n, hᵢ) with hᵢ GGX-distributed
//! (Hammersley points), which converges to ∫ L D (n·l) dl / ∫ D (n·l) dl. The samples
//! depend only on the level, so they are computed once per level in n's tangent frame
//! ([`ggx_lobe_samples`]) and rotated to each texel. Filtered
//! importance sampling (Colbert & Křivánek 2007): each sample reads the environment's
//! solid-angle-correct mip chain at lod = ½ log₂(Ωs/Ωp) + bias, Ωs = 1/(N pdf) the sample's
//! solid angle, pdf(l) = D(n·h)/4 for n = v, Ωp the solid angle of a level-0 texel. A
//! tiny bright sun is thus read from a mip where it is spread over the lobe: smooth lobes,
//! no fireflies.

use std::f32::consts::PI;

use crate::cpu::cube_sample::BorderedCube;
use crate::cpu::equirect_to_cube::fill_cube_level;
use crate::cpu::irradiance::{source_texels, SourceTexel};
use crate::environment::{Cubemap, IrradianceSource};
use crate::math::brdf::{alpha_from_roughness, d_ggx, ggx_prefilter_weight};
use crate::math::cubemap::cube_texel_direction;
use crate::math::sampling::{hammersley, importance_sample_ggx, tangent_frame};

/// Lod bias of filtered importance sampling. Colbert & Křivánek add +1 (one level blurrier
/// than the pdf suggests) to hide sample structure; against a brute-force convolution of
/// quarry_01_1k.hdr at r = 1/7, 128 samples, +1 gives 7.3 % energy-weighted error and 0
/// gives 4.7 % with no visible structure (tests/specular.rs checks for fireflies), so 0.
pub const LOD_BIAS: f32 = 0.0;

/// Default GGX samples per texel and level. Measured by `prefilter_accuracy_scan`
/// (tests/specular.rs) on the sampled r = 1/7 level of a 128² chain, energy-weighted error
/// against brute force: 32 samples 0.51 % (quarry), 64: 0.39 % (quarry) and 0.99 %
/// (studio_small_03), 128: 0.30 % and 0.90 %. 64 halves the time of the sampled levels
/// (the bulk of a default bake) for about 0.1 point.
pub const DEFAULT_SAMPLES: u32 = 64;

/// How a chain's mips map to perceptual roughness, and back: a shader reads roughness r at
/// `lod(r)`, and mip m is prefiltered at `roughness(m)`, its inverse.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum MipRoughness {
    /// r = m/(M − 1), lod = r·(M − 1) (DESIGN.md; Bevy's `environment_map.wgsl`,
    /// glTF-IBL-Sampler).
    Linear,
    /// r = 1 − √(1 − m/(M − 1)), lod = (M − 1)·r·(2 − r): three.js r187's PMREM
    /// (`PMREMGenerator` `lodToRoughness`, `roughnessToMip` in
    /// envmap_common_pars_fragment) and Filament's `perceptualRoughnessToLod`.
    Quadratic,
    /// Babylon.js, for a full chain of level-0 edge N = 2^(M − 1): mip m > 0 holds GGX at
    /// α = 2^(m/s) / N (`HDRFiltering`, s = [`BABYLON_LOD_SCALE`]; m = 0 the environment),
    /// r = √min(α, 1), and the shader reads lod = s·log2(N·(r² + ε)), ε =
    /// [`BABYLON_MINIMUM_VARIANCE`] (`getLodFromAlphaG`, `convertRoughnessToAverageSlope`).
    Babylon,
}

/// Babylon's `lodGenerationScale`, the default of its own prefiltering and what splitsum
/// writes into a `.env`.
pub const BABYLON_LOD_SCALE: f32 = 0.8;
/// Babylon's `MINIMUMVARIANCE`, added to r² to make the shader's α.
pub const BABYLON_MINIMUM_VARIANCE: f32 = 0.0005;

impl MipRoughness {
    /// Roughness of mip `m` of a chain of `levels`.
    pub fn roughness(self, m: u32, levels: u32) -> f32 {
        if levels <= 1 {
            return 0.0;
        }
        let t = m as f32 / (levels - 1) as f32;
        match self {
            MipRoughness::Linear => t,
            MipRoughness::Quadratic => 1.0 - (1.0 - t).max(0.0).sqrt(),
            MipRoughness::Babylon if m == 0 => 0.0,
            MipRoughness::Babylon => {
                let alpha = (m as f32 / BABYLON_LOD_SCALE - (levels - 1) as f32).exp2();
                alpha.min(1.0).sqrt()
            }
        }
    }

    /// The lod a shader reads roughness `r` at, in a chain of `levels`.
    pub fn lod(self, r: f32, levels: u32) -> f32 {
        let r = r.clamp(0.0, 1.0);
        let max_lod = levels.saturating_sub(1) as f32;
        match self {
            MipRoughness::Linear => r * max_lod,
            MipRoughness::Quadratic => r * (2.0 - r) * max_lod,
            MipRoughness::Babylon => (BABYLON_LOD_SCALE
                * (max_lod + (r * r + BABYLON_MINIMUM_VARIANCE).log2()))
            .clamp(0.0, max_lod),
        }
    }

    /// The mapping as written in manifests.
    pub fn formula(self) -> &'static str {
        match self {
            MipRoughness::Linear => "m / (levels - 1)",
            MipRoughness::Quadratic => "1 - sqrt(1 - m / (levels - 1))",
            MipRoughness::Babylon => {
                "sqrt(min(1, 2^(m / 0.8) / size)) for m > 0 (Babylon's lodGenerationScale 0.8), 0 for m = 0"
            }
        }
    }
}

/// The layout of a prefiltered chain: how many levels and the roughness of each.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct SpecularChain {
    /// Number of levels M (level 0 is the environment itself, r = 0).
    pub levels: u32,
    /// Roughness of each level.
    pub roughness: MipRoughness,
}

impl SpecularChain {
    /// `levels` levels at r = m/(M − 1).
    pub fn linear(levels: u32) -> Self {
        SpecularChain {
            levels,
            roughness: MipRoughness::Linear,
        }
    }

    /// Roughness of mip `m`.
    pub fn mip_roughness(&self, m: u32) -> f32 {
        self.roughness.roughness(m, self.levels)
    }
}

/// Roughness of mip `m` of a linear chain of `levels` (DESIGN.md: r = m / (M − 1)).
pub fn mip_roughness(m: u32, levels: u32) -> f32 {
    MipRoughness::Linear.roughness(m, levels)
}

/// A texel is "hot" when its radiance exceeds this multiple of the environment's mean.
pub const HOT_FACTOR: f32 = 16.0;
/// At most this many hot texels (the most energetic) are split off.
pub const MAX_HOT_TEXELS: usize = 512;

/// Indices of the texels whose luminance exceeds [`HOT_FACTOR`] × `mean`, at most
/// [`MAX_HOT_TEXELS`], most energetic first; `texels` yields (index, luminance, energy =
/// luminance × Ω). Equal energies keep index order, so the choice is deterministic. Shared
/// by the sampled levels' split ([`split_hot_texels`]) and the irradiance source's
/// ([`crate::environment::hot`]).
pub fn hottest_texels(texels: impl Iterator<Item = (usize, f64, f64)>, mean: f64) -> Vec<usize> {
    let mut hot: Vec<(usize, f64)> = texels
        .filter(|&(_, y, _)| y > HOT_FACTOR as f64 * mean)
        .map(|(k, _, e)| (k, e))
        .collect();
    hot.sort_by(|a, b| b.1.total_cmp(&a.1).then(a.0.cmp(&b.0)));
    hot.truncate(MAX_HOT_TEXELS);
    hot.into_iter().map(|h| h.0).collect()
}

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
    let lum =
        |t: &SourceTexel| 0.2126 * t.radiance[0] + 0.7152 * t.radiance[1] + 0.0722 * t.radiance[2];
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
    crate::cpu::cube_downsample::build_mips(&mut rest, env.levels.len() as u32);
    SampledSource {
        bordered: BorderedCube::new(&rest),
        rest,
        hot: hot.into_iter().map(|k| texels[k]).collect(),
    }
}

/// The exact part of a sampled texel: Σ L Ω (n·l) pdf(l) over the hot texels, with
/// pdf(l) = D(n·h)/4 (the density the samples are drawn from, for v = n).
pub fn hot_texels_sum(hot: &[SourceTexel], n: [f32; 3], alpha: f32) -> [f32; 3] {
    let mut sum = [0.0f32; 3];
    for t in hot {
        let l = t.dir_omega;
        let n_dot_l = n[0] * l[0] + n[1] * l[1] + n[2] * l[2];
        if n_dot_l > 0.0 {
            let n_dot_h = (0.5 * (1.0 + n_dot_l)).sqrt();
            let w = l[3] * n_dot_l * d_ggx(n_dot_h, alpha) * 0.25;
            for (s, r) in sum.iter_mut().zip(&t.radiance) {
                *s += w * r;
            }
        }
    }
    sum
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

/// Prefiltered radiance around unit direction `n`: filtered importance sampling of
/// `src.rest` with the `lobe` of [`ggx_lobe_samples`] (drawn from `samples` points) plus
/// the exact sum of `src.hot` at `roughness`, both over the sampled normaliser:
/// (Σᵢ L(lᵢ)(n·lᵢ) + N·Σ_hot) / Σᵢ (n·lᵢ).
pub fn prefilter_texel(
    src: &SampledSource,
    n: [f32; 3],
    roughness: f32,
    lobe: &[[f32; 4]],
    samples: u32,
) -> [f32; 4] {
    let (t, b) = tangent_frame(n);
    let mut sum = [0.0f32; 3];
    let mut weight = 0.0f32;
    for s in lobe {
        let l = [0, 1, 2].map(|k| t[k] * s[0] + b[k] * s[1] + n[k] * s[2]);
        let v = src.bordered.sample_lod(l, s[3]);
        for c in 0..3 {
            sum[c] += v[c] * s[2];
        }
        weight += s[2];
    }
    let hot = hot_texels_sum(&src.hot, n, alpha_from_roughness(roughness));
    let k = samples as f32;
    [
        (sum[0] + k * hot[0]) / weight,
        (sum[1] + k * hot[1]) / weight,
        (sum[2] + k * hot[2]) / weight,
        1.0,
    ]
}

/// Exact prefiltered radiance around unit `n`: Σ L D(n·h) (n·l) Ω / Σ D(n·h) (n·l) Ω over
/// every texel of a source mip, h = normalize(n + l). No noise and no leak of a bright sun
/// beyond its true lobe; used where the lobe is wide enough that a small mip resolves it.
pub fn prefilter_exact_texel(source: &[SourceTexel], n: [f32; 3], roughness: f32) -> [f32; 4] {
    let alpha = alpha_from_roughness(roughness);
    prefilter_lobe_texel(source, n, |n_dot_l| ggx_prefilter_weight(n_dot_l, alpha))
}

/// Σ L w(n·l) Ω / Σ w(n·l) Ω over the texels of `source` above n's horizon, for a lobe
/// weight `lobe` (D times n·l with n = v: [`ggx_prefilter_weight`], or
/// [`crate::math::brdf::charlie_prefilter_weight`] for sheen). A hot cell's normaliser
/// weight (`radiance[3]`) is 0: it adds light, not solid angle. The GPU mirror is
/// `prefilter_lobe_texel` in `shaders/convolve_exact.wgsl`.
pub fn prefilter_lobe_texel(
    source: &[SourceTexel],
    n: [f32; 3],
    lobe: impl Fn(f32) -> f32,
) -> [f32; 4] {
    let mut sum = [0.0f32; 3];
    let mut weight = 0.0f32;
    for t in source {
        let l = t.dir_omega;
        let n_dot_l = n[0] * l[0] + n[1] * l[1] + n[2] * l[2];
        if n_dot_l > 0.0 {
            let w = lobe(n_dot_l) * l[3];
            for (sc, lc) in sum.iter_mut().zip(&t.radiance) {
                *sc += w * lc;
            }
            weight += w * t.radiance[3];
        }
    }
    [sum[0] / weight, sum[1] / weight, sum[2] / weight, 1.0]
}

/// Lanes of [`ExactSource`]: eight f32, one AVX register or two SSE ones.
const LANES: usize = 8;

/// The texels of an exact sum as a structure of arrays in lanes of [`LANES`] (the last
/// lane group padded with texels of zero solid angle), so that the sum over them runs
/// branch-free and vectorises: [`ExactSource::prefilter`] computes
/// [`prefilter_exact_texel`] several times faster. The GPU kernel and the reference keep
/// the texel-by-texel loop.
pub struct ExactSource {
    /// Direction x, y, z and solid angle Ω, per lane group.
    dir_omega: Vec<[[f32; LANES]; 4]>,
    /// Radiance r, g, b and normaliser weight, per lane group.
    radiance: Vec<[[f32; LANES]; 4]>,
}

impl ExactSource {
    /// Packs `texels` into lanes.
    pub fn new(texels: &[SourceTexel]) -> Self {
        let groups = texels.len().div_ceil(LANES);
        let mut dir_omega = vec![[[0.0; LANES]; 4]; groups];
        let mut radiance = vec![[[0.0; LANES]; 4]; groups];
        for (k, t) in texels.iter().enumerate() {
            for c in 0..4 {
                dir_omega[k / LANES][c][k % LANES] = t.dir_omega[c];
                radiance[k / LANES][c][k % LANES] = t.radiance[c];
            }
        }
        ExactSource {
            dir_omega,
            radiance,
        }
    }

    /// [`prefilter_exact_texel`] over these texels. The same sum, with D(n·h) taken from
    /// (n·h)² = (1 + n·l)/2 directly and without its constant factor α²/π, which cancels
    /// in the ratio; texels below the horizon get weight 0 through max(n·l, 0) instead of
    /// a branch. Each lane keeps its own partial sums, added at the end.
    pub fn prefilter(&self, n: [f32; 3], roughness: f32) -> [f32; 4] {
        #[cfg(target_arch = "x86_64")]
        if std::is_x86_feature_detected!("avx") {
            // SAFETY: the CPU has AVX, checked just above.
            return unsafe { self.prefilter_avx(n, roughness) };
        }
        self.prefilter_lanes(n, roughness)
    }

    /// [`Self::prefilter_lanes`] compiled for AVX: one register per lane group instead of
    /// two SSE ones. Without FMA, so every lane does the same IEEE operations in the same
    /// order as the SSE build and the result is bit-identical on every x86-64 machine.
    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx")]
    fn prefilter_avx(&self, n: [f32; 3], roughness: f32) -> [f32; 4] {
        self.prefilter_lanes(n, roughness)
    }

    /// The lane sum itself (see [`Self::prefilter`]).
    #[inline(always)]
    fn prefilter_lanes(&self, n: [f32; 3], roughness: f32) -> [f32; 4] {
        let alpha = alpha_from_roughness(roughness);
        let k = alpha * alpha - 1.0;
        self.lobe_sum(n, |n_dot_l, omega| {
            // D(n·h) ∝ 1 / ((n·h)² (α² − 1) + 1)², (n·h)² = (1 + n·l) / 2
            let q = (0.5 + 0.5 * n_dot_l) * k + 1.0;
            n_dot_l * omega / (q * q)
        })
    }

    /// Σ L w / Σ w over these texels, `lobe(n·l, Ω)` giving a texel's weight w (the lobe
    /// times the solid angle) from its n·l, clamped at 0 (a texel below the horizon must
    /// get weight 0 from `lobe`), and its solid angle. Each lane keeps its own partial
    /// sums, added at the end; a `lobe` without calls or loops vectorises across lanes.
    #[inline(always)]
    pub fn lobe_sum(&self, n: [f32; 3], lobe: impl Fn(f32, f32) -> f32) -> [f32; 4] {
        let mut acc = [[0.0f32; LANES]; 4];
        for (d, rad) in self.dir_omega.iter().zip(&self.radiance) {
            for l in 0..LANES {
                let n_dot_l = (n[0] * d[0][l] + n[1] * d[1][l] + n[2] * d[2][l]).max(0.0);
                let w = lobe(n_dot_l, d[3][l]);
                for c in 0..4 {
                    acc[c][l] += w * rad[c][l];
                }
            }
        }
        let total = acc.map(|lanes| lanes.iter().sum::<f32>());
        [
            total[0] / total[3],
            total[1] / total[3],
            total[2] / total[3],
            1.0,
        ]
    }
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

/// How one prefiltered level is computed.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum LevelMethod {
    /// Exact sum over every texel of source mip `source_mip`.
    Exact {
        /// The source mip read.
        source_mip: u32,
    },
    /// Filtered importance sampling with this many samples per texel.
    Sampled {
        /// GGX samples per texel.
        samples: u32,
    },
}

/// Largest exact-sum cost (output texels × source texels) per level before importance
/// sampling is used instead (~2e8 weighted sums: ~0.6 CPU-s on this machine).
pub const EXACT_BUDGET: u64 = 200_000_000;

/// Source texels per GGX α in the exact sum: the source mip's texel angle (π/2)/n is at
/// most α / `EXACT_TEXELS_PER_ALPHA`, so D varies little across a texel.
pub const EXACT_TEXELS_PER_ALPHA: f32 = 16.0;

/// Largest source mip edge of an exact sum. 6·64² texels × 32 bytes = 768 KiB of storage
/// buffer: Mesa's lavapipe (22.3) silently reads zeros past the first 2 MiB of a storage
/// binding (found by `tests/specular.rs`), whatever limit it reports.
pub const EXACT_MAX_SOURCE: u32 = 64;

/// Picks the method for output mip `m` (at roughness `r`) of an `env_size` chain: the exact sum over the
/// smallest source mip fine enough for the lobe (texel angle ≤ α/16) when it fits
/// [`EXACT_BUDGET`], else filtered importance sampling.
pub fn level_method(env_size: u32, m: u32, r: f32, samples: u32) -> LevelMethod {
    let alpha = alpha_from_roughness(r);
    let out = (env_size >> m).max(1) as u64;
    // Smallest power of two n with (π/2)/n ≤ α/K, at most the environment's size.
    // (Clamped before the integer conversion: α = 0 asks for an infinitely fine mip.)
    let needed = (EXACT_TEXELS_PER_ALPHA * PI / (2.0 * alpha))
        .clamp(1.0, env_size as f32)
        .ceil() as u32;
    let n = needed
        .next_power_of_two()
        .min(env_size)
        .min(EXACT_MAX_SOURCE) as u64;
    let cost = 6 * out * out * 6 * n * n;
    if cost <= EXACT_BUDGET {
        LevelMethod::Exact {
            source_mip: (env_size as u64 / n).trailing_zeros(),
        }
    } else {
        LevelMethod::Sampled { samples }
    }
}

/// One prefiltered level of edge `size` at `roughness` by `method` (`sampled` is the
/// split of `env` the sampled method reads).
pub fn prefilter_level(
    env: &Cubemap,
    split: Option<&IrradianceSource>,
    sampled: &SampledSource,
    size: u32,
    roughness: f32,
    method: LevelMethod,
) -> Vec<[f32; 4]> {
    let dir = |face: u32, i: u32, j: u32| cube_texel_direction(face, i as i32, j as i32, size);
    match method {
        LevelMethod::Exact { source_mip } => {
            let source = ExactSource::new(&exact_source_texels(env, split, source_mip as usize));
            fill_cube_level(size, |face, i, j| {
                source.prefilter(dir(face, i, j), roughness)
            })
        }
        LevelMethod::Sampled { samples } => {
            let lobe = ggx_lobe_samples(samples, roughness, env.size);
            fill_cube_level(size, |face, i, j| {
                prefilter_texel(sampled, dir(face, i, j), roughness, &lobe, samples)
            })
        }
    }
}

/// Default edge of the smallest specular mip: the chain stops there instead of at 1×1
/// (see [`chain_levels`]). A 256 chain then has 7 levels, r = m/6. Chosen by the lookup
/// error a shader sees (seamless trilinear at lod = r·(M − 1), `tests/lookup.rs`
/// `layout_scan`): a 1×1 or 2×2 level cannot hold the r = 1 lobe (quarry_01: 30 % and
/// 11 % at r = 1), while fewer levels blend lobes farther apart (16² and 32² minima:
/// 16 % and 4 % at r = 0.35); 4² keeps every r ≥ 0.3 within 3.2 % on quarry_01 and
/// 4.2 % on royal_esplanade.
pub const DEFAULT_MIN_MIP_SIZE: u32 = 4;

/// Number of levels M of a specular chain from `size` down to `min_mip_size` (both powers
/// of two; a minimum above the size gives one level): log2(size / min) + 1.
pub fn chain_levels(size: u32, min_mip_size: u32) -> u32 {
    let min = min_mip_size.clamp(1, size.max(1));
    Cubemap::full_mip_count(size) - Cubemap::full_mip_count(min) + 1
}

/// The prefiltered chain of `env` (which must have every mip) in the layout of `chain`
/// (its level count clamped to the full chain): level 0 is the environment itself (r = 0),
/// level m is prefiltered at `chain.mip_roughness(m)`.
pub fn prefilter_specular(
    env: &Cubemap,
    split: Option<&IrradianceSource>,
    chain: SpecularChain,
    samples: u32,
) -> Cubemap {
    let levels = chain.levels.clamp(1, Cubemap::full_mip_count(env.size));
    let chain = SpecularChain { levels, ..chain };
    let mut out = Cubemap {
        size: env.size,
        levels: vec![env.levels[0].clone()],
    };
    let sampled = split_hot_texels(env);
    for m in 1..levels {
        let r = chain.mip_roughness(m);
        let method = level_method(env.size, m, r, samples);
        out.levels.push(prefilter_level(
            env,
            split,
            &sampled,
            env.level_size(m as usize),
            r,
            method,
        ));
    }
    out
}

/// The lane sums' test source: 1533 texels (not a multiple of [`LANES`]) of a patterned
/// 16² cube with a bright spot.
#[cfg(test)]
pub(crate) fn lane_test_source() -> Vec<SourceTexel> {
    let mut cube = crate::cpu::cube_sample::patterned_chain(16, 5);
    cube.levels[0][1000][0] += 5000.0;
    let mut texels = source_texels(&cube, 0);
    texels.truncate(texels.len() - 3);
    texels
}

/// The lane sums' test directions: 200 unit vectors spread over the sphere.
#[cfg(test)]
pub(crate) fn lane_test_normals() -> impl Iterator<Item = [f32; 3]> {
    (0..200).map(|k| {
        crate::math::cubemap::normalize([
            (k as f32 * 0.37).sin(),
            (k as f32 * 0.91).cos(),
            (k as f32 * 0.13).sin() - 0.2,
        ])
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Each mapping's lod is the inverse of its roughness per mip: a shader asking for a
    /// level's roughness reads that level (Babylon's only below α = 1, and up to its ε:
    /// 0.8 log2(1 + ε/α), 0.06 at the first level's α = 0.0093).
    #[test]
    fn lod_inverts_the_roughness_of_each_mip() {
        for (mapping, levels) in [
            (MipRoughness::Linear, 7),
            (MipRoughness::Quadratic, 5),
            (MipRoughness::Babylon, 9),
        ] {
            for m in 0..levels {
                let r = mapping.roughness(m, levels);
                if mapping == MipRoughness::Babylon && (m == 0 || r >= 1.0) {
                    continue;
                }
                let lod = mapping.lod(r, levels);
                let tol = match mapping {
                    MipRoughness::Babylon => {
                        0.02 + BABYLON_LOD_SCALE * (1.0 + BABYLON_MINIMUM_VARIANCE / (r * r)).log2()
                    }
                    _ => 0.02,
                };
                assert!(
                    (lod - m as f32).abs() < tol,
                    "{mapping:?} m {m}: r {r}, lod {lod}"
                );
            }
        }
        // Babylon's 256² chain: α = 2^(m / 0.8) / 256 reaches 1 at m = 6.4.
        assert_eq!(MipRoughness::Babylon.roughness(0, 9), 0.0);
        assert!((MipRoughness::Babylon.roughness(4, 9) - (32.0f32 / 256.0).sqrt()).abs() < 1e-6);
        assert_eq!(MipRoughness::Babylon.roughness(7, 9), 1.0);
        assert!((MipRoughness::Babylon.lod(1.0, 9) - 6.4006).abs() < 1e-3);
    }

    /// The lane-packed sum gives the texel-by-texel reference's value at every roughness of
    /// a chain, within 1e-5 + 2e-7/α² relative: two sums of 1533 f32 terms taken in
    /// different orders (~√N·ε ≈ 5e-6), and D's denominator (n·h)²(α² − 1) + 1, which
    /// cancels to about α² near the lobe's peak, so the one rounding that separates
    /// (n·h)² = (1 + n·l)/2 from √ then squared is amplified by 1/α² (1.2e-4 at r = 0.2,
    /// 3e-6 at r = 0.5; the lane sum is the one with fewer roundings),
    /// on a source with a bright spot and a texel count that is not a multiple of the
    /// lane width.
    #[test]
    fn lane_sum_equals_the_reference() {
        let texels = lane_test_source();
        let lanes = ExactSource::new(&texels);
        for r in [0.2f32, 0.35, 0.5, 0.8, 1.0] {
            for n in lane_test_normals() {
                let want = prefilter_exact_texel(&texels, n, r);
                let got = lanes.prefilter(n, r);
                let alpha2 = alpha_from_roughness(r).powi(2);
                for c in 0..3 {
                    let rel = (got[c] - want[c]).abs() / want[c].abs().max(1e-6);
                    assert!(
                        rel <= 1e-5 + 2e-7 / alpha2,
                        "r {r} n {n:?} channel {c}: {} vs {}",
                        got[c],
                        want[c]
                    );
                }
            }
        }
    }
}
