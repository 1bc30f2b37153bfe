//! Inputs found by the cargo-fuzz targets in fuzz/ (see fuzz/README.md): each must give a
//! clean error quickly, never a panic or a hang.

use std::alloc::{GlobalAlloc, Layout, System};
use std::path::Path;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::time::{Duration, Instant};

/// The system allocator, recording the largest single request (the OOM finds are about
/// allocations sized from a header, which a lazily zeroed page would hide from RSS).
struct Tracking;

static LARGEST: AtomicUsize = AtomicUsize::new(0);

unsafe impl GlobalAlloc for Tracking {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        LARGEST.fetch_max(layout.size(), Ordering::Relaxed);
        unsafe { System.alloc(layout) }
    }
    unsafe fn alloc_zeroed(&self, layout: Layout) -> *mut u8 {
        LARGEST.fetch_max(layout.size(), Ordering::Relaxed);
        unsafe { System.alloc_zeroed(layout) }
    }
    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        LARGEST.fetch_max(new_size, Ordering::Relaxed);
        unsafe { System.realloc(ptr, layout, new_size) }
    }
    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        unsafe { System.dealloc(ptr, layout) }
    }
}

#[global_allocator]
static ALLOCATOR: Tracking = Tracking;

fn check<T>(name: &str, decode: impl Fn(&Path, &[u8]) -> splitsum::Result<T>) {
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

/// No single allocation in this test binary so far exceeded 64 MiB.
fn assert_no_allocation_over_64_mib() {
    let largest = LARGEST.load(Ordering::Relaxed);
    assert!(largest < 64 << 20, "largest allocation {largest} bytes");
}

#[test]
fn ktx2_with_a_malformed_dfd() {
    check("ktx2-dfd-panic.ktx2", splitsum::io::ktx2::decode_cube);
}

#[test]
fn dds_that_timed_out() {
    check("dds-timeout.dds", splitsum::io::dds::decode_cube);
}

#[test]
fn ktx2_claiming_a_huge_uncompressed_level() {
    check(
        "ktx2-zstd-huge-length.ktx2",
        splitsum::io::ktx2::decode_cube,
    );
}

/// A 2 kB EXR whose header claims 16384×11000 (within the size limits): a decoder that
/// allocates the whole image before reading a block asks for 2.2 GB (a libFuzzer
/// out-of-memory find). Bands are allocated as blocks arrive (and this DWA file's chunks
/// are checked before decoding), so the error comes with no allocation larger than 64 MiB
/// (the largest any test in this binary may make).
#[test]
fn exr_claiming_a_huge_size_allocates_little() {
    let path = Path::new("tests/fuzz_regressions/exr-huge-claimed-size.exr");
    let bytes = std::fs::read(path).unwrap();
    let meta =
        exr::meta::MetaData::read_from_buffered(std::io::Cursor::new(&bytes), false).unwrap();
    let size = meta.headers[0].layer_size;
    assert!(size.0 as u64 * size.1 as u64 * 12 > 1 << 30, "{size:?}");
    check("exr-huge-claimed-size.exr", splitsum::io::exr::decode);
    assert_no_allocation_over_64_mib();
}

/// A DWA chunk whose leader claims 2⁶¹ AC coefficients: the `exr` crate asked the
/// allocator for 4 EiB, which aborts the process (an abort, not a panic, so no
/// catch_unwind could save it). splitsum checks every DWA chunk's counters first.
#[test]
fn exr_dwa_chunk_claiming_a_huge_count() {
    check("exr-dwa-huge-count.exr", splitsum::io::exr::decode);
    assert_no_allocation_over_64_mib();
}

/// A KTX 1 file whose level claims an imageSize of gigabytes in a file of kilobytes (a
/// libFuzzer out-of-memory find): the claim is now held to the bytes the file has left
/// before anything is allocated.
#[test]
fn ktx1_claiming_a_huge_image_size() {
    check("ktx1-huge-image-size.ktx", splitsum::io::ktx1::decode_cube);
    assert_no_allocation_over_64_mib();
}
