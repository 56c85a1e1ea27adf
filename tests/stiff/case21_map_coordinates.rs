//! Case 21: case 17's scene at map coordinates — a projected (UTM-like) easting and northing
//! and an Earth-centred (ECEF) position, offsets that f32 cannot store (at 5e6 its step is
//! 1/2). The scene is scaled by 1.1 first, so that its coordinates are decimals, not the
//! multiples of 1/8 case 17 chose to be exact: f32 world coordinates would round each point
//! its own way, not move the whole scene by one rounding.
//!
//! Expected: both tracers render it as at the origin. The scene is stored relative to its own
//! geometry (`glint_scene::storage_origin`: each position's difference from an origin at the
//! box of the bounded geometry taken in f64 and rounded once to f32), so f32 carries the
//! distances within the scene, as at the origin: the CPU image has the same first hit on every
//! pixel and every channel within CPU_REL of the untransformed one, and the GPU's FLIP against
//! its own CPU image stays within 2× of the untransformed scene's.
//!
//! Shown beside it, and required, so that the case stays stiff: the same scene stored in f32
//! world space (what Glint stored before) loses the scene on the CPU reference itself —
//! positions off by up to a quarter of a unit, first hits that differ.

use glam::DVec3;
use glint_core::compare::flip_mean;
use glint_core::probe_pixel;
use glint_core::rebase::rebased;
use glint_types::layout::WORLD_FRAME;

use crate::case17_translation_and_scale::{cpu_difference, scene};
use crate::gpu::render_both;
use crate::render::render_cpu_checked;

/// Offsets (x, y, z), y up: a UTM zone 32N easting and northing with a height, and an ECEF
/// position (Paris, metres).
const OFFSETS: [(&str, [f64; 3]); 2] =
    [("UTM 32N", [452_331.127, 81.5, 5_411_876.883]), ("ECEF", [4_201_234.56, 4_779_855.21, 171_653.09])];
/// Measured: worst channel 2.9e-6 (UTM) and 4.3e-6 (ECEF) — the scene's positions differ from
/// the untransformed ones by their f32 rounding at the scene's size (≈ 5e-7 units: the offsets
/// leave other fractions than the untransformed coordinates have), and a shading term at a
/// grazing light or a refraction amplifies that a little. Allowed: 1e-5, where f32 world
/// storage changes whole pixels (column 4: up to 21× their value, 75 and 206 first hits).
const CPU_REL: f64 = 1e-5;
/// The GPU's FLIP against its own CPU image, relative to the untransformed scene's (case 17's).
const FLIP_RATIO: f64 = 2.0;
/// The scale that makes case 17's coordinates decimals.
const SCALE: f64 = 1.1;
/// A pixel on the red sphere (96×72).
const W_PROBE: u32 = 60;
const H_PROBE: u32 = 40;

#[test]
fn a_scene_at_map_coordinates_renders_as_at_the_origin_on_both_backends() {
    let group = "stiff/case21-map-coordinates";
    let base_flat = scene([0.0; 3], SCALE).flat();
    let base = render_both(group, "untransformed", &base_flat);
    let base_flip = base.gpu.as_ref().map(|g| flip_mean(&base.cpu.image, &g.image));
    let mut out = String::new();
    let flip = |f: Option<f64>| f.map_or("-".to_string(), |f| format!("{f:.1e}"));
    say!(out, "case 21: case 17's scene, scaled by 1.1, at map coordinates (stored relative to its geometry)");
    say!(
        out,
        "  {:>13}  {:>16}  {:>15}  {:>17}  {:>22}  {:>21}",
        "",
        "CPU vs untransf.",
        "CPU hits differ",
        "GPU FLIP vs CPU",
        "world-stored CPU diff.",
        "world-stored hits diff"
    );
    say!(out, "  {:>13}  {:>16}  {:>15}  {:>17}  {:>22}  {:>21}", "untransformed", "-", "-", flip(base_flip), "-", "-");
    let mut failures = Vec::new();
    for (label, offset) in OFFSETS {
        let flat = scene(offset, SCALE).flat();
        assert_ne!(flat.header.frame, WORLD_FRAME, "{label}: stored relative to its geometry");
        let both = render_both(group, label, &flat);
        let (cpu_rel, hits) = cpu_difference(&base.cpu, &both.cpu);
        let gpu_flip = both.gpu.as_ref().map(|g| flip_mean(&both.cpu.image, &g.image));
        // The probe reports its hit point in world space: the untransformed one, moved.
        let (x, y) = (W_PROBE, H_PROBE);
        let probe = |f| probe_pixel(f, x, y, 0).expect("valid tags").point;
        let (far, near) = (probe(&flat), probe(&base_flat));
        let moved = far - DVec3::from(offset) - near;
        if moved.abs().max_element() > 1e-5 {
            failures.push(format!("{label}: the probe's point {far} is not the untransformed {near} moved"));
        }
        let world = render_cpu_checked(&rebased(&flat, WORLD_FRAME), 0, true);
        let (world_rel, world_hits) = cpu_difference(&base.cpu, &world);
        say!(
            out,
            "  {label:>13}  {cpu_rel:>16.2e}  {hits:>15}  {:>17}  {world_rel:>22.2e}  {world_hits:>21}",
            flip(gpu_flip)
        );
        if hits != 0 || cpu_rel > CPU_REL {
            failures.push(format!(
                "{label}: CPU differs from untransformed: {hits} first hits, {cpu_rel:e} (> {CPU_REL:e})"
            ));
        }
        if let (Some(f), Some(b)) = (gpu_flip, base_flip)
            && f > FLIP_RATIO * b
        {
            failures
                .push(format!("{label}: GPU FLIP against its CPU {f:.1e} > {:.1e} (2x untransformed)", FLIP_RATIO * b));
        }
        if world_hits == 0 {
            failures
                .push(format!("{label}: stored in world space the scene lost nothing: the case is no longer stiff"));
        }
    }
    eprint!("{out}");
    crate::generated::section("case21-map-coordinates", &out);
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}
