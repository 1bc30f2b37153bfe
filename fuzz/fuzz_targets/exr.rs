//! The OpenEXR reader must return Ok or a clean error for any bytes, never panic, and the
//! streaming reader (bands of whole blocks handed to a sink, as the loader reads a large
//! equirect) must either decline or give exactly what the whole decode gives.
#![no_main]
use std::io::Cursor;

use splitsum::io::exr::{decode, decode_streaming, read_info, RowSink};

struct Collect(Vec<[f32; 3]>);

impl RowSink for Collect {
    fn rows(&mut self, rows: &mut [[f32; 3]]) -> bool {
        self.0.extend_from_slice(rows);
        true
    }
}

libfuzzer_sys::fuzz_target!(|data: &[u8]| {
    let path = std::path::Path::new("fuzz.exr");
    let whole = decode(path, data);
    let streamed = read_info(path, Cursor::new(data))
        .and_then(|info| decode_streaming(path, info, Cursor::new(data), Collect(Vec::new()), 4096));
    if let (Ok(img), Ok(Some(rows))) = (&whole, &streamed) {
        assert!(
            img.data.iter().zip(&rows.0).all(|(a, b)| a.map(f32::to_bits) == b.map(f32::to_bits))
                && img.data.len() == rows.0.len(),
            "streamed rows differ"
        );
    }
});
