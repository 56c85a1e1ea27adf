//! Case 24: a far eye over a plane alone — a checkered ground seen obliquely through a telephoto,
//! 36.9° and 20° above it, from D = 1e5, 1e6 and 1e7 (the same 10-unit patch of it, 96×72, the
//! field of view narrowed with D), with no sphere or mesh to give the scene a size.
//!
//! Also an orthographic view of the patch grazing the plane, 0.1° above it, whose image does not
//! depend on D at all (each pixel's ground spans 80 checker squares: every rounding shows).
//!
//! Expected: the perspective differs by at most 3e-4 of the patch between the three (the patch's
//! depth over D, at 20°), so the CPU's images are alike but for pixel centres that close to a
//! checker edge (at most 0.5 % of the pixels unlike D = 1e5's), and the GPU's match the CPU's: no
//! first hit that differs, largest same-hit difference ≤ 1e-6 — at 0.1°, where f32's step on the
//! ground is 573 times its step across the ray, at most 0.2 % of the pixels on the other square.
//!
//! Why it was stiff: the camera anchors an eye far from its scene (case 22) by the scene's size,
//! and a scene of planes alone has none, so the eye was stored itself and every camera ray left
//! it in f32: its direction's step (6e-8 against a patch 1e-5 of the distance wide) moved each
//! ray a third of a pixel on the GPU and the f32 eye moved the CPU's: at D = 1e6 GPU against CPU
//! PSNR 14.8 dB (FLIP 0.128), and the CPU's image 374 pixels (5.4 %) unlike D = 1e5's. Such a
//! camera is now anchored where its axis meets the nearest plane, judged by its field of view.
//! The grazing view was stored around the eye (its height over the plane, 1.7e3 at 1e6, is the
//! size a scene of planes alone had): the plane's offset and the anchor rounded to that, 573
//! times as far along the ground, put 4.6 % of the CPU's pixels at 1e6 on the wrong square; a
//! narrow view's scene is now stored around the patch it sees.

use glint_core::compare::compare_images;

use crate::gpu::render_both;
use crate::scene::SceneText;

/// The patch of ground seen: its height at the focus.
const PATCH: f64 = 10.0;
/// The focus, off every power-of-two grid.
const FOCUS: [f64; 3] = [0.3, 0.0, 0.2];
/// The eye's elevation above the plane, in degrees, and whether the view is orthographic: above
/// and below 30°, where the GPU's frame once stopped looking for the patch (a review found it),
/// and grazing; the eye's azimuth is fixed.
const VIEWS: [(f64, bool); 3] = [(36.87, false), (20.0, false), (0.1, true)];

fn scene(elevation: f64, distance: f64, orthographic: bool) -> SceneText {
    let (sin, cos) = elevation.to_radians().sin_cos();
    let towards_eye = [0.6 * cos, sin, 0.8 * cos];
    let eye: [f64; 3] = std::array::from_fn(|k| FOCUS[k] + distance * towards_eye[k]);
    let fov = 2.0 * (0.5 * PATCH / distance).atan().to_degrees();
    let mut text = SceneText::new(96, 72, "max_depth = 1", eye, FOCUS, [0.0, 1.0, 0.0], fov);
    if orthographic {
        text.text.push_str(&format!("projection = \"orthographic\"\nview_height = {PATCH:?}\n"));
    }
    text.world([0.1; 3], [0.0; 3])
        .material("floor", "kd = 0.8\nchecker = { kd = 0.1, size = 1.0 }")
        .light("directional", "direction = [-0.3, -1.0, -0.2]")
        .plane([0.0; 3], [0.0, 1.0, 0.0], "floor")
}

#[test]
fn a_far_eye_over_a_lone_plane_sees_it_as_a_near_one_on_both_tracers() {
    let mut out = String::new();
    say!(out, "case 24: a 10-unit patch of a checkered plane seen obliquely from D (96×72)");
    say!(
        out,
        "  {:>9}  {:>12}  {:>7}  {:>23}  {:>19}  {:>14}  {:>10}  {:>11}",
        "elevation",
        "view",
        "D",
        "CPU pixels unlike 1e5's",
        "max |diff| same hit",
        "GPU pixels off",
        "PSNR (dB)",
        "hits differ"
    );
    for (elevation, orthographic) in VIEWS {
        let mut reference = None;
        for distance in [1e5, 1e6, 1e7] {
            let name = format!("far-eye-{elevation}-{distance:e}");
            let both = render_both("stiff/case24", &name, &scene(elevation, distance, orthographic).flat());
            let cpu = &both.cpu.image;
            let reference = reference.get_or_insert_with(|| cpu.pixels.clone());
            let unlike = cpu.pixels.iter().zip(reference.iter()).filter(|(a, b)| a != b).count();
            let Some(gpu) = &both.gpu else { continue };
            let e = compare_images(cpu, &gpu.image);
            let same_hit: Vec<f64> = cpu
                .pixels
                .iter()
                .zip(&gpu.image.pixels)
                .zip(cpu.first_hit.iter().zip(&gpu.image.first_hit))
                .filter(|(_, (a, b))| a == b)
                .map(|((c, g), _)| (*c - *g).abs().max_element())
                .collect();
            let worst = same_hit.iter().copied().fold(0.0_f64, f64::max);
            let off = same_hit.iter().filter(|d| **d > 1e-6).count();
            let hits = both.first_hit_mismatches().len();
            let view = if orthographic { "orthographic" } else { "perspective" };
            say!(
                out,
                "  {elevation:>8.1}°  {view:>12}  {distance:>7.0e}  {unlike:>23}  {worst:>19.2e}  {off:>14}  {:>10.1}  {hits:>11}",
                e.psnr
            );
            // At 0.1° a pixel whose ground point lies within f32's step there (573 of them across
            // the ray) of a checker edge may take the other square.
            let gpu_agrees = if elevation < 1.0 { off * 500 <= cpu.pixels.len() } else { worst <= 1e-6 };
            both.ensure(unlike * 200 <= cpu.pixels.len() && gpu_agrees && hits == 0, || {
                format!(
                    "{elevation}° {view}, D = {distance:e}: {unlike} CPU pixels unlike D = 1e5's, GPU off by {worst:.2e} \
                     on {off} pixels, {hits} hits differ"
                )
            });
        }
    }
    eprint!("{out}");
    crate::generated::section("case24-far-eye-over-a-plane", &out);
}

/// A diffuse floor 2 under an eye, lit by an attenuated point light, nothing else: moved by `x`.
fn lit_floor(x: f64) -> SceneText {
    let p = |v: [f64; 3]| [v[0] + x, v[1], v[2]];
    SceneText::new(64, 48, "max_depth = 0", p([0.5, 2.0, -3.0]), p([0.0; 3]), crate::Y, 50.0)
        .world([0.0; 3], [0.0; 3])
        .material("p", "ka = 0.0\nkd = 0.7")
        .light(
            "point",
            &format!(
                "position = {}\nattenuation = {{ c = 1.0, l = 0.5, q = 0.25 }}",
                crate::scene::arr(p([0.3, 1.0, 0.2]))
            ),
        )
        .plane(p([0.0; 3]), crate::Y, "p")
}

#[test]
fn planes_alone_far_from_the_origin_are_stored_around_the_eye() {
    // Before, a scene of planes alone was stored in world space: at x = 1e7 the eye, the light
    // and the plane's offset were rounded to 1, and the floor lit up to 20 % off.
    let at = |x: f64| crate::render::render_cpu_checked(&lit_floor(x).flat(), 2, true).image;
    let origin = at(0.0);
    for x in [1e6, 1e7] {
        let moved = at(x);
        let worst = origin
            .pixels
            .iter()
            .zip(&moved.pixels)
            .flat_map(|(a, b)| (0..3).map(move |c| crate::rel_err(b[c], a[c])))
            .fold(0.0, f64::max);
        assert!(worst < 1e-5, "x = {x:e}: the floor is lit {worst:.2e} off the origin's");
    }
}
