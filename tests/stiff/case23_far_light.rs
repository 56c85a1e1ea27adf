//! Case 23: a point light far away — the sun as a point light, 1e6 from a scene that is itself
//! 5,000 units from the world origin: a red and a mirror sphere on a floor, seen from 4 away,
//! lit from L = 10, 1e3 and 1e6 along the same direction (no attenuation, so the light's
//! distance changes only its direction's precision).
//!
//! Expected: the GPU renders it as close to the CPU reference whatever L is — its largest
//! difference on pixels with the same first hit within 2× of L = 10's (plus 1e-6 for a zero)
//! and no first hit that differs.
//!
//! Why it was stiff: the GPU traces in a frame whose origin it snaps to a grid of the scene's
//! extent (`glint_core::rebase::camera_frame`), and that extent was measured from the eye to the
//! farthest light too: a light 1e6 away made the grid 2^16, put the origin at the world origin,
//! 5,000 from what is seen, and stored the scene to f32 steps of 5e-4 there — shadows and the
//! mirror image went wrong (max difference 0.6, PSNR 34.5 dB against 133.7 with the light near).
//! The extent is now how far the surfaces reach from the focus; a light is not a surface.

use glint_core::compare::compare_images;

use crate::gpu::render_both;
use crate::scene::SceneText;

/// Where the scene sits: not on any power-of-two grid coarser than 8.
const X: f64 = 5_000.0;
/// The light's direction from the red sphere (unnormalised).
const TOWARDS_LIGHT: [f64; 3] = [0.3, 1.0, -0.2];
/// Multiple of L = 10's largest same-hit difference allowed at every L.
const RATIO: f64 = 2.0;

fn scene(light_distance: f64) -> SceneText {
    let n = (TOWARDS_LIGHT.iter().map(|c| c * c).sum::<f64>()).sqrt();
    let light: [f64; 3] = std::array::from_fn(|k| [X, 0.5, 0.0][k] + light_distance * TOWARDS_LIGHT[k] / n);
    SceneText::new(160, 120, "max_depth = 3", [X, 1.5, -4.0], [X, 0.5, 0.0], [0.0, 1.0, 0.0], 40.0)
        .world([0.05; 3], [0.1; 3])
        .material("red", "ka = [0.8, 0.1, 0.1]\nkd = [0.8, 0.1, 0.1]\nks = 0.5\nshininess = 50.0")
        .material("mirror", "ka = 0.05\nkd = 0.05\nkr = 0.9")
        .material("floor", "ka = 0.6\nkd = 0.6")
        .light("point", &format!("position = [{}, {}, {}]", light[0], light[1], light[2]))
        .sphere([X, 0.5, 0.0], 0.5, "red")
        .sphere([X + 1.2, 0.5, 0.5], 0.5, "mirror")
        .mesh(
            &[[X - 10.0, 0.0, -10.0], [X + 10.0, 0.0, -10.0], [X + 10.0, 0.0, 10.0], [X - 10.0, 0.0, 10.0]],
            &[[0, 2, 1], [0, 3, 2]],
            None,
            "floor",
        )
}

#[test]
fn a_far_point_light_keeps_the_gpu_as_close_to_the_cpu_as_a_near_one() {
    let mut out = String::new();
    say!(out, "case 23: a point light at distance L from a scene at x = 5,000 (GPU against the CPU reference)");
    say!(
        out,
        "  {:>7}  {:>19}  {:>10}  {:>10}  {:>15}",
        "L",
        "max |diff| same hit",
        "PSNR (dB)",
        "FLIP",
        "hits differ"
    );
    let mut base = None;
    for distance in [10.0, 1e3, 1e6] {
        let both = render_both("stiff/case23", &format!("far-light-{distance:e}"), &scene(distance).flat());
        let Some(gpu) = &both.gpu else { continue };
        let e = compare_images(&both.cpu.image, &gpu.image);
        // The largest same-hit difference (the p99 leaves out too much on 19,200 pixels).
        let worst = both
            .cpu
            .image
            .pixels
            .iter()
            .zip(&gpu.image.pixels)
            .zip(both.cpu.image.first_hit.iter().zip(&gpu.image.first_hit))
            .filter(|(_, (a, b))| a == b)
            .map(|((c, g), _)| (*c - *g).abs().max_element())
            .fold(0.0_f64, f64::max);
        let hits = both.first_hit_mismatches().len();
        say!(out, "  {distance:>7.1e}  {worst:>19.2e}  {:>10.1}  {:>10.1e}  {hits:>15}", e.psnr, e.flip_mean);
        let base = *base.get_or_insert(worst);
        both.ensure(worst <= RATIO * base + 1e-6 && hits == 0, || {
            format!("L = {distance:e}: GPU off the CPU by {worst:.2e} on same-hit pixels (L = 10: {base:.2e}), {hits} first hits differ")
        });
    }
    eprint!("{out}");
    crate::generated::section("case23-far-light", &out);
}
