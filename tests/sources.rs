//! Area sources (`environment::sun::source`): synthetic environments with known uniform
//! discs and rectangles of 2–20° on a smooth sky, rasterised with 8 × 8 sub-samples a
//! texel, at the equator, across the seam and over a pole, on a 1024 × 512 equirect and a
//! 256² cube. Each is found alone, with its shape, its direction within 0.2°, its size
//! within 5 % and its energy within 0.1 %; the sources and the residual hold the input's
//! flux per channel, and the residual is nowhere negative nor above the input.

mod common;

use common::{angle_deg, cross, direction, dot, normalize};
use splitsum::math::cubemap::{cube_texel_direction, cube_texel_solid_angle};
use splitsum::{find_sources, take_sources_out, Cubemap, Environment, Equirect, SourceShape};

/// The sources' irradiance E⊥: about a third of the light, against a sky of about 1
/// (its radiance is E⊥ over the shape's solid angle).
const LAMP_E: f64 = 3.0;
/// Sub-samples per texel edge of the rasterisation.
const SUB: usize = 8;

/// A known source: its centre, its shape (full sides or diameter in degrees) and, for a
/// rectangle, the turn of its width from the local east.
#[derive(Clone, Copy, Debug)]
enum Known {
    Disc {
        centre: [f64; 3],
        diameter: f64,
    },
    Rect {
        centre: [f64; 3],
        width: f64,
        height: f64,
        turn: f64,
    },
}

impl Known {
    fn centre(&self) -> [f64; 3] {
        match *self {
            Known::Disc { centre, .. } | Known::Rect { centre, .. } => centre,
        }
    }

    /// Its width axis and the axis across it, perpendicular to the centre.
    fn axes(&self, turn: f64) -> ([f64; 3], [f64; 3]) {
        let c = self.centre();
        let up = if c[1].abs() > 0.9 {
            [1.0, 0.0, 0.0]
        } else {
            [0.0, 1.0, 0.0]
        };
        let east = normalize(cross(up, c));
        let north = cross(c, east);
        let (ct, st) = (turn.to_radians().cos(), turn.to_radians().sin());
        let w: [f64; 3] = std::array::from_fn(|i| ct * east[i] + st * north[i]);
        (w, cross(c, w))
    }

    fn inside(&self, d: [f64; 3]) -> bool {
        match *self {
            Known::Disc { centre, diameter } => angle_deg(d, centre) <= diameter / 2.0,
            Known::Rect {
                centre,
                width,
                height,
                turn,
            } => {
                let z = dot(d, centre);
                let (w, h) = self.axes(turn);
                z > 0.0
                    && (dot(d, w) / z).abs() <= (width / 2.0).to_radians().tan()
                    && (dot(d, h) / z).abs() <= (height / 2.0).to_radians().tan()
            }
        }
    }

    /// Its uniform radiance: [`LAMP_E`] over its solid angle (a rectangle of half-sides
    /// α, β seen on its axis: 4 asin(sin α sin β)).
    fn radiance(&self) -> f64 {
        let omega = match *self {
            Known::Disc { diameter, .. } => {
                2.0 * std::f64::consts::PI * (1.0 - (diameter / 2.0).to_radians().cos())
            }
            Known::Rect { width, height, .. } => {
                let (a, b) = ((width / 2.0).to_radians(), (height / 2.0).to_radians());
                4.0 * (a.sin() * b.sin()).asin()
            }
        };
        LAMP_E / omega
    }

    /// The widest angle of the shape from its centre, in degrees.
    fn reach(&self) -> f64 {
        match *self {
            Known::Disc { diameter, .. } => diameter / 2.0,
            Known::Rect { width, height, .. } => {
                let (a, b) = (
                    (width / 2.0).to_radians().tan(),
                    (height / 2.0).to_radians().tan(),
                );
                (a * a + b * b).sqrt().atan().to_degrees()
            }
        }
    }
}

/// The smooth sky under the sources.
fn sky(d: [f64; 3]) -> [f64; 3] {
    let y = 0.6 + 0.3 * d[1] + 0.1 * d[0];
    [y, 0.9 * y, 0.7 * y]
}

/// The share of the sub-samples of a texel inside `known`: `dir(u, v)` is the direction
/// at texel coordinates offset (u, v) ∈ [0, 1)² from its corner; only texels within a
/// degree of the shape are sub-sampled.
fn coverage(known: &Known, centre_dir: [f64; 3], dir: impl Fn(f64, f64) -> [f64; 3]) -> f64 {
    if angle_deg(centre_dir, known.centre()) > known.reach() + 1.0 {
        return 0.0;
    }
    let mut hits = 0;
    for a in 0..SUB {
        for b in 0..SUB {
            let u = (a as f64 + 0.5) / SUB as f64;
            let v = (b as f64 + 0.5) / SUB as f64;
            hits += known.inside(dir(u, v)) as usize;
        }
    }
    hits as f64 / (SUB * SUB) as f64
}

/// The equirect of the sky and `known`, and the source's energy per channel Σ L c Ω.
fn equirect(known: &Known) -> (Environment, [f64; 3]) {
    let (w, h) = (1024usize, 512usize);
    let pi = std::f64::consts::PI;
    let at = |x: f64, y: f64| {
        let phi = (x / w as f64 - 0.5) * 2.0 * pi;
        let theta = y / h as f64 * pi;
        [
            theta.sin() * phi.cos(),
            theta.cos(),
            theta.sin() * phi.sin(),
        ]
    };
    let mut data = Vec::with_capacity(w * h);
    let mut energy = 0.0;
    let lamp = known.radiance();
    for y in 0..h {
        let omega = 2.0 * pi / w as f64
            * ((y as f64 / h as f64 * pi).cos() - ((y + 1) as f64 / h as f64 * pi).cos());
        for x in 0..w {
            let d = at(x as f64 + 0.5, y as f64 + 0.5);
            let c = coverage(known, d, |u, v| at(x as f64 + u, y as f64 + v));
            energy += lamp * c * omega;
            let s = sky(d);
            data.push([0, 1, 2].map(|i| (s[i] + lamp * c) as f32));
        }
    }
    let env = Environment::Equirect(Equirect {
        width: w as u32,
        height: h as u32,
        data,
    });
    (env, [energy; 3])
}

/// The 256² cube of the sky and `known`, and the source's energy.
fn cube(known: &Known) -> (Environment, [f64; 3]) {
    let n = 256u32;
    let mut level = Vec::with_capacity(6 * (n * n) as usize);
    let mut energy = 0.0;
    let lamp = known.radiance();
    for face in 0..6 {
        for j in 0..n {
            for i in 0..n {
                let d = cube_texel_direction(face, i as i32, j as i32, n).map(f64::from);
                let at = |u: f64, v: f64| {
                    let s = (i as f64 + u) * 2.0 / n as f64 - 1.0;
                    let t = (j as f64 + v) * 2.0 / n as f64 - 1.0;
                    normalize(
                        splitsum::math::cubemap::cube_face_direction(face, s as f32, t as f32)
                            .map(f64::from),
                    )
                };
                let c = coverage(known, d, at);
                energy += lamp * c * f64::from(cube_texel_solid_angle(i, j, n));
                let s = sky(d);
                level.push(
                    [s[0] + lamp * c, s[1] + lamp * c, s[2] + lamp * c, 1.0].map(|v| v as f32),
                );
            }
        }
    }
    let env = Environment::Cube(Cubemap {
        size: n,
        levels: vec![level],
    });
    (env, [energy; 3])
}

/// Σ L Ω per channel of `env`.
fn flux(env: &Environment) -> [f64; 3] {
    let mut sum = [0.0; 3];
    match env {
        Environment::Equirect(e) => {
            for (k, l) in e.data.iter().enumerate() {
                let omega = e.row_solid_angle((k / e.width as usize) as u32);
                for c in 0..3 {
                    sum[c] += f64::from(l[c]) * omega;
                }
            }
        }
        Environment::Cube(cube) => {
            let n = cube.size;
            for (k, l) in cube.levels[0].iter().enumerate() {
                let k = k as u32 % (n * n);
                let omega = f64::from(cube_texel_solid_angle(k % n, k / n, n));
                for c in 0..3 {
                    sum[c] += f64::from(l[c]) * omega;
                }
            }
        }
    }
    sum
}

fn texels(env: &Environment) -> Vec<[f32; 3]> {
    match env {
        Environment::Equirect(e) => e.data.clone(),
        Environment::Cube(c) => c.levels[0].iter().map(|t| [t[0], t[1], t[2]]).collect(),
    }
}

fn check(what: &str, known: Known, (env, energy): (Environment, [f64; 3])) {
    let found = find_sources(&env);
    assert_eq!(found.len(), 1, "{what}: {found:?}");
    let s = found[0];
    let off = angle_deg(s.direction.map(f64::from), known.centre());
    let e_off = (f64::from(s.irradiance[1]) / energy[1] - 1.0).abs();
    let size_off = match (known, s.shape) {
        (Known::Disc { diameter, .. }, SourceShape::Disc { radius_deg }) => {
            (2.0 * f64::from(radius_deg) / diameter - 1.0).abs()
        }
        (
            Known::Rect { width, height, .. },
            SourceShape::Rect {
                half_width_deg,
                half_height_deg,
                ..
            },
        ) => (2.0 * f64::from(half_width_deg) / width - 1.0)
            .abs()
            .max((2.0 * f64::from(half_height_deg) / height - 1.0).abs()),
        _ => panic!("{what}: {known:?} found as {:?}", s.shape),
    };
    eprintln!(
        "{what}: direction {off:.3}°, size {:.2} %, energy {:.4} %, {} (leaves {:.1} %)",
        100.0 * size_off,
        100.0 * e_off,
        s.shape,
        100.0 * s.shape_residual
    );
    assert!(off <= 0.2, "{what}: direction {off}° off: {s:?}");
    assert!(size_off <= 0.05, "{what}: size {size_off} off: {s:?}");
    assert!(e_off <= 1e-3, "{what}: energy {e_off} off: {s:?}");
    if let (Known::Rect { turn, .. }, SourceShape::Rect { width_axis, .. }) = (known, s.shape) {
        let (w, _) = known.axes(turn);
        let a = angle_deg(width_axis.map(f64::from), w);
        assert!(a.min(180.0 - a) <= 2.0, "{what}: width axis {a}° off");
    }

    // Energy-exact: the sources and the residual hold the input's flux; the residual is
    // nowhere negative and nowhere above the input.
    let (sources, residual) = take_sources_out(&env);
    let (before, after) = (flux(&env), flux(&residual));
    for c in 0..3 {
        let total = after[c]
            + sources
                .iter()
                .map(|s| f64::from(s.irradiance[c]))
                .sum::<f64>();
        assert!(
            (total / before[c] - 1.0).abs() <= 1e-6,
            "{what}: channel {c}: {total} vs {}",
            before[c]
        );
    }
    for (r, l) in texels(&residual).iter().zip(texels(&env)) {
        for c in 0..3 {
            assert!(r[c] >= 0.0 && r[c] <= l[c], "{what}: {r:?} from {l:?}");
        }
    }
}

#[test]
fn discs_are_found_with_their_size_and_energy() {
    for (place, centre) in [
        ("equator", direction(40.0, 5.0)),
        ("seam", direction(180.0, 20.0)),
        ("pole", direction(30.0, 88.0)),
    ] {
        for diameter in [2.0, 6.0, 20.0] {
            let known = Known::Disc { centre, diameter };
            check(
                &format!("equirect, {place}, disc {diameter}°"),
                known,
                equirect(&known),
            );
        }
    }
}

#[test]
fn rectangles_are_found_with_their_size_orientation_and_energy() {
    for (place, centre) in [
        ("equator", direction(-60.0, 10.0)),
        ("seam", direction(180.0, -15.0)),
        ("pole", direction(120.0, 85.0)),
    ] {
        for (width, height, turn) in [(4.0, 2.0, 30.0), (12.0, 5.0, 0.0), (20.0, 8.0, 70.0)] {
            let known = Known::Rect {
                centre,
                width,
                height,
                turn,
            };
            check(
                &format!("equirect, {place}, rectangle {width}° × {height}° turned {turn}°"),
                known,
                equirect(&known),
            );
        }
    }
}

#[test]
fn sources_on_a_cube_across_its_face_edges() {
    // On the edge between +X and +Z, and on the corner of +X, +Y and +Z.
    for (place, centre) in [
        ("edge", normalize([1.0, 0.1, 1.0])),
        ("corner", normalize([1.0, 1.0, 1.0])),
    ] {
        let disc = Known::Disc {
            centre,
            diameter: 8.0,
        };
        check(&format!("cube, {place}, disc 8°"), disc, cube(&disc));
        let rect = Known::Rect {
            centre,
            width: 14.0,
            height: 6.0,
            turn: 20.0,
        };
        check(
            &format!("cube, {place}, rectangle 14° × 6°"),
            rect,
            cube(&rect),
        );
    }
}

/// `inspect` lists the area sources for a person and a script: studio_small_03's lamp,
/// which no sun-sized light holds, with its shape and share, and as the light `--sun
/// split` takes out.
#[test]
fn inspect_lists_the_area_sources() {
    let studio = "tests/data/studio_small_03_1k.hdr";
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_splitsum"))
        .args(["inspect", studio, "--json"])
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    // The lamp is the first light `--sun split` takes out, as an area light.
    assert!(
        ["disc", "rect"].contains(&v["sun"]["shape"]["kind"].as_str().unwrap()),
        "{v}"
    );
    let sources = v["sources"].as_array().unwrap();
    assert!(!sources.is_empty(), "{v}");
    let s = &sources[0];
    assert!(s["share"].as_f64().unwrap() > 0.6, "{s}");
    assert!(
        ["disc", "rect"].contains(&s["shape"]["kind"].as_str().unwrap()),
        "{s}"
    );
    assert!(s["solid_angle_sr"].as_f64().unwrap() > 0.0, "{s}");
    let out = common::run_ok(common::splitsum().args(["inspect", studio]));
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(
        text.contains("source 1") && text.contains("% of the light"),
        "{text}"
    );
}
