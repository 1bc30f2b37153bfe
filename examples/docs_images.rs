//! Regenerates the pictures in `docs/`: `cargo run --release --example docs_images`.
//!
//! - `docs/brdf_lut.png`: the 128² LUT as `splitsum lut` writes it.
//! - `docs/equirect_directions.png` and `docs/cross_directions.png`: an environment whose
//!   colour is its direction (R = x, G = y, B = z, mapped from [−1, 1] to [0, 1]), as the
//!   equirect input and as the horizontal cross splitsum writes, with face borders.

use splitsum::environment::{Environment, Equirect};
use splitsum::math::cubemap::equirect_direction;

fn save_png(path: &str, w: u32, h: u32, rgb: &[[f32; 3]]) {
    let bytes: Vec<u8> = rgb
        .iter()
        .flat_map(|c| c.map(|v| (v.clamp(0.0, 1.0).powf(1.0 / 2.2) * 255.0).round() as u8))
        .collect();
    image::RgbImage::from_raw(w, h, bytes)
        .unwrap()
        .save(path)
        .unwrap();
}

fn main() {
    std::fs::create_dir_all("docs").unwrap();
    let lut = splitsum::backend::cpu::lut_interpolation::brdf_lut(
        128,
        128,
        &Default::default(),
        Default::default(),
    );
    splitsum::io::lut::write_lut("docs/brdf_lut.png".as_ref(), &lut, Default::default()).unwrap();

    let (w, h) = (512u32, 256u32);
    let data: Vec<[f32; 3]> = (0..h)
        .flat_map(|y| (0..w).map(move |x| (x, y)))
        .map(|(x, y)| {
            let d = equirect_direction((x as f32 + 0.5) / w as f32, (y as f32 + 0.5) / h as f32);
            d.map(|v| 0.5 * (v + 1.0))
        })
        .collect();
    save_png("docs/equirect_directions.png", w, h, &data);
    let env = Environment::Equirect(Equirect {
        width: w,
        height: h,
        data,
    });
    let cube = splitsum::stages::convert::environment_to_cube(
        &splitsum::backend::CpuBackend,
        &env,
        64,
        false,
        0.0,
    )
    .unwrap();
    let (cw, ch, mut cross) = splitsum::io::cubemap::to_cross(&cube);
    for (col, row) in splitsum::io::input::HORIZONTAL_CROSS {
        for k in 0..64 {
            for (x, y) in [
                (col * 64 + k, row * 64),
                (col * 64 + k, row * 64 + 63),
                (col * 64, row * 64 + k),
                (col * 64 + 63, row * 64 + k),
            ] {
                cross[(y * cw + x) as usize] = [0.0; 3];
            }
        }
    }
    save_png("docs/cross_directions.png", cw, ch, &cross);
}
