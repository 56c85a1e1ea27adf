//! The world's global attenuation of reflected and transmitted terms, closed form on the CPU:
//! a mirror facing a wall, and a clear sheet in front of one. The wall's radiance L_w is its
//! emission plus its ambient term (no lights), so the pixel is exactly k·f_att(d)·L_w, with d
//! the distance the child ray travels from the mirror (or sheet) to the wall, computed here
//! from the stored planes.

use glam::DVec3;
use glint_core::FlatScene;
use glint_types::layout::feature;

use crate::support::{SceneText, assert_rel, dv, plane_hit, primary_ray, render, w3};

const REL: f64 = 1e-9;
const I_A: [f64; 3] = [0.25, 0.5, 0.125];
const E_W: [f64; 3] = [0.5, 0.25, 1.0];
const K: [f64; 3] = [0.75, 0.5, 0.25];
const ATT: [f64; 3] = [0.5, 0.25, 0.125];
const Z: [f64; 3] = [0.0, 0.0, 1.0];

/// The camera at the origin looks along +z at `front` (z = `front_z`), behind which or in front
/// of which the wall (z = `wall_z`, facing the camera's side) stands.
fn scene(front: &str, front_z: f64, wall_z: f64, attenuation: Option<[f64; 3]>) -> FlatScene {
    let s = SceneText::new(16, 16, "max_depth = 1\nbailout = 0.0\nepsilon = 0.0", [0.0; 3], Z, [0.0, 1.0, 0.0], 30.0);
    let s = match attenuation {
        Some(att) => s.world_attenuated(I_A, [0.0; 3], att),
        None => s.world(I_A, [0.0; 3]),
    };
    let wall_normal = if wall_z < front_z { Z } else { [0.0, 0.0, -1.0] };
    s.material("front", front)
        .material("wall", &format!("ka = 1.0\nkd = 0.0\nks = 0.0\nemission = {E_W:?}"))
        .plane([0.0, 0.0, front_z], [0.0, 0.0, -1.0], "front")
        .plane([0.0, 0.0, wall_z], wall_normal, "wall")
        .flat()
}

/// Every pixel against k·f_att(d)·L_w; `bend` turns the camera ray at the front plane (the
/// mirror) or not (the sheet of ior 1).
fn check(flat: &FlatScene, mirror: bool, attenuated: bool) {
    let img = render(flat).image;
    let (front, wall) = (flat.planes[0].normal_offset, flat.planes[1].normal_offset);
    let g = flat.header.global_attenuation.map(f64::from);
    let l_w = dv(E_W) + dv(I_A);
    let k = dv(K);
    for y in 0..16 {
        for x in 0..16 {
            let (o, d) = primary_ray(flat, x, y);
            let t = plane_hit(o, d, w3(front), f64::from(front[3])).expect("the front plane fills the view");
            let p = o + t * d;
            let n = w3(front);
            let dir = if mirror { (d - 2.0 * d.dot(n) * n).normalize() } else { d };
            let dist = plane_hit(p, dir, w3(wall), f64::from(wall[3])).expect("the child ray meets the wall");
            let f = if attenuated { 1.0 / (g[0] + g[1] * dist + g[2] * dist * dist) } else { 1.0 };
            let want: DVec3 = k * f * l_w;
            assert_rel(img.get(x, y), want, REL, &format!("pixel ({x}, {y}), d = {dist}"));
        }
    }
}

#[test]
fn a_mirror_facing_a_wall_reflects_its_radiance_times_k_r_over_the_distance_polynomial() {
    let mirror = format!("ka = 0.0\nkd = 0.0\nks = 0.0\nkr = {K:?}");
    let flat = scene(&mirror, 5.0, -5.0, Some(ATT));
    assert_ne!(flat.header.features & feature::GLOBAL_ATTENUATION, 0);
    check(&flat, true, true);
    // Off by default: no feature bit and f_att = 1 (so the check above is not vacuous).
    let plain = scene(&mirror, 5.0, -5.0, None);
    assert_eq!(plain.header.features & feature::GLOBAL_ATTENUATION, 0);
    check(&plain, true, false);
    // The whole tracer (every feature compiled in) gives the same image.
    let full = crate::support::render_with(&flat, 1, false);
    assert_eq!(full.image.pixels, render(&flat).image.pixels);
}

#[test]
fn a_clear_sheet_transmits_the_wall_behind_it_times_k_t_over_the_distance_polynomial() {
    let sheet = format!("ka = 0.0\nkd = 0.0\nks = 0.0\nkt = {K:?}\nior = 1.0");
    let flat = scene(&sheet, 2.0, 12.0, Some(ATT));
    assert_ne!(flat.header.features & feature::GLOBAL_ATTENUATION, 0);
    check(&flat, false, true);
}

/// The bailout judges a child by its whole path weight, the attenuation of the rays before it
/// included: camera → mirror A (k_r = 0.5) → mirror B about 10 away (f_att = 1/(1 + 0.01·d²),
/// at most 0.5) → B's child, of weight 0.5 · f · 0.5 ≤ 0.125, below a bailout of 0.2, so never
/// traced, where A's child (0.5) always is. Left out of the weight, B's child (0.25) was traced
/// on the CPU alone, and only the GPU parity test told.
#[test]
fn the_bailout_weighs_a_child_with_the_attenuation_of_the_rays_before_it() {
    let s = SceneText::new(16, 16, "max_depth = 4\nbailout = 0.2\nepsilon = 0.0", [0.0; 3], Z, [0.0, 1.0, 0.0], 30.0);
    let mirror = "ka = 0.0\nkd = 0.0\nks = 0.0\nkr = 0.5";
    let flat = s
        .world_attenuated([0.0; 3], [0.0; 3], [1.0, 0.0, 0.01])
        .material("mirror", mirror)
        .plane([0.0, 0.0, 5.0], [0.0, 0.0, -1.0], "mirror")
        .plane([0.0, 0.0, -5.0], Z, "mirror")
        .flat();
    let counts = render(&flat).counts;
    let pixels = 16 * 16;
    assert_eq!((counts.camera, counts.reflection, counts.bailout_saved), (pixels, pixels, pixels), "{counts:?}");
}
