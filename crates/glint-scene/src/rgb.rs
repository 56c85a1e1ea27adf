//! An RGB triple that a scene file may write as one number (grey) or as `[r, g, b]`.

use std::fmt;

use serde::de::{self, SeqAccess, Visitor};
use serde::{Deserialize, Deserializer, Serialize, Serializer};

#[derive(Clone, Copy, Debug, PartialEq, Default)]
pub struct Rgb(pub [f64; 3]);

impl Rgb {
    pub const fn splat(v: f64) -> Self {
        Self([v, v, v])
    }

    pub const fn zero() -> Self {
        Self::splat(0.0)
    }

    pub const fn one() -> Self {
        Self::splat(1.0)
    }

    pub fn max_channel(self) -> f64 {
        self.0[0].max(self.0[1]).max(self.0[2])
    }

    pub fn min_channel(self) -> f64 {
        self.0[0].min(self.0[1]).min(self.0[2])
    }

    pub fn is_zero(self) -> bool {
        self.0 == [0.0; 3]
    }
}

impl From<[f64; 3]> for Rgb {
    fn from(v: [f64; 3]) -> Self {
        Self(v)
    }
}

impl Serialize for Rgb {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        let [r, g, b] = self.0;
        if r == g && g == b { s.serialize_f64(r) } else { self.0.serialize(s) }
    }
}

impl<'de> Deserialize<'de> for Rgb {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        struct RgbVisitor;

        impl<'de> Visitor<'de> for RgbVisitor {
            type Value = Rgb;

            fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
                f.write_str("a number (grey) or an array of three numbers [r, g, b]")
            }

            fn visit_f64<E: de::Error>(self, v: f64) -> Result<Rgb, E> {
                Ok(Rgb::splat(v))
            }

            fn visit_i64<E: de::Error>(self, v: i64) -> Result<Rgb, E> {
                Ok(Rgb::splat(v as f64))
            }

            fn visit_u64<E: de::Error>(self, v: u64) -> Result<Rgb, E> {
                Ok(Rgb::splat(v as f64))
            }

            fn visit_seq<A: SeqAccess<'de>>(self, mut seq: A) -> Result<Rgb, A::Error> {
                let mut out = [0.0; 3];
                for (i, slot) in out.iter_mut().enumerate() {
                    *slot = seq.next_element()?.ok_or_else(|| de::Error::invalid_length(i, &self))?;
                }
                if seq.next_element::<de::IgnoredAny>()?.is_some() {
                    return Err(de::Error::invalid_length(4, &self));
                }
                Ok(Rgb(out))
            }
        }

        d.deserialize_any(RgbVisitor)
    }
}
