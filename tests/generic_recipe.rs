//! The README's WGSL recipe for the generic target, run as written on the GPU: the block
//! under `splitsum bake` goes unchanged into a compute kernel that reads a default bake of
//! the bundled venice_sunset HDRI as an engine would load it (the KTX2 cubes as cube
//! textures with every level, the 16-bit `brdf_lut.png` rows as the file stores them, a
//! trilinear sampler and a clamped one), and its radiance is compared with the preview's
//! split-sum shading of the same files (`cpu::preview_split_sum`, the function the preview
//! and the viewer use) for metals and dielectrics at roughness 0 to 1 and n·v between 0.05
//! and 1 (at 0.3 and 0.05 the glossy cases take the recipe's four taps of the lobe). Any
//! convention the README states wrongly (the lod, the LUT's axes or row order, the faces,
//! the Fresnel term, a tap's place: an outer tap moved from 0.63 to 0.9 is 23 % off) moves
//! the result by far more than the tolerance.
//!
//! Tolerance: 1 % of the reference, per colour channel. The kernel samples with the
//! hardware's filtering and seamless-cube corner rule from half-float textures (the LUT's
//! 16-bit values become f16, 5e-4 relative), where the reference filters in f32 with
//! exact weights. lavapipe comes within 0.26 %; the bar leaves room for GPUs whose filter
//! weights are 8-bit fractions (a step of 1/256 between two texels). A wrong lod scale
//! (0.8 → 1) is 21 % off, swapped LUT axes 109 %.

mod common;

use glam::Vec3;
use splitsum::cpu::preview_split_sum::split_sum_shade;
use splitsum::plan::material::ShadeMaterial;
use splitsum::plan::scene::SplitSumLight;
use splitsum::plan::shading::ShadingTerms;
use splitsum::SpecularLookup;

/// Relative bar per channel (see the module documentation).
const TOLERANCE: f32 = 0.01;

/// The first (and only) ```wgsl block of the README.
fn readme_wgsl() -> String {
    let readme = std::fs::read_to_string("README.md").unwrap();
    let blocks: Vec<&str> = readme.split("```wgsl\n").skip(1).collect();
    assert_eq!(
        blocks.len(),
        1,
        "README.md has {} wgsl blocks",
        blocks.len()
    );
    blocks[0].split("```").next().unwrap().to_string()
}

/// A test case's inputs as the kernel reads them.
#[repr(C)]
#[derive(Clone, Copy, bytemuck::Pod, bytemuck::Zeroable)]
struct Case {
    n: [f32; 4],
    v: [f32; 4],
    f0_roughness: [f32; 4],
    albedo_metallic: [f32; 4],
}

/// The README's code between the names it takes as given and the result.
fn kernel(specular_levels: u32) -> String {
    format!(
        "@group(0) @binding(0) var specular_cube: texture_cube<f32>;
@group(0) @binding(1) var irradiance_cube: texture_cube<f32>;
@group(0) @binding(2) var brdf_lut: texture_2d<f32>;
@group(0) @binding(3) var lin: sampler;
@group(0) @binding(4) var clamp_lin: sampler;
struct Case {{ n: vec4<f32>, v: vec4<f32>, f0_roughness: vec4<f32>, albedo_metallic: vec4<f32> }}
@group(0) @binding(5) var<storage, read> cases: array<Case>;
@group(0) @binding(6) var<storage, read_write> radiance: array<vec4<f32>>;
const specular_levels: u32 = {specular_levels}u;

@compute @workgroup_size(64)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {{
    if (id.x >= arrayLength(&cases)) {{
        return;
    }}
    let given = cases[id.x];
    let n = given.n.xyz;
    let v = given.v.xyz;
    let roughness = given.f0_roughness.w;
    let f0 = given.f0_roughness.xyz;
    let albedo = given.albedo_metallic.xyz;
    let metallic = given.albedo_metallic.w;
// README.md, as written:
{}
    radiance[id.x] = vec4<f32>(specular + diffuse, 1.0);
}}
",
        readme_wgsl()
    )
}

/// A cube texture of half floats holding every level of `cube`, viewed as a cube.
fn cube_texture(ctx: &splitsum::gpu::GpuContext, cube: &splitsum::Cubemap) -> wgpu::TextureView {
    let texture = ctx.device.create_texture(&wgpu::TextureDescriptor {
        label: Some("recipe cube"),
        size: wgpu::Extent3d {
            width: cube.size,
            height: cube.size,
            depth_or_array_layers: 6,
        },
        mip_level_count: cube.levels.len() as u32,
        sample_count: 1,
        dimension: wgpu::TextureDimension::D2,
        format: wgpu::TextureFormat::Rgba16Float,
        usage: wgpu::TextureUsages::TEXTURE_BINDING | wgpu::TextureUsages::COPY_DST,
        view_formats: &[],
    });
    for (m, level) in cube.levels.iter().enumerate() {
        let n = cube.level_size(m);
        let halves: Vec<half::f16> = level
            .iter()
            .flatten()
            .map(|&x| half::f16::from_f32(x))
            .collect();
        write_level(ctx, &texture, m as u32, bytemuck::cast_slice(&halves), n, 6);
    }
    texture.create_view(&wgpu::TextureViewDescriptor {
        dimension: Some(wgpu::TextureViewDimension::Cube),
        ..Default::default()
    })
}

fn write_level(
    ctx: &splitsum::gpu::GpuContext,
    texture: &wgpu::Texture,
    mip: u32,
    bytes: &[u8],
    n: u32,
    layers: u32,
) {
    ctx.queue.write_texture(
        wgpu::TexelCopyTextureInfo {
            texture,
            mip_level: mip,
            origin: wgpu::Origin3d::ZERO,
            aspect: wgpu::TextureAspect::All,
        },
        bytes,
        wgpu::TexelCopyBufferLayout {
            offset: 0,
            bytes_per_row: Some(n * 8),
            rows_per_image: Some(n),
        },
        wgpu::Extent3d {
            width: n,
            height: n,
            depth_or_array_layers: layers,
        },
    );
}

/// `brdf_lut.png` as a user uploads it: the file's rows in order, (A, B) from its 16-bit
/// red and green.
fn lut_texture(ctx: &splitsum::gpu::GpuContext, path: &std::path::Path) -> wgpu::TextureView {
    let png = image::open(path).unwrap().to_rgba16();
    let (w, h) = png.dimensions();
    assert_eq!(w, h, "the LUT is square");
    let texture = splitsum::gpu::texture::create_texture_2d(
        &ctx.device,
        "recipe lut",
        (w, h, 1),
        wgpu::TextureFormat::Rgba16Float,
        wgpu::TextureUsages::TEXTURE_BINDING | wgpu::TextureUsages::COPY_DST,
    );
    let halves: Vec<half::f16> = png
        .pixels()
        .flat_map(|p| p.0.map(|c| half::f16::from_f32(c as f32 / 65535.0)))
        .collect();
    write_level(ctx, &texture, 0, bytemuck::cast_slice(&halves), w, 1);
    texture.create_view(&wgpu::TextureViewDescriptor::default())
}

/// Unit vectors spread over the sphere (a Fibonacci lattice).
fn directions(count: usize) -> Vec<Vec3> {
    let golden = std::f32::consts::PI * (3.0 - 5f32.sqrt());
    (0..count)
        .map(|i| {
            let y = 1.0 - 2.0 * (i as f32 + 0.5) / count as f32;
            let r = (1.0 - y * y).sqrt();
            let phi = golden * i as f32;
            Vec3::new(r * phi.cos(), y, r * phi.sin())
        })
        .collect()
}

#[test]
fn readme_wgsl_shades_as_the_preview() {
    let Some(ctx) = common::gpu() else {
        return;
    };
    let dir = common::output_dir("generic_recipe");
    common::run_ok(
        common::splitsum()
            .args(["bake", "tests/data/venice_sunset_1k.hdr", "-q", "-o"])
            .arg(&dir),
    );
    let bake_dir = dir.join("venice_sunset_1k");
    let (baked, lut) = splitsum::read_bake_dir(&bake_dir).unwrap();
    let lut = lut.expect("a generic bake writes brdf_lut.png");
    let levels = baked.specular.levels.len() as u32;

    // Metals and dielectrics at roughness 0 to 1, n over the sphere, v at n·v from 0.05 to 1.
    let materials = [
        (Vec3::new(1.0, 0.71, 0.29), 1.0, Vec3::ZERO),
        (Vec3::splat(0.04), 0.0, Vec3::new(0.8, 0.3, 0.2)),
    ];
    let mut cases = Vec::new();
    let mut reference = Vec::new();
    let light = SplitSumLight {
        specular: &baked.specular,
        irradiance: &baked.irradiance,
        lut: &lut,
        terms: ShadingTerms::GENERIC,
        filtered: SpecularLookup::GENERIC
            .filtered()
            .then_some(baked.chain.roughness),
    };
    for (k, n) in directions(96).into_iter().enumerate() {
        let tangent = n.any_orthonormal_vector();
        for (j, n_dot_v) in [1.0f32, 0.7, 0.3, 0.05].into_iter().enumerate() {
            let v = (n * n_dot_v + tangent * (1.0 - n_dot_v * n_dot_v).sqrt()).normalize();
            let roughness = ((k + j) % 5) as f32 / 4.0;
            let (f0, metallic, albedo) = materials[(k + j) % 2];
            cases.push(Case {
                n: n.extend(0.0).into(),
                v: v.extend(0.0).into(),
                f0_roughness: f0.extend(roughness).into(),
                albedo_metallic: albedo.extend(metallic).into(),
            });
            let m = ShadeMaterial {
                f0,
                metallic,
                albedo,
                roughness,
                lod: baked.chain.roughness.lod(roughness, levels),
                bend: SpecularLookup::GENERIC.bend(roughness, f0),
                stretch: SpecularLookup::GENERIC.stretch(),
            };
            reference.push(split_sum_shade(&light, n, v, n.dot(v).max(0.0), &m));
        }
    }

    let device = &ctx.device;
    // A recipe that does not compile (a name the kernel around it also declares, a WGSL
    // error) fails here with the compiler's message, not as a black result.
    let pipeline = splitsum::gpu::compute::with_error_scope(device, "README recipe", || {
        let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
            label: Some("README recipe"),
            source: wgpu::ShaderSource::Wgsl(kernel(levels).into()),
        });
        device.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
            label: Some("README recipe"),
            layout: None,
            module: &module,
            entry_point: Some("main"),
            compilation_options: Default::default(),
            cache: None,
        })
    })
    .unwrap_or_else(|e| panic!("the README's WGSL does not compile in its kernel: {e}"));
    let sampler = |address: wgpu::AddressMode| {
        device.create_sampler(&wgpu::SamplerDescriptor {
            address_mode_u: address,
            address_mode_v: address,
            address_mode_w: address,
            mag_filter: wgpu::FilterMode::Linear,
            min_filter: wgpu::FilterMode::Linear,
            mipmap_filter: wgpu::MipmapFilterMode::Linear,
            ..Default::default()
        })
    };
    let (lin, clamp_lin) = (
        sampler(wgpu::AddressMode::Repeat),
        sampler(wgpu::AddressMode::ClampToEdge),
    );
    let specular = cube_texture(&ctx, &baked.specular);
    let irradiance = cube_texture(&ctx, &baked.irradiance);
    let lut_view = lut_texture(&ctx, &bake_dir.join("brdf_lut.png"));
    let inputs = splitsum::gpu::compute::storage_buffer(device, "recipe cases", &cases);
    let size = (cases.len() * 16) as u64;
    let output = device.create_buffer(&wgpu::BufferDescriptor {
        label: Some("recipe radiance"),
        size,
        usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_SRC,
        mapped_at_creation: false,
    });
    let staging = device.create_buffer(&wgpu::BufferDescriptor {
        label: Some("recipe staging"),
        size,
        usage: wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::COPY_DST,
        mapped_at_creation: false,
    });
    let bind = splitsum::gpu::compute::bind_group(
        device,
        Some("README recipe"),
        &pipeline.get_bind_group_layout(0),
        &[
            wgpu::BindingResource::TextureView(&specular),
            wgpu::BindingResource::TextureView(&irradiance),
            wgpu::BindingResource::TextureView(&lut_view),
            wgpu::BindingResource::Sampler(&lin),
            wgpu::BindingResource::Sampler(&clamp_lin),
            inputs.as_entire_binding(),
            output.as_entire_binding(),
        ],
    );
    let mut encoder = device.create_command_encoder(&Default::default());
    {
        let mut pass = encoder.begin_compute_pass(&Default::default());
        pass.set_pipeline(&pipeline);
        pass.set_bind_group(0, &bind, &[]);
        pass.dispatch_workgroups((cases.len() as u32).div_ceil(64), 1, 1);
    }
    encoder.copy_buffer_to_buffer(&output, 0, &staging, 0, size);
    ctx.queue.submit([encoder.finish()]);
    let bytes = splitsum::gpu::compute::map_read(device, &staging).unwrap();
    let got: &[[f32; 4]] = bytemuck::cast_slice(&bytes);

    let mut worst = (0.0f32, 0);
    for (i, (g, want)) in got.iter().zip(&reference).enumerate() {
        for c in 0..3 {
            let e = (g[c] - want[c]).abs() / want[c].abs().max(1e-3);
            if e > worst.0 {
                worst = (e, i);
            }
        }
    }
    let (e, i) = worst;
    println!(
        "README's WGSL vs the preview's shading, {} cases: worst {:.3} % (case {i}: {:?} vs {:?})",
        cases.len(),
        100.0 * e,
        &got[i][..3],
        reference[i]
    );
    assert!(
        e <= TOLERANCE,
        "the README's WGSL is {:.2} % from the preview's shading (bar {:.0} %) at case {i}: {:?} vs {:?}",
        100.0 * e,
        100.0 * TOLERANCE,
        &got[i][..3],
        reference[i]
    );
}
