//! The GPU pixel probe's record and ray tree, turned into the CPU's `Breakdown` and `RayTree`
//! so both can be shown and compared term by term and node by node.

use glint_core::cpu::ray_tree::{Cut, RayNode, RayTree};
use glint_core::cpu::shade::{Breakdown, LightAngles, LightTerm};
use glint_core::cpu::v3 as v;
use glint_core::glam::DVec3;
use glint_types::layout::{
    NO_HIT, NO_PARENT, NODE_CUT_BAILOUT, NODE_CUT_DEPTH, NODE_HIT, NODE_TIR, PROBE_HIT, PROBE_TIR, ProbeLight,
    ProbeNode, ProbeRecord, ProbeTree, TREE_LIGHTS_TRUNCATED, TREE_OVERFLOW, UnknownTag,
};
use glint_types::{RayKind, SpecularModel};

/// The breakdown a probe record describes. The mirror subtree's radiance already includes its
/// weight; under total internal reflection it carried k_r + k_t and is split back per channel.
/// A lobe of a model no material has is an error, never a guess.
pub fn breakdown(r: &ProbeRecord) -> Result<Breakdown, UnknownTag> {
    if r.flags & PROBE_HIT == 0 {
        return Ok(Breakdown { object_id: NO_HIT, total: v(r.total), ..Breakdown::default() });
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
    Ok(Breakdown {
        object_id: r.object_id,
        material: r.material,
        t: f64::from(r.t),
        point: v(r.point),
        normal: v(r.normal),
        emission: v(r.emission),
        ambient: v(r.ambient),
        ka: v(r.ka),
        kd: v(r.kd),
        lights: light_terms(&r.lights, r.light_count)?,
        reflected,
        transmitted,
        total: v(r.total),
    })
}

/// The first `count` of `lights` (no more than it holds) as the CPU's terms.
fn light_terms(lights: &[ProbeLight], count: u32) -> Result<Vec<LightTerm>, UnknownTag> {
    lights[..(count as usize).min(lights.len())].iter().map(light_term).collect()
}

fn light_term(l: &ProbeLight) -> Result<LightTerm, UnknownTag> {
    let angles = LightAngles {
        n_dot_l: f64::from(l.n_dot_l),
        lobe_cosine: f64::from(l.lobe_cosine),
        lobe: f64::from(l.lobe),
        lobe_model: SpecularModel::try_from(l.lobe_model)?,
    };
    Ok(LightTerm {
        f_att: f64::from(l.f_att),
        spot: f64::from(l.spot),
        visibility: v(l.visibility),
        ambient: v(l.ambient),
        diffuse: v(l.diffuse),
        specular: v(l.specular),
        contribution: v(l.contribution),
        shadow_ray: l.shadow_ray != 0,
        angles,
    })
}

/// The ray tree the probe variant wrote into `bytes` (a `ProbeTree` buffer): its first
/// `min(node_count, MAX_PROBE_NODES)` nodes, with the overflow and light-truncation flags. A
/// node of a kind no ray has is an error, never a guess.
pub fn ray_tree(bytes: &[u8]) -> Result<RayTree, UnknownTag> {
    let header = std::mem::offset_of!(ProbeTree, nodes);
    let node_count: u32 = bytemuck::pod_read_unaligned(&bytes[0..4]);
    let flags: u32 = bytemuck::pod_read_unaligned(&bytes[4..8]);
    let size = size_of::<ProbeNode>();
    let kept = (bytes.len() - header) / size;
    let nodes = (0..(node_count as usize).min(kept))
        .map(|i| ray_node(&bytemuck::pod_read_unaligned(&bytes[header + i * size..header + (i + 1) * size])))
        .collect::<Result<_, _>>()?;
    Ok(RayTree { nodes, overflow: flags & TREE_OVERFLOW != 0, lights_truncated: flags & TREE_LIGHTS_TRUNCATED != 0 })
}

fn ray_node(n: &ProbeNode) -> Result<RayNode, UnknownTag> {
    let kind = RayKind::try_from(n.kind)?;
    let hit = n.flags & NODE_HIT != 0;
    let shadow = match kind {
        RayKind::Shadow => true,
        RayKind::Camera | RayKind::Reflection | RayKind::Refraction => false,
    };
    let cut = if n.flags & NODE_CUT_DEPTH != 0 {
        Some(Cut::MaxDepth)
    } else if n.flags & NODE_CUT_BAILOUT != 0 {
        Some(Cut::Bailout)
    } else {
        None
    };
    let terms = hit.then(|| light_terms(&n.lights, n.light_count)).transpose()?.map(|lights| Breakdown {
        object_id: n.object_id,
        material: n.material,
        t: f64::from(n.t),
        point: v(n.point),
        normal: v(n.normal),
        emission: v(n.emission),
        ambient: v(n.ambient),
        ka: v(n.ka),
        kd: v(n.kd),
        lights,
        ..Breakdown::default()
    });
    Ok(RayNode {
        kind,
        parent: (n.parent != NO_PARENT).then_some(n.parent as usize),
        depth: n.depth,
        origin: v(n.origin),
        dir: v(n.dir),
        t: (hit || shadow).then_some(f64::from(n.t)),
        factor: v(n.factor),
        weight: v(n.weight),
        attenuation: f64::from(n.attenuation),
        tir: n.flags & NODE_TIR != 0,
        cut,
        light: shadow.then_some(n.light),
        terms,
        radiance: None,
    })
}
