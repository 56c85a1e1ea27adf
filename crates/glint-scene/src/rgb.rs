//! An RGB triple that a scene file may write as one number (grey) or as `[r, g, b]`.

use serde::{Deserialize, Deserializer, Serialize, Serializer};

use crate::exact_len::{OneOrThree, one_or_three};

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
        Ok(match one_or_three(d, "a number (grey) or an array of three numbers [r, g, b]")? {
            OneOrThree::One(v) => Rgb::splat(v),
            OneOrThree::Three(rgb) => Rgb(rgb),
        })
    }
}
