//! The probed pixel's ray tree in the Probe panel: one collapsible node per ray (camera,
//! reflection, refraction, shadow, and the children the bailout or the depth limit cut), its
//! own factor k, its path weight and at a hit the local terms, CPU (f64) above GPU (f32), the
//! first node where the two trees differ highlighted and opened.

use egui::{Color32, RichText, Ui};
use glint_core::cpu::ray_tree::{RayNode, RayTree};
use glint_core::glam::DVec3;
use glint_core::probe_terms::{Term, first_difference, local_terms};
use glint_types::RayKind;
use glint_types::layout::MAX_PROBE_NODES;

use super::term_table::{BROUGHT_BACK, HIGHLIGHT, term_grid};
use crate::document::Document;
use crate::probe::{GpuProbe, ProbeState};

/// `v` in four decimals, one number when its channels are equal.
fn short(v: DVec3) -> String {
    if v.x == v.y && v.y == v.z { format!("{:.4}", v.x) } else { format!("({:.3}, {:.3}, {:.3})", v.x, v.y, v.z) }
}

/// What a ray ended on, in words.
fn target(n: &RayNode, doc: &Document) -> String {
    if let Some(cut) = n.cut {
        return cut.name().to_string();
    }
    match (n.kind, &n.terms) {
        (RayKind::Shadow, _) => format!("light {}, V = {}", n.light.unwrap_or(0), short(n.factor)),
        (_, Some(t)) => doc.object_label(t.object_id as usize),
        (_, None) => "background".into(),
    }
}

/// The node's title: index, kind and what it hit (its path weight is its second row: a
/// title does not wrap, and the panel must not grow to hold it).
pub fn title(i: usize, n: &RayNode, doc: &Document) -> String {
    let tir = if n.tir { " (TIR)" } else { "" };
    format!("#{i} {}{tir}: {}", n.kind.name(), target(n, doc))
}

/// The rows of node `c` (and its GPU twin `g`): its own factor, path weight, distance and the
/// local terms at its hit.
fn rows(c: &RayNode, g: Option<&RayNode>) -> Vec<Term> {
    let mut out = vec![
        Term::rgb("k (own factor)", c.factor, g.map(|g| g.factor)),
        Term::rgb("weight (path product of k)", c.weight, g.map(|g| g.weight)),
    ];
    if let Some(t) = c.t {
        out.push(Term::scalar("t", t, g.and_then(|g| g.t)));
    }
    if c.attenuation != 1.0 {
        out.push(Term::scalar("f_att(t) (world)", c.attenuation, g.map(|g| g.attenuation)));
    }
    if let Some(terms) = &c.terms {
        out.extend(local_terms(terms, g.and_then(|g| g.terms.as_ref())));
    }
    if let Some(r) = c.radiance {
        // The GPU sums each node's weighted terms into the pixel instead: it has no such value,
        // and its "–" needs the reason beside it (a lecturer asked).
        out.push(Term::rgb(BROUGHT_BACK, r, None));
    }
    out
}

pub fn ui(ui: &mut Ui, p: &ProbeState, doc: &Document) {
    ui.separator();
    ui.strong("Ray tree");
    let cpu = &p.cpu_tree;
    let cuts = cpu.nodes.iter().filter(|n| n.cut.is_some()).count();
    let count = |k: RayKind| cpu.count(k);
    ui.label(format!(
        "{} rays: {} reflection, {} refraction, {} shadow; {cuts} cut (dashed in the view)",
        cpu.nodes.len(),
        count(RayKind::Reflection),
        count(RayKind::Refraction),
        count(RayKind::Shadow)
    ));
    let gpu = p.gpu_tree.as_ref();
    if let Some(g) = gpu {
        if g.overflow {
            ui.colored_label(
                ui.visuals().error_fg_color,
                format!("GPU tree truncated: only its first {MAX_PROBE_NODES} rays were recorded"),
            );
        }
        if g.lights_truncated {
            ui.colored_label(
                ui.visuals().warn_fg_color,
                "GPU tree: only the first lights' terms and shadow rays were recorded",
            );
        }
    } else if matches!(p.gpu, GpuProbe::Pending(_)) {
        ui.weak("GPU tree: waiting for the probe…");
    }
    let first = p.tree_difference();
    match &first {
        Some(d) => {
            let kind = cpu.nodes.get(d.node).map_or("missing", |n| n.kind.name());
            ui.colored_label(HIGHLIGHT, format!("First differing node: #{} ({kind}): {}", d.node, d.what));
        }
        None if gpu.is_some() => {
            ui.label("CPU and GPU trees agree node by node within tolerance.");
        }
        None => {}
    }
    // The path from the root to the differing node opens by itself.
    let mut open = vec![false; cpu.nodes.len()];
    let mut at = first.as_ref().map(|d| d.node).filter(|&i| i < cpu.nodes.len());
    while let Some(i) = at {
        open[i] = true;
        at = cpu.nodes[i].parent;
    }
    if !cpu.nodes.is_empty() {
        node_ui(ui, cpu, gpu, 0, first.map(|d| d.node), &open, doc);
    }
}

fn node_ui(
    ui: &mut Ui,
    cpu: &RayTree,
    gpu: Option<&RayTree>,
    i: usize,
    first: Option<usize>,
    open: &[bool],
    doc: &Document,
) {
    let c = &cpu.nodes[i];
    let g = gpu.and_then(|t| t.nodes.get(i));
    let mut text = RichText::new(title(i, c, doc));
    if first == Some(i) {
        text = text.color(HIGHLIGHT).strong();
    } else if c.cut.is_some() {
        text = text.color(Color32::GRAY);
    }
    // The id changes with the differing node, so that the path to a new difference opens
    // (default_open applies to a header's first frame only) and stays collapsible.
    egui::CollapsingHeader::new(text).id_salt(("ray node", i, first)).default_open(i == 0 || open[i]).show(ui, |ui| {
        let rows = rows(c, g);
        let row = if first == Some(i) { first_difference(&rows) } else { None };
        term_grid(ui, ("ray node terms", i), &rows, row);
        for child in cpu.children(i) {
            node_ui(ui, cpu, gpu, child, first, open, doc);
        }
    });
}
