//! Stiff and extreme cases on the GPU, each against the CPU reference or a closed form.

use glint_core::layout::NO_HIT;

use super::support::{cpu, flat_from_toml, gpu_or_skip, gpu_render};

fn far_sphere(distance: f64, size: u32, radius_px: f64) -> (String, f64) {
    // fov chosen so that the disc's radius is about radius_px pixels.
    let half = (1.0 / distance).atan() * f64::from(size) / (2.0 * radius_px);
    let fov = 2.0 * half.to_degrees();
    let text = format!(
        "[render]\nwidth = {size}\nheight = {size}\nmax_depth = 0\n\
         [camera]\nposition = [0.0, 0.0, 0.0]\nlook_at = [0.0, 0.0, 1.0]\nfov_y = {fov:?}\n\
         [world]\nambient = 1.0\nbackground = 0.0\n\
         [materials.m]\nka = 1.0\nkd = 0.0\n\
         [[objects]]\ntype = \"sphere\"\ncenter = [0.0, 0.0, {distance:?}]\nradius = 1.0\nmaterial = \"m\"\n"
    );
    // Exact disc radius in pixels: tan of the angular radius over tan of the half fov.
    let r = (1.0f64 / distance).asin().tan() / half.tan() * f64::from(size) / 2.0;
    (text, r)
}

/// A unit sphere at 1e2 … 1e5: a disc on the GPU, its pixel count within one perimeter of the
/// analytic area (the f32 sphere test keeps its accuracy thanks to the stable quadratic).
#[test]
fn far_unit_sphere_is_a_disc() {
    let tracer = gpu_or_skip!();
    for d in [1e2, 1e3, 4.1e3, 1e4, 1e5] {
        let (text, r) = far_sphere(d, 64, 20.0);
        let flat = flat_from_toml(&text);
        let g = gpu_render(tracer, &flat, true);
        let hits = g.image.first_hit.iter().filter(|&&h| h != NO_HIT).count() as f64;
        let area = std::f64::consts::PI * r * r;
        let perimeter = 2.0 * std::f64::consts::PI * r;
        eprintln!("distance {d:e}: {hits} hit pixels, disc area {area:.1}, perimeter {perimeter:.1}");
        assert!((hits - area).abs() <= perimeter, "distance {d:e}: {hits} pixels vs area {area:.1}");
    }
}

fn grazing_plane(mode: &str, epsilon: f64, casts: bool) -> String {
    format!(
        "[render]\nwidth = 64\nheight = 64\nmax_depth = 0\nepsilon = {epsilon:?}\nepsilon_mode = \"{mode}\"\n\
         [camera]\nposition = [0.0, 6.0, -6.0]\nlook_at = [0.0, 0.0, 0.0]\nfov_y = 40.0\n\
         [world]\nambient = 0.0\n\
         [materials.floor]\nka = 0.0\nkd = 1.0\n\
         [[lights]]\ntype = \"point\"\nposition = [-500.0, 5.0, 0.0]\ncasts_shadows = {casts}\n\
         [[objects]]\ntype = \"plane\"\npoint = [0.0, 0.0, 0.0]\nnormal = [0.0, 1.0, 0.0]\nmaterial = \"floor\"\n"
    )
}

/// A point light grazing a plane (h/L = 1e-2) with ε = 0: the robust offset must leave no
/// acne on the GPU either. Acne = a pixel darker with shadows than without (nothing can
/// shadow it but the plane itself). The other strategies' fractions are reported.
#[test]
fn grazing_light_has_no_acne_with_robust_offsets() {
    let tracer = gpu_or_skip!();
    for mode in ["tmin", "nudge_ray", "nudge_normal", "robust"] {
        let lit = gpu_render(tracer, &flat_from_toml(&grazing_plane(mode, 0.0, false)), true);
        let shadowed = gpu_render(tracer, &flat_from_toml(&grazing_plane(mode, 0.0, true)), true);
        let acne =
            lit.image.pixels.iter().zip(&shadowed.image.pixels).filter(|(l, s)| s.x < l.x * (1.0 - 1e-6)).count();
        let fraction = acne as f64 / lit.image.pixels.len() as f64;
        eprintln!("GPU epsilon 0, {mode:<12}: acne on {:.1} % of the pixels", 100.0 * fraction);
        if mode == "robust" {
            assert_eq!(acne, 0, "robust offsets left acne on {acne} pixels");
        }
    }
}

/// Highlights with n = 1e4 and 1e6: finite, the peak on the same pixel as the CPU, and the
/// highlight within the f32 tolerance of pow: x^n amplifies the cosine's f32 error δ ≈ 4 ulp(1)
/// into a relative error of about n·δ (documented in docs/numerics.md).
#[test]
fn sharp_highlights_stay_within_the_f32_pow_tolerance() {
    let tracer = gpu_or_skip!();
    for n in [1e4, 1e6] {
        let text = format!(
            "[render]\nwidth = 64\nheight = 64\nmax_depth = 0\n\
             [camera]\nposition = [0.0, 0.0, -4.0]\nlook_at = [0.0, 0.0, 0.0]\nfov_y = 4.0\n\
             [world]\nambient = 0.0\n\
             [materials.m]\nka = 0.0\nkd = 0.0\nks = 1.0\nshininess = {n:?}\n\
             [[lights]]\ntype = \"directional\"\ndirection = [0.01, 0.0, 1.0]\n\
             [[objects]]\ntype = \"sphere\"\ncenter = [0.0, 0.0, 0.0]\nradius = 1.0\nmaterial = \"m\"\n"
        );
        let flat = flat_from_toml(&text);
        let c = cpu(&flat);
        let g = gpu_render(tracer, &flat, true);
        let peak = |px: &[glam::DVec3]| {
            px.iter().enumerate().max_by(|a, b| a.1.x.total_cmp(&b.1.x)).map(|(i, p)| (i, p.x)).unwrap()
        };
        let (ci, cv) = peak(&c.image.pixels);
        let (gi, gv) = peak(&g.image.pixels);
        let tolerance = (n * 4.0 * f64::from(f32::EPSILON)).min(1.0);
        let worst = c
            .image
            .pixels
            .iter()
            .zip(&g.image.pixels)
            .filter(|(c, _)| c.x > 1e-3 * cv)
            .map(|(c, g)| ((g.x - c.x) / c.x).abs())
            .fold(0.0, f64::max);
        eprintln!(
            "n = {n:e}: CPU peak {cv:.6} at {ci}, GPU peak {gv:.6} at {gi}; worst relative error {worst:.2e} (tolerance {tolerance:.2e})"
        );
        // At n = 1e6 the lobe is narrower than a pixel; the nearest pixel still sees 0.12.
        assert!(cv > 0.05, "n = {n:e}: the test scene samples no highlight ({cv})");
        assert_eq!(ci, gi, "n = {n:e}: peak pixel moved");
        assert!(worst <= tolerance, "n = {n:e}: relative error {worst:e} > {tolerance:e}");
    }
}

/// L = −V: the half vector vanishes; the specular term must be 0, not NaN.
#[test]
fn light_opposite_the_viewer_gives_no_nan() {
    let tracer = gpu_or_skip!();
    let text = "[render]\nwidth = 16\nheight = 16\nmax_depth = 0\n\
        [camera]\nposition = [0.0, 3.0, 0.0]\nlook_at = [0.0, 0.0, 0.0]\nup = [0.0, 0.0, 1.0]\nfov_y = 20.0\n\
        [world]\nambient = 0.0\n\
        [materials.m]\nka = 0.0\nkd = 0.5\nks = 1.0\nshininess = 10.0\n\
        [[lights]]\ntype = \"directional\"\ndirection = [0.0, 1.0, 0.0]\n\
        [[objects]]\ntype = \"plane\"\npoint = [0.0, 0.0, 0.0]\nnormal = [0.0, 1.0, 0.0]\nmaterial = \"m\"\n";
    let flat = flat_from_toml(text);
    let g = gpu_render(tracer, &flat, true);
    let c = cpu(&flat);
    assert!(g.image.pixels.iter().all(|p| *p == glam::DVec3::ZERO), "light from behind must give 0");
    assert_eq!(c.image.pixels, g.image.pixels);
}

/// Two facing perfect mirrors (k_r = 1) at depth 32 with bailout 0: finite, bounded by the sum
/// of 33 local terms, and equal to the CPU within f32 accumulation error.
#[test]
fn facing_mirrors_at_depth_32_stay_bounded() {
    let tracer = gpu_or_skip!();
    let text = "[render]\nwidth = 32\nheight = 32\nmax_depth = 32\nbailout = 0.0\n\
        [camera]\nposition = [0.0, 0.0, 0.0]\nlook_at = [0.0, 0.0, 1.0]\nfov_y = 30.0\n\
        [world]\nambient = 0.25\n\
        [materials.mirror]\nka = 0.1\nkd = 0.0\nkr = 1.0\n\
        [[objects]]\ntype = \"plane\"\npoint = [0.0, 0.0, 1.0]\nnormal = [0.0, 0.0, -1.0]\nmaterial = \"mirror\"\n\
        [[objects]]\ntype = \"plane\"\npoint = [0.0, 0.0, -1.0]\nnormal = [0.0, 0.0, 1.0]\nmaterial = \"mirror\"\n";
    let flat = flat_from_toml(text);
    let g = gpu_render(tracer, &flat, true);
    let c = cpu(&flat);
    let bound = 33.0 * 0.25 * 0.1;
    for (cp, gp) in c.image.pixels.iter().zip(&g.image.pixels) {
        assert!(gp.max_element() <= bound * (1.0 + 1e-5), "{gp} exceeds {bound}");
        assert!((*gp - *cp).abs().max_element() <= 1e-5, "GPU {gp} vs CPU {cp}");
    }
    assert_eq!(g.status, 0, "the stack or loop bound was hit");
    assert_eq!(g.counts.reflection, c.counts.reflection);
}
