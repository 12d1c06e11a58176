//! Dependencies between modules run one way. Reads every `crate::` and
//! `super::` path in `src/` (use trees expanded, re-exports of a `mod.rs`
//! followed to the file that defines the item) and checks that
//! - the top-level modules follow the layer order below (a module uses only
//!   modules listed before it) and form no cycle;
//! - inside each top-level module, the submodules form no cycle.
//!
//! Full-line comments and the inline `mod tests` of a file are not read:
//! tests may look at anything.

use std::collections::{BTreeMap, BTreeSet};
use std::path::Path;

/// Lower layers first: plain data and helpers, then the two renderers, then
/// what measures them, then the window.
const LAYERS: &[&str] = &[
    "files",
    "cli",
    "expr",
    "scene",
    "bvh",
    "compare",
    "reference",
    "gpu",
    "stress",
    "bench",
    "sandbox",
    "app",
    "web",
];

/// One source file: its module path (`["gpu", "context"]`) and text.
struct Source {
    module: Vec<String>,
    file: String,
    text: String,
}

fn sources() -> Vec<Source> {
    fn walk(dir: &Path, out: &mut Vec<Source>) {
        let mut entries: Vec<_> = std::fs::read_dir(dir)
            .unwrap_or_else(|e| panic!("cannot read {}: {e}", dir.display()))
            .map(|e| e.unwrap().path())
            .collect();
        entries.sort();
        for path in entries {
            if path.is_dir() {
                walk(&path, out);
                continue;
            }
            if path.extension().is_none_or(|e| e != "rs") {
                continue;
            }
            let relative = path.strip_prefix("src").unwrap().with_extension("");
            let mut module: Vec<String> = relative
                .components()
                .map(|c| c.as_os_str().to_string_lossy().into_owned())
                .collect();
            if module.last().is_some_and(|m| m == "mod") {
                module.pop();
            }
            if module == ["lib"] || module == ["main"] {
                continue;
            }
            let text = std::fs::read_to_string(&path).unwrap();
            out.push(Source {
                module,
                file: path.display().to_string(),
                text,
            });
        }
    }
    let mut out = Vec::new();
    walk(Path::new("src"), &mut out);
    out
}

/// The code of a file without full-line comments and without its inline
/// test module, as (line number, line) pairs.
fn code_lines(text: &str) -> Vec<(usize, &str)> {
    let mut lines = Vec::new();
    let mut iter = text.lines().enumerate().peekable();
    while let Some((i, line)) = iter.next() {
        let trimmed = line.trim_start();
        if trimmed.starts_with("#[cfg(test)]")
            && iter
                .peek()
                .is_some_and(|(_, next)| next.trim_start().starts_with("mod tests"))
        {
            break;
        }
        if !trimmed.starts_with("//") {
            lines.push((i + 1, line));
        }
    }
    lines
}

/// Parses a path (or use tree) starting at `text[at..]`: segments joined by
/// `::`, with `{a, b::c}` groups expanded. Returns every full path.
fn parse_tree(text: &[u8], at: &mut usize) -> Vec<Vec<String>> {
    let mut prefix = Vec::new();
    loop {
        while *at < text.len() && text[*at].is_ascii_whitespace() {
            *at += 1;
        }
        if *at < text.len() && text[*at] == b'{' {
            *at += 1;
            let mut paths = Vec::new();
            loop {
                while *at < text.len() && (text[*at].is_ascii_whitespace() || text[*at] == b',') {
                    *at += 1;
                }
                if *at >= text.len() || text[*at] == b'}' {
                    *at += 1;
                    break;
                }
                for tail in parse_tree(text, at) {
                    let mut path = prefix.clone();
                    path.extend(tail);
                    paths.push(path);
                }
            }
            return paths;
        }
        let start = *at;
        while *at < text.len() && (text[*at].is_ascii_alphanumeric() || text[*at] == b'_') {
            *at += 1;
        }
        if start == *at {
            // `*` or the end of the path.
            return vec![prefix];
        }
        prefix.push(String::from_utf8_lossy(&text[start..*at]).into_owned());
        if text[*at..].starts_with(b"::") {
            *at += 2;
        } else {
            return vec![prefix];
        }
    }
}

/// Every `crate::` and `super::` path of a file, made absolute, with the
/// line it is on.
fn paths_of(source: &Source) -> Vec<(usize, Vec<String>)> {
    let mut found = Vec::new();
    for (line_number, line) in code_lines(&source.text) {
        let bytes = line.as_bytes();
        let mut i = 0;
        while i < bytes.len() {
            let boundary =
                i == 0 || !(bytes[i - 1].is_ascii_alphanumeric() || bytes[i - 1] == b'_');
            let rest = &bytes[i..];
            if !(boundary && (rest.starts_with(b"crate::") || rest.starts_with(b"super::"))) {
                i += 1;
                continue;
            }
            let mut at = i;
            for path in parse_tree(bytes, &mut at) {
                if let Some(absolute) = absolute(&source.module, &path) {
                    found.push((line_number, absolute));
                }
            }
            i = at.max(i + 1);
        }
    }
    found
}

/// `crate::a::b` -> `[a, b]`; `super::b` from module `[x, y]` -> `[x, b]`.
fn absolute(module: &[String], path: &[String]) -> Option<Vec<String>> {
    let mut base: Vec<String> = module.to_vec();
    let mut rest = path;
    match rest.first().map(String::as_str) {
        Some("crate") => {
            base.clear();
            rest = &rest[1..];
        }
        Some("super") => {
            while rest.first().is_some_and(|s| s == "super") {
                base.pop()?;
                rest = &rest[1..];
            }
        }
        _ => return None,
    }
    base.extend(rest.iter().cloned());
    Some(base)
}

/// For each module with a `mod.rs`, the items it re-exports from its
/// submodules: `(module, item)` -> the submodule.
fn reexports(sources: &[Source]) -> BTreeMap<(Vec<String>, String), String> {
    let mut map = BTreeMap::new();
    for source in sources {
        if !source.file.ends_with("mod.rs") {
            continue;
        }
        for (_, line) in code_lines(&source.text) {
            let Some(tree) = line.trim_start().strip_prefix("pub use ") else {
                continue;
            };
            let mut at = 0;
            for path in parse_tree(tree.as_bytes(), &mut at) {
                if let (Some(first), Some(item)) = (path.first(), path.last())
                    && path.len() >= 2
                    && first != "crate"
                    && first != "super"
                {
                    map.insert((source.module.clone(), item.clone()), first.clone());
                }
            }
        }
    }
    map
}

/// An edge and where it comes from, for the messages.
type Edges = BTreeMap<(String, String), String>;

/// Module-level edges: between top-level modules, and between the
/// submodules of each top-level module (keyed by that module's name).
fn edges(sources: &[Source]) -> (Edges, BTreeMap<String, Edges>) {
    let modules: BTreeSet<Vec<String>> = sources.iter().map(|s| s.module.clone()).collect();
    let reexported = reexports(sources);
    let mut top = Edges::new();
    let mut inner: BTreeMap<String, Edges> = BTreeMap::new();
    for source in sources {
        for (line, mut path) in paths_of(source) {
            // Follow a re-export to the submodule that defines the item.
            while path.len() >= 2 {
                let parent = path[..path.len() - 1].to_vec();
                let item = path.last().unwrap().clone();
                match reexported.get(&(parent.clone(), item.clone())) {
                    Some(sub) if !modules.contains(&path) => {
                        let mut resolved = parent;
                        resolved.push(sub.clone());
                        resolved.push(item);
                        if resolved == path {
                            break;
                        }
                        path = resolved;
                    }
                    _ => break,
                }
            }
            let at = format!("{}:{line}", source.file);
            let from = &source.module;
            if path.is_empty() || !modules.contains(&path[..1]) {
                continue;
            }
            if path[0] != from[0] {
                top.entry((from[0].clone(), path[0].clone())).or_insert(at);
            } else if from.len() >= 2
                && path.len() >= 2
                && path[1] != from[1]
                && modules.contains(&path[..2])
            {
                inner
                    .entry(from[0].clone())
                    .or_default()
                    .entry((from[1].clone(), path[1].clone()))
                    .or_insert(at);
            }
        }
    }
    (top, inner)
}

/// A cycle in `edges`, as the list of its nodes, if there is one.
fn find_cycle(edges: &Edges) -> Option<Vec<String>> {
    let mut next: BTreeMap<&str, Vec<&str>> = BTreeMap::new();
    for (a, b) in edges.keys() {
        next.entry(a).or_default().push(b);
    }
    fn visit<'a>(
        node: &'a str,
        next: &BTreeMap<&'a str, Vec<&'a str>>,
        path: &mut Vec<&'a str>,
        done: &mut BTreeSet<&'a str>,
    ) -> Option<Vec<String>> {
        if let Some(start) = path.iter().position(|n| *n == node) {
            let mut cycle: Vec<String> = path[start..].iter().map(|s| s.to_string()).collect();
            cycle.push(node.to_string());
            return Some(cycle);
        }
        if !done.insert(node) {
            return None;
        }
        path.push(node);
        for n in next.get(node).into_iter().flatten() {
            if let Some(cycle) = visit(n, next, path, done) {
                return Some(cycle);
            }
        }
        path.pop();
        None
    }
    let mut done = BTreeSet::new();
    for node in next.keys() {
        if let Some(cycle) = visit(node, &next, &mut Vec::new(), &mut done) {
            return Some(cycle);
        }
    }
    None
}

fn describe(cycle: &[String], edges: &Edges) -> String {
    cycle
        .windows(2)
        .map(|w| {
            let at = &edges[&(w[0].clone(), w[1].clone())];
            format!("{} -> {} ({at})", w[0], w[1])
        })
        .collect::<Vec<_>>()
        .join(", ")
}

#[test]
fn top_level_modules_follow_the_layers() {
    let sources = sources();
    assert!(sources.len() > 20, "run from the repository root");
    let (top, _) = edges(&sources);
    let mut problems = Vec::new();
    let layer = |m: &str| LAYERS.iter().position(|l| *l == m);
    for ((from, to), at) in &top {
        if let (Some(a), Some(b)) = (layer(from), layer(to))
            && b >= a
        {
            problems.push(format!(
                "{from} uses {to} ({at}), but {to} is not below {from} in LAYERS"
            ));
        }
    }
    if let Some(cycle) = find_cycle(&top) {
        problems.push(format!("cycle: {}", describe(&cycle, &top)));
    }
    assert!(problems.is_empty(), "{}", problems.join("\n"));
    // The check sees real edges: gpu uses scene, app uses gpu.
    assert!(top.contains_key(&("gpu".into(), "scene".into())));
    assert!(top.contains_key(&("app".into(), "gpu".into())));
}

#[test]
fn submodules_form_no_cycle() {
    let (_, inner) = edges(&sources());
    let mut problems = Vec::new();
    for (module, edges) in &inner {
        if let Some(cycle) = find_cycle(edges) {
            problems.push(format!("in {module}: {}", describe(&cycle, edges)));
        }
    }
    assert!(problems.is_empty(), "{}", problems.join("\n"));
    // The check sees real edges, through re-exports too.
    let gpu = &inner["gpu"];
    assert!(gpu.contains_key(&("timer".into(), "context".into())));
    assert!(inner["scene"].contains_key(&("validate".into(), "parse".into())));
}

#[test]
fn the_checker_finds_a_cycle() {
    let mut edges = Edges::new();
    for (a, b) in [("a", "b"), ("b", "c"), ("c", "a"), ("c", "d")] {
        edges.insert((a.into(), b.into()), String::new());
    }
    let cycle = find_cycle(&edges).expect("a -> b -> c -> a");
    assert_eq!(cycle.len(), 4);
    edges.remove(&("c".into(), "a".into()));
    assert_eq!(find_cycle(&edges), None);
}
