//! The tags both tracers switch on, as Rust enums whose discriminants are the layout's
//! constants (which the reflection test checks against WGSL). Each is written once, in
//! [`tags!`]: its variants, their stored value and the name a scene file spells; `ALL`,
//! `name`, `from_name`, the serde spelling and `TryFrom<u32>` follow from that one list.
//! Every `match` on a tag is exhaustive, so a new kind is a compile error wherever it is not
//! handled.

use serde::{Deserialize, Serialize};

use crate::layout::{
    ATTENUATION_INVERSE_SQUARE, ATTENUATION_POLYNOMIAL, EPS_NUDGE_NORMAL, EPS_NUDGE_RAY, EPS_ROBUST, EPS_SKIP_CONVEX,
    EPS_TMIN, FILTER_BILINEAR, FILTER_NEAREST, FRESNEL_EXACT, FRESNEL_SCHLICK, GpuLight, GpuMaterial, INTEGRATOR_PATH,
    INTEGRATOR_WHITTED, LIGHT_DIRECTIONAL, LIGHT_POINT, LIGHT_SPOT, PATH_CAUSTIC, PATH_DIRECT, PATH_INDIRECT,
    PATH_REST, RAY_CAMERA, RAY_REFLECTION, RAY_REFRACTION, RAY_SHADOW, SPECULAR_BLINN, SPECULAR_COOK_TORRANCE,
    SPECULAR_PHONG, SPOT_FALLOFF_POWER, SPOT_FALLOFF_SMOOTH, UnknownTag, WRAP_CLAMP_TO_EDGE, WRAP_MIRRORED_REPEAT,
    WRAP_REPEAT,
};

/// One tag enum: `Variant = STORED_VALUE => "scene_file_name"` per variant, and what a stored
/// value no variant has is called in the error.
macro_rules! tags {
    (
        $(#[$meta:meta])*
        pub enum $name:ident ($what:literal) {
            $($(#[$vmeta:meta])* $variant:ident = $value:path => $spelling:literal,)+
        }
    ) => {
        $(#[$meta])*
        #[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize)]
        #[repr(u32)]
        pub enum $name {
            $($(#[$vmeta])* #[serde(rename = $spelling)] $variant = $value,)+
        }

        impl $name {
            /// Every variant, in the order of their stored values.
            pub const ALL: [Self; [$($spelling),+].len()] = [$(Self::$variant),+];

            /// The name a scene file uses.
            pub const fn name(self) -> &'static str {
                match self {
                    $(Self::$variant => $spelling,)+
                }
            }

            /// The variant a scene file calls `name`.
            pub fn from_name(name: &str) -> Option<Self> {
                Self::ALL.into_iter().find(|t| t.name() == name)
            }
        }

        /// Only a name: serde's derive also took `{ name = [] }` for a unit variant, and said
        /// "wanted string or table" of a number, naming neither the field's kind nor its names.
        impl<'de> Deserialize<'de> for $name {
            fn deserialize<D: serde::Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
                struct Names;

                impl serde::de::Visitor<'_> for Names {
                    type Value = $name;

                    fn expecting(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
                        let article = if $what.starts_with(['a', 'e', 'i', 'o', 'u']) { "an" } else { "a" };
                        write!(f, "{article} {} named by a string, one of: {}", $what, [$($spelling),+].join(", "))
                    }

                    fn visit_str<E: serde::de::Error>(self, v: &str) -> Result<$name, E> {
                        $name::from_name(v).ok_or_else(|| E::unknown_variant(v, &[$($spelling),+]))
                    }
                }

                d.deserialize_str(Names)
            }
        }

        impl From<$name> for u32 {
            fn from(tag: $name) -> u32 {
                tag as u32
            }
        }

        impl TryFrom<u32> for $name {
            type Error = UnknownTag;

            fn try_from(value: u32) -> Result<Self, UnknownTag> {
                match value {
                    $($value => Ok(Self::$variant),)+
                    _ => Err(UnknownTag { what: $what, value }),
                }
            }
        }
    };
}

tags! {
    /// The kind of a light source (`GpuLight::kind`).
    pub enum LightKind ("light kind") {
        Point = LIGHT_POINT => "point",
        Directional = LIGHT_DIRECTIONAL => "directional",
        Spot = LIGHT_SPOT => "spot",
    }
}

tags! {
    /// How a spot light's S falls off towards the edge of its cone (`falloff`; stored as
    /// `GpuLight::spot_falloff`).
    #[derive(Default)]
    pub enum SpotFalloff ("spot falloff") {
        /// S = max(L_N·(−L), 0)^exponent inside `cutoff`, 0 outside (OpenGL's).
        #[default]
        Power = SPOT_FALLOFF_POWER => "power",
        /// S = t², t = saturate((cos θ − cos outer) / (cos inner − cos outer)) (glTF's).
        Smooth = SPOT_FALLOFF_SMOOTH => "smooth",
    }
}

impl SpotFalloff {
    pub fn is_power(&self) -> bool {
        *self == Self::Power
    }
}

tags! {
    /// Which distance attenuation a light has (`attenuation.model`; stored as
    /// `GpuLight::attenuation_model`).
    #[derive(Default)]
    pub enum AttenuationModel ("attenuation model") {
        /// f_att = 1 / (c + l·d + q·d²), OpenGL's.
        #[default]
        Polynomial = ATTENUATION_POLYNOMIAL => "polynomial",
        /// f_att = 1/d², windowed by an optional range (glTF's KHR_lights_punctual).
        InverseSquare = ATTENUATION_INVERSE_SQUARE => "inverse_square",
    }
}

impl AttenuationModel {
    /// The fields of `attenuation = { … }` this model has (besides `model`).
    pub fn fields(self) -> &'static [&'static str] {
        match self {
            Self::Polynomial => &["c", "l", "q"],
            Self::InverseSquare => &["range"],
        }
    }
}

tags! {
    /// What a render computes (`[render] integrator`; stored as `SceneHeader::integrator`):
    /// the seed's ray tree, or the light transport it approximates.
    #[derive(Default)]
    pub enum Integrator ("integrator") {
        /// Whitted's ray tree: local Phong terms, mirror and refracted rays, the ambient term.
        #[default]
        Whitted = INTEGRATOR_WHITTED => "whitted",
        /// A unidirectional Monte Carlo path tracer (global illumination, the reference the
        /// Whitted image is held against).
        Path = INTEGRATOR_PATH => "path",
    }
}

impl Integrator {
    pub fn is_whitted(&self) -> bool {
        *self == Self::Whitted
    }
}

tags! {
    /// A kind of light a path brings back, by its scatters (`PATH_*`, a bit each; the image
    /// keeps or leaves out each by `SceneHeader::omit_kinds`). The four add up to the image.
    pub enum PathKind ("kind of light path") {
        /// Light met directly or through mirrors and glass: what Whitted's local terms compute.
        Direct = PATH_DIRECT => "direct",
        /// Light between diffuse surfaces (colour bleeding), which Whitted's ambient stands in for.
        Indirect = PATH_INDIRECT => "indirect",
        /// Light that reached a diffuse surface through a mirror or glass.
        Caustic = PATH_CAUSTIC => "caustic",
        /// Everything else: a mirror or glass between two diffuse scatters.
        Rest = PATH_REST => "rest",
    }
}

impl PathKind {
    /// What the kind is called on a label.
    pub const fn label(self) -> &'static str {
        match self {
            Self::Direct => "Direct light",
            Self::Indirect => "Indirect diffuse",
            Self::Caustic => "Caustics",
            Self::Rest => "The rest",
        }
    }

    /// `SceneHeader::omit_kinds` for an image of this kind alone.
    pub fn alone(self) -> u32 {
        Self::ALL.iter().map(|&k| u32::from(k)).filter(|&bit| bit != u32::from(self)).fold(0, |a, b| a | b)
    }
}

tags! {
    /// How secondary rays avoid hitting the surface they start on (the seed lists three
    /// remedies; `robust` is the modern, scale-aware one).
    #[derive(Default)]
    pub enum EpsilonMode ("epsilon mode") {
        /// Reject hits with t ≤ ε.
        Tmin = EPS_TMIN => "tmin",
        /// Move the origin by ε along the new ray's direction.
        NudgeRay = EPS_NUDGE_RAY => "nudge_ray",
        /// Move the origin by ε along the geometric normal, to the side the ray leaves into.
        NudgeNormal = EPS_NUDGE_NORMAL => "nudge_normal",
        /// Re-project the hit point onto the surface, offset it by a few ULPs along the normal
        /// (Wächter & Binder, Ray Tracing Gems ch. 6), then by ε.
        #[default]
        Robust = EPS_ROBUST => "robust",
        /// Start at the hit point and do not test the primitive the ray leaves (the seed's
        /// "convex objects do not test intersection if the ray's prior intersection is with
        /// that object"); a ray into a sphere finds its far side. Hits with t ≤ ε are rejected
        /// as with `tmin`.
        SkipConvex = EPS_SKIP_CONVEX => "skip_convex",
    }
}

tags! {
    /// Which specular lobe a material uses (`GpuMaterial::specular_model`).
    #[derive(Default)]
    pub enum SpecularModel ("specular model") {
        /// max(N·H, 0)^n with the half vector H (Blinn 1977, the OpenGL form of the seed).
        #[default]
        Blinn = SPECULAR_BLINN => "blinn",
        /// max(R·V, 0)^n with the mirrored light direction R (Phong 1975).
        Phong = SPECULAR_PHONG => "phong",
        /// F·D·G / (N·V): Cook & Torrance (1982) with the Beckmann distribution D of roughness
        /// m, the V-groove masking and shadowing G and the Fresnel factor F
        /// (docs/scene-format.md).
        CookTorrance = SPECULAR_COOK_TORRANCE => "cook_torrance",
    }
}

impl SpecularModel {
    /// A short label for tables and editors.
    pub fn label(self) -> &'static str {
        match self {
            Self::Blinn => "Blinn",
            Self::Phong => "Phong",
            Self::CookTorrance => "Cook–Torrance",
        }
    }
}

tags! {
    /// The Fresnel factor F of the Cook–Torrance lobe (`GpuMaterial::fresnel`), from the
    /// material's ior, at c = V·H.
    #[derive(Default)]
    pub enum Fresnel ("Fresnel factor") {
        /// The unpolarised dielectric Fresnel equation, as Cook & Torrance used it:
        /// F = ½ (g−c)²/(g+c)² · [1 + (c(g+c)−1)²/(c(g−c)+1)²], g² = η² + c² − 1 (1 where
        /// g² < 0). The default: Glint's CPU tracer is the reference, and the exact form costs
        /// a square root.
        #[default]
        Exact = FRESNEL_EXACT => "exact",
        /// Schlick's approximation F = F0 + (1 − F0)(1 − c)⁵, F0 = ((η − 1)/(η + 1))².
        Schlick = FRESNEL_SCHLICK => "schlick",
    }
}

tags! {
    /// How a texture coordinate outside [0, 1] is folded back (glTF sampler `wrapS`/`wrapT`).
    #[derive(Default)]
    pub enum Wrap ("texture wrap mode") {
        /// The texture tiles (glTF REPEAT, 10497; the default).
        #[default]
        Repeat = WRAP_REPEAT => "repeat",
        /// Texels beyond the edge are the edge texel (glTF CLAMP_TO_EDGE, 33071).
        ClampToEdge = WRAP_CLAMP_TO_EDGE => "clamp_to_edge",
        /// The texture tiles, every other copy mirrored (glTF MIRRORED_REPEAT, 33648).
        MirroredRepeat = WRAP_MIRRORED_REPEAT => "mirrored_repeat",
    }
}

tags! {
    /// How texels are combined at a texture coordinate (glTF `magFilter`; there are no
    /// mipmaps).
    #[derive(Default)]
    pub enum Filter ("texture filter") {
        /// The texel the coordinate falls in (glTF NEAREST, 9728).
        Nearest = FILTER_NEAREST => "nearest",
        /// The four nearest texel centres, weighted by distance (glTF LINEAR, 9729; the
        /// default).
        #[default]
        Bilinear = FILTER_BILINEAR => "bilinear",
    }
}

tags! {
    /// The kind of a ray of a probe's ray tree (`ProbeNode::kind`).
    pub enum RayKind ("ray kind") {
        Camera = RAY_CAMERA => "camera",
        Reflection = RAY_REFLECTION => "reflection",
        Refraction = RAY_REFRACTION => "refraction",
        Shadow = RAY_SHADOW => "shadow",
    }
}

/// The tags of one light the tracers switch on, decoded from its stored values.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct LightTags {
    pub kind: LightKind,
    pub attenuation: AttenuationModel,
    pub falloff: SpotFalloff,
}

impl LightTags {
    /// The tags `light` stores, or the first one no kind has.
    pub fn decode(light: &GpuLight) -> Result<Self, UnknownTag> {
        Ok(Self {
            kind: LightKind::try_from(light.kind)?,
            attenuation: AttenuationModel::try_from(light.attenuation_model)?,
            falloff: SpotFalloff::try_from(light.spot_falloff)?,
        })
    }
}

/// The tags of one material the tracers switch on, decoded from its stored values.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct MaterialTags {
    pub specular: SpecularModel,
    pub fresnel: Fresnel,
}

impl MaterialTags {
    /// The tags `material` stores, or the first one no kind has.
    pub fn decode(material: &GpuMaterial) -> Result<Self, UnknownTag> {
        Ok(Self {
            specular: SpecularModel::try_from(material.specular_model)?,
            fresnel: Fresnel::try_from(material.fresnel)?,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_tag_round_trips_through_its_value_and_name() {
        fn check<T>(all: &[T], name: fn(T) -> &'static str, from_name: fn(&str) -> Option<T>)
        where
            T: Copy + PartialEq + std::fmt::Debug + TryFrom<u32, Error = UnknownTag> + Into<u32>,
        {
            for (i, &t) in all.iter().enumerate() {
                assert_eq!(t.into(), i as u32, "{t:?}: stored values are 0, 1, 2, … in order");
                assert_eq!(T::try_from(t.into()), Ok(t));
                assert_eq!(from_name(name(t)), Some(t));
            }
            let past = all.len() as u32;
            assert!(T::try_from(past).is_err(), "{past} is no variant");
        }
        check(&LightKind::ALL, LightKind::name, LightKind::from_name);
        check(&SpotFalloff::ALL, SpotFalloff::name, SpotFalloff::from_name);
        check(&AttenuationModel::ALL, AttenuationModel::name, AttenuationModel::from_name);
        check(&EpsilonMode::ALL, EpsilonMode::name, EpsilonMode::from_name);
        check(&SpecularModel::ALL, SpecularModel::name, SpecularModel::from_name);
        check(&Fresnel::ALL, Fresnel::name, Fresnel::from_name);
        check(&Wrap::ALL, Wrap::name, Wrap::from_name);
        check(&Filter::ALL, Filter::name, Filter::from_name);
        check(&RayKind::ALL, RayKind::name, RayKind::from_name);
    }

    #[test]
    fn serde_spells_each_tag_by_its_name() {
        #[derive(Serialize, Deserialize)]
        struct Holder {
            kind: SpecularModel,
        }
        for t in SpecularModel::ALL {
            let text = format!("{{\"kind\":\"{}\"}}", t.name());
            let back: Holder = serde_json::from_str(&text).expect("the name deserialises");
            assert_eq!(back.kind, t);
            assert_eq!(serde_json::to_string(&Holder { kind: t }).expect("serialises"), text);
        }
        // Only a name: a number says what the field takes, and a table is no variant (serde's
        // derive took `{"kind": {"phong": []}}` and said "wanted string or table" of a number).
        let error = |text: &str| serde_json::from_str::<Holder>(text).err().map(|e| e.to_string()).unwrap_or_default();
        assert!(
            error("{\"kind\":1}").contains("expected a specular model named by a string, one of: blinn, phong"),
            "{}",
            error("{\"kind\":1}")
        );
        assert!(error("{\"kind\":{\"phong\":[]}}").contains("invalid type: map"));
        assert!(error("{\"kind\":\"glossy\"}").contains("unknown variant `glossy`"));
    }
}
