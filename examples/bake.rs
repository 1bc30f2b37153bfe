//! Bakes an environment for an engine through the library, as a `build.rs` or an asset
//! server would: `cargo run --release --example bake -- INPUT OUT_DIR [TARGET]`.
//! `tests/library_api.rs` builds this file as its own crate (with `default-features =
//! false`) and checks that it writes exactly what `splitsum bake --target T` writes.

fn main() -> Result<(), splitsum::Error> {
    let args: Vec<String> = std::env::args().collect();
    let (input, out_dir) = (&args[1], &args[2]);
    let target = splitsum::Target::by_name(args.get(3).map_or("generic", |s| s.as_str()));
    let mut baker = splitsum::Baker::new(splitsum::BakeOptions {
        backend: splitsum::BackendChoice::Cpu,
        ..splitsum::BakeOptions::for_target(target.unwrap_or(&splitsum::GENERIC))
    })?;
    let report = baker.bake(input.as_ref(), out_dir.as_ref())?;
    report
        .warnings
        .iter()
        .for_each(|w| eprintln!("warning: {w}"));
    Ok(())
}
