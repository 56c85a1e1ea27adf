//! Case 5: a watertight mesh — a tessellated plane (z = 1) whose shared edges and vertices lie
//! exactly on the pixel rays. With the camera at the origin, looking along +z with a 90° field
//! of view, the centre ray of pixel (x, y) of a 32×32 image meets z = 1 at ((2x − 31)/32,
//! (31 − 2y)/32), so the grids below put every pixel ray exactly (in exact arithmetic) on
//!
//! - a vertex shared by six triangles (vertices at odd multiples of 1/32),
//! - a shared diagonal edge (vertices at even multiples: the rays pass through cell centres),
//! - a shared horizontal edge (odd rows, even columns).
//!
//! Expected: no pixel inside the mesh's silhouette (here: the whole image) misses, on either
//! backend. Remedy: the watertight ray/triangle test of Woop, Benthin & Wald (JCGT 2013), whose
//! edge functions are computed identically for the two triangles that share an edge. For
//! comparison the table prints how many pixels a textbook Möller–Trumbore test in f32 (the
//! GPU's precision) would miss on the same rays.

use glint_core::FlatScene;
use glint_core::camera_eye;
use glint_types::layout::NO_HIT;

use crate::gpu::render_both;
use crate::scene::SceneText;
use crate::{Y, Z};

const N: u32 = 32;

/// Vertices at x = (2i + ox)/32, y = (2j + oy)/32 covering [−1, 1]² and a little more, split
/// into two triangles per cell along the rising diagonal.
fn grid(ox: i32, oy: i32) -> (Vec<[f64; 3]>, Vec<[u32; 3]>) {
    let coords = |o: i32| -> Vec<f64> { (-17..=17).map(|i| f64::from(2 * i + o) / 32.0).collect() };
    let (xs, ys) = (coords(ox), coords(oy));
    let mut v = Vec::new();
    for &y in &ys {
        for &x in &xs {
            v.push([x, y, 1.0]);
        }
    }
    let nx = xs.len() as u32;
    let mut t = Vec::new();
    for j in 0..ys.len() as u32 - 1 {
        for i in 0..nx - 1 {
            let (a, b, c, d) = (j * nx + i, j * nx + i + 1, (j + 1) * nx + i + 1, (j + 1) * nx + i);
            t.push([a, b, c]);
            t.push([a, c, d]);
        }
    }
    (v, t)
}

/// Pixels that a Möller–Trumbore test in f32 misses on the GPU's f32 camera rays.
fn moller_trumbore_f32_misses(flat: &FlatScene) -> usize {
    type V = [f32; 3];
    let sub = |a: V, b: V| [a[0] - b[0], a[1] - b[1], a[2] - b[2]];
    let dot = |a: V, b: V| a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
    let cross = |a: V, b: V| [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]];
    let v = |a: [f32; 4]| [a[0], a[1], a[2]];
    let c = &flat.camera;
    let at = |i: u32| v(flat.vertices[i as usize]);
    let tris: Vec<[V; 3]> = flat.triangles.iter().map(|t| [at(t.va), at(t.vb), at(t.vc)]).collect();
    let mut misses = 0;
    for y in 0..N {
        for x in 0..N {
            let ndc_x = 2.0 * (x as f32 + 0.5) / N as f32 - 1.0;
            let ndc_y = 1.0 - 2.0 * (y as f32 + 0.5) / N as f32;
            let d: V = std::array::from_fn(|i| v(c.forward)[i] + ndc_x * v(c.right)[i] + ndc_y * v(c.up)[i]);
            let len = dot(d, d).sqrt();
            let d = d.map(|e| e / len);
            let o = camera_eye(c).as_vec3().to_array();
            let hit = tris.iter().any(|&[a, b, cc]| {
                let (e1, e2) = (sub(b, a), sub(cc, a));
                let p = cross(d, e2);
                let det = dot(e1, p);
                if det == 0.0 {
                    return false;
                }
                let inv = 1.0 / det;
                let s = sub(o, a);
                let u = dot(s, p) * inv;
                let q = cross(s, e1);
                let w = dot(d, q) * inv;
                (0.0..=1.0).contains(&u) && w >= 0.0 && u + w <= 1.0 && dot(e2, q) * inv > 0.0
            });
            misses += usize::from(!hit);
        }
    }
    misses
}

#[test]
fn tessellated_plane_has_no_holes_where_rays_meet_shared_edges_and_vertices() {
    let mut out = String::new();
    say!(out, "case 5: tessellated plane with edges/vertices on the pixel rays; pixels missed ({N}x{N})");
    say!(
        out,
        "  {:<34}  {:>9}  {:>5}  {:>5}  {:>21}",
        "rays through",
        "triangles",
        "CPU",
        "GPU",
        "Möller–Trumbore f32"
    );
    for (what, ox, oy) in
        [("shared vertices (6 triangles)", 1, 1), ("shared diagonal edges", 0, 0), ("shared horizontal edges", 0, 1)]
    {
        let (v, t) = grid(ox, oy);
        let flat = SceneText::new(N, N, "max_depth = 0", [0.0; 3], Z, Y, 90.0)
            .world([0.5; 3], [0.0; 3])
            .material("m", "ka = 1.0\nkd = 0.0")
            .mesh(&v, &t, None, "m")
            .flat();
        assert_eq!(flat.camera.up[1], 1.0, "the 90° camera must be exact in f32");
        let both = render_both("stiff/case05", &format!("watertight-{ox}{oy}"), &flat);
        let mut misses = Vec::new();
        for (backend, img) in both.images() {
            let holes = img.first_hit.iter().filter(|&&h| h == NO_HIT).count();
            both.ensure(holes == 0, || format!("{}: {holes} pixels fall through the mesh ({what})", backend.name()));
            misses.push(holes.to_string());
        }
        if misses.len() == 1 {
            misses.push("-".into());
        }
        say!(
            out,
            "  {what:<34}  {:>9}  {:>5}  {:>5}  {:>21}",
            t.len(),
            misses[0],
            misses[1],
            moller_trumbore_f32_misses(&flat)
        );
    }
    eprint!("{out}");
    crate::generated::section("case05-watertight", &out);
}
