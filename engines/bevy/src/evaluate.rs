//! What the check measures in its renders: each shot against the HDRI, the sun case's
//! sides and shadow, and the results it prints and writes.

use std::collections::HashMap;

use bevy::prelude::*;

use crate::capture::save_png;
use crate::equirect::{luminance, Equirect};
use crate::{
    Check, View, DIFFUSE_BRIGHTNESS, DIFFUSE_CORRELATION, SHADOW_DEGREES, SHADOW_HEIGHT,
    SKY_LOG_DIFF, SUN_DEGREES, SUN_HDRI, SUN_LABEL, SUN_SIDES, SUN_SIDE_EDGE,
};

/// Pixel (x, y) of an RGBA float capture.
pub fn pixel(data: &[f32], size: u32, x: u32, y: u32) -> [f32; 3] {
    let i = 4 * (y * size + x) as usize;
    [data[i], data[i + 1], data[i + 2]]
}

/// Centroid of the pixels above half the maximum luminance (of those `keep` accepts).
fn bright_centroid(data: &[f32], size: u32, keep: impl Fn(u32, u32) -> bool) -> (f32, f32) {
    let mut max = 0.0f32;
    for y in 0..size {
        for x in 0..size {
            if keep(x, y) {
                max = max.max(luminance(pixel(data, size, x, y)));
            }
        }
    }
    let (mut sx, mut sy, mut sw) = (0.0, 0.0, 0.0);
    for y in 0..size {
        for x in 0..size {
            let l = luminance(pixel(data, size, x, y));
            if keep(x, y) && l >= 0.5 * max {
                sx += l * x as f32;
                sy += l * y as f32;
                sw += l;
            }
        }
    }
    (sx / sw, sy / sw)
}

fn correlation(a: &[f32], b: &[f32]) -> f32 {
    let n = a.len() as f32;
    let (ma, mb) = (a.iter().sum::<f32>() / n, b.iter().sum::<f32>() / n);
    let (mut ab, mut aa, mut bb) = (0.0, 0.0, 0.0);
    for (x, y) in a.iter().zip(b) {
        ab += (x - ma) * (y - mb);
        aa += (x - ma) * (x - ma);
        bb += (y - mb) * (y - mb);
    }
    ab / (aa * bb).sqrt()
}

/// Measures every shot against the HDRI, prints and writes the results; the exit code.
pub fn evaluate(check: &Check, captures: &HashMap<usize, Vec<Vec<f32>>>) -> u8 {
    let mut lines = Vec::new();
    let mut failed = false;
    let mut report = |ok: bool, text: String| {
        let line = format!("{} {text}", if ok { "ok  " } else { "FAIL" });
        println!("{line}");
        lines.push(line);
        failed |= !ok;
    };
    let reduced: HashMap<&str, Equirect> = check
        .equirects
        .iter()
        .map(|(k, e)| (*k, e.reduce(4)))
        .collect();
    for (i, shot) in check.shots.iter().enumerate() {
        let data = captures[&i].last().unwrap();
        let e = &check.equirects[shot.hdri];
        let n = shot.size;
        save_png(&check.out.join(format!("{}.png", shot.name())), data, n);
        let label = format!("{} {}", shot.hdri, shot.format);
        match shot.view {
            View::Sky => {
                let mut want = vec![0.0f32; data.len()];
                let mut diff = 0.0;
                for y in 0..n {
                    for x in 0..n {
                        let w = e.lookup(shot.ray(x as f32, y as f32));
                        let g = pixel(data, n, x, y);
                        let k = 4 * (y * n + x) as usize;
                        want[k..k + 3].copy_from_slice(&w);
                        for c in 0..3 {
                            diff += ((1.0 + g[c]).ln() - (1.0 + w[c]).ln()).abs();
                        }
                    }
                }
                diff /= (3 * n * n) as f32;
                save_png(
                    &check.out.join(format!("{}_equirect.png", shot.name())),
                    &want,
                    n,
                );
                let (gx, gy) = bright_centroid(data, n, |_, _| true);
                let (wx, wy) = bright_centroid(&want, n, |_, _| true);
                let angle = shot
                    .ray(gx, gy)
                    .angle_between(shot.ray(wx, wy))
                    .to_degrees();
                report(
                    angle <= SUN_DEGREES && diff <= SKY_LOG_DIFF,
                    format!("{label}: skybox sun {angle:.2}° from the equirect lookup's (bar {SUN_DEGREES}°), mean |Δ ln(1+L)| {diff:.4} (bar {SKY_LOG_DIFF})"),
                );
            }
            View::Mirror => {
                let on = |x: u32, y: u32| {
                    shot.sphere_hit(x as f32, y as f32)
                        .is_some_and(|(p, d)| -d.dot(p) > 0.2)
                };
                let (cx, cy) = bright_centroid(data, n, on);
                let reflected = shot
                    .sphere_hit(cx, cy)
                    .map(|(p, d)| d - 2.0 * d.dot(p) * p)
                    .unwrap_or(Vec3::ZERO);
                let angle = reflected.angle_between(check.suns[shot.hdri]).to_degrees();
                report(
                    angle <= SUN_DEGREES,
                    format!("{label}: mirror sphere reflects the sun {angle:.2}° from the HDRI's sun (bar {SUN_DEGREES}°)"),
                );
            }
            // Measured together in evaluate_sun.
            View::SunFull | View::SunSplit | View::SunShadow => {}
            View::Rough => {
                let r = &reduced[shot.hdri];
                let (mut got, mut want) = (Vec::new(), Vec::new());
                for y in 0..n {
                    for x in 0..n {
                        if let Some((p, d)) = shot.sphere_hit(x as f32, y as f32) {
                            // Away from the silhouette, where a pixel straddles the edge.
                            if -d.dot(p) > 0.2 {
                                got.push(luminance(pixel(data, n, x, y)));
                                want.push(luminance(r.irradiance_over_pi(p)));
                            }
                        }
                    }
                }
                let ratio = got.iter().sum::<f32>() / want.iter().sum::<f32>();
                let corr = correlation(&got, &want);
                report(
                    (ratio - 1.0).abs() <= DIFFUSE_BRIGHTNESS && corr >= DIFFUSE_CORRELATION,
                    format!(
                        "{label}: white dielectric r = 1 is {:+.2} % from E/π (bar {:.0} %), correlation {corr:.4} (bar {DIFFUSE_CORRELATION}), {} pixels",
                        100.0 * (ratio - 1.0),
                        100.0 * DIFFUSE_BRIGHTNESS,
                        got.len()
                    ),
                );
            }
        }
    }
    evaluate_sun(check, captures, &reduced[SUN_HDRI], &mut report);
    let text = lines.join("\n") + "\n";
    std::fs::write(check.out.join("results.txt"), text).unwrap();
    println!("renders and results.txt in {}", check.out.display());
    u8::from(failed)
}

/// The sun case: the diffuse sphere's sides (the split render against the full one, and
/// each against E/π of the HDRI, `reduced`), sun.json's direction against the HDRI's own
/// sun, and the box's shadow.
fn evaluate_sun(
    check: &Check,
    captures: &HashMap<usize, Vec<Vec<f32>>>,
    reduced: &Equirect,
    report: &mut impl FnMut(bool, String),
) {
    let shot_of = |view: View| {
        let i = check
            .shots
            .iter()
            .position(|s| s.view == view)
            .expect("the sun shots");
        (&check.shots[i], captures[&i].last().unwrap())
    };
    let toward = check.sun_light.direction;
    let angle = toward.angle_between(check.suns[SUN_HDRI]).to_degrees();
    report(
        angle <= SUN_DEGREES,
        format!("{SUN_HDRI} {SUN_LABEL}: sun.json's direction {angle:.2}° from the HDRI's sun (bar {SUN_DEGREES}°)"),
    );
    // Mean luminance on the lit and the shaded side: the render's, and E/π's.
    let sides = |view: View| {
        let (shot, data) = shot_of(view);
        let n = shot.size;
        let (mut lit, mut shaded) = ([0.0f64; 3], [0.0f64; 3]);
        for y in 0..n {
            for x in 0..n {
                let Some((p, d)) = shot.sphere_hit(x as f32, y as f32) else {
                    continue;
                };
                if -d.dot(p) <= 0.2 {
                    continue;
                }
                let c = p.dot(toward);
                let side = match c {
                    c if c >= SUN_SIDE_EDGE => &mut lit,
                    c if c <= -SUN_SIDE_EDGE => &mut shaded,
                    _ => continue,
                };
                side[0] += luminance(pixel(data, n, x, y)) as f64;
                side[1] += luminance(reduced.irradiance_over_pi(p)) as f64;
                side[2] += 1.0;
            }
        }
        (lit, shaded)
    };
    let (full_lit, full_shaded) = sides(View::SunFull);
    let (split_lit, split_shaded) = sides(View::SunSplit);
    let pc = |a: f64, b: f64| 100.0 * (a / b - 1.0);
    let lit = split_lit[0] / full_lit[0];
    let shaded = split_shaded[0] / full_shaded[0];
    report(
        (lit as f32 - 1.0).abs() <= SUN_SIDES && (shaded as f32 - 1.0).abs() <= SUN_SIDES,
        format!(
            "{SUN_HDRI} {SUN_LABEL}: diffuse sphere under the residual IBL + DirectionalLight against the full IBL: lit side {:+.2} % ({} pixels), shaded side {:+.2} % ({} pixels) (bar {:.0} %); against E/π of the HDRI: split {:+.2} / {:+.2} %, full {:+.2} / {:+.2} %",
            100.0 * (lit - 1.0),
            split_lit[2],
            100.0 * (shaded - 1.0),
            split_shaded[2],
            100.0 * SUN_SIDES,
            pc(split_lit[0], split_lit[1]),
            pc(split_shaded[0], split_shaded[1]),
            pc(full_lit[0], full_lit[1]),
            pc(full_shaded[0], full_shaded[1]),
        ),
    );

    // The shadow: the floor's pixels darker than half the lit floor's median, their
    // centroid on the floor against the shadow of the box's centre (the shadow of a
    // centrally symmetric solid is centrally symmetric about it).
    let (shot, data) = shot_of(View::SunShadow);
    let n = shot.size;
    let lums: Vec<f32> = (0..n * n)
        .map(|i| luminance(pixel(data, n, i % n, i / n)))
        .collect();
    let mut lit: Vec<f32> = lums.iter().copied().filter(|&l| l > 0.0).collect();
    lit.sort_by(f32::total_cmp);
    let median = lit.get(lit.len() / 2).copied().unwrap_or(0.0);
    let (mut sum, mut count) = (Vec2::ZERO, 0u32);
    for y in 0..n {
        for x in 0..n {
            if lums[(y * n + x) as usize] < 0.5 * median {
                let d = shot.ray(x as f32, y as f32);
                let o = shot.transform.translation;
                let floor = o + d * (-o.y / d.y);
                sum += Vec2::new(floor.x, floor.z);
                count += 1;
            }
        }
    }
    let centre = sum / count.max(1) as f32;
    let expected = Vec2::new(-toward.x, -toward.z) * SHADOW_HEIGHT / toward.y;
    let azimuth = |v: Vec2| v.y.atan2(v.x).to_degrees();
    let mut error = (azimuth(centre) - azimuth(expected)).abs();
    error = error.min(360.0 - error);
    report(
        count > 100 && error <= SHADOW_DEGREES,
        format!(
            "{SUN_HDRI} {SUN_LABEL}: the box's shadow at azimuth {:.2}°, where the sun puts it {:.2}° ({error:.2}°, bar {SHADOW_DEGREES}°; {count} pixels)",
            azimuth(centre),
            azimuth(expected)
        ),
    );
}
