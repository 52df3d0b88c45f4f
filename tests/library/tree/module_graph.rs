//! The library's layers hold: no module of `src/` imports a module that imports it, directly or
//! through others. Reads every `use crate::...` line under `src/` (grouped imports included,
//! names re-exported at the crate root resolved through `lib.rs`), builds the graph of the
//! top-level modules, and, inside each top-level module, the graph of its submodules (a parent
//! and its children are one unit: `mod.rs` declares and re-exports them). Fails on any cycle,
//! printing it.

use std::collections::{BTreeMap, BTreeSet};
use std::fs;
use std::path::{Path, PathBuf};

/// Every `.rs` file under `dir`.
pub(crate) fn sources(dir: &Path) -> Vec<PathBuf> {
    let mut out = Vec::new();
    let mut stack = vec![dir.to_path_buf()];
    while let Some(d) = stack.pop() {
        for entry in fs::read_dir(&d).unwrap() {
            let p = entry.unwrap().path();
            if p.is_dir() {
                stack.push(p);
            } else if p.extension().is_some_and(|e| e == "rs") {
                out.push(p);
            }
        }
    }
    out.sort();
    out
}

/// The module path of a file below `src/`: `points/dynamic/index.rs` is
/// `["points", "dynamic", "index"]`, a `mod.rs` its folder's path.
fn module_of(src: &Path, file: &Path) -> Vec<String> {
    let rel = file.strip_prefix(src).unwrap();
    let mut parts: Vec<String> = rel
        .iter()
        .map(|c| c.to_string_lossy().trim_end_matches(".rs").to_string())
        .collect();
    if parts.last().is_some_and(|p| p == "mod") {
        parts.pop();
    }
    parts
}

/// The text of every `use crate::...;` statement in `text` (joined across lines), without
/// `use crate::`.
fn crate_uses(text: &str) -> Vec<String> {
    let mut out = Vec::new();
    let mut rest = text;
    while let Some(at) = rest.find("use crate::") {
        let before = &rest[..at];
        let line_start = before.rfind('\n').map_or(0, |i| i + 1);
        let prefix = before[line_start..].trim();
        let tail = &rest[at + "use crate::".len()..];
        let end = tail.find(';').unwrap_or(tail.len());
        // Skip mentions in comments and docs.
        if prefix.is_empty() || prefix == "pub" || prefix.starts_with("pub(") {
            out.push(tail[..end].split_whitespace().collect::<Vec<_>>().join(" "));
        }
        rest = &tail[end..];
    }
    out
}

/// The paths one `use` tree names, as segments: `a::{b, c::d}` gives `[a, b]` and `[a, c, d]`.
fn expand(tree: &str) -> Vec<Vec<String>> {
    let tree = tree.trim();
    match tree.find('{') {
        None => vec![tree
            .split("::")
            .map(|s| s.trim().split(' ').next().unwrap_or("").to_string())
            .filter(|s| !s.is_empty())
            .collect()],
        Some(open) => {
            let head: Vec<String> = tree[..open]
                .split("::")
                .map(|s| s.trim().to_string())
                .filter(|s| !s.is_empty())
                .collect();
            let inner = &tree[open + 1..tree.rfind('}').unwrap()];
            let (mut depth, mut start, mut parts) = (0, 0, Vec::new());
            for (i, c) in inner.char_indices() {
                match c {
                    '{' => depth += 1,
                    '}' => depth -= 1,
                    ',' if depth == 0 => {
                        parts.push(&inner[start..i]);
                        start = i + 1;
                    }
                    _ => {}
                }
            }
            parts.push(&inner[start..]);
            parts
                .into_iter()
                .filter(|p| !p.trim().is_empty())
                .flat_map(expand)
                .map(|tail| head.iter().cloned().chain(tail).collect())
                .collect()
        }
    }
}

/// The names `lib.rs` re-exports at the crate root, with the module each comes from.
fn root_names(lib: &str) -> BTreeMap<String, String> {
    let mut names = BTreeMap::new();
    let mut rest = lib;
    while let Some(at) = rest.find("pub use ") {
        let tail = &rest[at + "pub use ".len()..];
        let end = tail.find(';').unwrap();
        for path in expand(&tail[..end]) {
            if path.len() >= 2 && path[0] != "crate" {
                names.insert(path.last().unwrap().clone(), path[0].clone());
            }
        }
        rest = &tail[end..];
    }
    names
}

/// A cycle in `graph`, if any, as the nodes along it.
fn find_cycle(graph: &BTreeMap<String, BTreeSet<String>>) -> Option<Vec<String>> {
    // Iterative depth-first search with colours: 1 on the stack, 2 done.
    let mut colour: BTreeMap<&str, u8> = BTreeMap::new();
    for start in graph.keys() {
        if colour.contains_key(start.as_str()) {
            continue;
        }
        let mut stack: Vec<(&str, Vec<&str>)> =
            vec![(start, graph[start].iter().map(String::as_str).collect())];
        colour.insert(start, 1);
        while let Some((node, pending)) = stack.last_mut() {
            let node = *node;
            match pending.pop() {
                Some(next) => match colour.get(next) {
                    Some(1) => {
                        let at = stack.iter().position(|(n, _)| *n == next).unwrap();
                        let mut cycle: Vec<String> =
                            stack[at..].iter().map(|(n, _)| n.to_string()).collect();
                        cycle.push(next.to_string());
                        return Some(cycle);
                    }
                    Some(_) => {}
                    None => {
                        colour.insert(next, 1);
                        let out = graph
                            .get(next)
                            .map(|s| s.iter().map(String::as_str).collect())
                            .unwrap_or_default();
                        stack.push((next, out));
                    }
                },
                None => {
                    colour.insert(node, 2);
                    stack.pop();
                }
            }
        }
    }
    None
}

/// Whether `name` is a submodule of the module in folder `dir` (not an item of its `mod.rs`).
fn is_module(dir: &Path, name: &str) -> bool {
    dir.join(format!("{name}.rs")).is_file() || dir.join(name).join("mod.rs").is_file()
}

/// The edges between top-level modules, and inside each top-level module between its direct
/// submodules.
fn graphs() -> BTreeMap<String, BTreeMap<String, BTreeSet<String>>> {
    let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("src");
    let lib = fs::read_to_string(src.join("lib.rs")).unwrap();
    let roots = root_names(&lib);
    let mut graphs: BTreeMap<String, BTreeMap<String, BTreeSet<String>>> = BTreeMap::new();
    for file in sources(&src) {
        let here = module_of(&src, &file);
        if here.is_empty() || here == ["lib"] {
            continue;
        }
        let text = fs::read_to_string(&file).unwrap();
        for tree in crate_uses(&text) {
            for mut path in expand(&tree) {
                if let Some(module) = roots.get(&path[0]) {
                    path.insert(0, module.clone());
                }
                let top = graphs.entry(String::new()).or_default();
                top.entry(here[0].clone()).or_default();
                if path[0] != here[0] {
                    top.get_mut(&here[0]).unwrap().insert(path[0].clone());
                } else if here.len() >= 2
                    && path.len() >= 2
                    && path[1] != here[1]
                    && is_module(&src.join(&path[0]), &path[1])
                {
                    let inner = graphs.entry(here[0].clone()).or_default();
                    inner
                        .entry(here[1].clone())
                        .or_default()
                        .insert(path[1].clone());
                }
            }
        }
    }
    graphs
}

#[test]
fn no_module_imports_a_module_that_imports_it() {
    let graphs = graphs();
    for (scope, graph) in &graphs {
        let name = if scope.is_empty() { "crate" } else { scope };
        println!("{name}:");
        for (from, to) in graph {
            println!(
                "  {from} -> {}",
                to.iter().cloned().collect::<Vec<_>>().join(", ")
            );
        }
    }
    let cycles: Vec<String> = graphs
        .iter()
        .filter_map(|(scope, g)| find_cycle(g).map(|c| format!("{scope}: {}", c.join(" -> "))))
        .collect();
    assert!(cycles.is_empty(), "import cycles: {cycles:#?}");
}

#[test]
fn the_reader_sees_grouped_and_root_imports() {
    let uses =
        crate_uses("use crate::geom::{Aabb, deep::{DeepCell, DeepKey}};\n// use crate::io;\n");
    assert_eq!(uses.len(), 1, "a comment is not an import");
    let paths = expand(&uses[0]);
    assert_eq!(
        paths,
        [
            vec!["geom", "Aabb"],
            vec!["geom", "deep", "DeepCell"],
            vec!["geom", "deep", "DeepKey"]
        ]
    );
    let roots = root_names("pub use geom::{Aabb, Cell};\npub use tree::NodeId;");
    assert_eq!(roots["Cell"], "geom");
    assert_eq!(roots["NodeId"], "tree");
    let mut g: BTreeMap<String, BTreeSet<String>> = BTreeMap::new();
    g.entry("a".into()).or_default().insert("b".into());
    g.entry("b".into()).or_default().insert("c".into());
    assert_eq!(find_cycle(&g), None);
    g.entry("c".into()).or_default().insert("a".into());
    let cycle = find_cycle(&g).unwrap();
    assert_eq!((cycle.first(), cycle.len()), (cycle.last(), 4));
}
