//! Stiff cases on the CPU tracer: extreme distances, grazing light with ε = 0, extreme
//! exponents, degenerate vectors, lights almost on a surface, deep mirror recursion. Every
//! render goes through `support::render`, which fails on any NaN or infinite pixel.

use glam::DVec3;
use glint_core::layout::NO_HIT;
use glint_core::scene::EpsilonMode;

use crate::support::{SceneText, assert_rel, blinn, num, phong, plane_hit, primary_ray, probe, render, sphere_hit, w3};

const Y: [f64; 3] = [0.0, 1.0, 0.0];
const Z: [f64; 3] = [0.0, 0.0, 1.0];

#[test]
fn unit_sphere_far_away_is_found() {
    const N: u32 = 65; // odd: the centre pixel looks exactly along the axis
    const R_PX: f64 = 20.0; // wanted disc radius in pixels
    eprintln!("unit sphere at distance D: hit pixels vs the analytic disc (radius {R_PX} px)");
    for distance in [1e2, 1e3, 1e4, 1e5, 1e6] {
        // Angular radius α of the sphere: sin α = 1/D. The disc of radius R_PX needs
        // tan(fov/2) = tan α · (N/2) / R_PX.
        let tan_alpha = 1.0 / (distance * distance - 1.0_f64).sqrt();
        let fov = (2.0 * (tan_alpha * f64::from(N) / 2.0 / R_PX).atan()).to_degrees();
        let flat = SceneText::new(N, N, "max_depth = 0", [0.0; 3], [0.0, 0.0, distance], Y, fov)
            .world([0.1; 3], [0.0; 3])
            .material("m", "ka = 1.0\nkd = 0.8\nks = 0.5")
            .light("directional", "direction = [0.3, -1.0, 1.0]")
            .sphere([0.0, 0.0, distance], 1.0, "m")
            .flat();
        let img = render(&flat).image;
        // Classify every pixel centre from the stored camera vectors: the ray through NDC
        // (x, y) makes an angle with the axis whose tangent is |x·right + y·up| (forward is
        // unit and orthogonal to both); it hits iff that tangent is below tan α.
        let (half_w, half_h) = (w3(flat.camera.right).length(), w3(flat.camera.up).length());
        let mut count = 0usize;
        for y in 0..N {
            for x in 0..N {
                let hit = img.first_hit[(y * N + x) as usize] != NO_HIT;
                count += usize::from(hit);
                let ndc_x = 2.0 * (f64::from(x) + 0.5) / f64::from(N) - 1.0;
                let ndc_y = 1.0 - 2.0 * (f64::from(y) + 0.5) / f64::from(N);
                let rho = (ndc_x * half_w).hypot(ndc_y * half_h) / tan_alpha;
                if rho < 1.0 - 1e-6 {
                    assert!(hit, "D = {distance:e}: pixel ({x}, {y}) at {rho:.6} of the disc radius is missed");
                } else if rho > 1.0 + 1e-6 {
                    assert!(!hit, "D = {distance:e}: pixel ({x}, {y}) at {rho:.6} of the disc radius is hit");
                }
            }
        }
        let r_px = tan_alpha / half_h * f64::from(N) / 2.0;
        let area = std::f64::consts::PI * r_px * r_px;
        let perimeter = 2.0 * std::f64::consts::PI * r_px;
        eprintln!("  D = {distance:>7.0e}: {count:>5} px, analytic {area:>8.1} px, allowed ± {perimeter:.1}");
        assert!((count as f64 - area).abs() <= perimeter, "D = {distance:e}: {count} hit pixels vs disc area {area}");
        // The centre pixel hits the near pole at t = D − 1.
        let b = probe(&flat, N / 2, N / 2);
        let rel = (b.t - (distance - 1.0)).abs() / (distance - 1.0);
        assert!(rel < 1e-12, "D = {distance:e}: t = {} (relative error {rel:e})", b.t);
    }
}

/// Renders a slightly tilted plane lit at a grazing angle (about 1.3°) by a point light, with
/// ε = 0, and returns (lit pixels, acne pixels): lit pixels whose radiance is darker than the
/// unshadowed analytic value (nothing can shadow a plane but the plane itself).
fn grazing_acne(mode: EpsilonMode) -> (usize, usize) {
    let (ia, ka, kd) = (0.125, 1.0, 0.75);
    let light = DVec3::new(-1.0, 0.9, 40.0);
    let flat = SceneText::new(
        64,
        48,
        &format!("max_depth = 0\nepsilon = 0.0\nepsilon_mode = \"{}\"", mode.name()),
        [0.3, 1.5, -2.0],
        [0.0, 0.2, 6.0],
        Y,
        60.0,
    )
    .world([ia; 3], [0.0; 3])
    .material("floor", &format!("ka = {}\nkd = {}\nks = 0.0", num(ka), num(kd)))
    .light("point", &format!("position = [{:?}, {:?}, {:?}]", light.x, light.y, light.z))
    .plane([0.0, 0.37, 0.0], [0.02, 1.0, 0.01], "floor")
    .flat();
    let img = render(&flat).image;
    let plane = flat.planes[0].normal_offset;
    let (n, k) = (w3(plane), f64::from(plane[3]));
    let (mut lit, mut acne) = (0, 0);
    for y in 0..48 {
        for x in 0..64 {
            let (o, d) = primary_ray(&flat, x, y);
            let Some(t) = plane_hit(o, d, n, k) else { continue };
            let p = o + t * d;
            let ndl = n.dot((light - p).normalize());
            if ndl <= 1e-9 || img.first_hit[(y * 64 + x) as usize] == NO_HIT {
                continue;
            }
            lit += 1;
            let unshadowed = ia * ka + kd * ndl;
            let got = img.get(x, y);
            assert!(got.max_element() <= unshadowed * (1.0 + 1e-6), "pixel ({x}, {y}) brighter than possible");
            if got.x < unshadowed * (1.0 - 1e-6) {
                acne += 1;
            }
        }
    }
    (lit, acne)
}

#[test]
fn grazing_light_with_zero_epsilon_acne_per_strategy() {
    let mut table = Vec::new();
    for mode in EpsilonMode::ALL {
        let (lit, acne) = grazing_acne(mode);
        assert!(lit > 1000, "{}: only {lit} lit pixels", mode.name());
        table.push((mode, lit, acne));
    }
    eprintln!("self-shadowing acne, plane lit at ~1.3° grazing by a point light, ε = 0:");
    eprintln!("  {:<14} {:>6} {:>6} {:>8}", "strategy", "lit", "acne", "fraction");
    for (mode, lit, acne) in &table {
        eprintln!("  {:<14} {:>6} {:>6} {:>7.1}%", mode.name(), lit, acne, 100.0 * *acne as f64 / *lit as f64);
    }
    let acne_of = |m: EpsilonMode| table.iter().find(|(mode, ..)| *mode == m).map(|t| t.2).unwrap();
    assert_eq!(acne_of(EpsilonMode::Robust), 0, "the robust offset must not self-shadow");
    // Otherwise this scene does not exercise self-intersection at all.
    assert!(acne_of(EpsilonMode::Tmin) > 0, "tmin with ε = 0 shows no acne: the scene is not stiff enough");
}

/// A sphere seen from (0, 0, −5) under a directional light travelling along `direction`, with
/// only a specular term (k_a = k_d = 0, k_s = 1, I_s = 1): the pixel is spec_j itself.
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

#[test]
fn shininess_zero_gives_one_wherever_lit() {
    for (model, spec) in [("blinn", blinn as fn(_, _, _, _) -> f64), ("phong", phong)] {
        let flat = specular_only(32, [-1.0, -1.0, 1.0], model, 0.0).flat();
        let img = render(&flat).image;
        let l = -w3(flat.lights[0].direction);
        let (mut ones, mut zeros) = (0, 0);
        for y in 0..32 {
            for x in 0..32 {
                let (o, d) = primary_ray(&flat, x, y);
                let Some((t, disc)) = sphere_hit(o, d, DVec3::ZERO, 1.0) else { continue };
                let ndl = (o + t * d).normalize().dot(l);
                if disc < 1e-6 || ndl.abs() < 1e-6 {
                    continue;
                }
                let want = if ndl > 0.0 { 1.0 } else { 0.0 };
                assert_eq!(spec((o + t * d).normalize(), l, -d, 0.0), want, "reference formula");
                assert_eq!(img.get(x, y), DVec3::splat(want), "{model}, n = 0, pixel ({x}, {y}), N·L = {ndl}");
                if ndl > 0.0 { ones += 1 } else { zeros += 1 }
            }
        }
        assert!(ones > 100 && zeros > 30, "{model}: {ones} lit, {zeros} unlit pixels");
    }
}

#[test]
fn shininess_a_million_is_finite_and_exact() {
    for (model, spec) in [("blinn", blinn as fn(_, _, _, _) -> f64), ("phong", phong)] {
        let flat = specular_only(32, [-1.0, -1.0, 1.0], model, 1e6).flat();
        let img = render(&flat).image;
        let l = -w3(flat.lights[0].direction);
        for y in 0..32 {
            for x in 0..32 {
                let (o, d) = primary_ray(&flat, x, y);
                let Some((t, disc)) = sphere_hit(o, d, DVec3::ZERO, 1.0) else { continue };
                if disc < 1e-6 {
                    continue;
                }
                let n = (o + t * d).normalize();
                if n.dot(l).abs() < 1e-6 {
                    continue;
                }
                // x^1e6 amplifies a relative error δ of x to 1e6·δ: 1e-7 leaves room for a few
                // ULPs of difference between two correct computations of N·H.
                let got = img.get(x, y);
                assert!(got.min_element() >= 0.0 && got.max_element() <= 1.0, "{model}: ({x}, {y}) = {got}");
                assert_rel(got, DVec3::splat(spec(n, l, -d, 1e6)), 1e-7, &format!("{model}, n = 1e6, ({x}, {y})"));
            }
        }
        // At the exact mirror configuration the lobe is 1 for any n: light along the view
        // axis (L = V = N at the near pole of the sphere, the centre of a 1×1 image).
        let b = probe(&specular_only(1, [0.0, 0.0, 1.0], model, 1e6).flat(), 0, 0);
        assert_eq!(b.total, DVec3::ONE, "{model}: n = 1e6 at the exact highlight");
    }
}

#[test]
fn light_opposite_the_viewer_gives_no_specular_and_no_nan() {
    // L = −V: the light is exactly behind the viewed point. H = (L + V)/|L + V| is 0/0.
    for model in ["blinn", "phong"] {
        for n in [0.0, 1.0, 32.0, 1e6] {
            let mat = format!("ka = 0.5\nkd = 0.5\nks = 1.0\nshininess = {}\nspecular_model = \"{model}\"", num(n));
            let base = || {
                SceneText::pinhole("max_depth = 0", [0.0, 0.0, -5.0], [0.0; 3], Y)
                    .world([0.25; 3], [0.0; 3])
                    .material("m", &mat)
                    .light("directional", "direction = [0.0, 0.0, -1.0]\nambient = 0.5")
            };
            let ambient_only = DVec3::splat(0.25 * 0.5 + 0.5 * 0.5);
            // Sphere and plane (seen from its back side: the two-sided normal turns to the
            // viewer, away from the light): N·L = −1, so no diffuse and no specular.
            for (what, scene) in
                [("sphere", base().sphere([0.0; 3], 1.0, "m")), ("plane back face", base().plane([0.0; 3], Z, "m"))]
            {
                let b = probe(&scene.flat(), 0, 0);
                let at = format!("{what}, {model}, n = {n}");
                assert_eq!(b.lights[0].specular, DVec3::ZERO, "{at}");
                assert_eq!(b.lights[0].diffuse, DVec3::ZERO, "{at}");
                assert_rel(b.total, ambient_only, 1e-12, &at);
                assert_eq!(render(&scene.flat()).image.get(0, 0), b.total, "{at}");
            }
            if n > 0.0 {
                // A triangle whose vertex normals point away from the viewer, towards the light
                // (against its winding on purpose; validation only warns): N·L = 1 > 0, so the
                // specular term is evaluated with L + V = 0 exactly.
                let tri = [[[-1.0, -1.0, 0.0], [0.0, 1.0, 0.0], [1.0, -1.0, 0.0]]];
                let scene = base().triangles(&tri, Some(&[Z, Z, Z]), "m");
                let b = probe(&scene.flat(), 0, 0);
                let at = format!("shading normals away from the viewer, {model}, n = {n}");
                assert!(b.total.is_finite(), "{at}: {}", b.total);
                assert_eq!(b.lights[0].specular, DVec3::ZERO, "{at}");
                render(&scene.flat());
            }
        }
    }
}

#[test]
fn light_almost_on_the_surface_stays_finite() {
    // A point light 1e-9 above a floor (and one exactly on it), under every epsilon strategy
    // and two epsilons. The centre pixel of the 9×9 view hits the origin, straight below.
    for mode in EpsilonMode::ALL {
        for eps in [0.0, 1e-6] {
            for (height, attenuation) in
                [(1e-9, "{ c = 1.0 }"), (1e-9, "{ c = 1.0, l = 1.0, q = 1.0 }"), (0.0, "{ c = 1.0 }")]
            {
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
                let img = render(&flat).image;
                // f_att ≤ 1, N·L ≤ 1, spec ≤ 1.
                let max = 0.125 * 0.5 + 0.75 + 0.5;
                let at = format!("{}, ε = {eps}, light at height {height}, attenuation {attenuation}", mode.name());
                for p in &img.pixels {
                    assert!(p.min_element() >= 0.0 && p.max_element() <= max * (1.0 + 1e-12), "{at}: {p}");
                }
                if height > 0.0 && mode == EpsilonMode::Robust {
                    // Straight below the light: N·L = 1, f_att = 1/(c + l·1e-9 + q·1e-18).
                    let d = f64::from(flat.lights[0].position[1]);
                    let f_att = if attenuation.contains("q") { 1.0 / (1.0 + d + d * d) } else { 1.0 };
                    let want = 0.125 * 0.5 + f_att * (0.75 + 0.5);
                    assert_rel(img.get(4, 4), DVec3::splat(want), 1e-9, &at);
                }
            }
        }
    }
}

/// Two parallel mirrors (planes z = 0 and z = 4, k_r = 1, plus k_a = k_d = 1/2), a point
/// light between them, depth 32, bailout 0. Global ambient 1/8 (exact in f32).
fn facing_mirrors(kr: f64, width: u32, position: [f64; 3], look_at: [f64; 3]) -> SceneText {
    SceneText::new(width, width, "max_depth = 32\nbailout = 0.0", position, look_at, Y, 60.0)
        .world([0.125; 3], [0.0; 3])
        .material("mirror", &format!("ka = 0.5\nkd = 0.5\nks = 0.0\nkr = {}", num(kr)))
        .light("point", "position = [0.0, 3.0, 1.0]")
        .plane([0.0; 3], Z, "mirror")
        .plane([0.0, 0.0, 4.0], [0.0, 0.0, -1.0], "mirror")
}

#[test]
fn facing_mirrors_at_depth_32_are_finite_and_bounded() {
    // Along the axis: the ray from (0, 0, 1) bounces between (0, 0, 4) and (0, 0, 0). With
    // k_r = 1 every one of the 33 hits (depths 0..=32) adds its local term in full: 17 at
    // z = 4 and 16 at z = 0.
    let light = DVec3::new(0.0, 3.0, 1.0);
    let local = |p: DVec3, n: DVec3| 0.125 * 0.5 + 0.5 * n.dot((light - p).normalize());
    let a = local(DVec3::new(0.0, 0.0, 4.0), DVec3::new(0.0, 0.0, -1.0));
    let b = local(DVec3::ZERO, DVec3::Z);
    let flat = facing_mirrors(1.0, 1, [0.0, 0.0, 1.0], [0.0, 0.0, 2.0]).flat();
    let r = render(&flat);
    assert_rel(r.image.get(0, 0), DVec3::splat(17.0 * a + 16.0 * b), 1e-9, "on-axis bounce sum");
    assert_eq!((r.counts.reflection, r.counts.bailout_saved), (32, 0));

    // Oblique views: every pixel is bounded by the geometric series of its local terms,
    // Σ_{k=0..32} k_r^k · max local (max local = I_a·k_a + I_d·k_d), and with k_r = 1 at
    // least 33 ambient terms.
    for kr in [1.0, 0.5] {
        let flat = facing_mirrors(kr, 24, [0.2, 0.1, 1.0], [1.0, 0.5, 4.0]).flat();
        let img = render(&flat).image;
        let series: f64 = (0..=32).map(|k| kr.powi(k)).sum();
        let upper = series * (0.125 * 0.5 + 0.5);
        let lower = if kr == 1.0 { 33.0 * 0.125 * 0.5 } else { 0.0 };
        for (i, p) in img.pixels.iter().enumerate() {
            assert!(
                p.min_element() >= lower * (1.0 - 1e-12) && p.max_element() <= upper * (1.0 + 1e-12),
                "k_r = {kr}, pixel {i} = {p}, allowed [{lower}, {upper}]"
            );
        }
    }
}
