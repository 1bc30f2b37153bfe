//! Layout detection (equirect / horizontal cross / vertical cross) for any image size the
//! readers accept: Ok or a clean error, never a panic or an out-of-bounds read.
#![no_main]
libfuzzer_sys::fuzz_target!(|data: &[u8]| {
    if data.len() < 4 {
        return;
    }
    // Sizes up to 1023 × 1023 keep each run fast; the readers bound real sizes earlier.
    let w = (u16::from_le_bytes([data[0], data[1]]) % 1024) as u32;
    let h = (u16::from_le_bytes([data[2], data[3]]) % 1024) as u32;
    let path = std::path::Path::new("fuzz.hdr");
    if splitsum::io::limits::check_dimensions(path, w, h).is_err() {
        return;
    }
    let img = splitsum::Equirect { width: w, height: h, data: vec![[1.0; 3]; (w * h) as usize] };
    let _ = splitsum::io::input::environment_from_image(path, img);
});
