//! The library's top-level modules form no cycle: each knows only those below it (the issue's
//! "the module graph has no cycle", and design.md's layers). A module's dependencies are the
//! `crate::NAME` paths in its code (comments left out, so doc links do not count); the wasm
//! bindings and the CLI sit on top and are left out.

use std::collections::{BTreeMap, BTreeSet};
use std::path::Path;

fn rust_files(dir: &Path, out: &mut Vec<std::path::PathBuf>) {
    for entry in std::fs::read_dir(dir).unwrap() {
        let path = entry.unwrap().path();
        if path.is_dir() {
            rust_files(&path, out);
        } else if path.extension().is_some_and(|e| e == "rs") {
            out.push(path);
        }
    }
}

/// Whether `from` depends on `to`, directly or through other modules.
fn reaches(graph: &BTreeMap<String, BTreeSet<String>>, from: &str, to: &str) -> bool {
    let mut seen = BTreeSet::new();
    let mut stack = vec![from.to_string()];
    while let Some(node) = stack.pop() {
        if node == to {
            return true;
        }
        if seen.insert(node.clone()) {
            stack.extend(graph.get(&node).into_iter().flatten().cloned());
        }
    }
    false
}

#[test]
fn modules_form_no_cycle() {
    let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("src");
    let mut files = Vec::new();
    rust_files(&src, &mut files);
    let mut graph: BTreeMap<String, BTreeSet<String>> = BTreeMap::new();
    for path in files {
        let relative = path.strip_prefix(&src).unwrap();
        let first = relative.components().next().unwrap().as_os_str().to_string_lossy();
        let module = first.trim_end_matches(".rs").to_string();
        if ["wasm", "bin", "lib"].contains(&module.as_str()) {
            continue;
        }
        let text = std::fs::read_to_string(&path).unwrap();
        let deps = graph.entry(module.clone()).or_default();
        for line in text.lines().filter(|l| !l.trim_start().starts_with("//")) {
            for (i, _) in line.match_indices("crate::") {
                let name: String = line[i + 7..]
                    .chars()
                    .take_while(|c| c.is_ascii_lowercase() || *c == '_')
                    .collect();
                if !name.is_empty() && name != module {
                    deps.insert(name);
                }
            }
        }
    }
    assert!(graph.len() >= 10, "modules found: {:?}", graph.keys());
    // `triangles` (triangle soups welded and joined into faces, for subsurf/three) sits beside
    // the scheme and evaluation layers: the layers below never reach it, and it needs nothing
    // but the mesh type and the error type.
    assert!(graph.contains_key("triangles"), "modules found: {:?}", graph.keys());
    for low in ["mesh", "refine", "rules"] {
        assert!(
            !reaches(&graph, low, "triangles"),
            "{low} depends on triangles; design.md's layers keep it below"
        );
    }
    let allowed: BTreeSet<String> = ["error", "mesh"].map(String::from).into();
    assert!(
        graph["triangles"].is_subset(&allowed),
        "triangles depends on {:?}; it should need only {allowed:?}",
        graph["triangles"]
    );
    // Depth-first search for a back edge.
    fn visit(
        node: &str,
        graph: &BTreeMap<String, BTreeSet<String>>,
        stack: &mut Vec<String>,
        done: &mut BTreeSet<String>,
    ) {
        if done.contains(node) {
            return;
        }
        if let Some(at) = stack.iter().position(|n| n == node) {
            panic!("module cycle: {} -> {node}", stack[at..].join(" -> "));
        }
        stack.push(node.to_string());
        for next in graph.get(node).into_iter().flatten() {
            visit(next, graph, stack, done);
        }
        stack.pop();
        done.insert(node.to_string());
    }
    let mut done = BTreeSet::new();
    for node in graph.keys() {
        visit(node, &graph, &mut Vec::new(), &mut done);
    }
}
