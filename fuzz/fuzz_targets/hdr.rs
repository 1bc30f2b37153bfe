//! The Radiance HDR reader must return Ok or a clean error for any bytes, never panic,
//! and the incremental reader (batches of rows, as the loader streams a file) must give
//! exactly what the whole-file decode gives.
#![no_main]
libfuzzer_sys::fuzz_target!(|data: &[u8]| {
    let path = std::path::Path::new("fuzz.hdr");
    let whole = splitsum::io::hdr::decode(path, data);
    let streamed = (|| {
        let mut reader = splitsum::io::hdr::HdrReader::new(path, data)?;
        let w = reader.width() as usize;
        let h = reader.height() as usize;
        let mut out = Vec::new();
        let mut batch = vec![[0.0f32; 3]; 7 * w];
        let mut y = 0;
        while y < h {
            let n = 7.min(h - y);
            reader.read_rows(&mut batch[..n * w])?;
            out.extend_from_slice(&batch[..n * w]);
            y += n;
        }
        Ok::<_, splitsum::Error>(out)
    })();
    match (whole, streamed) {
        (Ok(img), Ok(rows)) => assert!(img.data == rows, "streamed rows differ"),
        (Err(_), Err(_)) => {}
        (a, b) => panic!("whole {:?} vs streamed {:?}", a.is_ok(), b.is_ok()),
    }
});
