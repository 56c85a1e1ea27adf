//! Lights as a scene file spells them: the kind, the seed's distance attenuation f_att
//! (OpenGL's polynomial or glTF's inverse square) and spot cone S_j (the power falloff or
//! glTF's smooth one).

use glint_types::{AttenuationModel, LightKind, SpotFalloff};
use serde::{Deserialize, Serialize};

use super::buffered::{Content, ContentError};
use super::rgb::Rgb;

/// The smooth falloff's cone half-angles in degrees when a scene leaves them out: glTF's
/// defaults (innerConeAngle 0, outerConeAngle π/4).
pub const DEFAULT_INNER_CONE: f64 = 0.0;
pub const DEFAULT_OUTER_CONE: f64 = 45.0;

/// The spot cutoff that means no cone at all (as in OpenGL): the light shines every way, and
/// the cutoff every point and directional light has.
pub const NO_CONE_CUTOFF: f64 = 180.0;

/// One light. A flat record rather than an enum so that a light can change its type in the
/// viewer without losing its other settings; validation checks that each kind has the fields
/// it needs.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct LightDesc {
    #[serde(rename = "type")]
    pub kind: LightKind,
    /// Position (point and spot lights).
    #[serde(default, skip_serializing_if = "Option::is_none", deserialize_with = "crate::exact_len::option_array")]
    pub position: Option<[f64; 3]>,
    /// Direction the light travels in: from the light into the scene (directional), or the
    /// spot axis L_N (spot).
    #[serde(default, skip_serializing_if = "Option::is_none", deserialize_with = "crate::exact_len::option_array")]
    pub direction: Option<[f64; 3]>,
    /// I_d, the diffuse intensity.
    #[serde(default = "Rgb::one")]
    pub diffuse: Rgb,
    /// I_s, the specular intensity.
    #[serde(default = "Rgb::one")]
    pub specular: Rgb,
    /// I_a,j, the light's own ambient term (OpenGL style: attenuated, never shadowed).
    #[serde(default)]
    pub ambient: Rgb,
    /// f_att of point and spot lights: 1 / (c + l·d + q·d²) or inverse square.
    #[serde(default)]
    pub attenuation: Attenuation,
    /// The spot cone's falloff: `power` (exponent and cutoff) or `smooth` (inner and outer cone).
    #[serde(default, skip_serializing_if = "SpotFalloff::is_power")]
    pub falloff: SpotFalloff,
    /// Spot exponent s of (L_N·(−L))^s, ≥ 0 (power falloff).
    #[serde(default)]
    pub exponent: f64,
    /// Spot cone half-angle in degrees: [0, 90], or `NO_CONE_CUTOFF` (180) for no cone (power
    /// falloff).
    #[serde(default = "default_cutoff")]
    pub cutoff: f64,
    /// Half-angle in degrees where the smooth falloff begins (S = 1 inside);
    /// `DEFAULT_INNER_CONE` when absent.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub inner_cone: Option<f64>,
    /// Half-angle in degrees where the smooth falloff reaches 0; `DEFAULT_OUTER_CONE` when absent.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub outer_cone: Option<f64>,
    #[serde(default = "default_true")]
    pub casts_shadows: bool,
    /// Optional label shown in the viewer.
    #[serde(default, skip_serializing_if = "String::is_empty")]
    pub name: String,
}

impl LightDesc {
    /// A light of `kind` with every optional field at its default.
    pub fn new(kind: LightKind, position: [f64; 3], direction: [f64; 3]) -> Self {
        Self {
            kind,
            position: (kind != LightKind::Directional).then_some(position),
            direction: (kind != LightKind::Point).then_some(direction),
            diffuse: Rgb::one(),
            specular: Rgb::one(),
            ambient: Rgb::zero(),
            attenuation: Attenuation::default(),
            falloff: SpotFalloff::Power,
            exponent: 0.0,
            cutoff: default_cutoff(),
            inner_cone: None,
            outer_cone: None,
            casts_shadows: true,
            name: String::new(),
        }
    }
}

impl LightDesc {
    /// The smooth falloff's (inner, outer) cone half-angles in degrees, defaults filled in.
    pub fn cone_angles(&self) -> (f64, f64) {
        (self.inner_cone.unwrap_or(DEFAULT_INNER_CONE), self.outer_cone.unwrap_or(DEFAULT_OUTER_CONE))
    }
}

fn one() -> f64 {
    1.0
}

fn default_cutoff() -> f64 {
    NO_CONE_CUTOFF
}

fn default_true() -> bool {
    true
}

/// A point or spot light's distance attenuation f_att (d: distance from the shaded point to
/// the light). Written `attenuation = { c, l, q }` or `{ model = "inverse_square", range }`;
/// a field of the other model is a parse error naming it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Attenuation {
    /// f_att = 1 / (c + l·d + q·d²).
    Polynomial { c: f64, l: f64, q: f64 },
    /// f_att = clamp(1 − (d/range)⁴, 0, 1) / d², or 1/d² without a range (the
    /// KHR_lights_punctual recommendation); d² is bounded below by
    /// `MIN_ATTENUATION_DENOMINATOR`.
    InverseSquare { range: Option<f64> },
}

impl Default for Attenuation {
    fn default() -> Self {
        Self::NONE
    }
}

impl Attenuation {
    /// f_att = 1 everywhere: the polynomial (1, 0, 0), every directional light's.
    pub const NONE: Self = Self::Polynomial { c: 1.0, l: 0.0, q: 0.0 };

    /// glTF's point and spot light falloff: 1/d², windowed by `range` when there is one.
    pub fn inverse_square(range: Option<f64>) -> Self {
        Self::InverseSquare { range }
    }

    pub fn is_none(&self) -> bool {
        *self == Self::NONE
    }

    pub fn model(&self) -> AttenuationModel {
        match self {
            Self::Polynomial { .. } => AttenuationModel::Polynomial,
            Self::InverseSquare { .. } => AttenuationModel::InverseSquare,
        }
    }
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct PolynomialFields {
    #[serde(default = "one")]
    c: f64,
    #[serde(default)]
    l: f64,
    #[serde(default)]
    q: f64,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct InverseSquareFields {
    #[serde(default)]
    range: Option<f64>,
}

/// The polynomial form writes no `model` (as every scene before the inverse-square model).
impl Serialize for Attenuation {
    fn serialize<S: serde::Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        use serde::ser::SerializeMap;
        let mut map = serializer.serialize_map(None)?;
        match *self {
            Self::Polynomial { c, l, q } => {
                map.serialize_entry("c", &c)?;
                map.serialize_entry("l", &l)?;
                map.serialize_entry("q", &q)?;
            }
            Self::InverseSquare { range } => {
                map.serialize_entry("model", AttenuationModel::InverseSquare.name())?;
                if let Some(range) = range {
                    map.serialize_entry("range", &range)?;
                }
            }
        }
        map.end()
    }
}

/// By hand: the model decides which fields belong, and a field of the other model is an error
/// that says which model it belongs to (serde's own would only say "unknown field").
impl<'de> Deserialize<'de> for Attenuation {
    fn deserialize<D: serde::Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        use serde::de::Error;
        let mut table = match Content::deserialize(deserializer)? {
            Content::Map(table) => table,
            other => {
                return Err(D::Error::custom(format!(
                    "attenuation is a table ({{ c, l, q }} or {{ model = \"inverse_square\", range }}), not {} {other}",
                    other.type_str()
                )));
            }
        };
        let model = match table.iter().position(|(k, _)| k == "model").map(|i| table.remove(i).1) {
            None => AttenuationModel::Polynomial,
            Some(value) => {
                AttenuationModel::ALL.into_iter().find(|m| value.as_str() == Some(m.name())).ok_or_else(|| {
                    D::Error::custom(format!(
                        "attenuation.model must be \"polynomial\" or \"inverse_square\", not {value}"
                    ))
                })?
            }
        };
        for key in table.iter().map(|(k, _)| k) {
            if model.fields().contains(&key.as_str()) {
                continue;
            }
            let owner = AttenuationModel::ALL.into_iter().find(|m| m.fields().contains(&key.as_str()));
            let allowed = model.fields().join(", ");
            let message = match owner {
                Some(owner) => format!(
                    "attenuation.{key} belongs to model = \"{}\"; model = \"{}\" has only {allowed}",
                    owner.name(),
                    model.name()
                ),
                None => {
                    format!("attenuation.{key} is not a field; model = \"{}\" has {allowed} (and model)", model.name())
                }
            };
            return Err(D::Error::custom(message));
        }
        let fields = Content::Map(table);
        let one_line = |e: ContentError| D::Error::custom(format!("attenuation: {e}"));
        match model {
            AttenuationModel::Polynomial => {
                let PolynomialFields { c, l, q } = fields.into_value().map_err(one_line)?;
                Ok(Self::Polynomial { c, l, q })
            }
            AttenuationModel::InverseSquare => {
                let InverseSquareFields { range } = fields.into_value().map_err(one_line)?;
                Ok(Self::InverseSquare { range })
            }
        }
    }
}
