//! The KTX 1 cubemap reader (Filament's files) must return Ok or a clean error for any
//! bytes, never panic; the key/value and level parser under it likewise.
#![no_main]
libfuzzer_sys::fuzz_target!(|data: &[u8]| {
    let _ = splitsum::io::ktx1::decode_cube(std::path::Path::new("fuzz.ktx"), data);
});
