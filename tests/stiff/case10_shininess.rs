//! Case 10: shininess n ∈ {0, 1, 1e2, 1e4, 1e5, 1e6} on a sphere seen through a narrow field of
//! view, the highlight slightly off the image centre (specular only: the pixel is spec_j).
//!
//! Expected: finite values in [0, 1] on both backends; the brightest pixel is the same pixel on
//! both; for n = 0 the lobe is exactly 1 wherever N·L > 0. In the highlight (CPU value above
//! 1e-3 of the peak) the GPU's relative error stays within the WGSL pow tolerance documented
//! in docs/numerics.md: x^n amplifies a relative error δ of the cosine x into ≈ n·δ. WGSL's
//! pow(x, n) is exp2(n·log2 x), and log2 may err by 2^-21 absolute on [0.5, 2] (WGSL spec,
//! "Floating Point Accuracy"; the WebGPU CTS tests exactly that bound): a relative error of
//! ln 2·2^-21·n ≈ 3.3e-7·n. The f32 cosine N·H carries a couple of ulps itself (2·2^-23·n ≈
//! 2.4e-7·n). Tolerance: n·5.7e-7 plus 1e-6 for the rest of the f32 shading, at most 1 (a lobe
//! narrower than a pixel errs all-or-nothing). Measured on lavapipe: at most 2.6e-7·n.

use glam::DVec3;

use crate::Y;
use crate::gpu::render_both;
use crate::reference::{blinn, phong, primary_ray, sphere_hit};
use crate::scene::{SceneText, num, w3};

const N: u32 = 64;
/// δ: the relative error that x^n multiplies by n on the GPU — WGSL's log2 bound (2^-21
/// absolute near 1, times ln 2) plus two ulps of the f32 cosine.
const POW_DELTA: f64 = std::f64::consts::LN_2 / 2_097_152.0 + 2.0 * f32::EPSILON as f64;
const BASE: f64 = 1e-6;

fn tolerance(n: f64) -> f64 {
    (n * POW_DELTA + BASE).min(1.0)
}

#[test]
fn sharp_highlights_peak_on_the_same_pixel_within_the_pow_tolerance() {
    let mut out = String::new();
    say!(out, "case 10: specular lobe x^n on both backends ({N}x{N}, specular only)");
    say!(
        out,
        "  {:>6}  {:>10}  {:>10}  {:>9}  {:>17}  {:>10}  {:>8}",
        "n",
        "CPU peak",
        "GPU peak",
        "same px",
        "worst rel. error",
        "tolerance",
        "error/n"
    );
    for n in [0.0, 1.0, 1e2, 1e4, 1e5, 1e6] {
        let flat = SceneText::new(N, N, "max_depth = 0", [0.0, 0.0, -4.0], [0.0; 3], Y, 4.0)
            .world([0.0; 3], [0.0; 3])
            .material("m", &format!("ka = 0.0\nkd = 0.0\nks = 1.0\nshininess = {}", num(n)))
            .light("directional", "direction = [0.01, 0.0, 1.0]\ndiffuse = 0.0")
            .sphere([0.0; 3], 1.0, "m")
            .flat();
        let both = render_both("stiff/case10", &format!("shininess-{n:e}"), &flat);
        let peak =
            |px: &[DVec3]| px.iter().enumerate().max_by(|a, b| a.1.x.total_cmp(&b.1.x)).map(|(i, p)| (i, p.x)).unwrap();
        let (ci, cv) = peak(&both.cpu.image.pixels);
        for (backend, img) in both.images() {
            for (i, p) in img.pixels.iter().enumerate() {
                both.ensure(p.min_element() >= 0.0 && p.max_element() <= 1.0, || {
                    format!("{} n = {n}: pixel {i} = {p}", backend.name())
                });
                if n == 0.0 {
                    both.ensure(*p == DVec3::ONE, || format!("{} n = 0: pixel {i} = {p}, expected 1", backend.name()));
                }
            }
        }
        // At n = 1e6 the lobe is narrower than a pixel; the nearest pixel still sees ≈ 0.1.
        assert!(cv > 0.05, "n = {n:e}: the scene samples no highlight ({cv})");
        let Some(g) = &both.gpu else {
            say!(out, "  {n:>6.0e}  {cv:>10.6}  {:>10}", "-");
            continue;
        };
        let (gi, gv) = peak(&g.image.pixels);
        let worst = both
            .cpu
            .image
            .pixels
            .iter()
            .zip(&g.image.pixels)
            .filter(|(c, _)| c.x > 1e-3 * cv)
            .map(|(c, g)| ((g.x - c.x) / c.x).abs())
            .fold(0.0, f64::max);
        let tol = tolerance(n);
        say!(
            out,
            "  {n:>6.0e}  {cv:>10.6}  {gv:>10.6}  {:>9}  {worst:>17.2e}  {tol:>10.2e}  {:>8.2e}",
            ci == gi,
            if n > 0.0 { worst / n } else { 0.0 }
        );
        both.ensure(ci == gi, || format!("n = {n:e}: the peak moved from pixel {ci} (CPU) to {gi} (GPU)"));
        both.ensure(worst <= tol, || format!("n = {n:e}: relative error {worst:e} > {tol:e}"));
    }
    eprint!("{out}");
    crate::generated::section("case10-shininess", &out);
}

/// A unit sphere seen from (0, 0, −5) under a directional light travelling along `direction`,
/// specular only (k_a = k_d = 0, k_s = 1, I_s = 1): the pixel is the lobe itself.
fn specular_only(width: u32, direction: [f64; 3], model: &str, shininess: f64) -> SceneText {
    SceneText::new(width, width, "max_depth = 0", [0.0, 0.0, -5.0], [0.0; 3], Y, 30.0)
        .world([0.0; 3], [0.0; 3])
        .material(
            "m",
            &format!("ka = 0.0\nkd = 0.0\nks = 1.0\nshininess = {}\nspecular_model = \"{model}\"", num(shininess)),
        )
        .light("directional", &format!("direction = {direction:?}\ndiffuse = 0.0\nspecular = 1.0"))
        .sphere([0.0; 3], 1.0, "m")
}

/// Both lobes against the independent f64 formulas, n = 0 and 1e6, over a sphere lit from the
/// side (lit and unlit parts, a highlight): n = 0 gives exactly 1 where N·L > 0 and 0 where
/// N·L < 0 on both backends; n = 1e6 matches the formula to 1e-7 on the CPU (x^1e6 turns a
/// few ulps of N·H into 1e6·δ) and within the pow tolerance on the GPU; at the exact mirror
/// configuration (L = V = N) the lobe is exactly 1 for any n.
#[test]
fn both_lobes_at_n_0_and_1e6_match_the_closed_form() {
    for (model, spec) in [("blinn", blinn as fn(_, _, _, _) -> f64), ("phong", phong)] {
        for n in [0.0, 1e6] {
            let flat = specular_only(32, [-1.0, -1.0, 1.0], model, n).flat();
            let both = render_both("stiff/case10", &format!("{model}-n{n:e}"), &flat);
            let l = -w3(flat.lights[0].direction);
            for (backend, img) in both.images() {
                let (mut ones, mut zeros) = (0, 0);
                for y in 0..32 {
                    for x in 0..32 {
                        let (o, d) = primary_ray(&flat, x, y);
                        let Some((t, disc)) = sphere_hit(o, d, DVec3::ZERO, 1.0) else { continue };
                        let normal = (o + t * d).normalize();
                        let ndl = normal.dot(l);
                        if disc < 1e-6 || ndl.abs() < 1e-6 {
                            continue;
                        }
                        let (got, want) = (img.get(x, y), spec(normal, l, -d, n));
                        let at = || format!("{} {model}, n = {n}, ({x}, {y}): {got} vs {want}", backend.name());
                        both.ensure(got.min_element() >= 0.0 && got.max_element() <= 1.0, at);
                        if n == 0.0 {
                            both.ensure(got == DVec3::splat(if ndl > 0.0 { 1.0 } else { 0.0 }), at);
                            if ndl > 0.0 { ones += 1 } else { zeros += 1 }
                        } else {
                            let tol = backend.pick(1e-7, tolerance(n));
                            both.ensure((got.x - want).abs() <= tol * want.max(1e-6), at);
                        }
                    }
                }
                assert!(n > 0.0 || (ones > 100 && zeros > 30), "{model}: {ones} lit, {zeros} unlit pixels");
            }
            // The exact highlight: light along the view axis, the near pole, a 1×1 image.
            let both = render_both(
                "stiff/case10",
                &format!("{model}-n{n:e}-pole"),
                &specular_only(1, [0.0, 0.0, 1.0], model, n).flat(),
            );
            for (backend, img) in both.images() {
                both.ensure(img.get(0, 0) == DVec3::ONE, || {
                    format!("{} {model}: n = {n} at the exact highlight", backend.name())
                });
            }
        }
    }
}
