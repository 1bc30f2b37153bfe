//! The DDS cubemap reader must return Ok or a clean error for any bytes, never panic.
#![no_main]
libfuzzer_sys::fuzz_target!(|data: &[u8]| {
    let _ = splitsum::io::dds::decode_cube(std::path::Path::new("fuzz.dds"), data);
});
