//! Writes `$OUT_DIR/readme_recipe.rs` from the README's Bevy recipe (the code blocks under
//! `### Bevy`), so that the check compiles and runs the recipe as written: the Rust block
//! unchanged, then `add` (which schedules the recipe's `setup` at startup) and `COMMANDS`
//! (the shell lines, comments dropped).

use std::path::Path;

fn main() {
    let readme = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../README.md");
    println!("cargo:rerun-if-changed={}", readme.display());
    let text =
        std::fs::read_to_string(&readme).unwrap_or_else(|e| panic!("{}: {e}", readme.display()));
    let start = text
        .find("\n### Bevy")
        .expect("README.md has a '### Bevy' heading");
    let rest = &text[start + 1..];
    let section = &rest[..rest[4..].find("\n##").map_or(rest.len(), |e| e + 4)];
    let (mut rust, mut sh) = (Vec::new(), Vec::new());
    let mut lang: Option<&str> = None;
    for line in section.lines() {
        if let Some(tag) = line.strip_prefix("```") {
            lang = if lang.is_none() {
                Some(tag.trim())
            } else {
                None
            };
            continue;
        }
        match lang {
            Some("rust") => rust.push(line),
            Some("sh") => {
                let command = line.split('#').next().unwrap_or("").trim();
                if !command.is_empty() {
                    sh.push(command);
                }
            }
            _ => {}
        }
    }
    assert!(!rust.is_empty(), "no rust block under '### Bevy'");
    let out = format!(
        "// README.md, \"### Bevy\", as written.\n{}\n// The check's additions.\n\n/// Schedules the recipe's `setup`.\npub(super) fn add(app: &mut App) {{\n    app.add_systems(Startup, setup);\n}}\n\n/// The recipe's shell lines.\npub(super) const COMMANDS: &[&str] = &{:?};\n",
        rust.join("\n"),
        sh
    );
    let path = Path::new(&std::env::var("OUT_DIR").unwrap()).join("readme_recipe.rs");
    std::fs::write(&path, out).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
}
