//! ARCHITECTURE.md's dependency drawing is each crate's Cargo.toml, line for line, and its
//! normal dependencies point one way: down the drawing's order. The drawing had fallen behind
//! (seven crates said, eight built; direct edges left out) with nothing to notice it.

use std::collections::{BTreeMap, BTreeSet};

type Edges = BTreeMap<(String, bool), BTreeSet<String>>;

/// The Glint crates a Cargo.toml's `[dependencies]` (false) or `[dev-dependencies]` (true) name.
fn manifest_edges(name: &str, toml: &str, out: &mut Edges) {
    let mut section = None;
    for line in toml.lines().map(str::trim) {
        if line.starts_with('[') {
            section = match line {
                "[dependencies]" => Some(false),
                "[dev-dependencies]" => Some(true),
                _ => None,
            };
        } else if let Some(dev) = section {
            let dep = line.split(['.', ' ', '=']).next().unwrap_or("");
            if dep.starts_with("glint") {
                out.entry((name.to_string(), dev)).or_default().insert(dep.to_string());
            }
        }
    }
}

/// The drawing's lines `crate ──► a, b` (normal) and `crate ┄┄► a, b` (dev), in order.
fn drawn_edges(doc: &str) -> (Edges, Vec<String>) {
    let block = doc.split("```text").nth(1).and_then(|b| b.split("```").next()).expect("a ```text block");
    let (mut edges, mut order) = (Edges::new(), Vec::new());
    for line in block.lines() {
        for (arrow, dev) in [("──►", false), ("┄┄►", true)] {
            if let Some((from, to)) = line.split_once(arrow) {
                let from = from.trim().to_string();
                if !dev {
                    order.push(from.clone());
                }
                let to = to.split(',').map(str::trim).filter(|t| t.starts_with("glint")).map(String::from);
                edges.entry((from, dev)).or_default().extend(to);
            }
        }
    }
    edges.retain(|_, to| !to.is_empty());
    (edges, order)
}

#[test]
fn the_architecture_drawing_is_the_manifests() {
    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR"));
    let mut manifests = Edges::new();
    let read = |p: std::path::PathBuf| std::fs::read_to_string(&p).unwrap_or_else(|e| panic!("{}: {e}", p.display()));
    manifest_edges("glint", &read(root.join("Cargo.toml")), &mut manifests);
    let mut crates = vec!["glint".to_string()];
    for entry in std::fs::read_dir(root.join("crates")).expect("crates/") {
        let dir = entry.expect("an entry").path();
        let name = dir.file_name().unwrap().to_string_lossy().into_owned();
        if dir.join("Cargo.toml").exists() {
            manifest_edges(&name, &read(dir.join("Cargo.toml")), &mut manifests);
            crates.push(name);
        }
    }
    let doc = read(root.join("ARCHITECTURE.md"));
    let (drawn, order) = drawn_edges(&doc);
    assert_eq!(drawn, manifests, "ARCHITECTURE.md's drawing (left) against the Cargo.toml files (right)");
    let libraries = crates.len() - 1;
    let words = ["", "One", "Two", "Three", "Four", "Five", "Six", "Seven", "Eight", "Nine", "Ten"];
    let said = format!("{} library crates and one binary", words[libraries]);
    assert!(doc.contains(&said), "ARCHITECTURE.md should say \"{said}\"");
    for c in &crates {
        assert!(order.contains(c), "{c} has no line in the drawing");
    }
    // One way: a crate's normal dependencies are all drawn below it.
    for ((from, dev), to) in &drawn {
        let at = order.iter().position(|c| c == from).unwrap();
        for t in to.iter().filter(|_| !dev) {
            let below = order.iter().position(|c| c == t).is_some_and(|p| p > at);
            assert!(below, "{from} depends on {t}, which the drawing has above it");
        }
    }
}
