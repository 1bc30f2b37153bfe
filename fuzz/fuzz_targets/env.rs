//! The Babylon.js `.env` reader (its JSON header, the RGBD PNGs of every face and level)
//! must return Ok or a clean error for any bytes, never panic.
#![no_main]
libfuzzer_sys::fuzz_target!(|data: &[u8]| {
    let _ = splitsum::io::env::decode(std::path::Path::new("fuzz.env"), data);
});
