//! Lights: kinds, cones, attenuation.

// What the parent module declares for its children.
use super::{
    Attenuation, LightDesc, LightKind, MAX_ATTENUATION_DIP, MIN_ATTENUATION_DENOMINATOR, NO_CONE_CUTOFF, Report,
    SpotFalloff, as_f32, num, ranges, short,
};

pub(super) fn validate_light(path: &str, l: &LightDesc, r: &mut Report) {
    let kind = l.kind.name();
    match (l.kind, l.position) {
        (LightKind::Directional, Some(_)) => r.error(
            format!("{path}.position"),
            "a directional light has no position (remove it or use type = \"point\")",
        ),
        (LightKind::Point | LightKind::Spot, None) => {
            r.error(format!("{path}.position"), format!("a {kind} light needs a position [x, y, z]"))
        }
        (_, Some(p)) => {
            r.point(&format!("{path}.position"), p);
        }
        (_, None) => {}
    }
    match (l.kind, l.direction) {
        (LightKind::Point, Some(_)) => {
            r.error(format!("{path}.direction"), "a point light has no direction (use type = \"spot\")")
        }
        (LightKind::Directional | LightKind::Spot, None) => r.error(
            format!("{path}.direction"),
            format!("a {kind} light needs a direction [x, y, z] of non-zero length"),
        ),
        (_, Some(d)) => {
            r.direction(&format!("{path}.direction"), d);
        }
        (_, None) => {}
    }
    r.colour(&format!("{path}.diffuse"), l.diffuse);
    r.colour(&format!("{path}.specular"), l.specular);
    r.colour(&format!("{path}.ambient"), l.ambient);
    if l.kind == LightKind::Directional {
        if !l.attenuation.is_none() {
            r.error(format!("{path}.attenuation"), "a directional light is not attenuated (f_att = 1); remove it");
        }
    } else {
        validate_attenuation(&format!("{path}.attenuation"), l.attenuation, r);
    }
    match (l.kind, l.falloff) {
        (LightKind::Spot, SpotFalloff::Power) => {
            validate_power_cone(path, l, r);
            for (field, v) in [("inner_cone", l.inner_cone), ("outer_cone", l.outer_cone)] {
                if v.is_some() {
                    r.error(
                        format!("{path}.{field}"),
                        "belongs to falloff = \"smooth\"; this spot has the power falloff (exponent, cutoff)",
                    );
                }
            }
        }
        (LightKind::Spot, SpotFalloff::Smooth) => {
            validate_smooth_cone(path, l, r);
            if l.exponent != 0.0 {
                r.error(
                    format!("{path}.exponent"),
                    "belongs to falloff = \"power\"; a smooth spot has inner_cone and outer_cone",
                );
            }
            if l.cutoff != NO_CONE_CUTOFF {
                r.error(
                    format!("{path}.cutoff"),
                    "belongs to falloff = \"power\"; a smooth spot's cone ends at outer_cone",
                );
            }
        }
        (LightKind::Point | LightKind::Directional, _) => {
            let only_spots = [
                ("exponent", l.exponent != 0.0, "an exponent"),
                ("cutoff", l.cutoff != NO_CONE_CUTOFF, "a cutoff"),
                ("falloff", !l.falloff.is_power(), "a falloff"),
                ("inner_cone", l.inner_cone.is_some(), "an inner_cone"),
                ("outer_cone", l.outer_cone.is_some(), "an outer_cone"),
            ];
            for (field, present, what) in only_spots {
                if present {
                    r.error(
                        format!("{path}.{field}"),
                        format!("only spot lights have {what} (this is a {kind} light)"),
                    );
                }
            }
        }
    }
}

/// The power falloff: exponent s and the hard cutoff.
fn validate_power_cone(path: &str, l: &LightDesc, r: &mut Report) {
    r.finite_in(&format!("{path}.exponent"), l.exponent, ranges::SPOT_EXPONENT);
    let c = l.cutoff;
    if !(ranges::CUTOFF.contains(c) || c == NO_CONE_CUTOFF) {
        let (lo, hi) = (ranges::CUTOFF.min, ranges::CUTOFF.max);
        r.error(
            format!("{path}.cutoff"),
            format!("{} is outside the allowed range [{lo}, {hi}] or {NO_CONE_CUTOFF} (no cone)", num(c)),
        );
    }
    // OpenGL's rule, which Glint follows: without a cone (cutoff 180) the spot is a point light
    // and its exponent does nothing. The slides' I·(L_N·L)^s has no cone, so a lecturer's
    // exponent alone would silently light the whole sphere around it.
    if c == NO_CONE_CUTOFF && l.exponent > 0.0 && l.exponent.is_finite() {
        r.warn(
            format!("{path}.exponent"),
            format!(
                "{} does nothing without a cone: a spot with cutoff = {NO_CONE_CUTOFF} (the default) lights every \
                 direction as a point light (OpenGL's rule); set cutoff to at most 90 for (L_N·L)^s to fall off",
                num(l.exponent)
            ),
        );
    }
}

/// The smooth falloff: 0 ≤ inner ≤ outer ≤ 90 degrees.
fn validate_smooth_cone(path: &str, l: &LightDesc, r: &mut Report) {
    let (inner, outer) = l.cone_angles();
    let inner_ok = r.finite_in(&format!("{path}.inner_cone"), inner, ranges::CONE);
    let outer_ok = r.finite_in(&format!("{path}.outer_cone"), outer, ranges::CONE);
    if inner_ok && outer_ok && inner > outer {
        r.error(
            format!("{path}.inner_cone"),
            format!(
                "{} is larger than outer_cone = {}; allowed: 0 ≤ inner_cone ≤ outer_cone ≤ 90",
                num(inner),
                num(outer)
            ),
        );
    }
}

fn validate_attenuation(path: &str, a: Attenuation, r: &mut Report) {
    match a {
        Attenuation::Polynomial { c, l, q } => validate_polynomial(path, c, l, q, r),
        Attenuation::InverseSquare { range: Some(range) } => {
            if !ranges::LIGHT_RANGE.contains(range) {
                let why = ranges::LIGHT_RANGE.why_outside(range);
                r.error(
                    format!("{path}.range"),
                    format!("{} is outside the allowed range {}{why}", num(range), ranges::LIGHT_RANGE.bounds()),
                );
            }
        }
        Attenuation::InverseSquare { range: None } => {}
    }
}

/// c + l·d + q·d² must stay positive for every distance d ≥ 0.
pub(super) fn validate_polynomial(path: &str, c: f64, l: f64, q: f64, r: &mut Report) {
    // Check all three (no short circuit) so that every bad coefficient is reported.
    let checks: Vec<bool> = [("c", c), ("l", l), ("q", q)]
        .into_iter()
        .map(|(n, v)| r.finite_in(&format!("{path}.{n}"), v, ranges::ATTENUATION))
        .collect();
    let finite = checks.iter().all(|&ok| ok);
    if !finite {
        return;
    }
    // Judge the coefficients the tracers will use: rounded to f32.
    let (given_c, given_l, given_q) = (c, l, q);
    let (c, l, q) = (as_f32(c), as_f32(l), as_f32(q));
    // The bound as the tracers hold it too: c = 1e-6, the documented least, is 9.99999997e-7 in f32.
    let (min, f32_min) = (MIN_ATTENUATION_DENOMINATOR, as_f32(MIN_ATTENUATION_DENOMINATOR));
    let problem = if c < f32_min {
        // A light's attenuation has the inverse-square model; the world's global one does not.
        let light = path.ends_with(".attenuation");
        let hint = if c == 0.0 && l == 0.0 && q > 0.0 && light {
            "; for a pure 1/d² falloff write attenuation = { model = \"inverse_square\" }"
        } else if c == 0.0 && l == 0.0 && q == 0.0 && light {
            // `{ c = 0 }` alone: a newcomer after the textbook falloff, told only the bound.
            "; for no falloff leave attenuation out (c = 1), for the textbook 1/d² write attenuation = { model = \
             \"inverse_square\" }"
        } else {
            ""
        };
        Some(format!("c + l·d + q·d² is c at d = 0, so c must be ≥ {min:e}{hint}"))
    } else if q < 0.0 || (q == 0.0 && l < 0.0) {
        Some("c + l·d + q·d² falls below 0 at a large distance: it needs q ≥ 0, and l ≥ 0 when q = 0".to_string())
    } else if l < 0.0 {
        // The minimum, at d = −l/(2q) (q > 0 here).
        let (least, d) = (c - l * l / (4.0 * q), -l / (2.0 * q));
        if least < f32_min {
            Some(format!(
                "c + l·d + q·d² falls to {} at d = {}; it must stay ≥ {min:e} for all d ≥ 0",
                short(least),
                short(d)
            ))
        } else if least < c / MAX_ATTENUATION_DIP {
            Some(format!(
                "c + l·d + q·d² falls to {} at d = {}, {} times below c: f32 (the GPU tracer) cannot \
                 resolve a dip deeper than c / {MAX_ATTENUATION_DIP:e} (raise c or make l less negative)",
                short(least),
                short(d),
                short(c / least)
            ))
        } else {
            None
        }
    } else {
        None
    };
    if let Some(p) = problem {
        // A coefficient f32 rounds to 0 is judged as 0: said, or `q = 5e-324` reads as
        // contradicting "q ≥ 0" (a tester).
        let given = |name: &str, v: f64, stored: f64| {
            if stored == 0.0 && v != 0.0 {
                format!("{name} = {}, 0 in f32", num(v))
            } else {
                format!("{name} = {}", num(v))
            }
        };
        r.error(
            path,
            format!("{p} (got {}, {}, {})", given("c", given_c, c), given("l", given_l, l), given("q", given_q, q)),
        );
    }
}
