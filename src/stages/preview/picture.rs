//! The preview picture: the split-sum and ground-truth panels tone-mapped side by side, a
//! heat map of their relative difference with its colour bar, and labels, as an 8-bit
//! sRGB PNG.
//!
//! - Exposure: a linear scale 2^EV; by default the one that maps the environment's
//!   log-average luminance (over the sphere of directions, each texel weighted by its
//!   solid angle; Reinhard et al. 2002, "Photographic Tone Reproduction") to 0.18, so a
//!   sun does not darken the picture the way an arithmetic mean would; the log-average
//!   is taken no lower than the arithmetic mean over [`MAX_MEAN_RATIO`], so a lamp on a
//!   black field (whose log-average is the black's) is exposed for what it lights. The
//!   environment is the one as read, lights included, whatever was taken out of the IBL.
//! - Tone mapping: Khronos PBR Neutral (Khronos 3D Commerce, 2024), which keeps colours
//!   below 0.76 unchanged and compresses highlights towards white; then the sRGB
//!   transfer function (IEC 61966-2-1).
//! - Heat map: |Y_split-sum − Y_truth| / Y_truth of each sphere pixel's luminance
//!   (Rec. 709 weights), on a log scale from 0.1 % to 100 % (matplotlib's inferno,
//!   from the `colorous` crate); the background is dark grey.
//! - Labels: DejaVu Sans (Bitstream Vera licence, `assets/fonts/`), drawn with `ab_glyph`.

use ab_glyph::{Font, FontRef, PxScale, ScaleFont};
use image::{Rgb, RgbImage};

use crate::environment::Cubemap;
use crate::math::color::srgb8;
use crate::math::cubemap::cube_texel_solid_angle;
use crate::plan::scene::{Scene, MATERIALS, ROUGHNESS};

/// The label font (DejaVu Sans; licence in `assets/fonts/DejaVuSans-LICENSE.txt`).
pub const FONT: &[u8] = include_bytes!("../../../assets/fonts/DejaVuSans.ttf");

/// The luminance the default exposure maps the log-average to (Reinhard's key value).
pub const KEY_VALUE: f32 = 0.18;

/// The heat map's range of relative differences: log10 of its ends (0.1 % and 100 %).
pub const HEAT_LOG10_RANGE: [f32; 2] = [-3.0, 0.0];

/// Rec. 709 luminance and its weights, as the pictures measure them.
pub use crate::math::color::{luminance, LUMINANCE};

/// The largest ratio of the arithmetic mean luminance to the log-average the default
/// exposure follows. A white Lambertian sphere sends on average the arithmetic mean of
/// the environment's radiance, so past this ratio (a lamp of a few texels on black, a
/// studio's lamps on its dark backdrop) the log-average, which is the black's, would
/// expose that sphere ever brighter: at 8 it is exposed at most 1.44, grey to white after
/// tone mapping. The sunny and overcast bundled HDRIs' ratios are 1.0–5.3, and their
/// exposure is the log-average's; studio_small_03's is 83 (docs/accuracy.md, "The
/// figures").
pub const MAX_MEAN_RATIO: f64 = 8.0;

/// The default exposure scale of `env` (level 0): [`KEY_VALUE`] / max(exp(mean ln(ε +
/// Y)), mean Y / [`MAX_MEAN_RATIO`]), the means over directions, with ε = 1e-4 of the
/// arithmetic mean so black texels stay finite; 1 for an all-black environment.
pub fn auto_exposure(env: &Cubemap) -> f32 {
    let n = env.size;
    let (mut sum_y, mut sum_w) = (0.0f64, 0.0f64);
    let omegas: Vec<f64> = (0..n * n)
        .map(|k| cube_texel_solid_angle(k % n, k / n, n) as f64)
        .collect();
    for (k, t) in env.levels[0].iter().enumerate() {
        let w = omegas[k % omegas.len()];
        sum_y += w * luminance([t[0], t[1], t[2]]) as f64;
        sum_w += w;
    }
    let mean = sum_y / sum_w;
    if !(mean > 0.0 && mean.is_finite()) {
        return 1.0;
    }
    let eps = 1e-4 * mean;
    let log_mean = env.levels[0]
        .iter()
        .enumerate()
        .map(|(k, t)| omegas[k % omegas.len()] * (eps + luminance([t[0], t[1], t[2]]) as f64).ln())
        .sum::<f64>()
        / sum_w;
    (KEY_VALUE as f64 / log_mean.exp().max(mean / MAX_MEAN_RATIO)) as f32
}

/// PBR Neutral's startCompression (0.8 − 0.04): below it colours pass unchanged.
pub const PBR_NEUTRAL_START_COMPRESSION: f32 = 0.8 - 0.04;
/// PBR Neutral's desaturation of compressed highlights.
pub const PBR_NEUTRAL_DESATURATION: f32 = 0.15;

/// Khronos PBR Neutral tone mapping of linear RGB (the reference GLSL of the
/// specification, term for term).
pub fn pbr_neutral(c: [f32; 3]) -> [f32; 3] {
    const START_COMPRESSION: f32 = PBR_NEUTRAL_START_COMPRESSION;
    const DESATURATION: f32 = PBR_NEUTRAL_DESATURATION;
    let x = c[0].min(c[1]).min(c[2]);
    let offset = if x < 0.08 { x - 6.25 * x * x } else { 0.04 };
    let c = c.map(|v| v - offset);
    let peak = c[0].max(c[1]).max(c[2]);
    if peak < START_COMPRESSION {
        return c;
    }
    let d = 1.0 - START_COMPRESSION;
    let new_peak = 1.0 - d * d / (peak + d - START_COMPRESSION);
    let c = c.map(|v| v * new_peak / peak);
    let g = 1.0 - 1.0 / (DESATURATION * (peak - new_peak) + 1.0);
    c.map(|v| v + (new_peak - v) * g)
}

/// A linear radiance, exposed and tone-mapped, as an sRGB pixel.
pub fn display(c: [f32; 3], exposure: f32) -> Rgb<u8> {
    Rgb(pbr_neutral(c.map(|v| v.max(0.0) * exposure)).map(srgb8))
}

/// The heat-map colour of a relative difference.
pub fn heat_colour(relative: f32) -> Rgb<u8> {
    let [lo, hi] = HEAT_LOG10_RANGE;
    let t = ((relative.max(1e-30).log10() - lo) / (hi - lo)).clamp(0.0, 1.0);
    let c = colorous::INFERNO.eval_continuous(t as f64);
    Rgb([c.r, c.g, c.b])
}

/// Background of the heat-map panel.
pub const HEAT_BACKGROUND: Rgb<u8> = Rgb([40, 40, 40]);
/// Page colour around the panels.
const PAGE: Rgb<u8> = Rgb([24, 24, 24]);
/// Label colour.
const INK: Rgb<u8> = Rgb([230, 230, 230]);

/// Lines of the caption under the panels.
const CAPTION_LINES: f32 = 2.0;

/// What the caption under the panels says: the environment, the exposure, the truth's
/// samples.
#[derive(Clone, Copy, Debug)]
pub struct Caption<'a> {
    /// The environment's name (its file name).
    pub name: &'a str,
    /// The exposure in stops.
    pub exposure_ev: f32,
    /// Points per lobe and pixel of the truth (0: no truth).
    pub truth_samples: u32,
}

/// Where everything goes in the picture, in pixels.
#[derive(Clone, Copy, Debug)]
struct Layout {
    cell: u32,
    font: f32,
    left: u32,
    top: u32,
    gap: u32,
    bar: u32,
    width: u32,
    height: u32,
}

impl Layout {
    /// Three panels and the colour bar with a comparison, the split-sum panel alone
    /// without.
    fn new(scene: &Scene, compared: bool) -> Self {
        let c = scene.cell;
        let font = (c as f32 * 0.22).max(9.0);
        let left = (font * 5.5) as u32;
        let top = (font * 3.4) as u32;
        let gap = c / 4;
        let bar = c / 4;
        let width = if compared {
            left + 3 * scene.width() + 3 * gap + bar + (font * 3.6) as u32
        } else {
            left + scene.width() + gap
        };
        // Below the panels: the caption, two lines.
        let height = top + scene.height() + gap + (font * CAPTION_LINES * 1.5) as u32;
        Layout {
            cell: c,
            font,
            left,
            top,
            gap,
            bar,
            width,
            height,
        }
    }

    /// Left edge of panel `k` (0 split-sum, 1 truth, 2 heat map).
    fn panel_x(&self, scene: &Scene, k: u32) -> u32 {
        self.left + k * (scene.width() + self.gap)
    }
}

/// Width in pixels of `text` at `size`.
pub fn text_width(font: &FontRef, size: f32, text: &str) -> f32 {
    let f = font.as_scaled(PxScale::from(size));
    text.chars().map(|ch| f.h_advance(f.glyph_id(ch))).sum()
}

/// Rasterises `text` at `size` with its baseline at `y`, starting at `x`: calls `plot`
/// with each covered pixel (which may lie outside any image) and its coverage in [0, 1].
pub fn draw_glyphs(
    font: &FontRef,
    size: f32,
    x: f32,
    y: f32,
    text: &str,
    mut plot: impl FnMut(i32, i32, f32),
) {
    let scaled = font.as_scaled(PxScale::from(size));
    let mut pen = x;
    for ch in text.chars() {
        let id = scaled.glyph_id(ch);
        let glyph = id.with_scale_and_position(PxScale::from(size), ab_glyph::point(pen, y));
        pen += scaled.h_advance(id);
        let Some(outline) = font.outline_glyph(glyph) else {
            continue;
        };
        let bounds = outline.px_bounds();
        outline.draw(|gx, gy, coverage| {
            plot(
                bounds.min.x as i32 + gx as i32,
                bounds.min.y as i32 + gy as i32,
                coverage,
            );
        });
    }
}

/// Draws `text` with its baseline at `y`, starting at `x`, blending by coverage.
fn draw_text(img: &mut RgbImage, font: &FontRef, size: f32, x: f32, y: f32, text: &str) {
    let (w, h) = (img.width() as i32, img.height() as i32);
    draw_glyphs(font, size, x, y, text, |px, py, coverage| {
        if px < 0 || py < 0 || px >= w || py >= h {
            return;
        }
        let p = img.get_pixel_mut(px as u32, py as u32);
        for c in 0..3 {
            p.0[c] = (p.0[c] as f32 + (INK.0[c] as f32 - p.0[c] as f32) * coverage).round() as u8;
        }
    });
}

/// Draws `text` centred on `cx`.
fn draw_centred(img: &mut RgbImage, font: &FontRef, size: f32, cx: f32, y: f32, text: &str) {
    let w = text_width(font, size, text);
    draw_text(img, font, size, cx - 0.5 * w, y, text);
}

/// The ground-truth panel and each sphere pixel's relative difference (None off the
/// spheres), for the comparison half of the picture.
#[derive(Clone, Copy, Debug)]
pub struct Comparison<'a> {
    /// The truth panel (row-major linear RGB).
    pub truth: &'a [[f32; 3]],
    /// Per pixel |Y_split-sum − Y_truth| / Y_truth on the spheres.
    pub relative: &'a [Option<f32>],
}

/// The whole picture: the split-sum panel (row-major linear RGB) and, with a
/// `comparison`, the truth panel, the heat map and its colour bar. Fails only if the
/// bundled font does not parse.
pub fn compose(
    scene: &Scene,
    split_sum: &[[f32; 3]],
    comparison: Option<Comparison>,
    exposure: f32,
    caption: &Caption,
) -> Result<RgbImage, String> {
    let layout = Layout::new(scene, comparison.is_some());
    let mut img = RgbImage::from_pixel(layout.width, layout.height, PAGE);
    let (pw, ph) = (scene.width(), scene.height());
    for y in 0..ph {
        for x in 0..pw {
            let k = (y * pw + x) as usize;
            let py = layout.top + y;
            img.put_pixel(
                layout.panel_x(scene, 0) + x,
                py,
                display(split_sum[k], exposure),
            );
            if let Some(c) = comparison {
                let truth = display(c.truth[k], exposure);
                img.put_pixel(layout.panel_x(scene, 1) + x, py, truth);
                let heat = c.relative[k].map_or(HEAT_BACKGROUND, heat_colour);
                img.put_pixel(layout.panel_x(scene, 2) + x, py, heat);
            }
        }
    }

    let font = FontRef::try_from_slice(FONT).map_err(|e| format!("the label font: {e}"))?;
    let f = layout.font;
    let title_y = f * 1.3;
    let header_y = layout.top as f32 - f * 0.5;
    let titles = ["split-sum", "ground truth", "|split-sum − truth| / truth"];
    let panels = if comparison.is_some() { 3 } else { 1 };
    for (k, title) in titles.iter().enumerate().take(panels) {
        let cx = layout.panel_x(scene, k as u32) as f32 + 0.5 * pw as f32;
        draw_centred(&mut img, &font, f * 1.1, cx, title_y, title);
        for (c, r) in ROUGHNESS.iter().enumerate() {
            let cx = layout.panel_x(scene, k as u32) as f32 + (c as f32 + 0.5) * layout.cell as f32;
            let label = if c == 0 {
                format!("r = {r}")
            } else {
                format!("{r}")
            };
            draw_centred(&mut img, &font, f * 0.9, cx, header_y, &label);
        }
    }
    for (row, m) in MATERIALS.iter().enumerate() {
        let y = layout.top as f32 + (row as f32 + 0.5) * layout.cell as f32 + 0.35 * f;
        draw_text(&mut img, &font, f * 0.9, f * 0.4, y, m.name);
    }
    if comparison.is_some() {
        draw_colour_bar(&mut img, &font, scene, &layout);
    }
    let mut lines = vec![format!(
        "{} · exposure {:+.1} EV · columns: roughness{}",
        caption.name,
        caption.exposure_ev,
        if comparison.is_some() {
            format!(" · ground truth: {} samples a pixel and lobe", caption.truth_samples)
        } else {
            String::new()
        }
    )];
    if comparison.is_some() {
        lines.push(
            "The heat map measures the split-sum approximation itself (its v = n and separable-product assumptions), not a fault of the bake."
                .to_string(),
        );
    }
    let y0 = (layout.top + scene.height() + layout.gap) as f32 + f;
    for (k, line) in lines.iter().enumerate() {
        draw_text(&mut img, &font, f * 0.85, layout.left as f32, y0 + k as f32 * f * 1.4, line);
    }
    Ok(img)
}

/// The heat map's colour bar right of the third panel: 100 % at the top, 0.1 % at the
/// bottom, a labelled tick per decade.
fn draw_colour_bar(img: &mut RgbImage, font: &FontRef, scene: &Scene, layout: &Layout) {
    let (f, ph) = (layout.font, scene.height());
    let bar_x = layout.panel_x(scene, 3);
    let [lo, hi] = HEAT_LOG10_RANGE;
    for y in 0..ph {
        let t = 1.0 - (y as f32 + 0.5) / ph as f32;
        let c = heat_colour(10f32.powf(lo + t * (hi - lo)));
        for x in 0..layout.bar {
            img.put_pixel(bar_x + x, layout.top + y, c);
        }
    }
    let steps = (hi - lo).round() as i32;
    for s in 0..=steps {
        let e = lo + s as f32;
        let y = layout.top as f32 + (1.0 - (e - lo) / (hi - lo)) * ph as f32;
        let label = match e as i32 {
            -3 => "0.1 %".to_string(),
            p => format!("{} %", 10f32.powi(p + 2)),
        };
        for x in 0..layout.bar / 2 {
            let yy = (y.round() as u32).clamp(layout.top, layout.top + ph - 1);
            img.put_pixel(bar_x + layout.bar + x, yy, INK);
        }
        let ty = (y + 0.35 * f).clamp(layout.top as f32 + f * 0.7, (layout.top + ph) as f32);
        draw_text(
            img,
            font,
            f * 0.8,
            (bar_x + layout.bar + layout.bar / 2 + 2) as f32,
            ty,
            &label,
        );
    }
}
