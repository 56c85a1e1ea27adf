//! The GPU probe's ray tree (recorded by the probe variant of the tracer's own shader) against
//! the CPU's, node by node: the same rays in the same order, with values within the probe's
//! f32-against-f64 tolerance; a perturbed node is found; a tree past the buffer's capacity says
//! so.

use glint_core::cpu::ray_tree::{Cut, RayTree};
use glint_core::probe_terms::first_tree_difference as first_difference;
use glint_core::probe_tree;
use glint_types::RayKind;

use glint_test_support::scene::{SceneText, slab};

use super::support::{builtin, gpu_or_skip};

fn summary(t: &RayTree) -> String {
    let kinds: Vec<&str> = t.nodes.iter().map(|n| n.kind.name()).collect();
    format!("{} nodes {kinds:?}", t.nodes.len())
}

#[test]
fn gpu_tree_matches_cpu_tree_node_by_node_on_whitted() {
    let tracer = gpu_or_skip!();
    let flat = builtin("whitted", 160, 120, 1, 5);
    // The mirror, the glass sphere, the floor, the floor in the spheres' shadow; and (a sphere
    // never reflects totally inside: every internal angle is the entry's refracted one) the
    // camera inside a glass slab looking up 60° off its normal, past the critical angle.
    let slab = slab(1.5, 60.0).flat();
    let (sw, sh) = (slab.header.width, slab.header.height);
    let whitted = [(55, 45), (100, 70), (112, 62), (20, 110), (95, 100), (60, 95)].map(|p| (&flat, p));
    let (mut tir, mut shadowed, mut refracted, mut bailouts) = (0, 0, 0, 0);
    for (flat, (x, y)) in whitted.into_iter().chain([(&slab, (sw / 2, sh / 2))]) {
        let cpu = probe_tree(flat, x, y, 0).expect("valid tags");
        let gpu = tracer.probe(flat, x, y).expect("GPU probe");
        assert_eq!(gpu.status, 0, "({x}, {y}): status");
        assert!(!gpu.tree.overflow && !gpu.tree.lights_truncated, "({x}, {y})");
        assert_eq!(
            cpu.nodes.len(),
            gpu.tree.nodes.len(),
            "({x}, {y}): CPU {} GPU {}",
            summary(&cpu),
            summary(&gpu.tree)
        );
        if let Some(d) = first_difference(&cpu, &gpu.tree, flat.frame_origin()) {
            panic!(
                "({x}, {y}): node {} differs in {}:\nCPU {:#?}\nGPU {:#?}",
                d.node, d.what, cpu.nodes[d.node], gpu.tree.nodes[d.node]
            );
        }
        tir += cpu.nodes.iter().filter(|n| n.tir).count();
        shadowed += cpu.nodes.iter().filter(|n| n.kind == RayKind::Shadow && n.factor.max_element() < 1.0).count();
        refracted += cpu.count(RayKind::Refraction);
        bailouts += cpu.nodes.iter().filter(|n| n.cut == Some(Cut::Bailout)).count();
    }
    // The pixels must exercise what the tree records, not only camera rays.
    assert!(
        tir > 0 && shadowed > 0 && refracted > 2 && bailouts > 0,
        "tir {tir} shadowed {shadowed} refracted {refracted} bailouts {bailouts}"
    );
}

#[test]
fn a_perturbed_node_is_the_first_difference() {
    let tracer = gpu_or_skip!();
    let flat = builtin("whitted", 160, 120, 1, 5);
    let cpu = probe_tree(&flat, 100, 70, 0).expect("valid tags");
    let gpu = tracer.probe(&flat, 100, 70).expect("GPU probe").tree;
    assert_eq!(first_difference(&cpu, &gpu, flat.frame_origin()), None);
    let deep =
        cpu.nodes.iter().position(|n| n.depth == 2 && n.kind == RayKind::Refraction).expect("a depth-2 refraction");
    let mut bent = gpu.clone();
    bent.nodes[deep].weight *= 1.001;
    let d = first_difference(&cpu, &bent, flat.frame_origin()).expect("a difference");
    assert_eq!((d.node, d.what.as_str()), (deep, "weight"));
    let mut shaded = gpu.clone();
    let hit = cpu.nodes.iter().position(|n| n.depth == 1 && n.terms.is_some()).expect("a depth-1 hit");
    shaded.nodes[hit].terms.as_mut().expect("terms").lights[0].diffuse.y += 0.01;
    let d = first_difference(&cpu, &shaded, flat.frame_origin()).expect("a difference");
    assert_eq!((d.node, d.what.as_str()), (hit, "light 0: diffuse"));
    let mut short = gpu;
    short.nodes.pop();
    assert_eq!(first_difference(&cpu, &short, flat.frame_origin()).map(|d| d.node), Some(cpu.nodes.len() - 1));
}

/// A glass sphere over a mirror floor under 16 lights, at depth 14 without bailout: every
/// hit has up to 16 shadow rays and the glass and the floor bounce rays between them.
fn crowded_scene() -> glint_core::FlatScene {
    let mut s = SceneText::new(
        24,
        16,
        "max_depth = 14\nbailout = 0.0",
        [0.0, 1.0, -4.0],
        [0.0, 0.5, 0.0],
        [0.0, 1.0, 0.0],
        50.0,
    )
    .world([0.05; 3], [0.1, 0.1, 0.2])
    .material("glass", "ka = 0.0\nkd = 0.1\nks = 0.5\nshininess = 40.0\nkr = 0.3\nkt = 0.7\nior = 1.5")
    .material("floor", "ka = 0.1\nkd = 0.5\nks = 0.0\nkr = 0.9")
    .sphere([0.0, 0.6, 0.0], 0.6, "glass")
    .plane([0.0; 3], [0.0, 1.0, 0.0], "floor");
    for j in 0..16 {
        let a = f64::from(j) / 16.0 * std::f64::consts::TAU;
        let position =
            format!("position = [{:.3}, 4.0, {:.3}]\ndiffuse = 0.06\nspecular = 0.06", 3.0 * a.cos(), 3.0 * a.sin());
        s = s.light("point", &position);
    }
    s.flat()
}

#[test]
fn a_tree_past_the_buffer_overflows_with_a_flag_and_keeps_its_first_nodes() {
    let tracer = gpu_or_skip!();
    let flat = crowded_scene();
    let cpu = probe_tree(&flat, 12, 8, 0).expect("valid tags");
    let capacity = glint_types::layout::MAX_PROBE_NODES as usize;
    assert!(cpu.nodes.len() > capacity, "the CPU tree has only {} nodes", cpu.nodes.len());
    let gpu = tracer.probe(&flat, 12, 8).expect("GPU probe");
    assert!(gpu.tree.overflow, "no overflow flag with {} nodes", cpu.nodes.len());
    assert!(!gpu.tree.lights_truncated);
    assert_eq!(gpu.tree.nodes.len(), capacity);
    assert_eq!(first_difference(&cpu, &gpu.tree, flat.frame_origin()), None, "the kept nodes are the CPU's first");
}
