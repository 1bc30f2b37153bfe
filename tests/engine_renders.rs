//! The preview's engine modes against the engines' own renders: the spheres the three.js
//! engine check renders from a `--target three` bake (`engines/three/check.mjs` writes
//! their linear float pixels and camera) against the same spheres shaded by the preview's
//! three.js mode (`THREE_SHADING`, its CPU shading functions) from the same bake's files.
//! Runs after that check (`.ci/run`): `cargo test --release --test engine_renders --
//! --ignored --nocapture`.

mod common;

use std::path::Path;

use glam::Vec3;
use splitsum::backend::CpuBackend;
use splitsum::cpu::preview_split_sum::split_sum_shade;
use splitsum::environment::Cubemap;
use splitsum::io::ktx2::read_cube_chain;
use splitsum::plan::material::ShadeMaterial;
use splitsum::plan::scene::{SplitSumLight, MIN_N_DOT_V};
use splitsum::stages::preview::shading_lut;
use splitsum::targets::three::{THREE, THREE_SHADING};
use splitsum::Manifest;

/// The three.js check's output folder.
const OUT: &str = "target/engines/three";

/// How far the preview's three.js mode may be from three.js's own render of a sphere:
/// Σ |ΔY| / ΣY over the sphere well inside its silhouette (the half chord > 0.15 of
/// `engines/measure.js`'s `maskSphere`). Measured: at most 0.48 % (quarry_01's metal at
/// r = 0.25), 0.13 % on venice_sunset; 1 % leaves room for what differs between the two
/// renders: three's 128 × 64 mesh (its interpolated normals), its `geometryRoughness`
/// (modelled here from the exact normals of neighbouring pixels, where three takes screen
/// derivatives over 2 × 2 quads), its DFG in half floats, and SwiftShader's filtering.
/// (The recipe's terms in place of three's are 2.4 % off at r = 0.25 and 23 % at 0.5.)
const BAR: f64 = 0.01;

/// The three.js check's camera for the spheres: eye, vertical field of view (°) and edge.
struct Camera {
    eye: Vec3,
    forward: Vec3,
    right: Vec3,
    up: Vec3,
    tan_half: f32,
    size: u32,
}

impl Camera {
    fn read(results: &serde_json::Value) -> Camera {
        let c = &results["sphereCamera"];
        let eye = Vec3::from_slice(
            &c["eye"]
                .as_array()
                .unwrap()
                .iter()
                .map(|v| v.as_f64().unwrap() as f32)
                .collect::<Vec<_>>(),
        );
        // measure.pinhole: looking at the origin, +y up.
        let forward = (-eye).normalize();
        let right = forward.cross(Vec3::Y).normalize();
        let up = right.cross(forward);
        let fov = c["fov"].as_f64().unwrap() as f32;
        Camera {
            eye,
            forward,
            right,
            up,
            tan_half: (fov.to_radians() * 0.5).tan(),
            size: c["size"].as_u64().unwrap() as u32,
        }
    }

    /// The ray through the centre of pixel (x, y), row 0 at the bottom (measure.pixelRay).
    fn ray(&self, x: u32, y: u32) -> Vec3 {
        let n = self.size as f32;
        let sx = (2.0 * (x as f32 + 0.5) / n - 1.0) * self.tan_half;
        let sy = (2.0 * (y as f32 + 0.5) / n - 1.0) * self.tan_half;
        (self.forward + sx * self.right + sy * self.up).normalize()
    }

    /// Where the ray through pixel (x, y) meets the unit sphere, and its half chord.
    fn hit(&self, x: u32, y: u32) -> Option<(Vec3, Vec3, f32)> {
        let d = self.ray(x, y);
        let b = self.eye.dot(d);
        let disc = b * b - (self.eye.dot(self.eye) - 1.0);
        (disc >= 0.0).then(|| {
            let p = self.eye + d * (-b - disc.sqrt());
            (p, d, disc.sqrt())
        })
    }
}

/// The `--target three` bake's chain in the generic orientation (three's files mirror x).
fn generic_chain(dir: &Path) -> Cubemap {
    let stored = read_cube_chain(&dir.join("specular.ktx2")).unwrap();
    stored.remapped(THREE.orientation.texel_map().inverse())
}

#[test]
#[ignore]
fn three_spheres_match_the_preview_three_mode() {
    let results_path = Path::new(OUT).join("results.json");
    let Ok(text) = std::fs::read_to_string(&results_path) else {
        common::skip_peer(&format!(
            "{} not found (run engines/three/check.mjs first)",
            results_path.display()
        ));
        return;
    };
    let results: serde_json::Value = serde_json::from_str(&text).unwrap();
    let shading = THREE_SHADING;
    // three's shipped 16² DFG (`lut_accuracy`'s three_dfg_against_splitsum holds it to
    // the `smith-correlated` model at that size), as the preview computes it.
    let lut = shading_lut(&CpuBackend, &shading, None).unwrap();
    for hdri in ["quarry_01_1k", "venice_sunset_1k"] {
        let dir = Path::new(OUT).join("bakes").join(hdri);
        let manifest = Manifest::read(&dir).unwrap();
        assert_eq!(manifest.target.name, "three");
        let specular = generic_chain(&dir);
        let levels = specular.levels.len() as u32;
        let last = specular.levels.len() - 1;
        let irradiance = Cubemap {
            size: specular.level_size(last),
            levels: vec![specular.levels[last].clone()],
        };
        let light = SplitSumLight {
            specular: &specular,
            irradiance: &irradiance,
            lut: &lut,
            terms: shading.terms,
        };
        let camera = Camera::read(&results["results"][hdri]);
        let n = camera.size;
        // The exact sphere normal at a pixel, where its ray hits.
        let normal = |x: u32, y: u32| camera.hit(x, y).map(|(p, _, _)| p.normalize());
        for metalness in [1u32, 0] {
            for r in [0.25f32, 0.5, 1.0] {
                let file = Path::new(OUT).join(format!("{hdri}_sphere_m{metalness}_r{r}.rgba32f"));
                let bytes =
                    std::fs::read(&file).unwrap_or_else(|e| panic!("{}: {e}", file.display()));
                let px: Vec<f32> = bytes
                    .chunks_exact(4)
                    .map(|b| f32::from_le_bytes([b[0], b[1], b[2], b[3]]))
                    .collect();
                assert_eq!(px.len(), (4 * n * n) as usize, "{}", file.display());
                // A white material, as the check's MeshStandardMaterial.
                let (f0, albedo, metallic) = match metalness {
                    1 => (Vec3::ONE, Vec3::ONE, 1.0),
                    _ => (Vec3::splat(0.04), Vec3::ONE, 0.0),
                };
                let (mut diff, mut total) = (0.0f64, 0.0f64);
                for y in 0..n {
                    for x in 0..n {
                        let Some((p, d, depth)) = camera.hit(x, y) else {
                            continue;
                        };
                        if depth <= 0.15 {
                            continue;
                        }
                        let nrm = p.normalize();
                        // three's geometryRoughness: the largest change of the normal to the
                        // next pixel across or up.
                        let step =
                            |o: Option<Vec3>| o.map_or(0.0, |m| (m - nrm).abs().max_element());
                        let geometry = step(normal(x + 1, y)).max(step(normal(x, y + 1)));
                        let rough = (shading.roughness(r) + geometry).min(1.0);
                        let m = ShadeMaterial {
                            f0,
                            metallic,
                            albedo,
                            roughness: rough,
                            lod: THREE.roughness.lod(rough, levels),
                            bend: shading.lookup.bend(rough),
                            stretch: shading.lookup.stretch(),
                        };
                        let v = -d;
                        let c = split_sum_shade(&light, nrm, v, nrm.dot(v).max(MIN_N_DOT_V), &m);
                        let k = (4 * (y * n + x)) as usize;
                        let got =
                            common::luminance([px[k] as f64, px[k + 1] as f64, px[k + 2] as f64]);
                        let want = common::luminance([c.x as f64, c.y as f64, c.z as f64]);
                        diff += (got - want).abs();
                        total += want;
                    }
                }
                let mean = diff / total;
                eprintln!(
                    "{hdri} metalness {metalness} r {r}: three.js against the preview's three.js mode {:.2} %",
                    100.0 * mean
                );
                assert!(mean <= BAR, "{hdri} metalness {metalness} r {r}: {mean}");
            }
        }
    }
}
