//! Dependencies between modules run one way. Reads every `crate::` and
//! `super::` path in `src/` (use trees expanded, re-exports followed to the
//! file that defines the item) and checks that
//! - the top-level modules follow the layer order below (a module uses only
//!   modules listed before it) and form no cycle;
//! - inside every module, at every depth (`gpu`, `app::panel`...), the
//!   submodules form no cycle.
//!
//! Full-line comments and the inline `mod tests` of a file are not read:
//! tests may look at anything.

mod common;

use std::collections::{BTreeMap, BTreeSet};
use std::path::Path;

/// Lower layers first: plain data and helpers, then the two renderers, then
/// what measures them, then the window, then the subcommands of the binary.
const LAYERS: &[&str] = &[
    "files",
    "cli",
    "expr",
    "scene",
    "bvh",
    "compare",
    "reference",
    "gpu",
    "shader_params",
    "stress",
    "bench",
    "sandbox",
    "app",
    "web",
    "commands",
];

/// One source file: its module path (`["gpu", "context"]`) and text.
struct Source {
    module: Vec<String>,
    file: String,
    text: String,
}

fn sources() -> Vec<Source> {
    let mut out = Vec::new();
    for path in common::files_below(Path::new("src")) {
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

/// For each module, the items it re-exports from its own submodules
/// (`pub use sub::Item;` in a `mod.rs` or in `panel.rs` beside `panel/`):
/// `(module, item)` -> the submodule.
fn reexports(sources: &[Source]) -> BTreeMap<(Vec<String>, String), String> {
    let modules: BTreeSet<&[String]> = sources.iter().map(|s| s.module.as_slice()).collect();
    let mut map = BTreeMap::new();
    for source in sources {
        for (_, line) in code_lines(&source.text) {
            let Some(tree) = line.trim_start().strip_prefix("pub use ") else {
                continue;
            };
            let mut at = 0;
            for path in parse_tree(tree.as_bytes(), &mut at) {
                if let (Some(first), Some(item)) = (path.first(), path.last())
                    && path.len() >= 2
                    && modules.contains([source.module.as_slice(), &path[..1]].concat().as_slice())
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

/// The name under which [`edges`] keeps the edges between top-level modules.
const TOP: &str = "crate";

/// Module-level edges between siblings, at every depth, keyed by their
/// parent's path (`"crate"` for the top-level modules, `"gpu"`,
/// `"app::panel"`...). A path from `a::b::c` to `a::d::e` is an edge
/// `b -> d` under `"a"`: the two files' paths are cut where they first differ.
fn edges(sources: &[Source]) -> BTreeMap<String, Edges> {
    let modules: BTreeSet<Vec<String>> = sources.iter().map(|s| s.module.clone()).collect();
    let reexported = reexports(sources);
    let mut by_parent: BTreeMap<String, Edges> = BTreeMap::new();
    for source in sources {
        for (line, path) in paths_of(source) {
            let path = follow_reexports(path, &reexported, &modules);
            let from = &source.module;
            let common = from.iter().zip(&path).take_while(|(a, b)| a == b).count();
            if common >= from.len() || common >= path.len() || !modules.contains(&path[..=common]) {
                // Within the file's own module, one of its children, or not a module.
                continue;
            }
            let parent = if common == 0 {
                TOP.to_string()
            } else {
                from[..common].join("::")
            };
            by_parent
                .entry(parent)
                .or_default()
                .entry((from[common].clone(), path[common].clone()))
                .or_insert_with(|| format!("{}:{line}", source.file));
        }
    }
    by_parent
}

/// Follows a re-export to the submodule that defines the item, as often as
/// the item is re-exported.
fn follow_reexports(
    mut path: Vec<String>,
    reexported: &BTreeMap<(Vec<String>, String), String>,
    modules: &BTreeSet<Vec<String>>,
) -> Vec<String> {
    while path.len() >= 2 && !modules.contains(&path) {
        let parent = path[..path.len() - 1].to_vec();
        let item = path.last().unwrap().clone();
        let Some(sub) = reexported.get(&(parent.clone(), item.clone())) else {
            break;
        };
        let mut resolved = parent;
        resolved.push(sub.clone());
        resolved.push(item);
        if resolved == path {
            break;
        }
        path = resolved;
    }
    path
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
    let top = edges(&sources).remove(TOP).unwrap_or_default();
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

/// The problems [`submodules_form_no_cycle`] reports for these sources.
fn submodule_cycles(sources: &[Source]) -> Vec<String> {
    let mut problems = Vec::new();
    for (module, edges) in &edges(sources) {
        if module == TOP {
            continue;
        }
        if let Some(cycle) = find_cycle(edges) {
            problems.push(format!("in {module}: {}", describe(&cycle, edges)));
        }
    }
    problems
}

#[test]
fn submodules_form_no_cycle() {
    let sources = sources();
    let problems = submodule_cycles(&sources);
    assert!(problems.is_empty(), "{}", problems.join("\n"));
    // The check sees real edges, through re-exports too, and below the
    // second level.
    let inner = edges(&sources);
    assert!(inner["gpu"].contains_key(&("timer".into(), "context".into())));
    assert!(inner["scene"].contains_key(&("validate".into(), "parse".into())));
    assert!(inner["app::panel"].contains_key(&("shapes".into(), "widgets".into())));
}

/// A source file for the checker's own tests.
fn fake(module: &str, text: &str) -> Source {
    Source {
        module: module.split("::").map(String::from).collect(),
        file: format!("src/{}.rs", module.replace("::", "/")),
        text: text.to_string(),
    }
}

#[test]
fn the_checker_finds_a_cycle_three_levels_deep() {
    // `a::b::c` and `a::b::d` use each other, one through a re-export of
    // `a::b` and one by `super::`; `a::e` uses `a::b::c` one level up.
    let mut sources = vec![
        fake("a", ""),
        fake("a::b", "pub use d::Thing;\n"),
        fake("a::b::c", "use crate::a::b::Thing;\n"),
        fake("a::b::d", "use super::c::{self, Helper};\n"),
        fake("a::e", "use super::b::c::Helper;\n"),
    ];
    let by_parent = edges(&sources);
    assert!(by_parent["a::b"].contains_key(&("c".into(), "d".into())));
    assert!(by_parent["a"].contains_key(&("e".into(), "b".into())));
    let problems = submodule_cycles(&sources);
    assert_eq!(problems.len(), 1, "{problems:?}");
    assert!(problems[0].starts_with("in a::b: "), "{problems:?}");
    sources[3].text = String::new();
    assert_eq!(submodule_cycles(&sources), Vec::<String>::new());
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
