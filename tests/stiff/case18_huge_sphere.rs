//! Case 18: a sphere of radius 1e6 seen from 1 unit above its surface (a planet's ground seen by
//! someone standing on it), lit by a point light 1.5 units above the ground.
//!
//! Expected: the GPU's radiance within 1e-3 relative of the CPU's on every pixel whose camera ray
//! descends more steeply than 1° (the f32 storage is exact here: centre, radius and eye are
//! integers, so any difference is arithmetic). At 1° the ray meets the ground 57 units away.
//!
//! The cancellation: for a ray starting near the surface, c = |o − C|² − r² is ≈ 2·r·h = 2e6
//! while |o − C|² ≈ 1e12, whose f32 ulp is 65,536: the textbook c is off by percents, and so
//! are t and the hit point; the robust offset's re-projection C + r·n carries ulp(1e6) = 0.06
//! units of error, enough to start a shadow ray below the ground. The remedy is in
//! docs/numerics.md ("Cancellation in the f32 twins").

use glint_types::layout::NO_HIT;

use crate::gpu::render_both;
use crate::reference::primary_ray;
use crate::rel_err;
use crate::scene::SceneText;

const W: u32 = 64;
const H: u32 = 48;
pub const RADIUS: f64 = 1e6;
/// The bound on the relative radiance error of rays steeper than 1°.
const REL_GPU: f64 = 1e-3;
const STEEPER_THAN_DEG: f64 = 1.0;

pub fn scene() -> SceneText {
    SceneText::new(W, H, "max_depth = 2\nepsilon = 0.0", [0.0, 1.0, 0.0], [0.0, -0.5, 3.0], [0.0, 1.0, 0.0], 60.0)
        .world([0.0; 3], [0.0; 3])
        .material("ground", "ka = 0.0\nkd = [0.75, 0.5, 0.25]\nks = 0.5\nshininess = 32.0\nkr = 0.0")
        .light("point", "position = [0.5, 1.5, 4.0]\ndiffuse = 1.0\nspecular = 1.0")
        .sphere([0.0, -RADIUS, 0.0], RADIUS, "ground")
}

/// Worst relative radiance error of the GPU against the CPU over the hit pixels whose ray
/// descends more steeply than 1°, and how many pixels that is. `None` without a GPU.
pub fn worst_steep_error() -> Option<(f64, usize)> {
    let flat = scene().flat();
    let both = render_both("stiff/case18", "huge-sphere", &flat);
    let gpu = both.gpu.as_ref()?;
    let (mut worst, mut count) = (0.0_f64, 0usize);
    let sin_min = STEEPER_THAN_DEG.to_radians().sin();
    for y in 0..H {
        for x in 0..W {
            let i = (y * W + x) as usize;
            let (_, d) = primary_ray(&flat, x, y);
            if d.y > -sin_min || both.cpu.image.first_hit[i] == NO_HIT {
                continue;
            }
            both.ensure(gpu.image.first_hit[i] != NO_HIT, || format!("pixel ({x}, {y}) misses the ground on the GPU"));
            count += 1;
            let (a, b) = (both.cpu.image.pixels[i], gpu.image.pixels[i]);
            for c in 0..3 {
                worst = worst.max(rel_err(b[c], a[c]));
            }
        }
    }
    both.ensure(worst <= REL_GPU, || format!("GPU radiance off by {worst:.3e} relative (> {REL_GPU:e})"));
    Some((worst, count))
}

#[test]
fn ground_of_a_huge_sphere_shades_as_on_the_cpu() {
    if let Some((worst, count)) = worst_steep_error() {
        let mut out = String::new();
        say!(
            out,
            "case 18: sphere of radius {RADIUS:.0e} seen from 1 above its surface, {W}x{H}, a point light 1.5 above it"
        );
        say!(
            out,
            "  pixels steeper than {STEEPER_THAN_DEG}°: {count}; worst GPU radiance error relative to the CPU: {worst:.2e}"
        );
        eprint!("{out}");
        crate::generated::section("case18-huge-sphere", &out);
    }
}
