//! Case 7: axis-parallel rays and rays exactly parallel to a plane.
//!
//! An odd-sized image looking along +z: its centre row has d.y = 0 exactly, its centre column
//! d.x = 0, its centre pixel d = (0, 0, 1). In view are a floor (y = 0, parallel to the centre
//! row), a side wall (x = 2, parallel to the centre column), a sphere on the axis, and two
//! triangles seen exactly edge-on (one in the plane y = 1 of the centre row, one in the plane
//! x = 0 of the centre column). One directional light travels straight down (axis-parallel
//! shadow rays, parallel to the walls), one exactly parallel to the floor (N·L = 0 there; its
//! shadow rays from the side wall run parallel to the floor and, at y = 1, inside the plane of
//! the edge-on triangle). A second view looks straight down the −y axis.
//!
//! Expected, on both backends: no NaN or infinity (a division by zero would show as one, or as
//! a spurious hit); the parallel rays miss the planes and the edge-on triangles (which no pixel
//! may show); the axis ray meets the sphere at t = 19 (CPU: exactly); every pixel equals the
//! closed form of what it sees, the same object on both backends.

use glam::DVec3;

use crate::gpu::render_both;
use crate::reference::{assert_rel, plane_hit, primary_ray, probe};
use crate::scene::SceneText;
use crate::{Y, Z};

const N: u32 = 33;
const C: u32 = N / 2;

fn scene(position: [f64; 3], look_at: [f64; 3], up: [f64; 3]) -> SceneText {
    SceneText::new(N, N, "max_depth = 0", position, look_at, up, 60.0)
        .world([0.25; 3], [0.0; 3])
        .material("floor", "ka = 1.0\nkd = 0.5\nks = 0.0")
        .material("wall", "ka = 1.0\nkd = 0.25\nks = 0.0")
        .material("ball", "ka = 1.0\nkd = 0.0\nks = 0.0")
        .light("directional", "direction = [0.0, -1.0, 0.0]")
        .light("directional", "direction = [1.0, 0.0, 0.0]")
        .plane([0.0; 3], Y, "floor") // 0
        .plane([2.0, 0.0, 0.0], [-1.0, 0.0, 0.0], "wall") // 1
        .sphere([0.0, 1.0, 20.0], 1.0, "ball") // 2
        .triangles(&[[[-3.0, 1.0, 4.0], [3.0, 1.0, 4.0], [0.0, 1.0, 10.0]]], None, "wall") // 3
        .triangles(&[[[0.0, -1.0, 4.0], [0.0, 3.0, 4.0], [0.0, 1.0, 9.0]]], None, "wall") // 4
}

/// Signed distance of (x, y) from the triangle's boundary, positive inside (the triangles are
/// given counter-clockwise).
fn inside_2d(p: (f64, f64), t: [(f64, f64); 3]) -> f64 {
    (0..3)
        .map(|i| {
            let (a, b) = (t[i], t[(i + 1) % 3]);
            let (ex, ey) = (b.0 - a.0, b.1 - a.1);
            (ex * (p.1 - a.1) - ey * (p.0 - a.0)) / ex.hypot(ey)
        })
        .fold(f64::INFINITY, f64::min)
}

/// Whether a point is (certainly) shadowed: > 0 shadowed, < 0 lit, 0 too close to call.
fn shadow_sign(inside_tri: f64, radial: f64, margin: f64) -> i32 {
    let s = inside_tri.max(1.0 - radial); // > 0: inside the triangle or the sphere's disc
    if s > margin {
        1
    } else if s < -margin {
        -1
    } else {
        0
    }
}

/// The closed form of a pixel that sees `id` at `p`: I_a·k_a + Σ_j V_j·max(N·L_j, 0)·k_d. The
/// floor (N·L = 1, 0) is shadowed from the downward light by the edge-on triangle in y = 1 and
/// by the sphere; the side wall (N·L = 0, 1) from the sideways light by the triangle in x = 0
/// and by the sphere. `None` where no closed form applies or the shadow boundary is too close.
fn expected(id: u32, p: DVec3) -> Option<f64> {
    let m = 1e-4;
    match id {
        0 => {
            let tri = [(-3.0, 4.0), (3.0, 4.0), (0.0, 10.0)];
            let v = shadow_sign(inside_2d((p.x, p.z), tri), p.x.hypot(p.z - 20.0), m);
            (v != 0).then_some(0.25 + if v > 0 { 0.0 } else { 0.5 })
        }
        1 => {
            let tri = [(-1.0, 4.0), (3.0, 4.0), (1.0, 9.0)];
            let v = shadow_sign(inside_2d((p.y, p.z), tri), (p.y - 1.0).hypot(p.z - 20.0), m);
            (v != 0).then_some(0.25 + if v > 0 { 0.0 } else { 0.25 })
        }
        _ => None,
    }
}

/// Where the pixel's ray meets the object `id` (the floor or the side wall).
fn point_on(flat: &glint_core::FlatScene, x: u32, y: u32, id: u32) -> DVec3 {
    let (o, d) = primary_ray(flat, x, y);
    let t = match id {
        0 => plane_hit(o, d, DVec3::Y, 0.0),
        _ => plane_hit(o, d, -DVec3::X, -2.0),
    };
    o + t.expect("the pixel sees the plane") * d
}

#[test]
fn axis_parallel_rays_and_rays_parallel_to_planes() {
    let flat = scene([0.0, 1.0, 0.0], [0.0, 1.0, 5.0], Y).flat();
    let both = render_both("stiff/case07", "parallel-rays", &flat);
    let mut worst = [0.0_f64; 2];
    for (backend, img) in both.images() {
        let name = backend.name();
        for i in 0..N {
            let row = img.first_hit[(C * N + i) as usize];
            let col = img.first_hit[(i * N + C) as usize];
            both.ensure(row != 0, || format!("{name}: centre-row pixel {i} (d.y = 0) hit the floor"));
            both.ensure(col != 1, || format!("{name}: centre-column pixel {i} (d.x = 0) hit the side wall"));
        }
        let mut checked = 0;
        for (i, &id) in img.first_hit.iter().enumerate() {
            both.ensure(id != 3 && id != 4, || format!("{name}: pixel {i} shows an edge-on triangle ({id})"));
            if id > 1 {
                continue;
            }
            let (x, y) = (i as u32 % N, i as u32 / N);
            if let Some(want) = expected(id, point_on(&flat, x, y, id)) {
                // Measured 0 on both: every quantity here is a small dyadic number.
                let tol = backend.pick(1e-12, 1e-6);
                let got = img.pixels[i];
                worst[backend as usize] = worst[backend as usize].max((got - DVec3::splat(want)).abs().max_element());
                both.ensure((got - DVec3::splat(want)).abs().max_element() <= tol, || {
                    format!("{name}: pixel ({x}, {y}) on object {id} = {got}, expected {want}")
                });
                checked += 1;
            }
        }
        both.ensure(checked > N * N / 2, || format!("{name}: only {checked} pixels have a closed form"));
        both.ensure(img.first_hit[(C * N + C) as usize] == 2, || format!("{name}: the axis ray missed the sphere"));
    }
    // The floor and the side wall meet in the line y = 0, x = 2, and some pixel rays pass
    // exactly through it (ndc_x = −2·ndc_y): a tie, t_floor = t_wall to 1e-15, that rounding
    // decides. Everywhere else the first hits agree.
    for &i in &both.first_hit_mismatches() {
        let (x, y) = (i as u32 % N, i as u32 / N);
        let (o, d) = primary_ray(&flat, x, y);
        let (tf, tw) = (plane_hit(o, d, DVec3::Y, 0.0), plane_hit(o, d, -DVec3::X, -2.0));
        let tie = matches!((tf, tw), (Some(a), Some(b)) if (a - b).abs() <= 1e-9 * a);
        both.ensure(tie, || format!("({x}, {y}): first hits differ off the floor/wall corner (t {tf:?} / {tw:?})"));
    }
    eprintln!("case 7: parallel rays, worst |pixel − closed form|: CPU {:.1e}, GPU {:.1e}", worst[0], worst[1]);
    let b = probe(&flat, C, C);
    assert_eq!(b.t, 19.0, "the axis ray meets the sphere at t = 19");
    assert_rel(b.total, DVec3::splat(0.25), 0.0, "the sphere is ambient only");

    // Straight down the −y axis onto the floor: t = 5 exactly, N·L = 1.
    let flat = scene([0.3, 5.0, 0.2], [0.3, 0.0, 0.2], Z).flat();
    let both = render_both("stiff/case07", "looking-down", &flat);
    for (backend, img) in both.images() {
        both.ensure(img.first_hit[(C * N + C) as usize] == 0, || {
            format!("{}: the downward axis ray missed the floor", backend.name())
        });
    }
    let b = probe(&flat, C, C);
    assert_eq!((b.t, b.total), (5.0, DVec3::splat(0.75)), "downward axis ray");
}
