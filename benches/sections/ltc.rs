//! `cargo bench --bench bench -- ltc`: the LTC table's fit (`Backend::fit_ltc`) on each
//! backend, 32² (the table the preview and the viewer shade area lights from) and 64²
//! (`splitsum lut --ltc`'s default), one fit each after a 4² warm-up that pays the GPU's
//! shader compilation.

use splitsum::plan::shading::LightBrdf;

pub fn benchmarks() {
    println!("\n## LTC fit timings\n");
    println!("| size | backend | wall s | CPU s |");
    println!("|---|---|---|---|");
    for (name, backend) in crate::cpu_and_gpu_backends() {
        backend.fit_ltc(LightBrdf::GENERIC, 4).unwrap();
        for size in [32u32, 64] {
            let (wall, cpu) = crate::measure(1, || {
                backend.fit_ltc(LightBrdf::GENERIC, size).unwrap();
            });
            let name = match name {
                "gpu" => backend.description(),
                _ => name.to_string(),
            };
            println!("| {size} | {name} | {wall:.2} | {cpu:.2} |");
        }
    }
}
