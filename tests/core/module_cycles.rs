//! No module imports one that imports it back: the `use` lines and the `crate::`/`super::`
//! paths of every crate's sources, as edges between the two sibling modules that hold each end
//! (`crate::cpu::trace` using `crate::flat` is cpu → flat), and the strongly connected sets of
//! siblings that form circles: there must be none. Items under `#[cfg(test)]` are left out,
//! each to its end (a test module at the top of a file hid the rest of it).

use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};

/// The crates and their source roots, from the workspace root.
const CRATES: [(&str, &str); 9] = [
    ("glint_types", "crates/glint-types/src"),
    ("glint_scene", "crates/glint-scene/src"),
    ("glint_io", "crates/glint-io/src"),
    ("glint_core", "crates/glint-core/src"),
    ("glint_gpu", "crates/glint-gpu/src"),
    ("glint_viewer", "crates/glint-viewer/src"),
    ("glint_test_support", "crates/glint-test-support/src"),
    ("glint_fuzz", "crates/glint-fuzz/src"),
    ("glint", "src"),
];

/// `file`'s module path inside its crate (`cpu/trace.rs` → `[cpu, trace]`).
fn module_of(root: &Path, file: &Path) -> Vec<String> {
    let rel = file.strip_prefix(root).expect("under the root").with_extension("");
    let mut parts: Vec<String> = rel.iter().map(|p| p.to_string_lossy().into_owned()).collect();
    if matches!(parts.last().map(String::as_str), Some("mod" | "lib" | "main")) {
        parts.pop();
    }
    parts
}

fn files(dir: &Path, out: &mut Vec<PathBuf>) {
    for entry in std::fs::read_dir(dir).expect("read the source folder") {
        let path = entry.expect("a folder entry").path();
        if path.is_dir() {
            files(&path, out);
        } else if path.extension().is_some_and(|e| e == "rs") {
            out.push(path);
        }
    }
}

/// Every path in `text` that starts at `crate::`, `super::` or `self::`, with `use` trees
/// expanded (`crate::a::{b, c::d}` → `crate::a::b`, `crate::a::c::d`).
fn paths(text: &str) -> Vec<Vec<String>> {
    let mut out = Vec::new();
    let bytes: Vec<char> = text.chars().collect();
    let mut i = 0;
    while i < bytes.len() {
        let rest: String = bytes[i..bytes.len().min(i + 7)].iter().collect();
        let starts = ["crate::", "super::", "self::"].iter().any(|r| rest.starts_with(r));
        let boundary = i == 0 || !(bytes[i - 1].is_alphanumeric() || bytes[i - 1] == '_' || bytes[i - 1] == ':');
        if starts && boundary {
            let mut j = i;
            let mut depth = 0;
            while j < bytes.len() {
                let c = bytes[j];
                if c == '{' {
                    depth += 1;
                } else if c == '}' {
                    if depth == 0 {
                        break;
                    }
                    depth -= 1;
                } else if depth == 0 && !(c.is_alphanumeric() || c == '_' || c == ':') {
                    break;
                }
                j += 1;
            }
            let tree: String = bytes[i..j].iter().collect();
            expand("", &tree.replace(char::is_whitespace, ""), &mut out);
            i = j;
        } else {
            i += 1;
        }
    }
    out
}

/// The paths of the use tree `tree` under `prefix`.
fn expand(prefix: &str, tree: &str, out: &mut Vec<Vec<String>>) {
    match tree.find('{') {
        None => {
            let full = format!("{prefix}{tree}");
            out.push(full.split("::").filter(|s| !s.is_empty()).map(str::to_string).collect());
        }
        Some(open) => {
            let (head, body) = (&tree[..open], &tree[open + 1..tree.rfind('}').unwrap_or(tree.len())]);
            let mut depth = 0;
            let mut start = 0;
            for (k, c) in body.char_indices() {
                match c {
                    '{' => depth += 1,
                    '}' => depth -= 1,
                    ',' if depth == 0 => {
                        expand(&format!("{prefix}{head}"), &body[start..k], out);
                        start = k + 1;
                    }
                    _ => {}
                }
            }
            if start < body.len() {
                expand(&format!("{prefix}{head}"), &body[start..], out);
            }
        }
    }
}

/// The module `path` names, from module `at`, cut to the longest known module.
fn target(at: &[String], path: &[String], known: &BTreeSet<Vec<String>>) -> Option<Vec<String>> {
    let mut module: Vec<String> = match path.first()?.as_str() {
        "crate" => Vec::new(),
        "self" => at.to_vec(),
        "super" => at[..at.len().checked_sub(1)?].to_vec(),
        _ => return None,
    };
    let mut rest = &path[1..];
    while rest.first().is_some_and(|s| s == "super") {
        module.pop();
        rest = &rest[1..];
    }
    for part in rest {
        let mut next = module.clone();
        next.push(part.clone());
        if !known.contains(&next) {
            break;
        }
        module = next;
    }
    Some(module)
}

/// The sibling circles of `edges`: strongly connected sets of more than one module.
fn circles(edges: &BTreeMap<String, BTreeSet<String>>) -> Vec<Vec<String>> {
    let nodes: BTreeSet<&String> = edges.keys().chain(edges.values().flatten()).collect();
    let reach = |from: &String| {
        let mut seen = BTreeSet::new();
        let mut stack = vec![from.clone()];
        while let Some(n) = stack.pop() {
            for m in edges.get(&n).into_iter().flatten() {
                if seen.insert(m.clone()) {
                    stack.push(m.clone());
                }
            }
        }
        seen
    };
    let reached: BTreeMap<&String, BTreeSet<String>> = nodes.iter().map(|n| (*n, reach(n))).collect();
    let mut out: BTreeSet<Vec<String>> = BTreeSet::new();
    for n in &nodes {
        let set: Vec<String> = nodes
            .iter()
            .filter(|m| reached[*n].contains(**m) && reached[*m].contains(*n))
            .map(|m| (*m).clone())
            .collect();
        if set.len() > 1 {
            out.insert(set);
        }
    }
    out.into_iter().collect()
}

/// `text` without each item marked `#[cfg(test)]`: the item runs to its `;` or to the `}`
/// that closes its first `{` (braces in strings and comments are rare enough in this code's
/// test modules' headers not to matter; a miscount only leaves out more of a test).
fn without_test_items(text: &str) -> String {
    const MARK: &str = "#[cfg(test)]";
    let mut out = String::with_capacity(text.len());
    let mut rest = text;
    while let Some(at) = rest.find(MARK) {
        out.push_str(&rest[..at]);
        let item = &rest[at + MARK.len()..];
        let mut depth = 0usize;
        let mut end = item.len();
        for (i, c) in item.char_indices() {
            match c {
                '{' => depth += 1,
                '}' if depth > 0 => {
                    depth -= 1;
                    if depth == 0 {
                        end = i + 1;
                        break;
                    }
                }
                ';' if depth == 0 => {
                    end = i + 1;
                    break;
                }
                _ => {}
            }
        }
        rest = &item[end..];
    }
    out.push_str(rest);
    out
}

#[test]
fn a_test_item_is_left_out_and_what_follows_it_is_read() {
    let text =
        "use a;\n#[cfg(test)]\nmod tests {\n    use b;\n    fn f() { g() }\n}\nuse c;\n#[cfg(test)]\nuse d;\nuse e;\n";
    assert_eq!(without_test_items(text), "use a;\n\nuse c;\n\nuse e;\n");
}

#[test]
fn no_module_imports_one_that_imports_it_back() {
    let workspace = Path::new(env!("CARGO_MANIFEST_DIR"));
    let mut found: BTreeSet<(String, Vec<String>)> = BTreeSet::new();
    for (name, dir) in CRATES {
        let root = workspace.join(dir);
        let mut sources = Vec::new();
        files(&root, &mut sources);
        let known: BTreeSet<Vec<String>> = sources.iter().map(|f| module_of(&root, f)).collect();
        // Edges between siblings, by their parent module.
        let mut graph: BTreeMap<Vec<String>, BTreeMap<String, BTreeSet<String>>> = BTreeMap::new();
        for file in &sources {
            let at = module_of(&root, file);
            let text = std::fs::read_to_string(file).expect("read a source file");
            let code = without_test_items(&text);
            for path in paths(&code) {
                let Some(to) = target(&at, &path, &known) else { continue };
                let common = at.iter().zip(&to).take_while(|(a, b)| a == b).count();
                // A module and its own ancestors or descendants are one subtree.
                if common == at.len() || common == to.len() {
                    continue;
                }
                let parent = at[..common].to_vec();
                graph.entry(parent).or_default().entry(at[common].clone()).or_default().insert(to[common].clone());
            }
        }
        for edges in graph.values() {
            for circle in circles(edges) {
                found.insert((name.to_string(), circle));
            }
        }
    }
    assert!(found.is_empty(), "modules that import each other back (take the circle apart): {found:?}");
}
