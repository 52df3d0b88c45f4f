//! The written rule for the public surface (the crate documentation's "The public surface")
//! holds: about twenty names at the crate root, and every public iterator type in `iter`, at
//! that one path. Reads `src/lib.rs` and every file under `src/`.

use super::module_graph::sources;
use std::fs;
use std::path::Path;

/// The most names the crate root may re-export, modules and the prelude aside.
const ROOT_NAMES_LIMIT: usize = 24;

/// The names a `pub use` statement brings in: `pub use a::{B, C};` gives `B` and `C`.
fn used_names(statement: &str) -> Vec<String> {
    let body = statement
        .trim_start_matches("pub use")
        .trim_end_matches(';')
        .trim();
    let list = match (body.find('{'), body.rfind('}')) {
        (Some(open), Some(close)) => &body[open + 1..close],
        _ => body,
    };
    list.split(',')
        .map(|item| {
            item.trim()
                .rsplit("::")
                .next()
                .unwrap_or("")
                .trim()
                .to_string()
        })
        .filter(|name| !name.is_empty())
        .collect()
}

/// The `pub use` statements of `text` at the top level (not inside a `mod` block), each joined
/// onto one line.
fn top_level_reexports(text: &str) -> Vec<String> {
    let mut out = Vec::new();
    let mut depth = 0usize;
    let mut current: Option<String> = None;
    for line in text.lines() {
        let trimmed = line.trim();
        if trimmed.starts_with("//") {
            continue;
        }
        if let Some(statement) = current.as_mut() {
            statement.push(' ');
            statement.push_str(trimmed);
            if trimmed.ends_with(';') {
                out.push(current.take().unwrap());
            }
            continue;
        }
        if depth == 0 && trimmed.starts_with("pub use ") {
            if trimmed.ends_with(';') {
                out.push(trimmed.to_string());
            } else {
                current = Some(trimmed.to_string());
            }
            continue;
        }
        depth += trimmed.matches('{').count();
        depth = depth.saturating_sub(trimmed.matches('}').count());
    }
    out
}

/// The names re-exported by `pub mod iter { ... }` in `lib.rs`.
fn iter_module_names(lib: &str) -> Vec<String> {
    let start = lib
        .find("pub mod iter {")
        .expect("lib.rs declares `pub mod iter`");
    let end = start + lib[start..].find("\n}").expect("the iter module is closed");
    lib[start..end]
        .lines()
        .filter(|l| l.trim().starts_with("pub use "))
        .flat_map(|l| used_names(l.trim()))
        .collect()
}

/// Every public struct of `src/` that implements `Iterator`, with its file.
fn public_iterators(src: &Path) -> Vec<(String, String)> {
    let mut out = Vec::new();
    for path in sources(src) {
        let text = fs::read_to_string(&path).unwrap();
        for line in text.lines() {
            let Some(rest) = line.trim().strip_prefix("impl") else {
                continue;
            };
            let Some(after) = rest.split(" Iterator for ").nth(1) else {
                continue;
            };
            let name: String = after
                .chars()
                .take_while(|c| c.is_alphanumeric() || *c == '_')
                .collect();
            if text.contains(&format!("pub struct {name}")) {
                out.push((name, path.display().to_string()));
            }
        }
    }
    out
}

#[test]
fn the_root_names_about_twenty_items() {
    let lib = fs::read_to_string(Path::new(env!("CARGO_MANIFEST_DIR")).join("src/lib.rs")).unwrap();
    let names: Vec<String> = top_level_reexports(&lib)
        .iter()
        .flat_map(|s| used_names(s))
        .collect();
    assert!(
        (15..=ROOT_NAMES_LIMIT).contains(&names.len()),
        "the crate root re-exports {} names ({names:?}); the rule allows {ROOT_NAMES_LIMIT}",
        names.len()
    );
    for name in [
        "PointTree",
        "PointSet",
        "Error",
        "QueryError",
        "Aabb",
        "Tree",
    ] {
        assert!(
            names.iter().any(|n| n == name),
            "{name} is missing at the root"
        );
    }
}

#[test]
fn every_public_iterator_is_in_the_iter_module_only() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let lib = fs::read_to_string(root.join("src/lib.rs")).unwrap();
    let in_iter = iter_module_names(&lib);
    let iterators = public_iterators(&root.join("src"));
    assert!(
        iterators.len() >= 5,
        "found only {iterators:?}: the scan is broken"
    );
    for (name, file) in &iterators {
        assert!(
            in_iter.contains(name),
            "{name} ({file}) is a public iterator missing from `orthtree::iter`"
        );
    }
    // No module re-exports an iterator a second time.
    for path in sources(&root.join("src")) {
        if path.ends_with("lib.rs") {
            continue;
        }
        let text = fs::read_to_string(&path).unwrap();
        for statement in top_level_reexports(&text) {
            for name in used_names(&statement) {
                assert!(
                    !in_iter.contains(&name),
                    "{} re-exports the iterator {name}, which lives at `orthtree::iter`",
                    path.display()
                );
            }
        }
    }
}
