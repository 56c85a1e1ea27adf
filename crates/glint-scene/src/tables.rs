//! Fields whose value is a table refuse anything else. serde's derive also reads a struct from a
//! sequence of its fields in order, so without this `render = [16, 12, 3]` would silently set
//! width, height and spp. A table is read by the type's own derive through the parser's map,
//! so an error inside it keeps the parser's position of its field.

use std::collections::BTreeMap;
use std::fmt;
use std::marker::PhantomData;

use serde::de::value::MapAccessDeserializer;
use serde::de::{MapAccess, Visitor};
use serde::{Deserialize, Deserializer};

/// What a table-valued field says it expected.
const EXPECTED: &str = "a table ([section] or { key = value, … })";

struct TableVisitor<T> {
    expected: &'static str,
    value: PhantomData<T>,
}

impl<'de, T: Deserialize<'de>> Visitor<'de> for TableVisitor<T> {
    type Value = T;
    fn expecting(&self, f: &mut fmt::Formatter) -> fmt::Result {
        f.write_str(self.expected)
    }
    fn visit_map<A: MapAccess<'de>>(self, map: A) -> Result<T, A::Error> {
        T::deserialize(MapAccessDeserializer::new(map))
    }
}

/// A field that is one table.
pub(crate) fn table<'de, D: Deserializer<'de>, T: Deserialize<'de>>(deserializer: D) -> Result<T, D::Error> {
    table_of(deserializer, EXPECTED)
}

/// One table, and what to say it is when it is not (`expected`: "a light: a table …").
pub(crate) fn table_of<'de, D: Deserializer<'de>, T: Deserialize<'de>>(
    deserializer: D,
    expected: &'static str,
) -> Result<T, D::Error> {
    deserializer.deserialize_any(TableVisitor { expected, value: PhantomData })
}

/// An array, and what to say it is when it is not: `[objects]` written for `[[objects]]` was
/// "invalid type: map, expected a sequence", naming neither the field nor its form.
pub(crate) fn array_of<'de, D: Deserializer<'de>, T: Deserialize<'de>>(
    deserializer: D,
    expected: &'static str,
) -> Result<Vec<T>, D::Error> {
    struct ArrayVisitor<T> {
        expected: &'static str,
        value: PhantomData<T>,
    }
    impl<'de, T: Deserialize<'de>> Visitor<'de> for ArrayVisitor<T> {
        type Value = Vec<T>;
        fn expecting(&self, f: &mut fmt::Formatter) -> fmt::Result {
            f.write_str(self.expected)
        }
        fn visit_seq<A: serde::de::SeqAccess<'de>>(self, mut seq: A) -> Result<Vec<T>, A::Error> {
            let mut out = Vec::with_capacity(seq.size_hint().unwrap_or(0).min(4096));
            while let Some(item) = seq.next_element()? {
                out.push(item);
            }
            Ok(out)
        }
    }
    deserializer.deserialize_any(ArrayVisitor { expected, value: PhantomData })
}

/// An optional field that is one table when present (with `#[serde(default)]`).
pub(crate) fn option_table<'de, D: Deserializer<'de>, T: Deserialize<'de>>(
    deserializer: D,
) -> Result<Option<T>, D::Error> {
    table(deserializer).map(Some)
}

/// A table of named tables (`[materials.glass]`): each entry a table.
pub(crate) fn tables_by_name<'de, D: Deserializer<'de>, T: Deserialize<'de>>(
    deserializer: D,
) -> Result<BTreeMap<String, T>, D::Error> {
    struct Entry<T>(T);
    impl<'de, T: Deserialize<'de>> Deserialize<'de> for Entry<T> {
        fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
            table(deserializer).map(Entry)
        }
    }
    let entries: BTreeMap<String, Entry<T>> = table(deserializer)?;
    Ok(entries.into_iter().map(|(name, entry)| (name, entry.0)).collect())
}

#[cfg(test)]
mod tests {
    use serde::Deserialize;

    #[derive(Debug, Default, Deserialize, PartialEq)]
    #[serde(deny_unknown_fields, default)]
    struct Inner {
        a: u32,
        b: u32,
    }

    #[derive(Debug, Deserialize, PartialEq)]
    #[serde(deny_unknown_fields)]
    struct Outer {
        #[serde(default, deserialize_with = "super::table")]
        one: Inner,
        #[serde(default, deserialize_with = "super::option_table")]
        maybe: Option<Inner>,
        #[serde(default, deserialize_with = "super::tables_by_name")]
        named: std::collections::BTreeMap<String, Inner>,
    }

    fn read(text: &str) -> Result<Outer, String> {
        toml::from_str(text).map_err(|e| e.to_string())
    }

    #[test]
    fn tables_read_as_the_derive_reads_them() {
        let outer = read("one = { a = 1 }\nmaybe = { b = 2 }\n[named.x]\na = 3\n").unwrap();
        assert_eq!(outer.one, Inner { a: 1, b: 0 });
        assert_eq!(outer.maybe, Some(Inner { a: 0, b: 2 }));
        assert_eq!(outer.named["x"], Inner { a: 3, b: 0 });
        assert_eq!(read("").unwrap().maybe, None);
    }

    #[test]
    fn arrays_are_refused_where_a_table_belongs() {
        for text in ["one = [1, 2]", "maybe = [1, 2]", "named = [1]", "named = { x = [1, 2] }", "one = 3"] {
            let err = read(text).unwrap_err();
            assert!(err.contains("expected a table"), "{text}: {err}");
        }
    }

    #[test]
    fn an_error_inside_a_table_keeps_its_position() {
        let err = read("one = { a = 1 }\n[named.x]\nb = \"no\"\n").unwrap_err();
        assert!(err.contains("line 3"), "{err}");
    }
}
