//! A reference to a section of the documentation, `docs/NAME.md, "Title"`
//! (or `docs/NAME.md "Title"`, `docs/NAME.md ("Title"`), names a heading
//! that exists in that file: a comment, test or document that cites a
//! section which was renamed or never written points the reader nowhere.
//! Read in src/, shaders/, tests/, scripts/, docs/, web/ and README.md; a
//! reference may wrap onto the next comment line. And every file that
//! README.md or a page of docs/ links to or shows exists.

mod common;

use std::collections::{BTreeMap, BTreeSet};
use std::path::Path;

use common::files_below;

/// The folders and files read for references.
const ROOTS: &[&str] = &[
    "src",
    "shaders",
    "tests",
    "scripts",
    "docs",
    "web",
    "README.md",
];

/// The headings of each file of docs/ (`# Title`, `## Title`, ...), by
/// file name.
fn headings() -> BTreeMap<String, BTreeSet<String>> {
    let mut all = BTreeMap::new();
    for path in files_below(Path::new("docs")) {
        if path.extension().is_none_or(|e| e != "md") {
            continue;
        }
        let text = std::fs::read_to_string(&path).unwrap();
        let titles = text
            .lines()
            .filter_map(|line| {
                let title = line.trim_start_matches('#');
                (title.len() < line.len() && title.starts_with(' '))
                    .then(|| title.trim().to_string())
            })
            .collect();
        let name = path.file_name().unwrap().to_string_lossy().into_owned();
        all.insert(name, titles);
    }
    all
}

/// The text with the comment markers at the start of each line removed and
/// the lines joined by spaces, so that a reference wrapped onto the next
/// comment line reads as one.
fn flatten(text: &str) -> String {
    text.lines()
        .map(|line| {
            let line = line.trim_start();
            ["///", "//!", "//", "#", "*"]
                .iter()
                .find_map(|marker| line.strip_prefix(marker))
                .unwrap_or(line)
                .trim()
        })
        .collect::<Vec<_>>()
        .join(" ")
}

/// Every `(doc, title)` cited in `text`: `docs/NAME.md`, then `, "`, ` "`
/// or ` ("`, then a title that starts like one (a capital or a backtick).
fn references(text: &str) -> Vec<(String, String)> {
    let mut found = Vec::new();
    let mut rest = text;
    while let Some(at) = rest.find("docs/") {
        rest = &rest[at + "docs/".len()..];
        let name_len = rest
            .find(|c: char| !(c.is_ascii_alphanumeric() || c == '-' || c == '_'))
            .unwrap_or(rest.len());
        let Some(after) = rest[name_len..].strip_prefix(".md") else {
            continue;
        };
        let Some(quoted) = [", \"", " \"", " (\""]
            .iter()
            .find_map(|sep| after.strip_prefix(sep))
        else {
            continue;
        };
        let Some(end) = quoted.find('"') else {
            continue;
        };
        let title = &quoted[..end];
        if title.starts_with(|c: char| c.is_ascii_uppercase() || c == '`') {
            found.push((format!("{}.md", &rest[..name_len]), title.to_string()));
        }
    }
    found
}

#[test]
fn every_cited_section_of_docs_exists() {
    let headings = headings();
    assert!(headings.len() >= 5, "run from the repository root");
    let mut missing = Vec::new();
    let mut checked = 0;
    for root in ROOTS {
        for path in files_below(Path::new(root)) {
            // This file's own comments show the form with made-up names.
            if path == Path::new(file!()) {
                continue;
            }
            let Ok(text) = std::fs::read_to_string(&path) else {
                continue;
            };
            for (doc, title) in references(&flatten(&text)) {
                checked += 1;
                let exists = headings
                    .get(&doc)
                    .is_some_and(|titles| titles.iter().any(|t| t.starts_with(&title)));
                if !exists {
                    missing.push(format!("{}: docs/{doc}, \"{title}\"", path.display()));
                }
            }
        }
    }
    assert!(
        missing.is_empty(),
        "no such section:\n{}",
        missing.join("\n")
    );
    assert!(checked > 50, "only {checked} references read");
}

#[test]
fn references_are_read_across_comment_lines_and_only_with_a_title() {
    let text = flatten(
        "/// as computed (docs/accuracy.md,\n/// \"The stress table\") and docs/sandbox.md lists\n\
         // them; docs/scene-format.md (\"x^2 + y^2\" is an example) and\n\
         // docs/web.md \"Start-up time\"",
    );
    assert_eq!(
        references(&text),
        [
            ("accuracy.md".to_string(), "The stress table".to_string()),
            ("web.md".to_string(), "Start-up time".to_string()),
        ]
    );
}

/// The targets of the Markdown links and images of `text` (`[text](path)`,
/// `![alt](path)`), outside code (fenced blocks and spans), without their `#anchor`:
/// the ones that name a file, not an address or a place in the page.
fn linked_files(text: &str) -> Vec<String> {
    let mut targets = Vec::new();
    let mut fenced = false;
    for line in text.lines() {
        if line.trim_start().starts_with("```") {
            fenced = !fenced;
            continue;
        }
        if fenced {
            continue;
        }
        // The parts between backticks are code: every other one.
        let prose: String = line.split('`').step_by(2).collect::<Vec<_>>().join(" ");
        let line = prose.as_str();
        for (start, _) in line.match_indices("](") {
            let rest = &line[start + 2..];
            let Some(end) = rest.find(')') else { continue };
            let target = rest[..end].split('#').next().unwrap_or("").trim();
            let is_address = target.contains("://") || target.starts_with("mailto:");
            if !target.is_empty() && !is_address {
                targets.push(target.to_string());
            }
        }
    }
    targets
}

/// A link or image of README.md or docs/ to a file of the repository names
/// a file that exists: a picture generated but never committed (a
/// `.gitignore` rule keeps it out of every clone) is a broken image on the
/// page, and this test fails on the fresh clone that CI runs.
#[test]
fn every_file_the_docs_link_to_exists() {
    let mut pages: Vec<_> = files_below(Path::new("docs"))
        .into_iter()
        .filter(|p| p.extension().is_some_and(|e| e == "md"))
        .collect();
    pages.push(Path::new("README.md").to_path_buf());
    let mut missing = Vec::new();
    let mut checked = 0;
    for page in &pages {
        let text = std::fs::read_to_string(page).unwrap();
        let folder = page.parent().unwrap_or(Path::new(""));
        for target in linked_files(&text) {
            checked += 1;
            if !folder.join(&target).exists() {
                missing.push(format!("{}: {target}", page.display()));
            }
        }
    }
    assert!(missing.is_empty(), "no such file:\n{}", missing.join("\n"));
    assert!(checked > 20, "only {checked} links read");
}

#[test]
fn linked_files_leave_out_addresses_anchors_and_code() {
    let text = "![a](images/a.png) and [b](other.md#part), [c](https://x.org/y), \
                [d](#here), `int[](1, 2)`\n```\n[e](in/code.md)\n```\n[f](../f.md)";
    assert_eq!(linked_files(text), ["images/a.png", "other.md", "../f.md"]);
}
