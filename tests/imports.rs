//! Imports run one way: no circle of `use crate::...` / `use super::...` imports between the files under
//! `src/`. A module and its own submodules are one unit here (a child uses its parent's items, the
//! parent re-exports the child's), so only imports between files that are not each other's ancestor
//! count. Test modules (`#[cfg(test)]` and below, `tests.rs`) are left out.

use std::collections::{BTreeMap, BTreeSet};
use std::fs;
use std::path::{Path, PathBuf};

/// Every `.rs` file under `dir`.
fn sources(dir: &Path, out: &mut Vec<PathBuf>) {
    for entry in fs::read_dir(dir).expect("src is readable") {
        let path = entry.expect("a directory entry").path();
        if path.is_dir() {
            sources(&path, out);
        } else if path.extension().is_some_and(|e| e == "rs") {
            out.push(path);
        }
    }
}

/// The module path of a file relative to `src/`: `model/chain/mod.rs` is `["model", "chain"]`.
fn module_of(relative: &Path) -> Vec<String> {
    let mut parts: Vec<String> = relative
        .iter()
        .map(|p| p.to_string_lossy().into_owned())
        .collect();
    let last = parts.pop().expect("a file name");
    let stem = last.trim_end_matches(".rs");
    if !matches!(stem, "mod" | "lib" | "main") {
        parts.push(stem.to_string());
    }
    parts
}

/// The paths a file imports, up to its tests: its top-level `use` declarations (each joined into one
/// statement) and the `crate::` and `super::` paths written out in its code.
fn use_statements(text: &str) -> Vec<String> {
    let mut out = Vec::new();
    let mut current: Option<String> = None;
    for line in text.lines() {
        if line.starts_with("#[cfg(test)]") {
            break;
        }
        let code = line.trim_start();
        if current.is_none() && !code.starts_with("//") && !code.contains("use ") {
            out.extend(written_paths(code));
        }
        if let Some(statement) = current.as_mut() {
            statement.push_str(line.trim());
        } else {
            let rest = line
                .strip_prefix("pub use ")
                .or_else(|| line.strip_prefix("pub(crate) use "))
                .or_else(|| line.strip_prefix("pub(super) use "))
                .or_else(|| line.strip_prefix("use "));
            if let Some(rest) = rest {
                current = Some(rest.trim().to_string());
            }
        }
        if current.as_ref().is_some_and(|s| s.ends_with(';')) {
            out.push(
                current
                    .take()
                    .expect("a statement")
                    .trim_end_matches(';')
                    .to_string(),
            );
        }
    }
    out
}

/// The `crate::a::b` and `super::a` paths written in a line of code.
fn written_paths(code: &str) -> Vec<String> {
    let mut out = Vec::new();
    for root in ["crate::", "super::"] {
        let mut rest = code;
        while let Some(at) = rest.find(root) {
            let before = rest[..at].chars().next_back();
            let tail = &rest[at..];
            let end = tail
                .find(|c: char| !(c.is_alphanumeric() || c == '_' || c == ':'))
                .unwrap_or(tail.len());
            if !before.is_some_and(|c| c.is_alphanumeric() || c == '_' || c == ':') {
                out.push(tail[..end].trim_end_matches(':').to_string());
            }
            rest = &tail[end..];
        }
    }
    out
}

/// The paths a use tree names, braces expanded: `a::{b, c::{d, e}}` gives `a::b`, `a::c::d`, `a::c::e`.
fn expand(tree: &str) -> Vec<String> {
    let tree = tree.trim();
    let Some(open) = tree.find('{') else {
        let path = tree.split(" as ").next().unwrap_or(tree).trim();
        return vec![path.to_string()];
    };
    let prefix = &tree[..open];
    let inner = &tree[open + 1..tree.rfind('}').expect("a closing brace")];
    let mut parts = Vec::new();
    let (mut depth, mut start) = (0, 0);
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
        .map(|p| format!("{prefix}{p}"))
        .collect()
}

/// The module path a `use` path names from the file of `module` (`None` outside the crate).
fn absolute(module: &[String], path: &str) -> Option<Vec<String>> {
    let mut segments = path.split("::").map(str::trim);
    let mut base: Vec<String> = match segments.next()? {
        "crate" => Vec::new(),
        "super" => module[..module.len().checked_sub(1)?].to_vec(),
        "self" => module.to_vec(),
        _ => return None,
    };
    for s in segments {
        if s == "super" {
            base.pop()?;
        } else if s != "self" && s != "*" {
            base.push(s.to_string());
        }
    }
    Some(base)
}

/// Files (relative to `src/`) and the files each imports from, ancestors and descendants left out.
fn graph() -> BTreeMap<String, BTreeSet<String>> {
    let src = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("src");
    let mut files = Vec::new();
    sources(&src, &mut files);
    let mut modules: BTreeMap<Vec<String>, String> = BTreeMap::new();
    for file in &files {
        let relative = file.strip_prefix(&src).expect("under src");
        if relative.ends_with("tests.rs") {
            continue;
        }
        modules.insert(module_of(relative), relative.display().to_string());
    }
    let mut edges: BTreeMap<String, BTreeSet<String>> = BTreeMap::new();
    for (module, file) in &modules {
        let text = fs::read_to_string(src.join(file)).expect("a source file");
        let targets = edges.entry(file.clone()).or_default();
        for statement in use_statements(&text) {
            for path in expand(&statement) {
                let Some(mut target) = absolute(module, &path) else {
                    continue;
                };
                // The longest prefix that is a module with a file of its own.
                while !target.is_empty() && !modules.contains_key(&target) {
                    target.pop();
                }
                let related = target.starts_with(module) || module.starts_with(&target);
                if !related {
                    targets.insert(modules[&target].clone());
                }
            }
        }
    }
    edges
}

/// The strongly connected components of more than one file (Tarjan's algorithm).
fn circles(edges: &BTreeMap<String, BTreeSet<String>>) -> Vec<Vec<String>> {
    struct Walk<'a> {
        edges: &'a BTreeMap<String, BTreeSet<String>>,
        index: BTreeMap<&'a str, usize>,
        low: BTreeMap<&'a str, usize>,
        stack: Vec<&'a str>,
        on_stack: BTreeSet<&'a str>,
        found: Vec<Vec<String>>,
    }
    impl<'a> Walk<'a> {
        fn visit(&mut self, v: &'a str) {
            let n = self.index.len();
            self.index.insert(v, n);
            self.low.insert(v, n);
            self.stack.push(v);
            self.on_stack.insert(v);
            for w in self.edges.get(v).into_iter().flatten() {
                let w = w.as_str();
                if !self.index.contains_key(w) {
                    self.visit(w);
                    let low = self.low[v].min(self.low[w]);
                    self.low.insert(v, low);
                } else if self.on_stack.contains(w) {
                    let low = self.low[v].min(self.index[w]);
                    self.low.insert(v, low);
                }
            }
            if self.low[v] == self.index[v] {
                let mut component = Vec::new();
                while let Some(w) = self.stack.pop() {
                    self.on_stack.remove(w);
                    component.push(w.to_string());
                    if w == v {
                        break;
                    }
                }
                if component.len() > 1 {
                    component.sort();
                    self.found.push(component);
                }
            }
        }
    }
    let mut walk = Walk {
        edges,
        index: BTreeMap::new(),
        low: BTreeMap::new(),
        stack: Vec::new(),
        on_stack: BTreeSet::new(),
        found: Vec::new(),
    };
    for v in edges.keys() {
        if !walk.index.contains_key(v.as_str()) {
            walk.visit(v);
        }
    }
    walk.found
}

/// The circles among the files `inside` selects (imports to other files are left out).
fn circles_among(inside: impl Fn(&str) -> bool) -> Vec<Vec<String>> {
    let edges: BTreeMap<String, BTreeSet<String>> = graph()
        .into_iter()
        .filter(|(file, _)| inside(file))
        .map(|(file, targets)| (file, targets.into_iter().filter(|t| inside(t)).collect()))
        .collect();
    circles(&edges)
}

#[test]
fn the_reader_finds_imports_and_circles() {
    assert_eq!(
        expand("super::{a::B, c::{d, e as f}, g}"),
        ["super::a::B", "super::c::d", "super::c::e", "super::g"]
    );
    let module = ["model".to_string(), "cart".to_string()];
    assert_eq!(
        absolute(&module, "super::contact::Ball"),
        Some(vec![
            "model".to_string(),
            "contact".to_string(),
            "Ball".to_string()
        ])
    );
    assert_eq!(absolute(&module, "std::fmt"), None);
    assert_eq!(
        written_paths("let p = crate::config::user_preset(name)?; super::super::x::y();"),
        ["crate::config::user_preset", "super::super::x::y"]
    );
    let edges: BTreeMap<String, BTreeSet<String>> = [
        ("a", vec!["b"]),
        ("b", vec!["c"]),
        ("c", vec!["a"]),
        ("d", vec!["a"]),
    ]
    .into_iter()
    .map(|(f, t)| (f.to_string(), t.into_iter().map(String::from).collect()))
    .collect();
    assert_eq!(circles(&edges), [["a", "b", "c"]]);
    // The core's graph is read: the solver imports the registry.
    assert!(graph()["model/solve.rs"].contains("model/registry.rs"));
}

#[test]
fn the_core_and_the_analysis_have_no_import_circle() {
    let found = circles_among(|f| f.starts_with("model/") || f.starts_with("analysis/"));
    assert!(found.is_empty(), "import circles: {found:?}");
}

#[test]
fn no_file_under_src_is_in_an_import_circle() {
    let found = circles_among(|_| true);
    assert!(found.is_empty(), "import circles: {found:?}");
}
