//! The tags of the flat layout (`layout`'s constants, what both tracers switch on) decoded
//! into the scene's enums. Here, beside the enums, so that the layout depends on nothing of the
//! scene.

use super::{AttenuationModel, EpsilonMode, Filter, Fresnel, LightKind, SpecularModel, SpotFalloff, Wrap};
use crate::layout::{
    ATTENUATION_INVERSE_SQUARE, ATTENUATION_POLYNOMIAL, EPS_NUDGE_NORMAL, EPS_NUDGE_RAY, EPS_ROBUST, EPS_SKIP_CONVEX,
    EPS_TMIN, FILTER_BILINEAR, FILTER_NEAREST, FRESNEL_EXACT, FRESNEL_SCHLICK, LIGHT_DIRECTIONAL, LIGHT_POINT,
    LIGHT_SPOT, SPECULAR_BLINN, SPECULAR_COOK_TORRANCE, SPECULAR_PHONG, SPOT_FALLOFF_POWER, SPOT_FALLOFF_SMOOTH,
    UnknownTag, WRAP_CLAMP_TO_EDGE, WRAP_MIRRORED_REPEAT, WRAP_REPEAT,
};

/// The tags both tracers switch on are Rust enums on the CPU (`#[repr(u32)]`, their
/// discriminants the constants above, which the reflection test checks against WGSL): every
/// `match` on them is exhaustive, so a new kind is a compile error wherever it is not handled.
impl TryFrom<u32> for LightKind {
    type Error = UnknownTag;

    fn try_from(value: u32) -> Result<Self, UnknownTag> {
        match value {
            LIGHT_POINT => Ok(Self::Point),
            LIGHT_DIRECTIONAL => Ok(Self::Directional),
            LIGHT_SPOT => Ok(Self::Spot),
            _ => Err(UnknownTag { what: "light kind", value }),
        }
    }
}

impl TryFrom<u32> for AttenuationModel {
    type Error = UnknownTag;

    fn try_from(value: u32) -> Result<Self, UnknownTag> {
        match value {
            ATTENUATION_POLYNOMIAL => Ok(Self::Polynomial),
            ATTENUATION_INVERSE_SQUARE => Ok(Self::InverseSquare),
            _ => Err(UnknownTag { what: "attenuation model", value }),
        }
    }
}

impl TryFrom<u32> for SpotFalloff {
    type Error = UnknownTag;

    fn try_from(value: u32) -> Result<Self, UnknownTag> {
        match value {
            SPOT_FALLOFF_POWER => Ok(Self::Power),
            SPOT_FALLOFF_SMOOTH => Ok(Self::Smooth),
            _ => Err(UnknownTag { what: "spot falloff", value }),
        }
    }
}

impl TryFrom<u32> for EpsilonMode {
    type Error = UnknownTag;

    fn try_from(value: u32) -> Result<Self, UnknownTag> {
        match value {
            EPS_TMIN => Ok(Self::Tmin),
            EPS_NUDGE_RAY => Ok(Self::NudgeRay),
            EPS_NUDGE_NORMAL => Ok(Self::NudgeNormal),
            EPS_ROBUST => Ok(Self::Robust),
            EPS_SKIP_CONVEX => Ok(Self::SkipConvex),
            _ => Err(UnknownTag { what: "epsilon mode", value }),
        }
    }
}

impl TryFrom<u32> for Wrap {
    type Error = UnknownTag;

    fn try_from(value: u32) -> Result<Self, UnknownTag> {
        match value {
            WRAP_REPEAT => Ok(Self::Repeat),
            WRAP_CLAMP_TO_EDGE => Ok(Self::ClampToEdge),
            WRAP_MIRRORED_REPEAT => Ok(Self::MirroredRepeat),
            _ => Err(UnknownTag { what: "texture wrap mode", value }),
        }
    }
}

impl TryFrom<u32> for Filter {
    type Error = UnknownTag;

    fn try_from(value: u32) -> Result<Self, UnknownTag> {
        match value {
            FILTER_NEAREST => Ok(Self::Nearest),
            FILTER_BILINEAR => Ok(Self::Bilinear),
            _ => Err(UnknownTag { what: "texture filter", value }),
        }
    }
}

impl TryFrom<u32> for SpecularModel {
    type Error = UnknownTag;

    fn try_from(value: u32) -> Result<Self, UnknownTag> {
        match value {
            SPECULAR_BLINN => Ok(Self::Blinn),
            SPECULAR_PHONG => Ok(Self::Phong),
            SPECULAR_COOK_TORRANCE => Ok(Self::CookTorrance),
            _ => Err(UnknownTag { what: "specular model", value }),
        }
    }
}

impl TryFrom<u32> for Fresnel {
    type Error = UnknownTag;

    fn try_from(value: u32) -> Result<Self, UnknownTag> {
        match value {
            FRESNEL_EXACT => Ok(Self::Exact),
            FRESNEL_SCHLICK => Ok(Self::Schlick),
            _ => Err(UnknownTag { what: "Fresnel factor", value }),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn tags_round_trip_and_unknown_values_are_errors() {
        for kind in LightKind::ALL {
            assert_eq!(LightKind::try_from(kind as u32), Ok(kind));
        }
        for mode in EpsilonMode::ALL {
            assert_eq!(EpsilonMode::try_from(mode as u32), Ok(mode));
        }
        for model in AttenuationModel::ALL {
            assert_eq!(AttenuationModel::try_from(model as u32), Ok(model));
        }
        for falloff in SpotFalloff::ALL {
            assert_eq!(SpotFalloff::try_from(falloff as u32), Ok(falloff));
        }
        for model in SpecularModel::ALL {
            assert_eq!(SpecularModel::try_from(model as u32), Ok(model));
        }
        for fresnel in Fresnel::ALL {
            assert_eq!(Fresnel::try_from(fresnel as u32), Ok(fresnel));
        }
        for wrap in [Wrap::Repeat, Wrap::ClampToEdge, Wrap::MirroredRepeat] {
            assert_eq!(Wrap::try_from(wrap as u32), Ok(wrap));
        }
        for filter in [Filter::Nearest, Filter::Bilinear] {
            assert_eq!(Filter::try_from(filter as u32), Ok(filter));
        }
        assert_eq!(Wrap::try_from(3).unwrap_err().to_string(), "3 is not a valid texture wrap mode");
        assert_eq!(LightKind::try_from(7).unwrap_err().to_string(), "7 is not a valid light kind");
        assert_eq!(EpsilonMode::try_from(5).unwrap_err().to_string(), "5 is not a valid epsilon mode");
        assert_eq!(AttenuationModel::try_from(2).unwrap_err().to_string(), "2 is not a valid attenuation model");
        assert_eq!(SpotFalloff::try_from(2).unwrap_err().to_string(), "2 is not a valid spot falloff");
        assert_eq!(SpecularModel::try_from(3).unwrap_err().to_string(), "3 is not a valid specular model");
        assert_eq!(Fresnel::try_from(2).unwrap_err().to_string(), "2 is not a valid Fresnel factor");
    }
}
