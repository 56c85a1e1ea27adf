//! Switching a light between point, directional and spot: what the new type needs is made up
//! or given back, what it lacks is set aside, so that every light stays valid and a round trip
//! of types loses nothing. Domain logic of the document, used by the Lights panel.

use glint_core::glam::DVec3;
use glint_scene::{Attenuation, LightDesc, LightKind, NO_CONE_CUTOFF, SpotFalloff};

/// The cone a light gets when it becomes a spot light or leaves "no cone".
pub const NEW_CONE_CUTOFF: f64 = 30.0;

/// How far from the scene centre a light that had no position (a directional one) is put when
/// no camera distance gives a scale.
const FALLBACK_DISTANCE: f64 = 5.0;

/// The fields a light's current type does not have, set aside when the user switched it away
/// from a type that had them and given back when it switches back (one per light of the
/// document): a light of every type stays valid, and a round trip of types loses nothing.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct SetAside {
    position: Option<[f64; 3]>,
    direction: Option<[f64; 3]>,
    /// A point or spot light's f_att (a directional light has none).
    attenuation: Option<Attenuation>,
    cone: Option<Cone>,
}

/// A spot light's cone, all of its fields.
#[derive(Clone, Copy, Debug, PartialEq)]
struct Cone {
    falloff: SpotFalloff,
    exponent: f64,
    cutoff: f64,
    inner_cone: Option<f64>,
    outer_cone: Option<f64>,
}

impl Cone {
    /// The cone every point and directional light has: none (validation refuses any other).
    const NONE: Self =
        Self { falloff: SpotFalloff::Power, exponent: 0.0, cutoff: NO_CONE_CUTOFF, inner_cone: None, outer_cone: None };

    fn of(l: &LightDesc) -> Self {
        Self {
            falloff: l.falloff,
            exponent: l.exponent,
            cutoff: l.cutoff,
            inner_cone: l.inner_cone,
            outer_cone: l.outer_cone,
        }
    }

    fn apply(self, l: &mut LightDesc) {
        (l.falloff, l.exponent, l.cutoff, l.inner_cone, l.outer_cone) =
            (self.falloff, self.exponent, self.cutoff, self.inner_cone, self.outer_cone);
    }
}

/// Makes `light` a light of `kind` that validates. What the new type lacks goes to `aside`;
/// what it needs comes back from `aside`, or else is made up: a direction from the light's
/// position toward `centre` (the camera's look-at point), a position `distance` back along the
/// direction, a 30° cone.
pub fn switch_kind(light: &mut LightDesc, kind: LightKind, aside: &mut SetAside, centre: DVec3, distance: f64) {
    if kind == light.kind {
        return;
    }
    // First what the new type needs, while the old position is still there to aim from.
    if kind != LightKind::Point && light.direction.is_none() {
        let from = light.position.or(aside.position).map_or(centre + DVec3::Y, DVec3::from);
        let toward = aside.direction.take().map(DVec3::from).unwrap_or((centre - from).normalize_or(DVec3::NEG_Y));
        light.direction = Some(toward.to_array());
    }
    if kind != LightKind::Directional && light.position.is_none() {
        let back = light.direction.map_or(DVec3::NEG_Y, DVec3::from).normalize_or(DVec3::NEG_Y);
        let d = if distance.is_finite() && distance > 0.0 { distance } else { FALLBACK_DISTANCE };
        light.position = Some(aside.position.take().unwrap_or((centre - back * d).to_array()));
    }
    // Then what it lacks, set aside.
    if light.kind == LightKind::Spot {
        aside.cone = Some(Cone::of(light));
        Cone::NONE.apply(light);
    }
    if kind == LightKind::Directional {
        aside.position = light.position.take().or(aside.position);
        if !light.attenuation.is_none() {
            aside.attenuation = Some(light.attenuation);
        }
        light.attenuation = Attenuation::NONE;
    }
    if kind == LightKind::Point {
        aside.direction = light.direction.take().or(aside.direction);
    }
    // And what it had before, given back.
    if light.kind == LightKind::Directional
        && let Some(a) = aside.attenuation.take()
    {
        light.attenuation = a;
    }
    if kind == LightKind::Spot {
        match aside.cone.take() {
            Some(c) => c.apply(light),
            None => light.cutoff = NEW_CONE_CUTOFF,
        }
    }
    light.kind = kind;
}

#[cfg(test)]
mod tests {
    use glint_scene::{SceneDesc, validate};

    use super::*;
    use crate::document::Document;

    fn valid(light: &LightDesc) -> bool {
        let mut desc: SceneDesc = Document::empty().desc;
        desc.lights = vec![light.clone()];
        let errors = validate(&desc).errors;
        errors.iter().all(|e| !e.field.starts_with("lights"))
    }

    #[test]
    fn every_sequence_of_types_gives_a_valid_light_and_a_round_trip_restores_it() {
        let mut spot = LightDesc::new(LightKind::Spot, [1.0, 4.0, -2.0], [0.0, -1.0, 0.2]);
        (spot.falloff, spot.cutoff, spot.inner_cone, spot.outer_cone) =
            (SpotFalloff::Smooth, NO_CONE_CUTOFF, Some(10.0), Some(25.0));
        spot.attenuation = Attenuation::inverse_square(Some(8.0));
        let point = LightDesc {
            attenuation: Attenuation::Polynomial { c: 1.0, l: 0.1, q: 0.01 },
            ..LightDesc::new(LightKind::Point, [-4.0, 7.0, -5.0], [0.0; 3])
        };
        let directional = LightDesc::new(LightKind::Directional, [0.0; 3], [1.0, -1.0, 0.0]);
        for start in [point, spot, directional] {
            assert!(valid(&start), "{start:?}");
            // Every pair of successive types, back to the first.
            for path in [
                [LightKind::Point, LightKind::Directional, LightKind::Spot],
                [LightKind::Spot, LightKind::Directional, LightKind::Point],
            ] {
                let (mut light, mut aside) = (start.clone(), SetAside::default());
                for kind in path.into_iter().chain(path).chain([start.kind]) {
                    switch_kind(&mut light, kind, &mut aside, DVec3::new(0.0, 1.0, 0.0), 5.0);
                    assert_eq!(light.kind, kind);
                    assert!(valid(&light), "{:?} after {path:?}: {light:?}", start.kind);
                }
                assert_eq!(light, start, "a round trip of types restores the light");
            }
        }
    }

    #[test]
    fn made_up_fields_aim_at_the_centre() {
        let centre = DVec3::new(0.0, 1.0, 0.0);
        let mut light = LightDesc::new(LightKind::Point, [-4.0, 7.0, -5.0], [0.0; 3]);
        let mut aside = SetAside::default();
        switch_kind(&mut light, LightKind::Directional, &mut aside, centre, 5.0);
        let d = DVec3::from(light.direction.expect("a direction"));
        let expected = (centre - DVec3::new(-4.0, 7.0, -5.0)).normalize();
        assert!((d - expected).length() < 1e-12, "{d}");
        // A directional light that never had a position gets one upstream of the centre.
        let mut sun = LightDesc::new(LightKind::Directional, [0.0; 3], [0.0, -2.0, 0.0]);
        switch_kind(&mut sun, LightKind::Spot, &mut SetAside::default(), centre, 5.0);
        assert_eq!(sun.position, Some([0.0, 6.0, 0.0]));
        assert_eq!((sun.direction, sun.cutoff), (Some([0.0, -2.0, 0.0]), NEW_CONE_CUTOFF));
    }
}
