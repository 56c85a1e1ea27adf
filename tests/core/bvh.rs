//! The BVH (`Accel::Bvh`) against brute force (`Accel::None`): bit-identical CPU images
//! (pixels' f64 bits, first hits, ray counts) for every built-in scene and for generated meshes
//! — UV spheres of ~10k and ~100k triangles (the latter over 65,536), coplanar duplicates of
//! different materials, needles, spheres tying with triangles at equal t, and a glass sphere
//! in front of a transmissive mesh (filtered shadows) — plus random incoherent rays checked
//! hit by hit and shadow product by shadow product.
//!
//! These renders call `render_cpu` directly (not the golden-hash hook): the hook's recorded
//! hashes are brute force's, and every suite render it checks already runs with the default,
//! the BVH.

use std::f64::consts::PI;

use glint_core::cpu::FAR;
use glint_core::cpu::intersect::{Leaving, Prim};
use glint_core::cpu::walk::{closest_hit, shadow_transmittance};
use glint_core::cpu::{Accel, Ray, TraceContext};
use glint_core::glam::DVec3;
use glint_core::{CpuOptions, CpuRender, FlatScene, RenderControl, render_cpu};
use glint_io::BUILTIN_SCENES;
use glint_types::layout::feature;

use crate::support::SceneText;
use glint_test_support::scene::{mesh_scene, uv_sphere};

const Y: [f64; 3] = [0.0, 1.0, 0.0];

fn render(flat: &FlatScene, accel: Accel) -> CpuRender {
    let options = CpuOptions { threads: 2, accel, ..CpuOptions::default() };
    render_cpu(flat, &options, RenderControl::default()).expect("CPU render")
}

/// Renders with both and asserts the images are bit-identical; returns the BVH render.
fn assert_identical(what: &str, flat: &FlatScene) -> CpuRender {
    let (bvh, none) = (render(flat, Accel::Bvh), render(flat, Accel::None));
    assert_eq!(bvh.image.pixels.len(), none.image.pixels.len(), "{what}");
    for (i, (p, q)) in bvh.image.pixels.iter().zip(&none.image.pixels).enumerate() {
        let (pb, qb) = (p.to_array().map(f64::to_bits), q.to_array().map(f64::to_bits));
        assert_eq!(pb, qb, "{what}: pixel {i} differs: BVH {p} vs brute force {q}");
    }
    assert_eq!(bvh.image.first_hit, none.image.first_hit, "{what}: first-hit ids");
    assert_eq!(bvh.counts, none.counts, "{what}: ray counts");
    bvh
}

#[test]
fn builtin_scenes_are_identical_with_and_without_the_bvh() {
    for b in BUILTIN_SCENES {
        // Generated scenes at a size brute force renders quickly (578 triangles).
        let (desc, _) = b.load(b.is_generated().then_some(12)).expect("built-in scene loads");
        let mut settings = desc.render.clone();
        (settings.width, settings.height) = (64, 48);
        assert_identical(b.name, &FlatScene::build(&desc, &settings));
    }
}

#[test]
fn uv_sphere_of_10k_triangles() {
    let flat = mesh_scene(64, 48, uv_sphere(50, [0.0, 0.1, 0.0], 1.0)).flat();
    // 4·50² triangles less the zero-area ones at the poles.
    assert!(flat.triangles.len() > 9_800, "{} triangles", flat.triangles.len());
    assert_identical("10k sphere", &flat);
}

#[test]
fn uv_sphere_of_100k_triangles_beyond_65536() {
    // Brute force over 100k triangles is slow: a small image.
    let flat = mesh_scene(40, 30, uv_sphere(158, [0.0, 0.1, 0.0], 1.0)).flat();
    assert!(flat.triangles.len() > 65_536, "{} triangles", flat.triangles.len());
    assert!(flat.triangles.len() > 99_000);
    assert_identical("100k sphere", &flat);
}

#[test]
fn coplanar_overlapping_duplicates_of_different_materials() {
    // A grid of quads in an oblique plane, three times: as is, with the vertices rotated and
    // shifted by half a cell (overlapping, not coinciding), each with its own material.
    let p = |x: f64, y: f64| [x, y, 1.3 + 0.2 * x - 0.1 * y];
    let mut copies = Vec::new();
    for (shift, rotate) in [(0.0, false), (0.0, true), (0.05, false)] {
        let mut tris = Vec::new();
        for j in 0..10 {
            for i in 0..10 {
                let (x, y) = (-1.0 + 0.2 * f64::from(i) + shift, -1.0 + 0.2 * f64::from(j) + shift);
                let (a, b, c, d) = (p(x, y), p(x + 0.2, y), p(x + 0.2, y + 0.2), p(x, y + 0.2));
                if rotate {
                    tris.push([b, c, a]);
                    tris.push([c, d, a]);
                } else {
                    tris.push([a, b, c]);
                    tris.push([a, c, d]);
                }
            }
        }
        copies.push(tris);
    }
    let scene = SceneText::new(64, 48, "max_depth = 0", [0.31, 0.17, -1.0], [0.0, 0.0, 1.3], Y, 60.0)
        .world([0.25; 3], [0.0; 3])
        .material("first", "ka = [1.0, 0.0, 0.0]\nkd = 0.0")
        .material("second", "ka = [0.0, 1.0, 0.0]\nkd = 0.0")
        .material("third", "ka = [0.0, 0.0, 1.0]\nkd = 0.0")
        .triangles(&copies[0], None, "first")
        .triangles(&copies[1], None, "second")
        .triangles(&copies[2], None, "third");
    let r = assert_identical("coplanar duplicates", &scene.flat());
    // The rotated copy ties with the first exactly (case 4 of the stiff suite) and never wins.
    let won = |id: u32| r.image.first_hit.iter().filter(|&&h| h == id).count();
    assert!(won(0) > 300 && won(1) == 0, "first {}, rotated copy {}", won(0), won(1));
}

#[test]
fn needle_triangles() {
    // Long, nearly zero-width triangles fanned around the view axis, and some along it.
    let mut tris = Vec::new();
    for k in 0..200 {
        let a = 2.0 * PI * f64::from(k) / 200.0;
        let (s, c) = a.sin_cos();
        let w = 1e-4 * (1.0 + f64::from(k % 7));
        tris.push([
            [0.0, 0.0, 2.0],
            [3.0 * c, 3.0 * s, 2.0 + 0.01 * f64::from(k)],
            [3.0 * c - w * s, 3.0 * s + w * c, 2.0],
        ]);
        tris.push([[0.1 * c, 0.1 * s, 0.5], [0.1 * c, 0.1 * s + w, 0.5], [0.1 * c, 0.1 * s, 40.0]]);
    }
    let scene = SceneText::new(64, 48, "max_depth = 1", [0.0, 0.0, -1.0], [0.0, 0.0, 1.0], Y, 60.0)
        .world([0.2; 3], [0.0, 0.0, 0.1])
        .material("metal", "ka = 0.3\nkd = 0.5\nks = 0.5\nkr = 0.3")
        .light("point", "position = [0.0, 2.0, -1.0]\ndiffuse = 0.8\nspecular = 0.5")
        .triangles(&tris, None, "metal");
    assert_identical("needles", &scene.flat());
}

#[test]
fn spheres_and_triangles_tying_at_equal_t() {
    // Along the axis the camera ray meets the sphere's pole, a triangle through it and a
    // duplicate sphere at exactly the same t; duplicate spheres tie everywhere. The first in
    // brute force's order (spheres by index, then triangles) must win on both.
    let tri = [[-0.5, -0.5, 4.0], [0.5, -0.5, 4.0], [0.0, 0.7, 4.0]];
    for (w, h) in [(1, 1), (33, 25)] {
        let scene = SceneText::new(w, h, "max_depth = 0", [0.0, 0.0, 0.0], [0.0, 0.0, 1.0], Y, 40.0)
            .world([0.25; 3], [0.0; 3])
            .material("a", "ka = [1.0, 0.0, 0.0]\nkd = 0.0")
            .material("b", "ka = [0.0, 1.0, 0.0]\nkd = 0.0")
            .material("c", "ka = [0.0, 0.0, 1.0]\nkd = 0.0")
            .triangles(&[tri], None, "c")
            .sphere([0.0, 0.0, 5.0], 1.0, "a")
            .sphere([0.0, 0.0, 5.0], 1.0, "b")
            .triangles(&[tri], None, "b");
        let r = assert_identical("equal t", &scene.flat());
        if w == 1 {
            // Object 1 is the first sphere: it beats the (earlier-listed) triangle at t = 4.
            assert_eq!(r.image.first_hit, vec![1]);
        }
    }
}

#[test]
fn glass_sphere_in_front_of_a_transmissive_mesh() {
    // Shadow rays cross the glass twice and several transmissive triangles: the filtered
    // product must be multiplied in brute force's order.
    let scene = SceneText::new(64, 48, "max_depth = 3", [0.0, 0.5, -3.5], [0.0, 0.0, 0.0], Y, 50.0)
        .world([0.1; 3], [0.1, 0.1, 0.2])
        .material("ground", "ka = 0.2\nkd = 0.7\nks = 0.0")
        .material("glass", "ka = 0.0\nkd = 0.0\nks = 0.3\nkr = 0.1\nkt = [0.9, 0.7, 0.8]\nior = 1.5")
        .material("tinted", "ka = 0.1\nkd = 0.3\nks = 0.2\nkt = [0.3, 0.6, 0.9]\nior = 1.0")
        .light("point", "position = [0.5, 4.0, -2.0]\ndiffuse = 0.9\nspecular = 0.5")
        .light("spot", "position = [-1.0, 3.0, -1.0]\ndirection = [0.3, -1.0, 0.4]\ncutoff = 40.0\ndiffuse = 0.5")
        .plane([0.0, -1.2, 0.0], Y, "ground")
        .sphere([0.0, 0.2, -1.0], 0.7, "glass")
        .sphere([0.2, 0.4, -0.8], 0.3, "glass")
        .mesh(&uv_sphere(20, [0.3, 0.0, 1.0], 0.9).0, &uv_sphere(20, [0.3, 0.0, 1.0], 0.9).1, None, "tinted");
    let flat = scene.flat();
    assert_ne!(flat.header.features & feature::FILTERED_SHADOWS, 0);
    assert_identical("glass in front of a mesh", &flat);
}

/// xorshift64*, uniform in [0, 1).
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> f64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        (self.0.wrapping_mul(0x2545_f491_4f6c_dd1d) >> 11) as f64 / (1u64 << 53) as f64
    }

    fn dir(&mut self) -> DVec3 {
        loop {
            let d = DVec3::new(2.0 * self.next() - 1.0, 2.0 * self.next() - 1.0, 2.0 * self.next() - 1.0);
            let l = d.length();
            if l > 1e-3 && l <= 1.0 {
                return d / l;
            }
        }
    }
}

#[test]
fn incoherent_rays_find_the_same_hits_and_shadow_products() {
    let scene = SceneText::new(8, 8, "max_depth = 1", [0.0, 0.5, -3.5], [0.0, 0.0, 0.0], Y, 50.0)
        .material("glass", "ka = 0.0\nkd = 0.0\nkt = [0.9, 0.7, 0.8]\nior = 1.5")
        .material("tinted", "ka = 0.1\nkd = 0.3\nkt = [0.3, 0.6, 0.9]")
        .material("opaque", "ka = 0.1\nkd = 0.3")
        .light("point", "position = [0.5, 4.0, -2.0]\ndiffuse = 0.9")
        .plane([0.0, -1.2, 0.0], Y, "tinted")
        .sphere([0.0, 0.2, -1.0], 0.7, "glass")
        .sphere([0.0, 0.2, -1.0], 0.7, "tinted")
        .sphere([0.5, 0.0, 0.5], 0.4, "opaque")
        .mesh(&uv_sphere(30, [0.3, 0.0, 1.0], 0.9).0, &uv_sphere(30, [0.3, 0.0, 1.0], 0.9).1, None, "tinted")
        .mesh(&uv_sphere(10, [-0.8, 0.3, 0.2], 0.5).0, &uv_sphere(10, [-0.8, 0.3, 0.2], 0.5).1, None, "opaque");
    let flat = scene.flat();
    let bvh = TraceContext::new(&flat).expect("valid tags").with_accel(Accel::Bvh);
    let none = TraceContext::new(&flat).expect("valid tags").with_accel(Accel::None);
    let mut rng = Rng(0x9e37_79b9_7f4a_7c15);
    let mut hits = 0;
    for i in 0..20_000 {
        let origin = DVec3::new(4.0 * rng.next() - 2.0, 3.0 * rng.next() - 1.5, 4.0 * rng.next() - 2.0);
        let ray = Ray { origin, dir: rng.dir() };
        let t_min = if i % 3 == 0 { 0.0 } else { 1e-4 };
        let none_left = Leaving::NONE;
        let (a, b) =
            (closest_hit(&bvh, &ray, t_min, FAR, &none_left), closest_hit(&none, &ray, t_min, FAR, &none_left));
        assert_eq!(a, b, "ray {i}: {ray:?}");
        hits += usize::from(a.is_some());
        let t_max = 0.5 + 4.0 * rng.next();
        let (a, b) = (
            shadow_transmittance(&bvh, &ray, t_min, t_max, &none_left),
            shadow_transmittance(&none, &ray, t_min, t_max, &none_left),
        );
        assert_eq!(a.to_array().map(f64::to_bits), b.to_array().map(f64::to_bits), "shadow ray {i}: {ray:?}");
    }
    assert!(hits > 5_000, "{hits} hits");
}

/// `skip_convex`'s rule (the primitive a ray leaves is not tested, a sphere it enters only by
/// its far root) through the BVH and brute force: the same hits and shadow products, for rays
/// leaving each sphere (both ways), the plane and triangles of both meshes.
#[test]
fn rays_leaving_a_primitive_skip_it_alike_through_the_bvh_and_brute_force() {
    let scene =
        SceneText::new(8, 8, "max_depth = 1\nepsilon_mode = \"skip_convex\"", [0.0, 0.5, -3.5], [0.0; 3], Y, 50.0)
            .material("glass", "ka = 0.0\nkd = 0.0\nkt = [0.9, 0.7, 0.8]\nior = 1.5")
            .material("tinted", "ka = 0.1\nkd = 0.3\nkt = [0.3, 0.6, 0.9]")
            .light("point", "position = [0.5, 4.0, -2.0]\ndiffuse = 0.9")
            .plane([0.0, -1.2, 0.0], Y, "tinted")
            .sphere([0.0, 0.2, -1.0], 0.7, "glass")
            .sphere([0.5, 0.0, 0.5], 0.4, "tinted")
            .mesh(&uv_sphere(12, [0.3, 0.0, 1.0], 0.9).0, &uv_sphere(12, [0.3, 0.0, 1.0], 0.9).1, None, "tinted");
    let flat = scene.flat();
    assert!(flat.header.features & feature::SKIP_LEFT != 0);
    let bvh = TraceContext::new(&flat).expect("valid tags").with_accel(Accel::Bvh);
    let none = TraceContext::new(&flat).expect("valid tags").with_accel(Accel::None);
    let mut rng = Rng(0x2545_f491_4f6c_dd1d);
    let (mut hits, mut differs) = (0, 0);
    for i in 0..20_000u32 {
        let leaving = match i % 4 {
            0 => Leaving { prim: Some(Prim::Sphere), index: (i / 4) % 2, inside: i % 8 < 4 },
            1 => Leaving { prim: Some(Prim::Plane), index: 0, inside: false },
            _ => Leaving { prim: Some(Prim::Triangle), index: (i * 7) % flat.triangles.len() as u32, inside: false },
        };
        // Start on the primitive left, so that skipping it matters.
        let dir = rng.dir();
        let origin = match leaving.prim {
            Some(Prim::Sphere) => {
                let cr = flat.spheres[leaving.index as usize].center_radius;
                let c = DVec3::new(cr[0].into(), cr[1].into(), cr[2].into());
                c + f64::from(cr[3]) * rng.dir()
            }
            Some(Prim::Plane) => DVec3::new(4.0 * rng.next() - 2.0, -1.2, 4.0 * rng.next() - 2.0),
            _ => {
                let tri = flat.triangles[leaving.index as usize];
                let v = |k: u32| {
                    let p = flat.vertices[k as usize];
                    DVec3::new(p[0].into(), p[1].into(), p[2].into())
                };
                (v(tri.va) + v(tri.vb) + v(tri.vc)) / 3.0
            }
        };
        let ray = Ray { origin, dir };
        let (a, b) = (closest_hit(&bvh, &ray, 0.0, FAR, &leaving), closest_hit(&none, &ray, 0.0, FAR, &leaving));
        assert_eq!(a, b, "ray {i} leaving {leaving:?}: {ray:?}");
        hits += usize::from(a.is_some());
        differs += usize::from(a != closest_hit(&none, &ray, 0.0, FAR, &Leaving::NONE));
        let t_max = 0.5 + 4.0 * rng.next();
        let (a, b) = (
            shadow_transmittance(&bvh, &ray, 0.0, t_max, &leaving),
            shadow_transmittance(&none, &ray, 0.0, t_max, &leaving),
        );
        assert_eq!(a.to_array().map(f64::to_bits), b.to_array().map(f64::to_bits), "shadow ray {i}: {ray:?}");
    }
    // The rule must actually change hits (else this test could not fail).
    assert!(hits > 2_000 && differs > 1_000, "{hits} hits, {differs} changed by the skip");
}
