//! The scene text as a tree of TOML values that remember where they are in the
//! text. serde turns the text into a [`Scene`](super::Scene) and forgets all
//! positions; this tree gives them back, so that an error about
//! `spheres[2].radius` can name its line, and an error that serde reports at a
//! position can name its key.

use std::ops::Range;

use toml::Spanned;
use toml::de::{DeTable, DeValue};

use super::SceneError;
use super::key_path::{KeyPath, Step};

/// A value of the tree with its byte range in the text.
pub(super) type Node<'t> = Spanned<DeValue<'t>>;

/// Longest piece of the text quoted in a message; longer ones are cut short.
const MAX_QUOTE: usize = 40;

/// A parsed scene file: its text and its tree.
pub(super) struct Document<'t> {
    text: &'t str,
    root: Node<'t>,
}

impl<'t> Document<'t> {
    /// Parses the TOML syntax only; types and keys are serde's job.
    pub(super) fn parse(text: &'t str) -> Result<Self, SceneError> {
        let root = DeTable::parse(text).map_err(|e| syntax_error(text, &e))?;
        let span = root.span();
        let root = Spanned::new(span, DeValue::Table(root.into_inner()));
        Ok(Self { text, root })
    }

    /// The whole document, a table.
    pub(super) fn root(&self) -> &Node<'t> {
        &self.root
    }

    /// The value at `path`, if the file has it.
    pub(super) fn get(&self, path: &KeyPath) -> Option<&Node<'t>> {
        path.steps()
            .iter()
            .try_fold(&self.root, |node, step| child(node, step))
    }

    /// The text of a value as written, cut short if long, for "got ..." in
    /// messages about values that serde could not even read.
    pub(super) fn quote(&self, node: &Node<'_>) -> String {
        quote(self.text, node.span())
    }

    /// An error about the value at `path`, placed at its line. When the file
    /// lacks the value itself, the nearest enclosing one gives the line.
    pub(super) fn error(&self, path: &KeyPath, message: impl Into<String>) -> SceneError {
        let error = SceneError::new(message);
        let error = if path.is_root() {
            error
        } else {
            error.with_key(path)
        };
        match self.locate(path) {
            Some(offset) => error.at(self.position(offset)),
            None => error,
        }
    }

    /// The path of the innermost key or value whose text contains `span`:
    /// this names the key of an error that serde reports by position.
    pub(super) fn path_at(&self, span: &Range<usize>) -> KeyPath {
        find_in_value(&self.root, span, KeyPath::default()).unwrap_or_default()
    }

    /// The 1-based (line, column) of a byte offset.
    pub(super) fn position(&self, offset: usize) -> (usize, usize) {
        position(self.text, offset)
    }

    /// The first value for which `pred` holds, searching depth first with
    /// the keys of a table in the order toml keeps them (by name).
    pub(super) fn find(
        &self,
        pred: impl Fn(&KeyPath, &Node<'t>) -> bool,
    ) -> Option<(KeyPath, &Node<'t>)> {
        find_node(&self.root, KeyPath::default(), &pred)
    }

    /// Start of the deepest value along `path` that the file has; `None` if
    /// it has none of it (the root table has no place in the text).
    fn locate(&self, path: &KeyPath) -> Option<usize> {
        let mut node = &self.root;
        let mut found = None;
        for step in path.steps() {
            let Some(next) = child(node, step) else { break };
            node = next;
            found = Some(next.span().start);
        }
        found
    }
}

/// Where a byte offset of the text is, as a 1-based (line, column); columns
/// count characters, not bytes.
fn position(text: &str, offset: usize) -> (usize, usize) {
    let before = &text.as_bytes()[..offset.min(text.len())];
    let line_start = before
        .iter()
        .rposition(|&b| b == b'\n')
        .map_or(0, |i| i + 1);
    let line = before.iter().filter(|&&b| b == b'\n').count() + 1;
    // Every UTF-8 character has exactly one byte that is not 0b10xx_xxxx.
    let column = before[line_start..]
        .iter()
        .filter(|&&b| b & 0xC0 != 0x80)
        .count()
        + 1;
    (line, column)
}

/// A TOML syntax error, with the text it points at quoted: the parser's
/// message ("duplicate key") does not say which.
fn syntax_error(text: &str, e: &toml::de::Error) -> SceneError {
    let found = e.span().map(|span| quote(text, span)).unwrap_or_default();
    let message = match (e.message(), found.as_str()) {
        (message, "") => message.to_owned(),
        ("duplicate key", key) => format!("duplicate key `{key}`"),
        (message, found) => format!("{message}, found `{found}`"),
    };
    let error = SceneError::new(message);
    match e.span() {
        Some(span) => error.at(position(text, span.start)),
        None => error,
    }
}

/// The first line of `text[span]`, cut to [`MAX_QUOTE`] characters.
fn quote(text: &str, span: Range<usize>) -> String {
    let quoted = text.get(span).unwrap_or_default();
    let line = quoted.lines().next().unwrap_or_default();
    if line.chars().count() <= MAX_QUOTE && line.len() == quoted.len() {
        line.to_owned()
    } else {
        let cut: String = line.chars().take(MAX_QUOTE).collect();
        format!("{cut}...")
    }
}

fn child<'a, 't>(node: &'a Node<'t>, step: &Step) -> Option<&'a Node<'t>> {
    match step {
        Step::Key(key) => node.get_ref().get(key.as_str()),
        Step::Index(index) => node.get_ref().get(*index),
    }
}

fn contains(outer: &Range<usize>, inner: &Range<usize>) -> bool {
    outer.start <= inner.start && inner.end <= outer.end
}

/// Searches children first, so that the innermost match wins. Children are
/// searched even when `node`'s own span does not contain `span`: the span of
/// a `[table]` is its header, and its keys come after it.
fn find_in_value(node: &Node<'_>, span: &Range<usize>, path: KeyPath) -> Option<KeyPath> {
    let inner = match node.get_ref() {
        DeValue::Table(table) => find_in_table(table, span, &path),
        DeValue::Array(items) => items
            .iter()
            .enumerate()
            .find_map(|(i, item)| find_in_value(item, span, path.index(i))),
        _ => None,
    };
    inner.or_else(|| contains(&node.span(), span).then_some(path))
}

fn find_in_table(table: &DeTable<'_>, span: &Range<usize>, path: &KeyPath) -> Option<KeyPath> {
    table.iter().find_map(|(key, value)| {
        let path = path.key(key.get_ref());
        if contains(&key.span(), span) {
            Some(path)
        } else {
            find_in_value(value, span, path)
        }
    })
}

fn find_node<'a, 't>(
    node: &'a Node<'t>,
    path: KeyPath,
    pred: &impl Fn(&KeyPath, &Node<'t>) -> bool,
) -> Option<(KeyPath, &'a Node<'t>)> {
    if pred(&path, node) {
        return Some((path, node));
    }
    match node.get_ref() {
        DeValue::Table(table) => table
            .iter()
            .find_map(|(key, value)| find_node(value, path.key(key.get_ref()), pred)),
        DeValue::Array(items) => items
            .iter()
            .enumerate()
            .find_map(|(i, item)| find_node(item, path.index(i), pred)),
        _ => None,
    }
}
