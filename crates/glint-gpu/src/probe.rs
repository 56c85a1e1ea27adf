//! The GPU pixel probe's record, turned into the CPU's `Breakdown` so both can be shown and
//! compared term by term.

use glint_core::cpu::shade::{Breakdown, LightTerm};
use glint_core::cpu::v3 as v;
use glint_core::glam::DVec3;
use glint_core::layout::{NO_HIT, PROBE_HIT, PROBE_TIR, ProbeRecord};

/// The breakdown a probe record describes. The mirror subtree's radiance already includes its
/// weight; under total internal reflection it carried k_r + k_t and is split back per channel.
pub fn breakdown(r: &ProbeRecord) -> Breakdown {
    if r.flags & PROBE_HIT == 0 {
        return Breakdown { object_id: NO_HIT, total: v(r.total), ..Breakdown::default() };
    }
    let (kr, kt) = (v(r.kr), v(r.kt));
    let mirror = v(r.mirror_sum);
    let (reflected, transmitted) = if r.flags & PROBE_TIR != 0 {
        let k = kr + kt;
        let i = DVec3::select(k.cmpgt(DVec3::ZERO), mirror / k, DVec3::ZERO);
        (kr * i, kt * i)
    } else {
        (mirror, v(r.refraction_sum))
    };
    Breakdown {
        object_id: r.object_id,
        material: r.material,
        t: f64::from(r.t),
        point: v(r.point),
        normal: v(r.normal),
        emission: v(r.emission),
        ambient: v(r.ambient),
        ka: v(r.ka),
        kd: v(r.kd),
        lights: r.lights[..r.light_count as usize]
            .iter()
            .map(|l| LightTerm {
                f_att: f64::from(l.f_att),
                spot: f64::from(l.spot),
                visibility: v(l.visibility),
                ambient: v(l.ambient),
                diffuse: v(l.diffuse),
                specular: v(l.specular),
                contribution: v(l.contribution),
            })
            .collect(),
        reflected,
        transmitted,
        total: v(r.total),
    }
}
