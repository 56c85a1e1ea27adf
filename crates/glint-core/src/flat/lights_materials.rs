//! Materials and lights in the flat layout.

// What the parent module declares for its children.
use super::{
    Attenuation, DVec3, GpuLight, GpuMaterial, LIGHT_CASTS_SHADOWS, LightDesc, LightKind, MaterialDesc, NO_CONE_CUTOFF,
    NO_CONE_VERSIN, NO_TEXTURE, Rgb, SpotFalloff, TextureTable, rgb4, vec4,
};

/// A material in the flat layout, its textures added to `table`. A checker is a texture of
/// k_d and its second colour over a white k_d, so that k_d · texel is exactly either colour.
pub(super) fn flat_material(m: &MaterialDesc, table: &mut TextureTable) -> GpuMaterial {
    let (kd, diffuse_texture) = match (&m.checker, &m.texture) {
        (Some(c), _) => (rgb4(Rgb::one()), table.add_checker(m.kd, c)),
        (None, Some(t)) => (rgb4(m.kd), table.add(t)),
        (None, None) => (rgb4(m.kd), NO_TEXTURE),
    };
    GpuMaterial {
        ka: rgb4(m.ka),
        kd,
        ks: rgb4(m.ks),
        kr: rgb4(m.kr),
        kt: rgb4(m.kt),
        emission: rgb4(m.emission),
        shininess: m.shininess as f32,
        ior: m.ior as f32,
        specular_model: m.specular_model as u32,
        diffuse_texture,
        emission_texture: m.emission_texture.as_ref().map_or(NO_TEXTURE, |t| table.add(t)),
        roughness: m.roughness as f32,
        fresnel: m.fresnel as u32,
        pad: 0,
    }
}

/// cos(angle) of a cone half-angle in [0, 90] degrees, as sin(90° − angle): exact at both ends
/// (1 and 0), where cos(90°.to_radians()) would be 6e-17 and leave a point exactly at 90°
/// outside a closed cone.
/// 1 − cos of a cone's half-angle, as 2·sin²(θ/2): no cancellation for small cones, and exact
/// at 0° (0), 90° (1, where sin² 45° rounds to 1/2) and 180° (2).
fn cone_versin(degrees: f64) -> f64 {
    let s = (degrees / 2.0).to_radians().sin();
    2.0 * s * s
}

/// A light in the flat layout: position relative to the storage origin `origin` (a point or
/// spot light's; a directional light's is unused and stays), unit direction, the attenuation
/// model with its parameters, the spot cone as versines (1 − cos).
pub(super) fn flat_light(l: &LightDesc, origin: DVec3) -> GpuLight {
    let position = match l.kind {
        LightKind::Point | LightKind::Spot => l.position.map_or(DVec3::ZERO, DVec3::from) - origin,
        LightKind::Directional => l.position.map_or(DVec3::ZERO, DVec3::from),
    };
    let direction = l.direction.map_or(DVec3::ZERO, |d| DVec3::from(d).normalize());
    let (attenuation, range) = match l.attenuation {
        Attenuation::Polynomial { c, l, q } => ([c as f32, l as f32, q as f32, 0.0], 0.0),
        Attenuation::InverseSquare { range } => ([1.0, 0.0, 0.0, 0.0], range.map_or(0.0, |r| r as f32)),
    };
    // (s, versine of the cutoff or outer cone, versine of the inner cone)
    let (spot_exponent, versin_cutoff, versin_inner) = match (l.kind, l.falloff) {
        (LightKind::Spot, SpotFalloff::Power) if l.cutoff < NO_CONE_CUTOFF => {
            (l.exponent as f32, cone_versin(l.cutoff), 0.0)
        }
        (LightKind::Spot, SpotFalloff::Power) => (l.exponent as f32, f64::from(NO_CONE_VERSIN), 0.0),
        (LightKind::Spot, SpotFalloff::Smooth) => {
            let (inner, outer) = l.cone_angles();
            (0.0, cone_versin(outer), cone_versin(inner))
        }
        (LightKind::Point | LightKind::Directional, _) => (0.0, f64::from(NO_CONE_VERSIN), 0.0),
    };
    let spot_falloff = match l.kind {
        LightKind::Spot => l.falloff,
        LightKind::Point | LightKind::Directional => SpotFalloff::Power,
    };
    GpuLight {
        position: vec4(position, 1.0),
        direction: vec4(direction, 0.0),
        diffuse: rgb4(l.diffuse),
        specular: rgb4(l.specular),
        ambient: rgb4(l.ambient),
        attenuation,
        kind: l.kind as u32,
        flags: if l.casts_shadows { LIGHT_CASTS_SHADOWS } else { 0 },
        spot_exponent,
        spot_versin_cutoff: versin_cutoff as f32,
        attenuation_model: l.attenuation.model() as u32,
        spot_falloff: spot_falloff as u32,
        range,
        spot_versin_inner: versin_inner as f32,
    }
}
