//! The viewer's HUD: lines of text (the preview's DejaVu Sans, drawn with `ab_glyph`) on a
//! translucent panel in the top-left corner, as an sRGB image with straight alpha that
//! the present pass lays over the frame. Line k's box is [`line_box`]`(k)`, so a test can
//! find the material line in a screenshot.

use ab_glyph::{Font, FontRef, PxScale, ScaleFont};
use image::{Rgba, RgbaImage};

use crate::stages::preview::picture::{draw_glyphs, text_width, FONT};

/// Text size in pixels.
pub const TEXT_PX: f32 = 15.0;
/// Distance between baselines.
pub const LINE_PX: u32 = 19;
/// Margin of the panel from the frame's corner, and of the text from the panel's edge.
pub const MARGIN_PX: u32 = 8;
/// The panel's colour and opacity.
const PANEL: Rgba<u8> = Rgba([12, 12, 12, 170]);
/// The text's colour.
const INK: [u8; 3] = [235, 235, 235];

/// (x, y, width, height) of line `k`'s box in the frame, `width` wide.
pub fn line_box(k: u32, width: u32) -> (u32, u32, u32, u32) {
    let x = 2 * MARGIN_PX;
    let y = 2 * MARGIN_PX + k * LINE_PX;
    (x, y, width.saturating_sub(x + 2 * MARGIN_PX), LINE_PX)
}

/// The HUD of `lines` over a `width` × `height` frame (transparent where it draws nothing).
/// Fails only if the bundled font does not parse.
pub fn draw(lines: &[String], width: u32, height: u32) -> Result<RgbaImage, String> {
    let mut img = RgbaImage::new(width, height);
    if lines.is_empty() {
        return Ok(img);
    }
    let font = FontRef::try_from_slice(FONT).map_err(|e| format!("the HUD font: {e}"))?;
    let text_w = lines
        .iter()
        .map(|l| text_width(&font, TEXT_PX, l))
        .fold(0.0, f32::max);
    let panel_w = (text_w.ceil() as u32 + 2 * MARGIN_PX).min(width.saturating_sub(MARGIN_PX));
    let panel_h =
        (lines.len() as u32 * LINE_PX + 2 * MARGIN_PX).min(height.saturating_sub(MARGIN_PX));
    for y in MARGIN_PX..MARGIN_PX + panel_h {
        for x in MARGIN_PX..MARGIN_PX + panel_w {
            img.put_pixel(x, y, PANEL);
        }
    }
    let ascent = font.as_scaled(PxScale::from(TEXT_PX)).ascent();
    for (k, line) in lines.iter().enumerate() {
        let (x, y, _, _) = line_box(k as u32, width);
        draw_glyphs(
            &font,
            TEXT_PX,
            x as f32,
            y as f32 + ascent,
            line,
            |px, py, coverage| {
                if px < 0 || py < 0 || px >= width as i32 || py >= height as i32 {
                    return;
                }
                let p = img.get_pixel_mut(px as u32, py as u32);
                // Text over the panel: straight alpha, the panel's colour and opacity mixed
                // towards the ink by the coverage.
                let a = p.0[3] as f32 / 255.0;
                let alpha = a + (1.0 - a) * coverage;
                for (channel, ink) in p.0.iter_mut().zip(INK) {
                    let under = *channel as f32 * a;
                    let mixed = under * (1.0 - coverage) + ink as f32 * coverage;
                    *channel = (mixed / alpha.max(1e-6)).round().clamp(0.0, 255.0) as u8;
                }
                p.0[3] = (alpha * 255.0).round() as u8;
            },
        );
    }
    Ok(img)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Text lands in its line's box, the panel is translucent, the rest transparent.
    #[test]
    fn lines_land_in_their_boxes() {
        let img = draw(&["material: 1 gold".into(), "x".into()], 320, 120).unwrap();
        let (x, y, w, h) = line_box(0, 320);
        let inked = (y..y + h)
            .flat_map(|yy| (x..x + w).map(move |xx| (xx, yy)))
            .filter(|&(xx, yy)| img.get_pixel(xx, yy).0[0] > 200)
            .count();
        assert!(inked > 30, "{inked}");
        assert_eq!(img.get_pixel(MARGIN_PX, MARGIN_PX).0[3], PANEL.0[3]);
        assert_eq!(img.get_pixel(319, 119).0[3], 0);
    }
}
