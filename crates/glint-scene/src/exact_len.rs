//! Fixed-length arrays read from a scene file with their length checked both ways. serde reads
//! `[T; N]` by taking N items and leaves the rest unread, and the TOML reader does not object:
//! `position = [0, 1, -5, "not a number"]` and a triangle `[0, 1, 2, 99999]` (a quad written as
//! a triangle) were read without a word. Too few items were already an error; too many now are
//! too, in serde's own words ("invalid length 4, expected an array of length 3").

use std::marker::PhantomData;

use serde::de::{Deserialize, Deserializer, Error, IgnoredAny, SeqAccess, Visitor};

struct Expected(usize);

impl serde::de::Expected for Expected {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "an array of length {}", self.0)
    }
}

/// `[T; N]` read item by item into place (a mesh's vertices are not gathered into a `Vec`
/// each first), with the rest counted for the message.
struct Exact<T, const N: usize>([T; N]);

impl<'de, T: Deserialize<'de> + Copy + Default, const N: usize> Deserialize<'de> for Exact<T, N> {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        struct Items<T, const N: usize>(PhantomData<T>);
        impl<'de, T: Deserialize<'de> + Copy + Default, const N: usize> Visitor<'de> for Items<T, N> {
            type Value = Exact<T, N>;

            fn expecting(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
                write!(f, "an array of length {N}")
            }

            fn visit_seq<A: SeqAccess<'de>>(self, mut seq: A) -> Result<Self::Value, A::Error> {
                let mut items = [T::default(); N];
                for (i, item) in items.iter_mut().enumerate() {
                    *item = seq.next_element()?.ok_or_else(|| A::Error::invalid_length(i, &Expected(N)))?;
                }
                let mut len = N;
                while seq.next_element::<IgnoredAny>()?.is_some() {
                    len += 1;
                }
                if len > N {
                    return Err(A::Error::invalid_length(len, &Expected(N)));
                }
                Ok(Exact(items))
            }
        }
        d.deserialize_seq(Items(PhantomData))
    }
}

/// `[T; N]`, exactly N items.
pub fn array<'de, D: Deserializer<'de>, T: Deserialize<'de> + Copy + Default, const N: usize>(
    d: D,
) -> Result<[T; N], D::Error> {
    Exact::deserialize(d).map(|e| e.0)
}

/// `Option<[T; N]>` (with `#[serde(default)]` for an absent field).
pub fn option_array<'de, D: Deserializer<'de>, T: Deserialize<'de> + Copy + Default, const N: usize>(
    d: D,
) -> Result<Option<[T; N]>, D::Error> {
    Ok(Option::<Exact<T, N>>::deserialize(d)?.map(|e| e.0))
}

/// `Vec<[T; N]>`, every element exactly N items.
pub fn arrays<'de, D: Deserializer<'de>, T: Deserialize<'de> + Copy + Default, const N: usize>(
    d: D,
) -> Result<Vec<[T; N]>, D::Error> {
    Ok(Vec::<Exact<T, N>>::deserialize(d)?.into_iter().map(|e| e.0).collect())
}

/// `Option<Vec<[T; N]>>` (with `#[serde(default)]` for an absent field).
pub fn option_arrays<'de, D: Deserializer<'de>, T: Deserialize<'de> + Copy + Default, const N: usize>(
    d: D,
) -> Result<Option<Vec<[T; N]>>, D::Error> {
    Ok(Option::<Vec<Exact<T, N>>>::deserialize(d)?.map(|all| all.into_iter().map(|e| e.0).collect()))
}

/// A number or an array of exactly three numbers: a colour's grey or [r, g, b], a scale's
/// uniform factor or [x, y, z].
pub(crate) enum OneOrThree {
    One(f64),
    Three([f64; 3]),
}

/// `OneOrThree`, with `expecting` naming both forms in a message ("a number (grey) or an array
/// of three numbers [r, g, b]"; serde's untagged enum said "data did not match any variant").
pub(crate) fn one_or_three<'de, D: Deserializer<'de>>(d: D, expecting: &'static str) -> Result<OneOrThree, D::Error> {
    struct Forms(&'static str);

    impl<'de> Visitor<'de> for Forms {
        type Value = OneOrThree;

        fn expecting(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
            f.write_str(self.0)
        }

        fn visit_f64<E: Error>(self, v: f64) -> Result<OneOrThree, E> {
            Ok(OneOrThree::One(v))
        }

        fn visit_i64<E: Error>(self, v: i64) -> Result<OneOrThree, E> {
            Ok(OneOrThree::One(v as f64))
        }

        fn visit_u64<E: Error>(self, v: u64) -> Result<OneOrThree, E> {
            Ok(OneOrThree::One(v as f64))
        }

        fn visit_seq<A: SeqAccess<'de>>(self, mut seq: A) -> Result<OneOrThree, A::Error> {
            let mut out = [0.0; 3];
            for (i, slot) in out.iter_mut().enumerate() {
                *slot = seq.next_element()?.ok_or_else(|| Error::invalid_length(i, &self))?;
            }
            if seq.next_element::<IgnoredAny>()?.is_some() {
                return Err(Error::invalid_length(4, &self));
            }
            Ok(OneOrThree::Three(out))
        }
    }

    d.deserialize_any(Forms(expecting))
}

#[cfg(test)]
mod tests {
    use serde::Deserialize;

    #[derive(Debug, Deserialize)]
    struct Fields {
        #[serde(deserialize_with = "super::array")]
        point: [f64; 3],
        #[serde(default, deserialize_with = "super::option_arrays")]
        uvs: Option<Vec<[f64; 2]>>,
    }

    #[test]
    fn one_item_too_many_or_too_few_is_an_error_naming_the_lengths() {
        let read = |text: &str| toml::from_str::<Fields>(text).map_err(|e| e.to_string());
        assert_eq!(read("point = [1.0, 2.0, 3.0]").unwrap().point, [1.0, 2.0, 3.0]);
        assert_eq!(read("point = [1, 2, 3]\nuvs = [[0, 1]]").unwrap().uvs, Some(vec![[0.0, 1.0]]));
        for (text, len) in [
            ("point = [1.0, 2.0, 3.0, 4.0]", 4),
            ("point = [1.0, 2.0]", 2),
            ("point = [1.0, 2.0, 3.0]\nuvs = [[0.0, 0.0], [0.0, 0.0, 3.0]]", 3),
        ] {
            let e = read(text).unwrap_err();
            assert!(e.contains(&format!("invalid length {len}, expected an array of")), "{text}: {e}");
        }
        // A wrong item is named by serde as before.
        assert!(read("point = [1.0, 2.0, \"x\"]").unwrap_err().contains("invalid type"));
    }
}
