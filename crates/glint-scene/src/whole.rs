//! Whole-number settings read with their allowed range in the parser's message: `max_depth = -1`
//! said "expected u32", a type the author never chose. Only what a u32 cannot hold is refused
//! here; validation checks the range itself, for scenes from every source alike.

use std::fmt;

use serde::Deserializer;
use serde::de::{Error, Unexpected, Visitor};

use crate::limits::{Range, ranges};

struct WholeIn(Range<u32>);

impl Visitor<'_> for WholeIn {
    type Value = u32;
    fn expecting(&self, f: &mut fmt::Formatter) -> fmt::Result {
        write!(f, "a whole number in [{}, {}]", self.0.min, self.0.max)
    }
    fn visit_i64<E: Error>(self, v: i64) -> Result<u32, E> {
        u32::try_from(v).map_err(|_| E::invalid_value(Unexpected::Signed(v), &self))
    }
    fn visit_u64<E: Error>(self, v: u64) -> Result<u32, E> {
        u32::try_from(v).map_err(|_| E::invalid_value(Unexpected::Unsigned(v), &self))
    }
}

fn whole_in<'de, D: Deserializer<'de>>(deserializer: D, range: Range<u32>) -> Result<u32, D::Error> {
    deserializer.deserialize_u32(WholeIn(range))
}

/// An image's width or height.
pub(crate) fn image_side<'de, D: Deserializer<'de>>(deserializer: D) -> Result<u32, D::Error> {
    whole_in(deserializer, ranges::IMAGE_SIDE)
}

/// Samples per pixel.
pub(crate) fn spp<'de, D: Deserializer<'de>>(deserializer: D) -> Result<u32, D::Error> {
    whole_in(deserializer, ranges::SPP)
}

/// The ray tree's depth.
pub(crate) fn depth<'de, D: Deserializer<'de>>(deserializer: D) -> Result<u32, D::Error> {
    whole_in(deserializer, ranges::DEPTH)
}

/// The random sequence's seed: any u32.
pub(crate) fn seed<'de, D: Deserializer<'de>>(deserializer: D) -> Result<u32, D::Error> {
    whole_in(deserializer, Range::linear(0, u32::MAX))
}

#[cfg(test)]
mod tests {
    use crate::RenderSettings;

    fn error(text: &str) -> String {
        toml::from_str::<RenderSettings>(text).expect_err("refused").to_string()
    }

    #[test]
    fn a_count_a_u32_cannot_hold_names_its_allowed_range() {
        let depth = error("max_depth = -1");
        assert!(depth.contains("invalid value: integer `-1`, expected a whole number in [0, 1024]"), "{depth}");
        let spp = error("spp = 99999999999");
        assert!(spp.contains("integer `99999999999`, expected a whole number in [1, 4096]"), "{spp}");
        assert!(error("width = 1.5").contains("floating point `1.5`, expected a whole number in [1, 16384]"));
        assert!(error("seed = -2").contains("expected a whole number in [0, 4294967295]"));
    }

    #[test]
    fn a_count_a_u32_holds_is_left_to_validation() {
        // Outside the range, but validation says so with the field and flag names.
        let settings: RenderSettings = toml::from_str("spp = 0\nmax_depth = 5000").expect("parses");
        assert_eq!((settings.spp, settings.max_depth), (0, 5000));
    }
}
