//! Inputs found by the cargo-fuzz targets in fuzz/ (see fuzz/README.md): each must give a
//! clean error quickly, never a panic or a hang.

use std::path::Path;
use std::time::{Duration, Instant};

fn check(name: &str, decode: impl Fn(&Path, &[u8]) -> splitsum::Result<splitsum::Cubemap>) {
    let path = Path::new("tests/fuzz_regressions").join(name);
    let bytes = std::fs::read(&path).unwrap();
    let start = Instant::now();
    let result = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| {
        decode(&path, &bytes).map(|_| ())
    }));
    let elapsed = start.elapsed();
    let result = result.unwrap_or_else(|_| panic!("{name}: the reader panicked"));
    assert!(result.is_err(), "{name}: expected an error");
    assert!(elapsed < Duration::from_secs(2), "{name}: took {elapsed:?}");
    println!("{name}: {} in {elapsed:?}", result.unwrap_err());
}

#[test]
fn ktx2_with_a_malformed_dfd() {
    check("ktx2-dfd-panic.ktx2", splitsum::io::input::decode_ktx2_cube);
}

#[test]
fn dds_that_timed_out() {
    check("dds-timeout.dds", splitsum::io::input::decode_dds_cube);
}

#[test]
fn ktx2_claiming_a_huge_uncompressed_level() {
    check(
        "ktx2-zstd-huge-length.ktx2",
        splitsum::io::input::decode_ktx2_cube,
    );
}
