//! From the parsed document to a [`Scene`] struct, with serde: types, unknown
//! keys and missing keys. serde's errors are given a key path and a line, and
//! reworded where serde's words are about Rust rather than the scene file.

use serde::Deserialize;
use toml::de::{DeValue, ValueDeserializer};

use super::MAX_DEPTH;
use super::document::{Document, Node};
use super::key_path::{KeyPath, Step};
use super::{Scene, SceneError, ShapeKind, for_each_shape_kind};

/// The scene the document describes, not yet checked against the ranges of
/// the rendering model (that is [`super::validate`]'s job).
pub(super) fn deserialize(doc: &Document<'_>) -> Result<Scene, SceneError> {
    let scene = Scene::deserialize(ValueDeserializer::from(doc.root().clone()))
        .map_err(|e| serde_error(doc, &e))?;
    check_vector_lengths(doc)?;
    Ok(scene)
}

/// glam reads the first three numbers of an array and ignores the rest, so
/// `to = [0, 1, 0, 5]` would load without a word. Every array of numbers in
/// a scene is a vector, and a vector has three; but for the keys a shape
/// kind names in [`super::Shape::NOT_VECTORS`] (serde checks their length),
/// and arrays of vectors (an implicit surface's `bounds`, whose vectors are
/// checked one by one).
fn check_vector_lengths(doc: &Document<'_>) -> Result<(), SceneError> {
    let wrong_length = |path: &KeyPath, node: &Node<'_>| match node.get_ref() {
        DeValue::Array(items) => {
            let of_tables_or_arrays = items
                .iter()
                .all(|v| v.get_ref().is_table() || v.get_ref().is_array());
            items.len() != 3 && !of_tables_or_arrays && !not_a_vector(path)
        }
        _ => false,
    };
    match doc.find(wrong_length) {
        Some((path, node)) => {
            let got = doc.quote(node);
            Err(doc.error(&path, format!("must be an array of 3 numbers, got {got}")))
        }
        None => Ok(()),
    }
}

/// Whether `path` is a shape's key that its kind says is no vector
/// ([`super::Shape::NOT_VECTORS`]).
fn not_a_vector(path: &KeyPath) -> bool {
    let [Step::Key(array), Step::Index(_), Step::Key(key)] = path.steps() else {
        return false;
    };
    ShapeKind::from_key(array).is_some_and(|kind| kind.not_vectors().contains(&key.as_str()))
}

/// serde's error, with the key it is about, placed where serde points (for an
/// unknown key that is the key, not its value). An empty span is how toml
/// points at the root table, which has no place in the text.
fn serde_error(doc: &Document<'_>, e: &toml::de::Error) -> SceneError {
    let root = KeyPath::default();
    let table = error_path(doc, e, &root);
    if let Some(at_key) = flattened_error(doc, &table) {
        return located_error(doc, &at_key, &table);
    }
    // serde reads a flattened vector of 4 numbers as an error that a table
    // read alone does not see (glam ignores the fourth): the check of the
    // vectors' lengths names it.
    if is_flattened_table(doc, &table)
        && let Err(wrong_length) = check_vector_lengths(doc)
    {
        return wrong_length;
    }
    located_error(doc, e, &root)
}

/// Whether `path` is a table that serde reads from flattened parts: a
/// shape's (`spheres[2]`) or `[render]`.
fn is_flattened_table(doc: &Document<'_>, path: &KeyPath) -> bool {
    let table = doc.get(path).is_some_and(|node| node.get_ref().is_table());
    let flattened = match path.steps() {
        [Step::Key(key)] => key == "render",
        [Step::Key(array), Step::Index(_)] => ShapeKind::from_key(array).is_some(),
        _ => false,
    };
    table && flattened
}

/// The path of the value or key that serde's error points at, `otherwise`
/// for an error that points nowhere.
fn error_path(doc: &Document<'_>, e: &toml::de::Error, otherwise: &KeyPath) -> KeyPath {
    let span = e.span().filter(|span| !span.is_empty());
    span.map_or_else(|| otherwise.clone(), |span| doc.path_at(&span))
}

/// [`serde_error`] once flattened keys are accounted for; an error that
/// points nowhere is about `otherwise`.
fn located_error(doc: &Document<'_>, e: &toml::de::Error, otherwise: &KeyPath) -> SceneError {
    let span = e.span().filter(|span| !span.is_empty());
    let path = error_path(doc, e, otherwise);
    if let Some((key, expected)) = unknown_flattened_key(&path, e.message()) {
        return doc.error(&path.key(key), format!("unknown key `{key}`{expected}"));
    }
    let (path, message) = explain(doc, path, e.message());
    let error = doc.error(&path, message);
    match span {
        Some(span) => error.at(doc.position(span.start)),
        None => error,
    }
}

/// serde reads a shape's kind, placement and material flattened into its
/// table (`Instance`, docs/implementation.md, "Adding a shape kind"), and
/// `[render]`'s shared keys beside every kind's (`Render`), from keys that
/// no longer know their place in the text, and blames an error in one part
/// on the table at `path`. Read alone from the table, each part gives the
/// error at the key (src/scene/flattened.rs).
fn flattened_error(doc: &Document<'_>, path: &KeyPath) -> Option<toml::de::Error> {
    let node = doc.get(path).filter(|node| node.get_ref().is_table())?;
    let table = || ValueDeserializer::from(node.clone());
    if *path == KeyPath::default().key("render") {
        return super::Render::error_at_key(table);
    }
    let [Step::Key(array), Step::Index(_)] = path.steps() else {
        return None;
    };
    macro_rules! read_flattened {
        ($($kind:ident: $field:ident),* $(,)?) => {
            match array.as_str() {
                $(stringify!($field) => {
                    super::Instance::<super::$kind>::error_at_key(table)
                })*
                _ => None,
            }
        };
    }
    for_each_shape_kind!(read_flattened)
}

/// The key of serde's "unknown field `key`" (and the rest of the message,
/// the keys expected) when the error blames the table `path` (a shape with
/// flattened keys) rather than the key.
fn unknown_flattened_key<'m>(path: &KeyPath, message: &'m str) -> Option<(&'m str, &'m str)> {
    let (key, rest) = message.strip_prefix("unknown field `")?.split_once('`')?;
    (!path.ends_with_key(key)).then_some((key, rest))
}

/// The key and message to show for serde's `message` about `path`.
fn explain(doc: &Document<'_>, path: KeyPath, message: &str) -> (KeyPath, String) {
    if let Some(field) = missing_field(message) {
        let message = missing_message(doc, &path, field);
        return (path.key(field), message);
    }
    if let Some(rest) = message.strip_prefix("unknown field") {
        return (path, format!("unknown key{rest}"));
    }
    let node = doc.get(&path);
    if path == KeyPath::default().key("render").key("max_depth") {
        return (path, max_depth_message(doc, node));
    }
    if message.contains("untagged enum AxisScale") {
        let got = node.map(|node| doc.quote(node)).unwrap_or_default();
        return (
            path,
            format!("must be a number or an array of 3 numbers, got {got}"),
        );
    }
    (path, in_plain_words(message))
}

/// The field of serde's "missing field `radius`".
fn missing_field(message: &str) -> Option<&str> {
    message.strip_prefix("missing field `")?.strip_suffix('`')
}

fn missing_message(doc: &Document<'_>, table: &KeyPath, field: &str) -> String {
    if !table.is_root() {
        return "required key is missing".to_owned();
    }
    let is_empty = matches!(doc.root().get_ref(), DeValue::Table(t) if t.is_empty());
    let why = if is_empty {
        " (the scene is empty)"
    } else {
        ""
    };
    format!("required table [{field}] is missing{why}")
}

/// serde says "expected u32"; students write `max_depth = 5.0` and need to be
/// told that the decimal point is what is wrong.
fn max_depth_message(doc: &Document<'_>, node: Option<&Node<'_>>) -> String {
    let got = node.map(|node| doc.quote(node)).unwrap_or_default();
    let is_float = node.is_some_and(|node| node.get_ref().is_float());
    let hint = if is_float { " (no decimal point)" } else { "" };
    format!("must be an integer in 0..={MAX_DEPTH}{hint}, got {got}")
}

/// serde's words for Rust types, replaced by the scene file's words.
fn in_plain_words(message: &str) -> String {
    const WORDS: [(&str, &str); 6] = [
        ("a sequence of 3 f64 values", "an array of 3 numbers"),
        ("expected f64", "expected a number"),
        ("expected a sequence", "expected an array"),
        ("invalid type: sequence", "invalid type: array"),
        ("invalid type: map", "invalid type: table"),
        (" as i128", " (beyond the 64-bit range of TOML integers)"),
    ];
    let mut message = WORDS
        .iter()
        .fold(message.to_owned(), |m, (rust, toml)| m.replace(rust, toml));
    // "expected struct Camera": the struct is a table in the file.
    if let Some(at) = message.find("expected struct ") {
        message.truncate(at);
        message.push_str("expected a table");
    }
    message
}
