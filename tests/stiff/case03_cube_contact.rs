//! Case 3: a unit cube (an indexed mesh of 12 triangles) resting on a floor plane, and floating
//! above it at gaps 1e-6, 1e-4 and 1e-2, lit by a point light from the side so that the cube
//! casts a shadow that starts at its base.
//!
//! Expected: no light leak at the contact, and no acne: every floor pixel whose shadow ray
//! (floor point → light) the exact geometry puts inside the cube — computed here in f64 by a
//! slab test against the cube's stored f32 corners — is black (ambient 0), and every pixel whose
//! shadow ray clears the cube is lit with k_d·I·N·L. Only pixels whose shadow ray passes within
//! a thin margin of the cube's surface are left out (the backends' own rounding decides them):
//! CPU 1e-9, GPU the measured margin below. Checked with the default `robust` strategy; the
//! leaks and acne of the other strategies are printed for comparison.

use glam::DVec3;
use glint_core::FlatScene;
use glint_scene::EpsilonMode;

use crate::Y;
use crate::gpu::{Backend, render_both};
use crate::reference::{plane_hit, primary_ray};
use crate::scene::{SceneText, w3};

const W: u32 = 64;
const H: u32 = 48;
const GAPS: [f64; 4] = [0.0, 1e-6, 1e-4, 1e-2];
const LIGHT: [f64; 3] = [-4.0, 2.5, 0.7];

/// Shadow rays passing closer than this to the cube's surface may be decided either way.
/// Measured (lavapipe, robust): both backends decide every shadow ray of this view as the exact
/// geometry does (the closest pass is farther than any margin below). Allowed on the GPU 1e-5,
/// ≈ 100 ulps of the unit-sized coordinates: f32 floor points and directions are good to a few
/// ulps; 1e-5 is a thousandth of a pixel's footprint on the floor.
const MARGIN_GPU: f64 = 1e-5;
const MARGIN_CPU: f64 = 1e-9;
/// Relative error of a lit floor pixel against k_d·I·N·L. Measured: CPU 3.0e-16, GPU 4.3e-7
/// (f32 shading).
const REL_CPU: f64 = 1e-12;
const REL_GPU: f64 = 1e-5;

fn cube(gap: f64) -> (Vec<[f64; 3]>, Vec<[u32; 3]>) {
    let mut v = Vec::new();
    for i in 0..8 {
        let x = if i & 1 == 0 { -0.5 } else { 0.5 };
        let y = if i & 2 == 0 { gap } else { gap + 1.0 };
        let z = if i & 4 == 0 { -0.5 } else { 0.5 };
        v.push([x, y, z]);
    }
    // Outward winding, two triangles per face, every edge shared.
    let quads = [[0, 4, 6, 2], [1, 3, 7, 5], [0, 1, 5, 4], [2, 6, 7, 3], [0, 2, 3, 1], [4, 5, 7, 6]];
    let tris = quads.iter().flat_map(|q| [[q[0], q[1], q[2]], [q[0], q[2], q[3]]]).collect();
    (v, tris)
}

fn scene(gap: f64, mode: EpsilonMode) -> SceneText {
    let (v, t) = cube(gap);
    SceneText::new(
        W,
        H,
        &format!("max_depth = 0\nepsilon_mode = \"{}\"", mode.name()),
        [2.2, 1.3, -2.0],
        [0.8, 0.15, 0.1],
        Y,
        45.0,
    )
    .world([0.0; 3], [0.0; 3])
    .material("floor", "ka = 0.0\nkd = 0.75\nks = 0.0")
    .material("box", "ka = 0.0\nkd = 0.5\nks = 0.0")
    .light("point", &format!("position = {LIGHT:?}\ndiffuse = 1.0"))
    .plane([0.0; 3], Y, "floor")
    .mesh(&v, &t, None, "box")
}

/// Whether the segment p → q passes through the axis-aligned box [lo, hi] (slab test), with
/// the box grown by `grow` (negative: shrunk).
fn segment_hits_box(p: DVec3, q: DVec3, lo: DVec3, hi: DVec3, grow: f64) -> bool {
    let (lo, hi) = (lo - DVec3::splat(grow), hi + DVec3::splat(grow));
    let d = q - p;
    let (mut t0, mut t1) = (0.0_f64, 1.0_f64);
    for i in 0..3 {
        if d[i] == 0.0 {
            if p[i] < lo[i] || p[i] > hi[i] {
                return false;
            }
            continue;
        }
        let (a, b) = ((lo[i] - p[i]) / d[i], (hi[i] - p[i]) / d[i]);
        t0 = t0.max(a.min(b));
        t1 = t1.min(a.max(b));
    }
    t0 <= t1
}

#[derive(Default, Clone, Copy)]
struct Outcome {
    shadowed: usize,
    near_contact: usize,
    lit: usize,
    leaks: usize,
    acne: usize,
    /// Largest distance from the cube's surface at which the backend decided a shadow ray
    /// differently from the exact geometry (0: never).
    worst_margin: f64,
    worst_rel: f64,
}

/// How far the box must be grown (`shadowed` false: the backend saw light where the exact
/// segment is blocked, so shrink) before the exact test agrees with the backend: bisection.
fn needed_margin(p: DVec3, light: DVec3, lo: DVec3, hi: DVec3, backend_shadowed: bool) -> f64 {
    let agrees = |m: f64| segment_hits_box(p, light, lo, hi, if backend_shadowed { m } else { -m }) == backend_shadowed;
    if agrees(0.0) {
        return 0.0;
    }
    let (mut a, mut b) = (0.0, 1e-2);
    for _ in 0..60 {
        let m = 0.5 * (a + b);
        if agrees(m) { b = m } else { a = m }
    }
    b
}

fn check(
    flat: &FlatScene,
    backend: Backend,
    img: &glint_core::HdrImage,
    report_only: bool,
    ensure: &dyn Fn(bool, String),
) -> Outcome {
    let tri = &flat.triangles;
    let corners: Vec<DVec3> =
        tri.iter().flat_map(|t| [t.va, t.vb, t.vc]).map(|i| w3(flat.vertices[i as usize])).collect();
    let lo = corners.iter().copied().reduce(DVec3::min).unwrap();
    let hi = corners.iter().copied().reduce(DVec3::max).unwrap();
    let light = w3(flat.lights[0].position);
    let floor_id = 0;
    let margin = backend.pick(MARGIN_CPU, MARGIN_GPU);
    let mut out = Outcome::default();
    for y in 0..H {
        for x in 0..W {
            if img.first_hit[(y * W + x) as usize] != floor_id {
                continue;
            }
            let (o, d) = primary_ray(flat, x, y);
            let p = o + plane_hit(o, d, DVec3::Y, 0.0).expect("floor") * d;
            let got = img.get(x, y).x;
            let l = (light - p).normalize();
            let want = 0.75 * l.y;
            let backend_shadowed = got == 0.0;
            out.worst_margin = out.worst_margin.max(needed_margin(p, light, lo, hi, backend_shadowed));
            if !backend_shadowed {
                out.worst_rel = out.worst_rel.max((got - want).abs() / want);
            }
            if segment_hits_box(p, light, lo, hi, -margin) {
                out.shadowed += 1;
                // Within 5 cm of the cube's footprint: the contact region.
                let outside = (p.x.abs() - 0.5).max(p.z.abs() - 0.5);
                out.near_contact += usize::from(outside < 0.05);
                if got != 0.0 {
                    out.leaks += 1;
                    if !report_only {
                        ensure(false, format!("{}: light leaks onto ({x}, {y}) at {p}: {got}", backend.name()));
                    }
                }
            } else if !segment_hits_box(p, light, lo, hi, margin) {
                out.lit += 1;
                let ok = (got - want).abs() <= backend.pick(REL_CPU, REL_GPU) * want;
                if !ok {
                    out.acne += 1;
                    if !report_only {
                        ensure(false, format!("{}: ({x}, {y}) at {p} = {got}, expected lit {want}", backend.name()));
                    }
                }
            }
        }
    }
    out
}

#[test]
fn cube_on_and_above_a_floor_leaks_no_light() {
    let mut out = String::new();
    say!(
        out,
        "case 3: cube resting on / floating above a floor; shadowed floor pixels lit (leaks) and lit ones darkened (acne), CPU / GPU"
    );
    say!(
        out,
        "  {:<13} {:>6}  {:>11}  {:>11}  {:>9}  {:>9}",
        "strategy",
        "gap",
        "shadowed",
        "at contact",
        "leaks",
        "acne"
    );
    let (mut worst_margin, mut worst_rel_cpu, mut worst_rel_gpu) = (0.0_f64, 0.0_f64, 0.0_f64);
    for mode in EpsilonMode::ALL {
        for gap in GAPS {
            let flat = scene(gap, mode).flat();
            let name = format!("cube-{}-gap{gap:e}", mode.name());
            let both = render_both("stiff/case03", &name, &flat);
            let mut outs: Vec<Outcome> = Vec::new();
            for (backend, img) in both.images() {
                let o = check(&flat, backend, img, mode != EpsilonMode::Robust, &|ok, m| both.ensure(ok, || m));
                if mode == EpsilonMode::Robust {
                    // The test must look at the contact at all.
                    both.ensure(o.near_contact >= 20 && o.lit >= 500, || {
                        format!("only {} contact and {} lit pixels", o.near_contact, o.lit)
                    });
                }
                outs.push(o);
            }
            let col = |f: fn(&Outcome) -> usize| outs.iter().map(|o| f(o).to_string()).collect::<Vec<_>>().join(" / ");
            say!(
                out,
                "  {:<13} {:>6}  {:>11}  {:>11}  {:>9}  {:>9}",
                mode.name(),
                if gap == 0.0 { "0".to_string() } else { format!("{gap:.0e}") },
                col(|o| o.shadowed),
                col(|o| o.near_contact),
                col(|o| o.leaks),
                col(|o| o.acne)
            );
            if mode == EpsilonMode::Robust {
                worst_margin = worst_margin.max(outs.last().map_or(0.0, |o| o.worst_margin));
                worst_rel_cpu = worst_rel_cpu.max(outs[0].worst_rel);
                worst_rel_gpu = worst_rel_gpu.max(outs.get(1).map_or(0.0, |o| o.worst_rel));
            }
        }
    }
    say!(
        out,
        "  robust: worst distance from the cube of a shadow ray decided unlike the exact geometry {worst_margin:.1e} (GPU);"
    );
    say!(out, "          worst relative error of a lit pixel CPU {worst_rel_cpu:.1e}, GPU {worst_rel_gpu:.1e}");
    eprint!("{out}");
    crate::generated::section("case03-cube-contact", &out);
}
