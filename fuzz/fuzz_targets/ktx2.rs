//! The KTX2 cubemap reader must return Ok or a clean error for any bytes, never panic.
#![no_main]
libfuzzer_sys::fuzz_target!(|data: &[u8]| {
    let _ = splitsum::io::ktx2::decode_cube(std::path::Path::new("fuzz.ktx2"), data);
});
