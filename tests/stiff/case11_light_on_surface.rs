//! Case 11: a point light at distance 0, 1e-9 and 1e-6 above a floor (straight above the
//! point the centre pixel sees), under every epsilon strategy, ε ∈ {0, 1e-6}, with and
//! without attenuation; and a point light inside a closed sphere that stands on the floor.
//!
//! Expected, on both backends: every pixel finite and within [0, I_a·k_a + max f_att·(k_d + k_s)]
//! (f_att ≤ 1 here); with the light exactly on the floor N·L = 0 everywhere, so the floor shows
//! its ambient term only; with `robust` the centre pixel equals the closed form
//! I_a·k_a + f_att·(k_d + k_s) (N·L = 1, N·H = 1) — to 1e-9 on the CPU, 1e-6 on the GPU.
//!
//! The light inside the sphere: nothing outside the sphere may be lit (ambient 0, so the whole
//! image stays black). Shadow rays stop short of the light by INT_SCALE = 256 ulps of their
//! length (so that a light sitting on a surface is not shadowed by it, as above); an occluder
//! closer to the light than that does not shadow it. In f64 that is 5.7e-14 of the distance;
//! in f32 3.1e-5 — so on the GPU a light closer than that to the sphere's inside leaks through
//! it (here at a gap of 1e-6, shadow rays ≈ 3 long). Required: black everywhere on the CPU; on
//! the GPU black except where a shadow ray crosses the sphere within that reach of the light.

use glam::DVec3;
use glint_scene::EpsilonMode;

use crate::gpu::{Backend, render_both};
use crate::reference::{assert_rel, plane_hit, primary_ray, sphere_hit};
use crate::scene::{SceneText, num, w3};
use crate::{Y, Z};

/// How far short of a point light the GPU's shadow rays stop, relative to their length:
/// INT_SCALE = 256 ulps of f32 (offset.wgsl's SHADOW_REL).
const REACH: f64 = 256.0 * f32::EPSILON as f64;

#[test]
fn light_almost_on_the_surface_stays_finite() {
    let mut worst = [0.0_f64; 2];
    for mode in EpsilonMode::ALL {
        for eps in [0.0, 1e-6] {
            for (height, attenuation) in [
                (0.0, "{ c = 1.0 }"),
                (1e-9, "{ c = 1.0 }"),
                (1e-9, "{ c = 1.0, l = 1.0, q = 1.0 }"),
                (1e-6, "{ c = 1.0, l = 1.0, q = 1.0 }"),
            ] {
                let flat = SceneText::new(
                    9,
                    9,
                    &format!("max_depth = 0\nepsilon = {}\nepsilon_mode = \"{}\"", num(eps), mode.name()),
                    [0.0, 1.0, 0.0],
                    [0.0; 3],
                    Z,
                    60.0,
                )
                .world([0.125; 3], [0.0; 3])
                .material("floor", "ka = 0.5\nkd = 0.75\nks = 0.5\nshininess = 8.0")
                .light("point", &format!("position = [0.0, {}, 0.0]\nattenuation = {attenuation}", num(height)))
                .plane([0.0; 3], Y, "floor")
                .flat();
                let name = format!(
                    "{}-eps{eps:e}-h{height:e}-{}",
                    mode.name(),
                    if attenuation.contains('q') { "att" } else { "c" }
                );
                let both = render_both("stiff/case11", &name, &flat);
                let ambient = 0.125 * 0.5;
                let max = ambient + 0.75 + 0.5;
                for (backend, img) in both.images() {
                    let at = format!("{} {name}", backend.name());
                    for p in &img.pixels {
                        both.ensure(p.min_element() >= 0.0 && p.max_element() <= max * (1.0 + 1e-6), || {
                            format!("{at}: {p}")
                        });
                        if height == 0.0 {
                            let tol = backend.pick(1e-12, 1e-6);
                            both.ensure((*p - DVec3::splat(ambient)).abs().max_element() <= tol, || {
                                format!("{at}: {p} is not ambient only")
                            });
                        }
                    }
                    if height > 0.0 && mode == EpsilonMode::Robust {
                        // Straight below the light: N·L = 1, f_att = 1/(c + l·h + q·h²).
                        let d = f64::from(flat.lights[0].position[1]);
                        let f_att = if attenuation.contains('q') { 1.0 / (1.0 + d + d * d) } else { 1.0 };
                        let want = ambient + f_att * (0.75 + 0.5);
                        // Measured: CPU 0, GPU 4.4e-8 (the f32 attenuation and sum).
                        assert_rel(img.get(4, 4), DVec3::splat(want), backend.pick(1e-9, 1e-6), &at);
                        worst[backend as usize] = worst[backend as usize].max(crate::rel_err(img.get(4, 4).x, want));
                    }
                }
            }
        }
    }
    eprintln!(
        "case 11: light 1e-9 and 1e-6 above the floor, robust: worst relative error of the pixel below it CPU {:.1e}, GPU {:.1e}",
        worst[0], worst[1]
    );
}

#[test]
fn light_inside_a_closed_sphere_leaves_the_outside_black() {
    let mut out = String::new();
    let centre = DVec3::new(0.0, 1.5, 0.0);
    let toward = DVec3::new(1.0, -1.0, -1.0).normalize(); // the side facing the lit floor and the camera
    say!(
        out,
        "case 11: point light inside a closed sphere (r = 1) over a floor; pixels lit outside the sphere, CPU / GPU"
    );
    say!(out, "  {:>17}  {:>11}  {:>28}", "gap to the inside", "lit pixels", "worst s/d of a lit pixel");
    for gap in [1.0, 1e-2, 1e-4, 1e-6] {
        let light = centre + (1.0 - gap) * toward;
        let flat = SceneText::new(48, 36, "max_depth = 0", [3.0, 2.5, -4.0], [0.0, 0.8, 0.0], Y, 50.0)
            .world([0.0; 3], [0.0; 3])
            .material("m", "ka = 1.0\nkd = 0.8\nks = 0.5")
            .light("point", &format!("position = {:?}", light.to_array()))
            .sphere(centre.to_array(), 1.0, "m")
            .plane([0.0; 3], Y, "m")
            .flat();
        let (lp, c) = (w3(flat.lights[0].position), w3(flat.spheres[0].center_radius));
        // The stored light really is inside, `gap` from the surface.
        let stored_gap = 1.0 - (lp - c).length();
        assert!(stored_gap > 0.0 && (stored_gap - gap).abs() <= 1e-7 + 1e-6 * gap, "stored gap {stored_gap}");
        let both = render_both("stiff/case11", &format!("inside-sphere-gap{gap:e}"), &flat);
        let mut cells = Vec::new();
        let mut worst = 0.0_f64;
        for (backend, img) in both.images() {
            let mut lit = 0;
            for y in 0..36 {
                for x in 0..48 {
                    if img.get(x, y) == DVec3::ZERO {
                        continue;
                    }
                    lit += 1;
                    both.ensure(backend == Backend::Gpu, || {
                        format!("CPU: ({x}, {y}) outside the sphere is lit (gap {gap:e})")
                    });
                    // A leak on the GPU: the shadow ray from the floor point p leaves the sphere at
                    // distance s before the light; it must be within the documented reach.
                    let (o, d) = primary_ray(&flat, x, y);
                    let p = o + plane_hit(o, d, DVec3::Y, 0.0).expect("a lit pixel is on the floor") * d;
                    let (dist, dir) = ((lp - p).length(), (lp - p).normalize());
                    let (t0, _) = sphere_hit(p, dir, c, 1.0).expect("the shadow ray meets the sphere");
                    let s = dist - t0;
                    worst = worst.max(s / dist);
                    both.ensure(s <= 2.0 * REACH * dist, || {
                        format!("GPU: ({x}, {y}) lit through {s:e} of sphere before the light")
                    });
                }
            }
            cells.push(lit.to_string());
        }
        say!(out, "  {gap:>17.0e}  {:>11}  {worst:>28.2e}", cells.join(" / "));
    }
    say!(out, "  (the GPU's shadow rays stop short of the light by 256 ulps = {REACH:.2e} of their length)");
    eprint!("{out}");
    crate::generated::section("case11-light-in-sphere", &out);
}
