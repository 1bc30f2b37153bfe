//! The README and the documents say what the code does, in the present tense:
//! - the README stays a user's document (at most 400 lines);
//! - no README, document or comment speaks of the past or of one machine, or cites a file
//!   a reader of the repository does not have;
//! - each engine recipe in the README is run as written by the engine's check (the web
//!   engines: `engines/recipe.mjs`; Bevy: `engines/bevy/build.rs`), and Bevy's calls only
//!   what the check calls, so the recipes cannot drift from code that runs in the engine;
//! - the viewer's key table lists every key the viewer has.

use std::path::{Path, PathBuf};

const README_MAX_LINES: usize = 400;

/// Phrases that speak of the past, of one machine, or of the project's tracker, matched
/// in any letter case. The tracker's phrases are assembled (as the outside folder's name
/// below), so that this file does not itself carry what it forbids.
const FORBIDDEN: &[&str] = &[
    concat!("issue", " tracker"),
    concat!("the ", "issue's"),
    "this machine",
    "vcpu",
    "two-core",
    "currently",
    "not done yet",
    "came out",
    "(found by",
    "measured worse here",
    "used to",
    "no longer",
    "previously",
];

/// The documents outside the repository (the design brief and the notes it came with), by
/// the stems of their upper-case names (`<STEM>.md`, matched in that case: the repository's
/// own `docs/design.md` is not one of them), and the folder they live in.
const OUTSIDE_STEMS: &[&str] = &["design", "engines", "references", "platform"];
const OUTSIDE_FOLDER: &str = concat!("../", "shared");

/// What a line of the repository must not contain: each forbidden phrase in any case, each
/// outside file's name, the outside folder.
fn offences(line: &str) -> Vec<String> {
    let lower = line.to_lowercase();
    let mut found: Vec<String> = FORBIDDEN
        .iter()
        .filter(|p| lower.contains(*p))
        .map(|p| p.to_string())
        .collect();
    found.extend(
        OUTSIDE_STEMS
            .iter()
            .map(|s| format!("{}.md", s.to_uppercase()))
            .chain([OUTSIDE_FOLDER.to_string()])
            .filter(|name| line.contains(name.as_str())),
    );
    found
}

fn read(path: &Path) -> String {
    std::fs::read_to_string(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()))
}

fn files_under(dir: &str, ext: &[&str], out: &mut Vec<PathBuf>) {
    files_under_skipping(dir, ext, out)
}

/// As `files_under`, leaving out installed packages (`node_modules`) and build outputs.
fn files_under_skipping(dir: &str, ext: &[&str], out: &mut Vec<PathBuf>) {
    for entry in std::fs::read_dir(dir).unwrap() {
        let path = entry.unwrap().path();
        if path.is_dir() {
            if path
                .file_name()
                .is_some_and(|n| n == "node_modules" || n == "target")
            {
                continue;
            }
            files_under_skipping(path.to_str().unwrap(), ext, out);
        } else if path
            .extension()
            .is_some_and(|e| ext.iter().any(|x| e == *x))
        {
            out.push(path);
        }
    }
}

#[test]
fn readme_is_short() {
    let lines = read(Path::new("README.md")).lines().count();
    assert!(
        lines <= README_MAX_LINES,
        "README.md has {lines} lines (at most {README_MAX_LINES})"
    );
}

#[test]
fn no_past_no_machine_no_outside_files() {
    let mut files = vec![PathBuf::from("README.md"), PathBuf::from("CONTRIBUTING.md")];
    files_under("docs", &["md"], &mut files);
    files_under("src", &["rs"], &mut files);
    files_under("shaders", &["wgsl"], &mut files);
    for dir in ["tests", "benches", "examples", "fuzz/fuzz_targets"] {
        files_under(dir, &["rs"], &mut files);
    }
    for engine in ["three", "filament", "babylon", "gltf", "bevy"] {
        files_under_skipping(
            &format!("engines/{engine}"),
            &["mjs", "js", "rs", "md"],
            &mut files,
        );
    }
    files_under("bevy", &["rs"], &mut files);
    files.push(PathBuf::from("fuzz/README.md"));
    files.push(PathBuf::from(".ci/run"));
    // This file lists the phrases.
    files.retain(|p| p != Path::new("tests/readme.rs"));
    let mut found = Vec::new();
    for path in &files {
        for (n, line) in read(path).lines().enumerate() {
            for phrase in offences(line) {
                found.push(format!(
                    "{}:{}: '{phrase}': {}",
                    path.display(),
                    n + 1,
                    line.trim()
                ));
            }
        }
    }
    assert!(found.is_empty(), "{}", found.join("\n"));
}

/// The code blocks (js or rust) under the README heading that starts with `heading`, up to
/// the next heading of the same or a higher level.
fn recipe(readme: &str, heading: &str) -> String {
    let start = readme
        .find(&format!("\n### {heading}"))
        .unwrap_or_else(|| panic!("no README heading '### {heading}'"));
    let rest = &readme[start + 1..];
    let end = rest[4..].find("\n##").map_or(rest.len(), |e| e + 4);
    let section = &rest[..end];
    let mut code = String::new();
    let mut inside = false;
    for line in section.lines() {
        if let Some(lang) = line.strip_prefix("```") {
            inside = !inside && matches!(lang, "js" | "rust");
            continue;
        }
        if inside {
            // Comments are prose and strings are data, not calls.
            let line = line.split("//").next().unwrap_or("");
            let line = strip_strings(line);
            code.push_str(&line);
            code.push('\n');
        }
    }
    assert!(!code.trim().is_empty(), "no code under '{heading}'");
    code
}

/// `line` with the contents of its string literals removed.
fn strip_strings(line: &str) -> String {
    let mut out = String::new();
    let mut quote = None;
    for c in line.chars() {
        match quote {
            Some(q) if c == q => {
                quote = None;
                out.push(c);
            }
            Some(_) => {}
            None => {
                if matches!(c, '"' | '\'' | '`') {
                    quote = Some(c);
                }
                out.push(c);
            }
        }
    }
    out
}

/// The names a snippet calls or constructs: `name(`, `.name`, `Name {`, `Name::`.
fn called_names(code: &str) -> Vec<String> {
    let chars: Vec<char> = code.chars().collect();
    let mut names = Vec::new();
    let mut i = 0;
    while i < chars.len() {
        if chars[i].is_alphabetic() || chars[i] == '_' {
            let start = i;
            while i < chars.len() && (chars[i].is_alphanumeric() || chars[i] == '_') {
                i += 1;
            }
            let name: String = chars[start..i].iter().collect();
            let before = start.checked_sub(1).map(|k| chars[k]);
            let after: String = chars[i..].iter().take(3).collect();
            let after = after.trim_start();
            let is_call = after.starts_with('(')
                || before == Some('.')
                || after.starts_with("::")
                || (name.starts_with(char::is_uppercase) && after.starts_with('{'));
            if is_call {
                names.push(name);
            }
        } else {
            i += 1;
        }
    }
    names.sort();
    names.dedup();
    names
}

/// Names of the language and the platform that a check need not call to vouch for them.
const PLATFORM: &[&str] = &[
    "fetch",
    "arrayBuffer",
    "json",
    "Uint8Array",
    "then",
    "default",
    "spawn",
    "load",
    "Some",
    "texture",
];

/// The engine checks that run the README's recipe as written (`engines/recipe.mjs`): the
/// README heading and the check that runs the code under it.
const RECIPES_RUN: &[(&str, &str)] = &[
    ("three.js", "engines/three/check.mjs"),
    ("Filament", "engines/filament/check.mjs"),
    ("Babylon.js", "engines/babylon/check.mjs"),
    ("glTF Sample Viewer", "engines/gltf/check.mjs"),
];

#[test]
fn engine_checks_run_the_readme_recipes() {
    let readme = read(Path::new("README.md"));
    let mut missing = Vec::new();
    for (heading, check) in RECIPES_RUN {
        // The heading has its code block.
        recipe(&readme, heading);
        let code = read(Path::new(check));
        if !code.contains(&format!("heading: '{heading}'")) || !code.contains("  recipe,\n") {
            missing.push(format!(
                "{check} does not run the README's '{heading}' recipe"
            ));
        }
    }
    // Bevy's check compiles the README's Rust block into itself.
    let build = read(Path::new("engines/bevy/build.rs"));
    let main = read(Path::new("engines/bevy/src/main.rs"));
    if !build.contains("\"\\n### Bevy\"") || !main.contains("readme_recipe::add(&mut app)") {
        missing.push("engines/bevy does not build and run the README's 'Bevy' recipe".into());
    }
    assert!(missing.is_empty(), "{}", missing.join("\n"));
}

/// The Bevy check (which compiles the README's recipe) needs a Bevy build that CI does not
/// make; here the recipe is held to calling only what the check's own code calls.
#[test]
fn engine_recipes_call_what_the_checks_call() {
    let readme = read(Path::new("README.md"));
    let checks: &[(&str, &str)] = &[("Bevy", "engines/bevy/src")];
    let mut missing = Vec::new();
    for (heading, dir) in checks {
        let mut files = Vec::new();
        files_under(dir, &["rs"], &mut files);
        let code: String = files.iter().map(|f| read(f)).collect();
        for name in called_names(&recipe(&readme, heading)) {
            if PLATFORM.contains(&name.as_str()) {
                continue;
            }
            if !code.contains(&name) {
                missing.push(format!("{heading}: '{name}' is not in {dir}"));
            }
        }
    }
    assert!(missing.is_empty(), "{}", missing.join("\n"));
}

/// The text under the README heading `## {heading}`, up to the next `## ` heading.
fn section<'a>(readme: &'a str, heading: &str) -> &'a str {
    let start = readme
        .find(&format!("\n## {heading}\n"))
        .unwrap_or_else(|| panic!("no README heading '## {heading}'"));
    let rest = &readme[start + 1..];
    let end = rest[1..].find("\n## ").map_or(rest.len(), |e| e + 1);
    &rest[..end]
}

/// The commands of the `sh` blocks of `text`, their comments left out.
fn sh_commands(text: &str) -> Vec<String> {
    let mut commands = Vec::new();
    let mut inside = false;
    for line in text.lines() {
        if let Some(lang) = line.strip_prefix("```") {
            inside = !inside && lang == "sh";
            continue;
        }
        let command = line.split(" #").next().unwrap_or("").trim();
        if inside && !command.is_empty() {
            commands.push(command.to_string());
        }
    }
    commands
}

/// How the quick start runs the tool from a clone, before `cargo install`.
const RUN: &str = "cargo run --release -- ";

/// The quick start runs in a fresh clone as written: its first command builds the tool and
/// bakes a bundled HDRI, its second runs the tests, and every command is a `cargo` one
/// (`splitsum` is on the PATH only after the Install section's `cargo install`), each run
/// naming a command the README lists and files the clone has or the bake writes.
#[test]
fn the_quick_start_runs_in_a_fresh_clone() {
    let readme = read(Path::new("README.md"));
    assert!(
        sh_commands(section(&readme, "Install"))
            .contains(&"cargo install --path . --locked".into()),
        "the Install section installs with cargo install --path . --locked"
    );
    let commands = sh_commands(section(&readme, "Quick start"));
    let input = "tests/data/venice_sunset_1k.hdr";
    assert_eq!(
        commands[..2],
        [
            format!("{RUN}bake {input}"),
            "cargo test --release".to_string()
        ],
        "the quick start's first two commands"
    );
    let listed = section(&readme, "Commands");
    let bake_dir = format!(
        "out/{}",
        Path::new(input).file_stem().unwrap().to_str().unwrap()
    );
    for command in &commands {
        assert!(
            command.starts_with("cargo "),
            "'{command}' needs the install"
        );
        let Some(args) = command.strip_prefix(RUN) else {
            continue;
        };
        let mut args = args.split_whitespace();
        let name = args.next().unwrap_or_default();
        assert!(
            listed.contains(&format!("splitsum {name} ")),
            "'{command}': the README lists no command '{name}'"
        );
        for arg in args.filter(|a| !a.starts_with('-')) {
            assert!(
                Path::new(arg).exists() || arg == bake_dir,
                "'{command}': {arg} is neither in the clone nor the bake's folder"
            );
        }
    }
}

#[test]
fn the_key_table_lists_every_key() {
    let readme = read(Path::new("README.md"));
    for (key, token, _, _) in splitsum::VIEW_KEYS {
        let first = key.split([' ', ',', '/']).next().unwrap_or(key);
        assert!(readme.contains(first), "README's key table lacks '{key}'");
        for t in token
            .split(['/', '…'])
            .map(str::trim)
            .filter(|t| !t.is_empty())
        {
            assert!(
                readme.contains(&format!("`{t}`")),
                "README's key table lacks the token '{t}'"
            );
        }
    }
}
