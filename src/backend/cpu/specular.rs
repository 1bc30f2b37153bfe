//! The CPU backend's prefiltered specular chain: each level by the method the chain's plan
//! picks ([`level_method`]), exact levels through the lane sums ([`ExactSource`]), sampled
//! levels through [`prefilter_texel`] on the bordered cube.

use crate::backend::cpu::lanes::ExactSource;
use crate::cpu::prefilter_sampled::prefilter_texel;
use crate::environment::walk::fill_cube_level;
use crate::environment::{Cubemap, IrradianceSource};
use crate::math::cubemap::cube_texel_direction;
use crate::plan::chain::{level_method, LevelMethod, SpecularChain};
use crate::plan::sources::{exact_source_texels, ggx_lobe_samples, split_hot_texels, SampledSource};

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
