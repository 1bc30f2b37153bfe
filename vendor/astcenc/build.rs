//! Compiles Arm's astc-encoder library (the `astcenc_*.cpp` sources under
//! astc-encoder/Source, without its command-line tool) and the layout shim with `cc`.
//!
//! The SIMD level follows the target's Rust features, so the library runs wherever the Rust
//! code does: a default x86-64 build gets SSE2, `-C target-cpu=native` (or
//! `-C target-feature=+sse4.1,+popcnt,+avx2,...`) gets the wider paths astcenc chooses from
//! the compiler's own predefined macros (astcenc_mathlib.h).

use std::path::Path;

/// The compiler flag for each Rust target feature astc-encoder has a code path for.
const FEATURE_FLAGS: [(&str, &str); 6] = [
    ("sse4.1", "-msse4.1"),
    ("sse4.2", "-msse4.2"),
    ("popcnt", "-mpopcnt"),
    ("f16c", "-mf16c"),
    ("fma", "-mfma"),
    ("avx2", "-mavx2"),
];

fn main() {
    let source = Path::new("astc-encoder/Source");
    let mut files: Vec<_> = std::fs::read_dir(source)
        .expect("astc-encoder/Source is vendored with the crate")
        .map(|e| e.expect("astc-encoder/Source is readable").path())
        .filter(|p| {
            let name = p.file_name().and_then(|n| n.to_str()).unwrap_or("");
            name.starts_with("astcenc_") && name.ends_with(".cpp")
        })
        .collect();
    files.sort();

    let mut build = cc::Build::new();
    build
        .cpp(true)
        .std("c++14")
        .include(source)
        .files(&files)
        .file("src/layout.cpp")
        // Gives the entry points C linkage (ASTCENC_PUBLIC in astcenc.h), so Rust can call
        // them by their plain names; the library is still linked statically.
        .define("ASTCENC_DYNAMIC_LIBRARY", None)
        // Arm's sources build warning-free with their own flags, not necessarily with every
        // compiler's defaults; their warnings are not ours to act on.
        .warnings(false);
    let features = std::env::var("CARGO_CFG_TARGET_FEATURE").unwrap_or_default();
    let arch = std::env::var("CARGO_CFG_TARGET_ARCH").unwrap_or_default();
    if arch == "x86_64" || arch == "x86" {
        for (feature, flag) in FEATURE_FLAGS {
            if features.split(',').any(|f| f == feature) {
                build.flag_if_supported(flag);
            }
        }
    }
    build.compile("astcenc");

    println!("cargo:rerun-if-changed=build.rs");
    println!("cargo:rerun-if-changed=src/layout.cpp");
    println!("cargo:rerun-if-changed=astc-encoder/Source");
}
