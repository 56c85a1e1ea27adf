//! A value of any self-describing format read whole, then deserialised again: what the
//! hand-written `Deserialize` impls need to see a table before they choose its kind (an
//! object's `type`, an attenuation's `model`). It is the description's own, so that the
//! description depends on no file format; errors of the second pass name the field they are
//! about (`radius: invalid type: string "x", expected f64`).

use std::fmt;

use serde::de::{self, DeserializeSeed, IntoDeserializer, MapAccess, SeqAccess, Visitor};
use serde::{Deserialize, Deserializer, forward_to_deserialize_any};

/// A buffered value. Maps keep their keys' order.
#[derive(Clone, Debug, PartialEq)]
pub(crate) enum Content {
    Bool(bool),
    I64(i64),
    U64(u64),
    F64(f64),
    Str(String),
    Seq(Vec<Content>),
    Map(Vec<(String, Content)>),
}

impl Content {
    /// The value's kind, in the scene format's words.
    pub(crate) fn type_str(&self) -> &'static str {
        match self {
            Self::Bool(_) => "boolean",
            Self::I64(_) | Self::U64(_) => "integer",
            Self::F64(_) => "float",
            Self::Str(_) => "string",
            Self::Seq(_) => "array",
            Self::Map(_) => "table",
        }
    }

    pub(crate) fn as_str(&self) -> Option<&str> {
        match self {
            Self::Str(s) => Some(s),
            _ => None,
        }
    }

    /// `T` from this value; an error names the field path inside it (`center[1]: …`).
    pub(crate) fn into_value<'de, T: Deserialize<'de>>(self) -> Result<T, ContentError> {
        T::deserialize(self)
    }
}

impl fmt::Display for Content {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::Bool(b) => write!(f, "{b}"),
            Self::I64(v) => write!(f, "{v}"),
            Self::U64(v) => write!(f, "{v}"),
            Self::F64(v) => write!(f, "{v}"),
            Self::Str(s) => write!(f, "{s:?}"),
            Self::Seq(items) => {
                f.write_str("[")?;
                for (i, item) in items.iter().enumerate() {
                    write!(f, "{}{item}", if i == 0 { "" } else { ", " })?;
                }
                f.write_str("]")
            }
            Self::Map(entries) => {
                f.write_str("{ ")?;
                for (i, (k, v)) in entries.iter().enumerate() {
                    write!(f, "{}{k} = {v}", if i == 0 { "" } else { ", " })?;
                }
                f.write_str(" }")
            }
        }
    }
}

impl<'de> Deserialize<'de> for Content {
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        struct ContentVisitor;
        impl<'de> Visitor<'de> for ContentVisitor {
            type Value = Content;
            fn expecting(&self, f: &mut fmt::Formatter) -> fmt::Result {
                f.write_str("a value")
            }
            fn visit_bool<E>(self, v: bool) -> Result<Content, E> {
                Ok(Content::Bool(v))
            }
            fn visit_i64<E>(self, v: i64) -> Result<Content, E> {
                Ok(Content::I64(v))
            }
            fn visit_u64<E>(self, v: u64) -> Result<Content, E> {
                Ok(Content::U64(v))
            }
            fn visit_f64<E>(self, v: f64) -> Result<Content, E> {
                Ok(Content::F64(v))
            }
            fn visit_str<E>(self, v: &str) -> Result<Content, E> {
                Ok(Content::Str(v.to_owned()))
            }
            fn visit_string<E>(self, v: String) -> Result<Content, E> {
                Ok(Content::Str(v))
            }
            fn visit_seq<A: SeqAccess<'de>>(self, mut seq: A) -> Result<Content, A::Error> {
                let mut items = Vec::new();
                while let Some(item) = seq.next_element()? {
                    items.push(item);
                }
                Ok(Content::Seq(items))
            }
            fn visit_map<A: MapAccess<'de>>(self, mut map: A) -> Result<Content, A::Error> {
                let mut entries = Vec::new();
                while let Some(entry) = map.next_entry::<String, Content>()? {
                    entries.push(entry);
                }
                Ok(Content::Map(entries))
            }
        }
        deserializer.deserialize_any(ContentVisitor)
    }
}

/// An error of the second pass, its message led by the path of the field it is about.
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct ContentError {
    path: String,
    message: String,
}

impl ContentError {
    /// The error one level up: `key` (a field name, or `[i]`) joins the path's front.
    fn inside(mut self, key: &str) -> Self {
        let dot = if self.path.is_empty() || self.path.starts_with('[') { "" } else { "." };
        self.path = format!("{key}{dot}{}", self.path);
        self
    }
}

impl fmt::Display for ContentError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        if self.path.is_empty() { f.write_str(&self.message) } else { write!(f, "{}: {}", self.path, self.message) }
    }
}

impl std::error::Error for ContentError {}

impl de::Error for ContentError {
    fn custom<T: fmt::Display>(msg: T) -> Self {
        Self { path: String::new(), message: msg.to_string() }
    }
}

impl<'de> Deserializer<'de> for Content {
    type Error = ContentError;

    fn deserialize_any<V: Visitor<'de>>(self, visitor: V) -> Result<V::Value, ContentError> {
        match self {
            Self::Bool(v) => visitor.visit_bool(v),
            Self::I64(v) => visitor.visit_i64(v),
            Self::U64(v) => visitor.visit_u64(v),
            Self::F64(v) => visitor.visit_f64(v),
            Self::Str(v) => visitor.visit_string(v),
            Self::Seq(items) => visitor.visit_seq(Items { items: items.into_iter().enumerate() }),
            Self::Map(entries) => visitor.visit_map(Entries { entries: entries.into_iter(), key: None }),
        }
    }

    /// A present value is `Some` (the scene format has no null).
    fn deserialize_option<V: Visitor<'de>>(self, visitor: V) -> Result<V::Value, ContentError> {
        visitor.visit_some(self)
    }

    /// Unit variants by name (the tags).
    fn deserialize_enum<V: Visitor<'de>>(
        self,
        _name: &'static str,
        _variants: &'static [&'static str],
        visitor: V,
    ) -> Result<V::Value, ContentError> {
        match self {
            Self::Str(s) => visitor.visit_enum(s.into_deserializer()),
            other => Err(de::Error::invalid_type(de::Unexpected::Other(other.type_str()), &"a name")),
        }
    }

    fn deserialize_newtype_struct<V: Visitor<'de>>(
        self,
        _name: &'static str,
        visitor: V,
    ) -> Result<V::Value, ContentError> {
        visitor.visit_newtype_struct(self)
    }

    forward_to_deserialize_any! {
        bool i8 i16 i32 i64 i128 u8 u16 u32 u64 u128 f32 f64 char str string bytes byte_buf unit unit_struct seq
        tuple tuple_struct map struct identifier ignored_any
    }
}

impl IntoDeserializer<'_, ContentError> for Content {
    type Deserializer = Self;

    fn into_deserializer(self) -> Self {
        self
    }
}

struct Items {
    items: std::iter::Enumerate<std::vec::IntoIter<Content>>,
}

impl<'de> SeqAccess<'de> for Items {
    type Error = ContentError;

    fn next_element_seed<T: DeserializeSeed<'de>>(&mut self, seed: T) -> Result<Option<T::Value>, ContentError> {
        let Some((i, item)) = self.items.next() else { return Ok(None) };
        seed.deserialize(item).map(Some).map_err(|e| e.inside(&format!("[{i}]")))
    }

    fn size_hint(&self) -> Option<usize> {
        Some(self.items.len())
    }
}

struct Entries {
    entries: std::vec::IntoIter<(String, Content)>,
    key: Option<(String, Content)>,
}

impl<'de> MapAccess<'de> for Entries {
    type Error = ContentError;

    fn next_key_seed<K: DeserializeSeed<'de>>(&mut self, seed: K) -> Result<Option<K::Value>, ContentError> {
        let Some((key, value)) = self.entries.next() else { return Ok(None) };
        let found = seed.deserialize(key.clone().into_deserializer())?;
        self.key = Some((key, value));
        Ok(Some(found))
    }

    fn next_value_seed<V: DeserializeSeed<'de>>(&mut self, seed: V) -> Result<V::Value, ContentError> {
        let (key, value) = self.key.take().ok_or_else(|| de::Error::custom("a value asked before its key"))?;
        seed.deserialize(value).map_err(|e| e.inside(&key))
    }

    fn size_hint(&self) -> Option<usize> {
        Some(self.entries.len())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[derive(Debug, Deserialize, PartialEq)]
    #[serde(deny_unknown_fields)]
    struct Sphere {
        center: [f64; 3],
        radius: f64,
        name: Option<String>,
    }

    fn map(entries: &[(&str, Content)]) -> Content {
        Content::Map(entries.iter().map(|(k, v)| ((*k).to_owned(), v.clone())).collect())
    }

    #[test]
    fn values_read_again_with_integers_widened_and_non_finite_kept() {
        let center = Content::Seq(vec![Content::I64(1), Content::F64(f64::INFINITY), Content::U64(3)]);
        let s: Sphere = map(&[("radius", Content::F64(f64::NAN)), ("center", center)]).into_value().expect("reads");
        assert_eq!(s.center[..1], [1.0]);
        assert!(s.center[1].is_infinite() && s.radius.is_nan() && s.name.is_none());
    }

    #[test]
    fn errors_name_the_field_path() {
        let center = Content::Seq(vec![Content::I64(1), Content::Str("x".into()), Content::I64(3)]);
        let e = map(&[("center", center), ("radius", Content::I64(1))]).into_value::<Sphere>().unwrap_err();
        assert_eq!(e.to_string(), "center[1]: invalid type: string \"x\", expected f64");
        let e = map(&[("radius", Content::Str("x".into()))]).into_value::<Sphere>().unwrap_err();
        assert!(e.to_string().starts_with("radius: invalid type: string"), "{e}");
        let e = map(&[("radius", Content::I64(1)), ("colour", Content::Bool(true))]).into_value::<Sphere>();
        assert!(e.unwrap_err().to_string().starts_with("unknown field `colour`"));
    }
}
