//! The viewer's CPU renderer: the G-buffer of [`crate::view::raster`], then the shading
//! and present passes written function for function like the GPU renderer's deferred path
//! (`shaders/view_split_sum.wgsl` with `common/view_shade.wgsl`, `view_truth.wgsl`,
//! `view_present.wgsl` with `common/view_display.wgsl`), with the preview's shading
//! functions (`cpu::preview_split_sum::split_sum_shade`, `cpu::preview_truth::truth_shade`).
//! It renders where no adapter is (`--backend cpu`, offscreen) and checks the GPU's
//! frames.

use glam::Vec3;
use image::RgbaImage;
use rayon::prelude::*;

use crate::cpu::preview_split_sum::split_sum_shade;
use crate::cpu::preview_truth::{pixel_shift, truth_shade};
use crate::environment::sample::sample_cube_lod;
use crate::math::brdf::alpha_from_roughness;
use crate::math::color::linear_to_srgb;
use crate::plan::ltc::{LtcPoint, LtcTable, QuadLight};
use crate::plan::material::{directional_light, point_light, ShadeMaterial};
use crate::plan::scene::MIN_N_DOT_V;
use crate::plan::shading::LightBrdf;
use crate::stages::preview::picture::{luminance, pbr_neutral, HEAT_BACKGROUND};
use crate::view::camera::CameraFrame;
use crate::view::floor::{floor_layer, FloorTable, FLOOR_LAYERS};
use crate::view::floor_shadow::FloorShadows;
use crate::view::frame::{
    unpack_material, FrameUniform, Mode, PresentUniform, Surface, ViewLight, MAX_SHADOW_MAPS,
    SPLIT_RECORD,
};
use crate::view::raster::GBuffer;
use crate::view::shadow;

/// What a shading pass sees at pixel `k` (`PixelView` in view_surface.wgsl): its ray's
/// direction, the G-buffer's surface, position and normal there, the view direction
/// v = −dir, n·v clamped away from 0 by `frame.front[3]` and the surface's material (the
/// floor's on background pixels, which use only `dir`).
struct PixelView {
    dir: Vec3,
    surface: Surface,
    p: Vec3,
    n: Vec3,
    v: Vec3,
    n_dot_v: f32,
    m: ShadeMaterial,
}

/// A G-buffer pixel: (surface, position, normal) (`load_surface` in
/// view_gbuffer_read.wgsl).
fn load_surface(g: &GBuffer, k: usize) -> (Surface, Vec3, Vec3) {
    let p = g.position[k];
    (
        Surface::from_id(p[3]),
        Vec3::from_slice(&p[..3]),
        Vec3::from_slice(&g.normal[k][..3]),
    )
}

fn surface_material(frame: &FrameUniform, s: Surface) -> ShadeMaterial {
    match s {
        Surface::Object => unpack_material(&frame.object),
        _ => unpack_material(&frame.floor),
    }
}

/// `pixel_view` in view_gbuffer_read.wgsl (`surface_view` in view_surface.wgsl).
fn pixel_view(frame: &FrameUniform, camera: &CameraFrame, g: &GBuffer, k: usize) -> PixelView {
    let (x, y) = ((k as u32) % frame.width, (k as u32) / frame.width);
    let (_, dir) = camera.pixel_ray(x, y, frame.width, frame.height);
    let (surface, p, n) = load_surface(g, k);
    let v = -dir;
    PixelView {
        dir,
        surface,
        p,
        n,
        v,
        n_dot_v: n.dot(v).max(frame.front[3]),
        m: surface_material(frame, surface),
    }
}

/// The point lights on, shading the surface a pixel sees (`direct_lights` in
/// view_surface.wgsl).
fn direct_lights(frame: &FrameUniform, lights: &[[f32; 4]], px: &PixelView) -> Vec3 {
    (0..frame.light_count as usize)
        .map(|i| {
            let (pos, colour) = (lights[2 * i], lights[2 * i + 1]);
            point_light(
                px.p,
                px.n,
                px.v,
                px.n_dot_v,
                &px.m,
                Vec3::from_slice(&pos[..3]),
                Vec3::from_slice(&colour[..3]),
                frame.floor_plane[2],
            )
        })
        .sum()
}

/// What the shading passes read of the lights' shadows: the maps' texels, layer after
/// layer (read as `frame.sun` says), and the floor's grids.
#[derive(Clone, Copy)]
pub struct Shadows<'a> {
    /// The maps' texels.
    pub maps: &'a [f32],
    /// The floor's grids of the same maps.
    pub floor: &'a FloorShadows,
}

/// Each light's visibility for the surface a pixel sees, by light: for the first `count`
/// lights that have a map, the floor's from its grid, the object's from the map; 1 for
/// the rest (`surface_visibility` in view_floor_shadow.wgsl; the object's alone is
/// `lights_visibility` in view_sun.wgsl, the floor's `floor_lights_visibility`).
fn lights_visibility(
    frame: &FrameUniform,
    shadow: Shadows<'_>,
    px: &PixelView,
    count: u32,
) -> [f32; MAX_SHADOW_MAPS] {
    let mut visibility = [1.0; MAX_SHADOW_MAPS];
    let lit = count.min(frame.sun[2]) as usize;
    if px.surface == Surface::Floor {
        let grid = shadow.floor.visibilities(px.p);
        visibility[..lit].copy_from_slice(&grid[..lit]);
        return visibility;
    }
    for (k, v) in visibility.iter_mut().enumerate().take(lit) {
        *v = shadow::layer_visibility(&frame.shadow, frame.sun[3], shadow.maps, k, px.p, px.n);
    }
    visibility
}

/// Light `index`'s (a record's w) share of `visibility`: 1 past the maps.
fn shadowed(visibility: &[f32; MAX_SHADOW_MAPS], index: f32) -> f32 {
    visibility.get(index as usize).copied().unwrap_or(1.0)
}

/// A directional light of irradiance `e` from `l` shading the surface a pixel sees.
fn directional(px: &PixelView, l: Vec3, e: Vec3) -> Vec3 {
    let alpha = alpha_from_roughness(px.m.roughness);
    let (spec, diff) = directional_light(
        px.n,
        px.v,
        px.n_dot_v,
        alpha,
        px.m.f0,
        px.m.metallic,
        l,
        e,
        LightBrdf::GENERIC,
    );
    spec + diff * px.m.albedo
}

/// The area lights of a frame, decoded once from `sun_texels` for every pixel: the LTC
/// table they are shaded from and each split-out light's quadrilateral (None for a
/// directional light), by light.
struct AreaLights {
    table: Option<std::sync::Arc<LtcTable>>,
    quads: Vec<Option<QuadLight>>,
}

impl AreaLights {
    /// The area lights of `light` (none without one).
    fn of(light: &ViewLight) -> AreaLights {
        let texels = &light.sun_texels;
        let entry = |e: [f32; 4]| Vec3::from_slice(&e[..3]);
        let quads = (0..light.sun_count() as usize)
            .map(|i| {
                let [t, _, a, f] = [0, 1, 2, 3].map(|k| texels[SPLIT_RECORD * i + k]);
                let first = a[0] as usize;
                (a[1] > 0.0).then(|| QuadLight {
                    corners: std::array::from_fn(|k| entry(texels[first + k])),
                    centre: entry(t),
                    solid_angle: t[3],
                    vector_form_factor: entry(f),
                })
            })
            .collect();
        AreaLights {
            table: light.ltc.clone(),
            quads,
        }
    }
}

/// Split light `i` of `texels` shading the surface a pixel sees, unshadowed, and its shadow
/// map's index (its record's w): a directional light of E⊥, or an area light from
/// `area`'s table at the pixel's LTC `point`.
fn split_light(
    texels: &[[f32; 4]],
    area: &AreaLights,
    point: Option<&LtcPoint>,
    px: &PixelView,
    i: usize,
) -> (Vec3, f32) {
    let [t, r] = [0, 1].map(|k| texels[SPLIT_RECORD * i + k]);
    let radiance = Vec3::from_slice(&r[..3]);
    let c = match (point, &area.quads[i]) {
        (Some(point), Some(quad)) => {
            let (spec, diff) = point.shade_quad(px.n, px.v, px.n_dot_v, &px.m, quad, radiance);
            spec + diff * px.m.albedo
        }
        _ => directional(px, Vec3::from_slice(&t[..3]), radiance * t[3]),
    };
    (c, r[3])
}

/// The pixel's LTC, once for every area light (none without a table).
fn ltc_point(area: &AreaLights, px: &PixelView) -> Option<LtcPoint> {
    area.table
        .as_ref()
        .map(|table| LtcPoint::new(table, px.n, px.v, px.n_dot_v, &px.m))
}

/// The `count` lights split out shading the surface a pixel sees, each through its
/// visibility in `shadow` (the maps' texels): a directional light of E⊥, or an area
/// light from `area`'s table (`split_lights_shade` in view_sun.wgsl, which reads the
/// quadrilateral and the table from `texels`).
fn split_lights_shade(
    frame: &FrameUniform,
    texels: &[[f32; 4]],
    area: &AreaLights,
    shadow: Shadows<'_>,
    px: &PixelView,
    count: u32,
) -> Vec3 {
    let visibility = lights_visibility(frame, shadow, px, count);
    let point = ltc_point(area, px);
    (0..count as usize)
        .map(|i| {
            let (c, index) = split_light(texels, area, point.as_ref(), px, i);
            c * shadowed(&visibility, index)
        })
        .sum()
}

/// The floor's shading by view direction, layer by layer (`view::floor`): the floor's
/// split-sum IBL and the lights split out, each light in its shadow map's layer, shaded as
/// a floor pixel seen along v would be shaded pixel by pixel (n·v clamped as `pixel_view`
/// clamps it), for the unit v towards the eye. `floor` is the floor's material.
pub fn floor_layers<'a>(
    light: &'a ViewLight,
    floor: &'a ShadeMaterial,
) -> impl Fn(Vec3) -> [Vec3; FLOOR_LAYERS] + Sync + 'a {
    let split = light.split_sum();
    let area = AreaLights::of(light);
    move |v| {
        let px = PixelView {
            dir: -v,
            surface: Surface::Floor,
            p: Vec3::ZERO,
            n: Vec3::Y,
            v,
            n_dot_v: v.y.max(MIN_N_DOT_V),
            m: *floor,
        };
        let mut layers = [Vec3::ZERO; FLOOR_LAYERS];
        layers[0] = split_sum_shade(&split, px.n, px.v, px.n_dot_v, &px.m);
        let point = ltc_point(&area, &px);
        for i in 0..light.sun_count() as usize {
            let (c, index) = split_light(&light.sun_texels, &area, point.as_ref(), &px, i);
            layers[floor_layer(index)] += c;
        }
        layers
    }
}

/// The floor's table of `light` ([`floor_layers`] at the table's view directions).
pub fn floor_table(light: &ViewLight, floor: &ShadeMaterial) -> FloorTable {
    FloorTable::new(floor_layers(light, floor))
}

/// The truth's `count` texels of the lights' regions from entry `first` on, shading the
/// surface a pixel sees, each through its light's visibility (`truth_texels_shade` in
/// view_sun.wgsl).
fn truth_texels_shade(
    frame: &FrameUniform,
    texels: &[[f32; 4]],
    shadow: Shadows<'_>,
    px: &PixelView,
    (first, count): (usize, u32),
) -> Vec3 {
    // The lights' visibilities, when there is a texel to shade.
    let lights = if count > 0 { frame.sun[0] } else { 0 };
    let visibility = lights_visibility(frame, shadow, px, lights);
    (0..count as usize)
        .map(|i| {
            let (t, r) = (texels[first + 2 * i], texels[first + 2 * i + 1]);
            let c = directional(
                px,
                Vec3::from_slice(&t[..3]),
                Vec3::from_slice(&r[..3]) * t[3],
            );
            c * shadowed(&visibility, r[3])
        })
        .sum()
}

/// The split-sum pass: per pixel (radiance, surface id), the background's and the
/// surfaces' as `background_radiance` and `surface_radiance` in view_shade.wgsl; `shadow`
/// the lights' shadows, `floor` the floor's table of `light` ([`floor_table`]).
pub fn shade_split_sum(
    frame: &FrameUniform,
    (light, floor): (&ViewLight, &FloorTable),
    lights: &[[f32; 4]],
    shadow: Shadows<'_>,
    g: &GBuffer,
) -> Vec<[f32; 4]> {
    let camera = frame.camera();
    let split = light.split_sum();
    let area = AreaLights::of(light);
    (0..g.position.len())
        .into_par_iter()
        .map(|k| {
            let px = pixel_view(frame, &camera, g, k);
            let c = match px.surface {
                Surface::Background => {
                    Vec3::from(sample_cube_lod(&light.specular, px.dir.into(), 0.0))
                }
                Surface::Floor => {
                    let visibility = lights_visibility(frame, shadow, &px, frame.sun[0]);
                    floor.radiance(px.v, &visibility, frame.sun[0])
                        + direct_lights(frame, lights, &px)
                }
                Surface::Object => {
                    split_sum_shade(&split, px.n, px.v, px.n_dot_v, &px.m)
                        + direct_lights(frame, lights, &px)
                        + split_lights_shade(
                            frame,
                            &light.sun_texels,
                            &area,
                            shadow,
                            &px,
                            frame.sun[0],
                        )
                }
            };
            c.extend(px.surface as u32 as f32).into()
        })
        .collect()
}

/// One truth estimate with `points`, accumulated into `accum` (restarted at
/// `frame.truth_frame` 0); `shadow` as for [`shade_split_sum`].
pub fn shade_truth(
    frame: &FrameUniform,
    light: &ViewLight,
    points: &[[f32; 4]],
    lights: &[[f32; 4]],
    shadow: Shadows<'_>,
    g: &GBuffer,
    accum: &mut [[f32; 4]],
) {
    let camera = frame.camera();
    let truth = light.truth(points);
    let weight = points.len() as f32;
    accum.par_iter_mut().enumerate().for_each(|(k, a)| {
        let px = pixel_view(frame, &camera, g, k);
        let c = if px.surface == Surface::Background {
            Vec3::from(sample_cube_lod(&light.env, px.dir.into(), 0.0))
        } else {
            let seed = (k as u32).wrapping_add(
                frame
                    .truth_frame
                    .wrapping_mul(frame.width)
                    .wrapping_mul(frame.height),
            );
            truth_shade(&truth, px.n, px.v, px.n_dot_v, &px.m, pixel_shift(seed))
                + direct_lights(frame, lights, &px)
                + truth_texels_shade(
                    frame,
                    &light.sun_texels,
                    shadow,
                    &px,
                    (SPLIT_RECORD * frame.sun[0] as usize, frame.sun[1]),
                )
        };
        let estimate = [c.x * weight, c.y * weight, c.z * weight, weight];
        if frame.truth_frame == 0 {
            *a = estimate;
        } else {
            for i in 0..4 {
                a[i] += estimate[i];
            }
        }
    });
}

/// A linear radiance, exposed, tone-mapped and sRGB-encoded, in [0, 1] (`display` in
/// view_display.wgsl).
fn display(c: [f32; 3], exposure: f32) -> [f32; 3] {
    pbr_neutral(c.map(|v| v.max(0.0) * exposure)).map(linear_to_srgb)
}

/// The heat-map colour of a relative difference from the colour table, as the present
/// pass interpolates it.
pub fn heat_colour(table: &[[f32; 4]], p: &PresentUniform, relative: f32) -> [f32; 3] {
    let t = ((relative.max(1e-30).ln() / std::f32::consts::LN_10 - p.heat_lo)
        / (p.heat_hi - p.heat_lo))
        .clamp(0.0, 1.0);
    let x = t * (p.heat_entries - 1) as f32;
    let i = (x.floor() as usize).min(p.heat_entries as usize - 2);
    let f = x - i as f32;
    [0, 1, 2].map(|c| table[i][c] + (table[i + 1][c] - table[i][c]) * f)
}

/// One pixel of the present pass, sRGB-encoded in [0, 1] before the HUD.
pub fn present_pixel(
    p: &PresentUniform,
    table: &[[f32; 4]],
    shaded: [f32; 4],
    accum: [f32; 4],
) -> [f32; 3] {
    let rgb = |v: [f32; 4]| [v[0], v[1], v[2]];
    let mean = |a: [f32; 4]| [a[0] / a[3], a[1] / a[3], a[2] / a[3]];
    if p.mode == Mode::SplitSum as u32 || accum[3] <= 0.0 {
        display(rgb(shaded), p.exposure)
    } else if p.mode == Mode::Truth as u32 {
        display(mean(accum), p.exposure)
    } else if shaded[3] < 0.5 {
        HEAT_BACKGROUND.0.map(|v| v as f32 / 255.0)
    } else {
        let t = luminance(mean(accum));
        heat_colour(table, p, (luminance(rgb(shaded)) - t).abs() / t.max(1e-30))
    }
}

/// The present pass: the mode's picture with `hud` (straight alpha, sRGB) over it, as
/// 8-bit sRGB.
pub fn present(
    p: &PresentUniform,
    table: &[[f32; 4]],
    shaded: &[[f32; 4]],
    accum: &[[f32; 4]],
    hud: &RgbaImage,
) -> RgbaImage {
    let mut out = RgbaImage::new(p.width, p.height);
    let pixels: Vec<[u8; 4]> = (0..shaded.len())
        .into_par_iter()
        .map(|k| {
            let c = present_pixel(p, table, shaded[k], accum[k]);
            let (x, y) = ((k as u32) % p.width, (k as u32) / p.width);
            let h = hud.get_pixel(x, y).0.map(|v| v as f32 / 255.0);
            let c = [0, 1, 2].map(|i| c[i] + (h[i] - c[i]) * h[3]);
            // The 8-bit store of the encoded value, as `math::color::srgb8` rounds.
            let q = c.map(|v| (v.clamp(0.0, 1.0) * 255.0).round() as u8);
            [q[0], q[1], q[2], 255]
        })
        .collect();
    for (k, px) in pixels.into_iter().enumerate() {
        out.put_pixel((k as u32) % p.width, (k as u32) / p.width, image::Rgba(px));
    }
    out
}
