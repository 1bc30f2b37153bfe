//! The library's layering (the list in `src/lib.rs`'s documentation), checked from the
//! source: every `crate::` path outside comments (in `use` lines and in code) is resolved to
//! the module it names, and
//! - no module imports from a layer above its own;
//! - no two modules import each other (a parent re-exporting its children with `pub use`
//!   is not an import);
//! - no file of `src/` is over 600 lines.

use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};

/// Top-level modules by layer, bottom first (`src/lib.rs`, "Layers").
const LAYERS: &[&[&str]] = &[
    &["error"],
    &["math"],
    &["environment"],
    &["plan"],
    &["cpu", "gpu"],
    &["backend"],
    &["stages"],
    &["io", "targets"],
    &["bake", "verify"],
    &["view"],
];

/// Largest file of `src/`.
const MAX_LINES: usize = 600;

fn layer_of(top: &str) -> usize {
    LAYERS
        .iter()
        .position(|l| l.contains(&top))
        .unwrap_or_else(|| panic!("module {top} is in no layer of tests/layers.rs"))
}

/// Every library source file with its module path (`stages::preview`); the binary's own
/// files (`main.rs`, `cli/`) sit above every layer and are left out.
fn library_files() -> Vec<(String, PathBuf)> {
    fn walk(dir: &Path, out: &mut Vec<PathBuf>) {
        for entry in std::fs::read_dir(dir).unwrap() {
            let path = entry.unwrap().path();
            if path.is_dir() {
                walk(&path, out);
            } else if path.extension().is_some_and(|e| e == "rs") {
                out.push(path);
            }
        }
    }
    let mut files = Vec::new();
    walk(Path::new("src"), &mut files);
    files
        .into_iter()
        .filter_map(|p| {
            let rel = p.strip_prefix("src").unwrap().with_extension("");
            let parts: Vec<String> = rel
                .components()
                .map(|c| c.as_os_str().to_string_lossy().into_owned())
                .collect();
            let parts: Vec<String> = parts.into_iter().filter(|p| p != "mod").collect();
            match parts.first().map(String::as_str) {
                None | Some("lib" | "main" | "cli") => None,
                _ => Some((parts.join("::"), p)),
            }
        })
        .collect()
}

/// The code of a file without comments (line comments, doc comments) and string literals'
/// contents, so that `crate::` in prose is not an import.
fn code_of(text: &str) -> String {
    let mut out = String::new();
    for line in text.lines() {
        let mut code = String::new();
        let mut in_string = false;
        let mut chars = line.chars().peekable();
        while let Some(c) = chars.next() {
            if in_string {
                if c == '\\' {
                    chars.next();
                } else if c == '"' {
                    in_string = false;
                    code.push('"');
                }
                continue;
            }
            if c == '/' && chars.peek() == Some(&'/') {
                break;
            }
            if c == '"' {
                in_string = true;
            }
            code.push(c);
        }
        out.push_str(&code);
        out.push('\n');
    }
    out
}

/// The paths (`a::b::C`) that `crate::` introduces in `code`, braces of `use` groups
/// expanded one level deep per group; `pub use` lines (re-exports) are skipped.
fn crate_paths(code: &str) -> Vec<String> {
    let mut paths = Vec::new();
    let mut statements = code.split(';');
    for stmt in &mut statements {
        let trimmed = stmt.trim_start();
        let is_reexport = trimmed.starts_with("pub use") || trimmed.starts_with("pub(crate) use");
        let mut rest = stmt;
        while let Some(i) = rest.find("crate::") {
            let after = &rest[i + "crate::".len()..];
            rest = after;
            if is_reexport {
                continue;
            }
            paths.extend(expand(after));
        }
    }
    paths
}

/// The paths of one `crate::` occurrence: `a::b::c`, or a group `{a::b, c::{d, e}}`
/// expanded recursively (`a::b`, `c::d`, `c::e`).
fn expand(after: &str) -> Vec<String> {
    let Some(group) = after.strip_prefix('{') else {
        let path: String = after
            .chars()
            .take_while(|c| c.is_alphanumeric() || *c == '_' || *c == ':')
            .collect();
        let path = path.trim_end_matches("::");
        // `crate::a::{b, c}`: the group continues the path.
        let rest = &after[path.len()..];
        return match rest.strip_prefix("::") {
            Some(group) if group.starts_with('{') => expand(group)
                .into_iter()
                .map(|p| format!("{path}::{p}"))
                .collect(),
            _ => vec![path.to_string()],
        };
    };
    let mut depth = 1;
    let mut end = group.len();
    for (k, c) in group.char_indices() {
        match c {
            '{' => depth += 1,
            '}' => depth -= 1,
            _ => {}
        }
        if depth == 0 {
            end = k;
            break;
        }
    }
    let inner = &group[..end];
    let mut items = Vec::new();
    let (mut depth, mut start) = (0, 0);
    for (k, c) in inner.char_indices() {
        match c {
            '{' => depth += 1,
            '}' => depth -= 1,
            ',' if depth == 0 => {
                items.push(&inner[start..k]);
                start = k + 1;
            }
            _ => {}
        }
    }
    items.push(&inner[start..]);
    items
        .into_iter()
        .map(str::trim)
        .filter(|s| !s.is_empty() && *s != "self")
        .flat_map(expand)
        .collect()
}

/// The module a path names: its longest prefix that is a module of the crate.
fn module_of(path: &str, modules: &BTreeSet<String>) -> Option<String> {
    let parts: Vec<&str> = path.split("::").collect();
    (1..=parts.len())
        .rev()
        .map(|k| parts[..k].join("::"))
        .find(|m| modules.contains(m))
}

fn is_ancestor(a: &str, b: &str) -> bool {
    b.starts_with(&format!("{a}::"))
}

#[test]
fn no_module_imports_from_above_and_none_import_each_other() {
    let files = library_files();
    let modules: BTreeSet<String> = files.iter().map(|(m, _)| m.clone()).collect();
    let mut imports: BTreeMap<String, BTreeSet<String>> = BTreeMap::new();
    let mut upward = Vec::new();
    for (module, path) in &files {
        let text = std::fs::read_to_string(path).unwrap();
        let top = module.split("::").next().unwrap();
        for p in crate_paths(&code_of(&text)) {
            let Some(target) = module_of(&p, &modules) else {
                continue; // a root re-export (`crate::Result`) or an item of lib.rs
            };
            let target_top = target.split("::").next().unwrap();
            if layer_of(target_top) > layer_of(top) {
                upward.push(format!("{} imports crate::{p}", path.display()));
            }
            if target != *module {
                imports.entry(module.clone()).or_default().insert(target);
            }
        }
    }
    assert!(
        upward.is_empty(),
        "imports from a layer above:\n{}",
        upward.join("\n")
    );
    let mut mutual = Vec::new();
    for (a, targets) in &imports {
        for b in targets {
            if a < b
                && !is_ancestor(a, b)
                && !is_ancestor(b, a)
                && imports.get(b).is_some_and(|t| t.contains(a))
            {
                mutual.push(format!("{a} <-> {b}"));
            }
        }
    }
    assert!(
        mutual.is_empty(),
        "modules importing each other:\n{}",
        mutual.join("\n")
    );
}

#[test]
fn no_source_file_is_over_the_limit() {
    let mut long = Vec::new();
    for (_, path) in library_files() {
        let lines = std::fs::read_to_string(&path).unwrap().lines().count();
        if lines > MAX_LINES {
            long.push(format!("{} ({lines} lines)", path.display()));
        }
    }
    for extra in ["src/main.rs", "src/lib.rs"] {
        let lines = std::fs::read_to_string(extra).unwrap().lines().count();
        if lines > MAX_LINES {
            long.push(format!("{extra} ({lines} lines)"));
        }
    }
    assert!(
        long.is_empty(),
        "files over {MAX_LINES} lines: {}",
        long.join(", ")
    );
}

/// The checker itself: an upward import in a `use` group and in code is found, comments
/// and re-exports are not imports.
#[test]
fn the_checker_reads_use_groups_code_and_comments() {
    let code = code_of(
        "use crate::{math::brdf::d_ggx, plan::{chain::X, lut}};\n// crate::bake::hidden\npub use crate::io::Y;\nlet x = crate::stages::light::f();\n",
    );
    let paths = crate_paths(&code);
    assert_eq!(
        paths,
        [
            "math::brdf::d_ggx",
            "plan::chain::X",
            "plan::lut",
            "stages::light::f"
        ],
        "{code}"
    );
    let modules: BTreeSet<String> = ["math", "math::brdf", "plan", "plan::chain", "stages::light"]
        .map(String::from)
        .into();
    assert_eq!(
        module_of("math::brdf::d_ggx", &modules).as_deref(),
        Some("math::brdf")
    );
}
