//! The bounds of every number a scene holds, and the range type the viewer's editors share.

use crate::number::{format_bound, format_number};

/// `v` as the tracers store it: rounded to f32.
pub(crate) fn as_f32(v: f64) -> f64 {
    f64::from(v as f32)
}

/// Coordinates and sizes are limited so that squares and sums stay finite in f32
/// (the GPU tracer computes |o − c|² for spheres).
pub const MAX_COORD: f64 = 1e9;
pub const MAX_SHININESS: f64 = 1e6;
pub const MAX_SPOT_EXPONENT: f64 = 1e6;
pub const MAX_INTENSITY: f64 = 1e9;
pub const MAX_IMAGE_SIDE: u32 = 16384;
pub const MAX_SPP: u32 = 4096;
pub const MAX_DEPTH: u32 = 1024;
pub const MAX_EPSILON: f64 = 1e3;
pub const MAX_IOR: f64 = 1e3;
/// The Beckmann roughness m (RMS microfacet slope) of the Cook–Torrance lobe lies in
/// [MIN_ROUGHNESS, MAX_ROUGHNESS]. At m = 1 (a mean slope of 45°) the V-groove G and the
/// Beckmann lobe are at the end of what they model (from m > 1/√2 on, D peaks away from the
/// normal); a rougher surface is a diffuse one. At m = 1e-3 D peaks at 1/m² = 1e6, the bound
/// validation puts on f_att too, and m² = 1e-6 and m²·cos⁴α stay normal f32 numbers on the GPU
/// wherever the lobe is not cut off; a smoother surface is a mirror (k_r).
pub const MIN_ROUGHNESS: f64 = 1e-3;
pub const MAX_ROUGHNESS: f64 = 1.0;
/// Smallest value c + l·d + q·d² may take: f_att = 1/(…) stays ≤ 1e6, so that radiance stays
/// far from f32 overflow on the GPU. The inverse-square model divides by max(d², this) for the
/// same bound: a point within 1e-3 of its light gets f_att = 1e6 at most.
pub const MIN_ATTENUATION_DENOMINATOR: f64 = 1e-6;
/// How far below c a polynomial denominator's minimum (l < 0) may dip. Near the dip its three
/// terms are each about c and cancel; the GPU sums them in f32, off by about 2.4e-7 of c, so
/// f_att there stays within 0.25 % (a dip to c / 1.6e7 made it infinite).
pub const MAX_ATTENUATION_DIP: f64 = 1e4;

/// The shortest a direction (a camera's up, a light's direction, a plane's or a vertex's normal)
/// may be: it must stay a usable direction after rounding to f32 and normalising there.
pub const MIN_DIRECTION_LENGTH: f64 = 1e-12;

/// Whether `d` is finite and longer than `MIN_DIRECTION_LENGTH`: the one test validation and
/// the importers hold normals and directions to (they had three thresholds between them).
pub fn usable_direction(d: [f64; 3]) -> bool {
    d.iter().all(|c| c.is_finite()) && d.iter().map(|c| c * c).sum::<f64>().sqrt() > MIN_DIRECTION_LENGTH
}

/// The values one number of a scene may take. Validation checks every number against its
/// entry in [`ranges`], and the viewer's editors take their ranges from there too, so an
/// editor neither clamps a valid value away nor offers an invalid one.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Range<T> {
    pub min: T,
    pub max: T,
    /// (min, max] instead of [min, max], for what the tracers divide by (a size, an index of
    /// refraction): the value must stay above `min` when rounded to f32, as both tracers read it.
    pub min_excluded: bool,
    /// The useful values span decades: an editor shows them on a logarithmic scale.
    pub log: bool,
}

impl<T> Range<T> {
    /// [min, max] on a linear scale.
    pub const fn linear(min: T, max: T) -> Self {
        Self { min, max, min_excluded: false, log: false }
    }

    /// [min, max] on a logarithmic scale.
    pub const fn logarithmic(min: T, max: T) -> Self {
        Self { min, max, min_excluded: false, log: true }
    }

    /// (min, max] on a logarithmic scale.
    pub const fn logarithmic_above(min: T, max: T) -> Self {
        Self { min, max, min_excluded: true, log: true }
    }
}

impl Range<f64> {
    /// The range as messages write it: `[1e-9, 1e9]`, or `(0, 1000]` where the minimum is
    /// excluded.
    pub fn bounds(&self) -> String {
        let open = if self.min_excluded { '(' } else { '[' };
        format!("{open}{}, {}]", format_bound(self.min), format_bound(self.max))
    }

    /// Whether `v` is a finite number in the range.
    pub fn contains(&self, v: f64) -> bool {
        let above_min = if self.min_excluded { as_f32(v) > self.min } else { v >= self.min };
        v.is_finite() && above_min && v <= self.max
    }

    /// Why `v` is outside, where the range alone does not say: a value above an excluded
    /// minimum that f32, in which the tracers store it, rounds down to that minimum (an ior of
    /// 1e-46 is above 0, but stored it is 0). Empty otherwise.
    pub fn why_outside(&self, v: f64) -> String {
        if self.min_excluded && v.is_finite() && v > self.min && as_f32(v) <= self.min {
            format!(
                ": {} rounds to {} in f32, the precision the tracers store it in",
                format_number(v),
                format_number(self.min)
            )
        } else {
            String::new()
        }
    }
}

impl Range<u32> {
    pub fn contains(&self, v: u32) -> bool {
        (self.min..=self.max).contains(&v)
    }
}

/// The allowed range of every number a scene holds, one entry per kind of field.
pub mod ranges {
    use super::{
        MAX_COORD, MAX_DEPTH, MAX_EPSILON, MAX_IMAGE_SIDE, MAX_INTENSITY, MAX_IOR, MAX_ROUGHNESS, MAX_SHININESS,
        MAX_SPOT_EXPONENT, MAX_SPP, MIN_ROUGHNESS, Range,
    };

    pub const IMAGE_SIDE: Range<u32> = Range::logarithmic(1, MAX_IMAGE_SIDE);
    pub const SPP: Range<u32> = Range::logarithmic(1, MAX_SPP);
    /// Recursion depth: 0 is local shading only.
    pub const DEPTH: Range<u32> = Range::logarithmic(0, MAX_DEPTH);
    pub const BAILOUT: Range<f64> = Range::linear(0.0, 1.0);
    pub const EPSILON: Range<f64> = Range::logarithmic(0.0, MAX_EPSILON);
    pub const FOV_Y: Range<f64> = Range::linear(1e-6, 179.0);
    /// An orthographic camera's view height: from the smallest distance a look-at point may be
    /// from the eye to the span of the coordinates.
    pub const VIEW_HEIGHT: Range<f64> = Range::logarithmic(1e-9, MAX_COORD);
    /// Each component of a position or direction.
    pub const COORD: Range<f64> = Range::linear(-MAX_COORD, MAX_COORD);
    /// Each channel of a colour or intensity (reflectances, emission, light intensities).
    pub const COLOUR: Range<f64> = Range::linear(0.0, MAX_INTENSITY);
    pub const SHININESS: Range<f64> = Range::logarithmic(0.0, MAX_SHININESS);
    pub const IOR: Range<f64> = Range::logarithmic_above(0.0, MAX_IOR);
    /// The Beckmann roughness m of the Cook–Torrance lobe.
    pub const ROUGHNESS: Range<f64> = Range::logarithmic(MIN_ROUGHNESS, MAX_ROUGHNESS);
    /// A sphere's radius.
    pub const SIZE: Range<f64> = Range::logarithmic_above(0.0, MAX_COORD);
    /// A checker's square size: the texture scales planar coordinates by 1 / (2·size), which
    /// must stay finite in f32 (the GPU refused 1e-39, which the CPU rendered); 1e-9 as a view
    /// height's least.
    pub const CHECKER_SIZE: Range<f64> = Range::logarithmic(1e-9, MAX_COORD);
    /// Each of the attenuation coefficients c, l, q (their sum has a rule of its own).
    pub const ATTENUATION: Range<f64> = Range::linear(-MAX_INTENSITY, MAX_INTENSITY);
    pub const SPOT_EXPONENT: Range<f64> = Range::logarithmic(0.0, MAX_SPOT_EXPONENT);
    /// A model's exposure (`--exposure`, `exposure` of a model object).
    pub const EXPOSURE: Range<f64> = Range::logarithmic_above(0.0, 1e6);
    /// A spot cone's half-angle in degrees; `NO_CONE_CUTOFF` is allowed besides.
    pub const CUTOFF: Range<f64> = Range::linear(0.0, 90.0);
    /// The smooth falloff's inner and outer cone half-angles in degrees (inner ≤ outer besides).
    pub const CONE: Range<f64> = Range::linear(0.0, 90.0);
    /// The inverse-square model's range window, in scene units.
    pub const LIGHT_RANGE: Range<f64> = Range::logarithmic_above(0.0, MAX_COORD);
}

#[cfg(test)]
mod tests {
    use super::ranges;

    #[test]
    fn a_value_above_an_excluded_minimum_that_f32_rounds_to_it_is_told_so() {
        assert!(!ranges::IOR.contains(1e-46));
        let why = ranges::IOR.why_outside(1e-46);
        assert!(why.contains("1e-46 rounds to 0 in f32"), "{why}");
        // Outside for the plain reason: nothing to add.
        for v in [0.0, -1.0, 2e3, f64::NAN] {
            assert!(ranges::IOR.why_outside(v).is_empty(), "{v}");
        }
        assert!(ranges::SIZE.why_outside(1e-50).contains("rounds to 0"));
    }
}
