//! Case 9: the light exactly opposite the viewer, L = −V, and perturbed from it by 1e-7 rad.
//!
//! The view direction is generic (not an axis), so the stored f32 directions carry rounding.
//! Three surfaces face the light in turn: a sphere and a plane seen from the viewer (two-sided
//! shading turns their normals to the viewer, N·L = −1), and a triangle whose vertex normals
//! point at the light, away from the viewer (N·L = 1), where the Blinn half vector
//! H = (L + V)/|L + V| is 0/0.
//!
//! Expected, on both backends and both lobes (Blinn, Phong): the specular term is 0 for n > 0
//! and, by the convention x^0 = 1 used everywhere else, 1 for n = 0 where N·L > 0 — and the same
//! (to 1e-6) with the light moved by 1e-7 rad in any direction: continuous. In exact arithmetic
//! the perturbed Blinn lobe is max(−sin(θ/2), 0)^n = 0 (the normal is −V), the Phong lobe
//! max(−cos θ, 0)^n = 0.
//!
//! The table sweeps the angle θ between L and −V on both backends: the lobe of normals at the
//! light (exact value 0, required ≤ 1e-6 at every θ) and, for contrast, of normals along the
//! exact half vector (grazing: N ⟂ V; exact value 1), which shows how the direction of
//! H = (L + V)/|L + V| degrades as θ approaches the f32 precision of the stored directions.

use glam::{DQuat, DVec3};

use crate::Y;
use crate::gpu::render_both;
use crate::scene::{SceneText, num};

fn frame() -> (DVec3, DVec3, DVec3) {
    let f = DVec3::new(0.3, -0.2, 1.0).normalize();
    let u = f.cross(DVec3::Y).normalize();
    (f, u, f.cross(u))
}

/// Pinhole view along F; the light travels towards the viewer along −L, L = F turned by θ about
/// `axis`. `surface`: 0 sphere, 1 plane seen from its back, 2 triangle with vertex normals F,
/// 3 triangle with vertex normals H = (L − F)/|L − F|, the exact half vector (grazing).
fn scene(surface: u32, model: &str, n: f64, theta: f64, axis: DVec3) -> SceneText {
    let (f, u, v) = frame();
    let l = DQuat::from_axis_angle(axis, theta) * f;
    let c = 5.0 * f;
    let s = SceneText::pinhole("max_depth = 0", [0.0; 3], c.to_array(), Y)
        .world([0.0; 3], [0.0; 3])
        .material("m", &format!("ka = 0.0\nkd = 0.0\nks = 1.0\nshininess = {}\nspecular_model = \"{model}\"", num(n)))
        .light("directional", &format!("direction = {:?}\ndiffuse = 0.0\nspecular = 1.0", (-l).to_array()));
    match surface {
        0 => s.sphere((c + f).to_array(), 1.0, "m"),
        1 => s.plane(c.to_array(), f.to_array(), "m"),
        _ => {
            let normal = if surface == 2 { f } else { (l - f).normalize() };
            // Wound so that the geometric normal faces the viewer (−F) and the vertex normals
            // (F) face the light: two-sided shading keeps them as they are.
            let tri = [(c - 0.5 * u - 0.5 * v).to_array(), (c + v).to_array(), (c + 0.5 * u - 0.5 * v).to_array()];
            s.triangles(&[tri], Some(&[normal.to_array(); 3]), "m")
        }
    }
}

#[test]
fn light_opposite_the_viewer_gives_no_specular_and_is_continuous() {
    let mut out = String::new();
    let (_, u, v) = frame();
    let axes = [u, v, (u + v).normalize()];
    let mut worst = [0.0_f64; 2];
    for surface in 0..3 {
        for model in ["blinn", "phong"] {
            for n in [0.0, 1.0, 32.0, 1e6] {
                let want = if surface == 2 && n == 0.0 { 1.0 } else { 0.0 };
                for (theta, axis) in [(0.0, u)].into_iter().chain(axes.map(|a| (1e-7, a))) {
                    let flat = scene(surface, model, n, theta, axis).flat();
                    if theta == 0.0 {
                        assert_eq!(
                            flat.lights[0].direction[..3],
                            flat.camera.forward[..3].iter().map(|c| -c).collect::<Vec<_>>()[..]
                        );
                    }
                    let name = format!("opposite-s{surface}-{model}-n{n}-theta{theta:e}");
                    let both = render_both("stiff/case09", &name, &flat);
                    for (backend, img) in both.images() {
                        let got = img.get(0, 0).x;
                        let err = (got - want).abs();
                        worst[backend as usize] = worst[backend as usize].max(err);
                        both.ensure(err <= 1e-6, || {
                            format!("{} {name}: specular {got}, expected {want}", backend.name())
                        });
                    }
                }
            }
        }
    }
    say!(out, "case 9: L = −V and 1e-7 away: worst |specular − expected| CPU {:.1e}, GPU {:.1e}", worst[0], worst[1]);

    say!(out, "  Blinn lobe as L turns away from −V by θ, n = 1 on normals pointing at the light (exact value 0)");
    say!(out, "  and n = 100 on normals along the exact half vector, at grazing (exact value 1):");
    say!(out, "  {:>8}  {:>19}  {:>19}", "θ", "N = L: CPU / GPU", "N = H: CPU / GPU");
    for theta in [0.0, 1e-8, 1e-7, 1e-6, 1e-5, 1e-4, 1e-3, 1e-2] {
        let mut cells = Vec::new();
        for (surface, n) in [(2, 1.0), (3, 100.0)] {
            if surface == 3 && theta == 0.0 {
                cells.push("-".to_string());
                continue;
            }
            let flat = scene(surface, "blinn", n, theta, axes[2]).flat();
            let both = render_both("stiff/case09", &format!("sweep-{surface}-{theta:e}"), &flat);
            let values: Vec<String> = both.images().iter().map(|(_, img)| format!("{:.2e}", img.get(0, 0).x)).collect();
            if surface == 2 {
                for (backend, img) in both.images() {
                    both.ensure(img.get(0, 0).x <= 1e-6, || {
                        format!("{} θ = {theta:e}: {} where the lobe is 0", backend.name(), img.get(0, 0).x)
                    });
                }
            }
            cells.push(values.join(" / "));
        }
        say!(out, "  {theta:>8.0e}  {:>19}  {:>19}", cells[0], cells[1]);
    }
    eprint!("{out}");
    crate::generated::section("case09-light-opposite", &out);
}
