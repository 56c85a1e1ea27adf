//! Case 28: case 22's unit sphere seen through an orthographic camera — parallel rays from the
//! eye's plane, the view 2·N/(2·R_PX) high so that the disc is R_PX pixels in radius at any
//! distance — along the same oblique axis, at D = 2 … 1e6 from the eye, the sphere near the
//! origin and 3e4 from it.
//!
//! Expected: on both backends the same disc at every D (an orthographic image does not change
//! as the eye moves along its axis): every pixel centre decided as the f64 classification
//! (lateral distance from the axis < 1) decides it except within a thin ring around the
//! silhouette (CPU 1e-6 of the radius, GPU 1e-5; a radius of 20 px puts 12 pixel centres
//! exactly on it, which rounding decides either way), GPU shading as close to the CPU's as at
//! D = 2, and the centre pixel's probe at t = D − 1 from the eye's plane.
//!
//! Why it is stiff: an orthographic camera is the limit of case 22's telephoto. Each ray starts
//! at eye + x·right + y·up: from an eye D away in f32 the start is off by D·6e-8, a pixel at
//! D ≈ 1e6 here, and the direction's error grows over D as well. Remedy, as case 22's: both
//! tracers start the rays on the plane through the view axis's anchor near the scene and reach
//! back to the eye's plane with a negative t_min (`GpuCamera::anchor`); an orthographic camera is
//! anchored whatever its distance (`WorldCamera::stored`, and at its focus on the GPU,
//! `flat::telephoto`).

use glam::DVec3;

use crate::case01_far_sphere::{N, R_PX};
use crate::case22_telephoto::{check_centre, check_disc, check_shading, gpu_shading_inside};
use crate::gpu::render_both;
use crate::scene::SceneText;

const CENTRES: [[f64; 3]; 2] = [[0.3, -0.2, 0.7], [30_000.3, -0.2, 0.7]];
const SIGHT: [f64; 3] = [0.48, -0.36, 0.8];
const CPU_RING: f64 = 1e-6;
const GPU_RING: f64 = 1e-5;

fn unit(v: [f64; 3]) -> [f64; 3] {
    let n = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
    v.map(|c| c / n)
}

/// The view's height: N pixels, R_PX of them the unit radius.
fn view_height() -> f64 {
    f64::from(N) / R_PX
}

fn scene(centre: [f64; 3], distance: f64) -> SceneText {
    let s = unit(SIGHT);
    let eye = std::array::from_fn(|k| centre[k] - distance * s[k]);
    let mut text = SceneText::new(N, N, "max_depth = 0", eye, centre, [0.0, 1.0, 0.0], 45.0);
    text.text.push_str(&format!("projection = \"orthographic\"\nview_height = {:?}\n", view_height()));
    text.world([0.1; 3], [0.0; 3])
        .material("m", "ka = 1.0\nkd = 0.8\nks = 0.5\nshininess = 20.0")
        .light("directional", "direction = [0.3, -1.0, 1.0]")
        .sphere(centre, 1.0, "m")
}

/// Pixel centre (x, y)'s distance from the view axis in units of the radius: < 1 inside.
fn rho(x: u32, y: u32) -> f64 {
    let half = 0.5 * view_height();
    let ndc_x = 2.0 * (f64::from(x) + 0.5) / f64::from(N) - 1.0;
    let ndc_y = 1.0 - 2.0 * (f64::from(y) + 0.5) / f64::from(N);
    (ndc_x * half).hypot(ndc_y * half)
}

#[test]
fn a_sphere_seen_through_an_orthographic_camera_is_the_same_disc_at_every_distance() {
    let mut out = String::new();
    say!(out, "case 28: case 22's sphere through an orthographic camera ({N}x{N}, disc radius {R_PX} px)");
    say!(
        out,
        "  {:>9}  {:>7}  {:>8}  {:>5}  {:>5}  {:>14}  {:>14}  {:>16}",
        "centre x",
        "D",
        "stored",
        "CPU",
        "GPU",
        "CPU worst ring",
        "GPU worst ring",
        "GPU−CPU shading"
    );
    let area = std::f64::consts::PI * R_PX * R_PX;
    let perimeter = 2.0 * std::f64::consts::PI * R_PX;
    let mut base_shading = None;
    for (centre, distance) in CENTRES.into_iter().flat_map(|c| [2.0, 1e2, 1e4, 1e6].map(|d| (c, d))) {
        let text = scene(centre, distance);
        let desc = text.desc();
        let flat = text.flat();
        let both = render_both("stiff/case28", &format!("orthographic-{}-{distance:e}", centre[0]), &flat);
        let what = format!("centre {centre:?}, D = {distance:e}");
        let (counts, worst) = check_disc(&both, rho, (area, perimeter), [CPU_RING, GPU_RING], &what);
        let shading = gpu_shading_inside(&both, rho);
        check_shading(&both, shading, &mut base_shading, &what, "D = 2");
        let gpu = |v: String| if both.gpu.is_some() { v } else { "-".into() };
        say!(
            out,
            "  {:>9.1}  {distance:>7.1e}  {:>8}  {:>5}  {:>5}  {:>14.2e}  {:>14}  {:>16}",
            centre[0],
            if flat.camera.anchor[3] > 0.0 { "anchored" } else { "eye" },
            counts[0],
            gpu(counts[1].to_string()),
            worst[0],
            gpu(format!("{:.2e}", worst[1])),
            shading.map_or("-".into(), |s| format!("{s:.2e}"))
        );
        // The centre pixel meets the near pole at t = D − 1 from the eye's plane, and its ray
        // tree's camera ray leaves the eye.
        check_centre(&flat, DVec3::from(desc.camera.position), distance, &what);
    }
    eprint!("{out}");
    crate::generated::section("case28-orthographic", &out);
}
