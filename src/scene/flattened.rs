//! Tables that serde reads from parts flattened side by side (a shape's
//! kind, placement and material; `[render]`'s shared keys and each kind's).
//! serde reads flattened keys from a buffer that no longer knows their
//! place in the text, so it blames an error in a part on the whole table;
//! these read the table again, key names first and then part by part,
//! to find the key (src/scene/parse.rs).

use std::cell::Cell;

use indexmap::IndexMap;
use serde::Deserialize;
use serde::de::{Error as _, IgnoredAny, Visitor};

/// The first key of `table` that is not `known`, as serde words an unknown
/// key with the keys expected; `None` when every key is known (or `table`
/// is no table).
pub(crate) fn unknown_key<'de, D>(table: D, known: &[&str]) -> Option<D::Error>
where
    D: serde::Deserializer<'de>,
{
    let keys = IndexMap::<String, IgnoredAny>::deserialize(table).ok()?;
    let unknown = keys.keys().find(|key| !known.contains(&key.as_str()))?;
    let expected: Vec<String> = known.iter().map(|key| format!("`{key}`")).collect();
    let expected = expected.join(", ");
    let message = format!("unknown field `{unknown}`, expected one of {expected}");
    Some(D::Error::custom(message))
}

/// The keys a derived serde struct reads, as it names them to the
/// deserializer (none for a type that reads no struct, `Unplaced`).
pub(crate) fn keys_of<'de, T: Deserialize<'de>>() -> &'static [&'static str] {
    let keys = Cell::new(&[][..]);
    let _ = T::deserialize(KeyNames(&keys));
    keys.get()
}

/// A deserializer that only records the field names of the struct asked
/// of it.
struct KeyNames<'a>(&'a Cell<&'static [&'static str]>);

impl<'de> serde::Deserializer<'de> for KeyNames<'_> {
    type Error = serde::de::value::Error;

    fn deserialize_any<V: Visitor<'de>>(self, _: V) -> Result<V::Value, Self::Error> {
        Err(Self::Error::custom("not a struct"))
    }

    fn deserialize_struct<V: Visitor<'de>>(
        self,
        _name: &'static str,
        fields: &'static [&'static str],
        _: V,
    ) -> Result<V::Value, Self::Error> {
        self.0.set(fields);
        Err(Self::Error::custom("only the names were read"))
    }

    serde::forward_to_deserialize_any! {
        bool i8 i16 i32 i64 i128 u8 u16 u32 u64 u128 f32 f64 char str string
        bytes byte_buf option unit unit_struct newtype_struct seq tuple
        tuple_struct map enum identifier ignored_any
    }
}
