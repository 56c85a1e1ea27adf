//! Shared helpers: scene text builders, rendering, and an independent re-derivation of the
//! geometry (camera rays, sphere and plane hits) so that expected values never come from the
//! tracer itself.

use std::fmt::Write as _;
use std::path::Path;

use glam::DVec3;
use glint_core::cpu::probe::Breakdown;
use glint_core::scene::{SceneDesc, parse_scene};
use glint_core::{CpuOptions, CpuRender, FlatScene, RenderControl, probe_pixel, render_cpu};

/// Widens a stored `[f32; 4]` (xyz) exactly to f64.
pub fn w3(a: [f32; 4]) -> DVec3 {
    DVec3::new(f64::from(a[0]), f64::from(a[1]), f64::from(a[2]))
}

/// A TOML array `[x, y, z]` that round-trips the f64 values exactly (`{:?}` is the shortest
/// representation that reads back to the same number, and always a TOML float).
pub fn arr(v: [f64; 3]) -> String {
    format!("[{:?}, {:?}, {:?}]", v[0], v[1], v[2])
}

/// A TOML float.
pub fn num(v: f64) -> String {
    format!("{v:?}")
}

/// Incrementally written scene text.
#[derive(Debug, Default, Clone)]
pub struct SceneText {
    pub text: String,
}

impl SceneText {
    /// `[render]` with the image size and extra `key = value` lines, and `[camera]`.
    pub fn new(
        width: u32,
        height: u32,
        render_extra: &str,
        position: [f64; 3],
        look_at: [f64; 3],
        up: [f64; 3],
        fov: f64,
    ) -> Self {
        let mut text = String::new();
        writeln!(text, "[render]\nwidth = {width}\nheight = {height}\n{render_extra}\n").unwrap();
        writeln!(
            text,
            "[camera]\nposition = {}\nlook_at = {}\nup = {}\nfov_y = {}\n",
            arr(position),
            arr(look_at),
            arr(up),
            num(fov)
        )
        .unwrap();
        Self { text }
    }

    /// A 1×1 image whose only (centre) pixel looks exactly along look_at − position.
    pub fn pinhole(render_extra: &str, position: [f64; 3], look_at: [f64; 3], up: [f64; 3]) -> Self {
        Self::new(1, 1, render_extra, position, look_at, up, 30.0)
    }

    pub fn world(mut self, ambient: [f64; 3], background: [f64; 3]) -> Self {
        writeln!(self.text, "[world]\nambient = {}\nbackground = {}\n", arr(ambient), arr(background)).unwrap();
        self
    }

    /// `[materials.NAME]` with the given `key = value` lines. Unlisted fields take the
    /// scene-format defaults, so tests list every field they rely on.
    pub fn material(mut self, name: &str, fields: &str) -> Self {
        writeln!(self.text, "[materials.{name}]\n{fields}\n").unwrap();
        self
    }

    pub fn light(mut self, kind: &str, fields: &str) -> Self {
        writeln!(self.text, "[[lights]]\ntype = \"{kind}\"\n{fields}\n").unwrap();
        self
    }

    pub fn sphere(mut self, center: [f64; 3], radius: f64, material: &str) -> Self {
        writeln!(
            self.text,
            "[[objects]]\ntype = \"sphere\"\ncenter = {}\nradius = {}\nmaterial = \"{material}\"\n",
            arr(center),
            num(radius)
        )
        .unwrap();
        self
    }

    pub fn plane(mut self, point: [f64; 3], normal: [f64; 3], material: &str) -> Self {
        writeln!(
            self.text,
            "[[objects]]\ntype = \"plane\"\npoint = {}\nnormal = {}\nmaterial = \"{material}\"\n",
            arr(point),
            arr(normal)
        )
        .unwrap();
        self
    }

    /// A mesh of the given triangles (each its own three vertices), optional vertex normals.
    pub fn triangles(mut self, tris: &[[[f64; 3]; 3]], normals: Option<&[[f64; 3]]>, material: &str) -> Self {
        let vertices: Vec<String> = tris.iter().flatten().map(|v| arr(*v)).collect();
        let indices: Vec<String> =
            (0..tris.len()).map(|i| format!("[{}, {}, {}]", 3 * i, 3 * i + 1, 3 * i + 2)).collect();
        writeln!(
            self.text,
            "[[objects]]\ntype = \"mesh\"\nvertices = [{}]\ntriangles = [{}]\nmaterial = \"{material}\"",
            vertices.join(", "),
            indices.join(", ")
        )
        .unwrap();
        if let Some(n) = normals {
            let n: Vec<String> = n.iter().map(|v| arr(*v)).collect();
            writeln!(self.text, "normals = [{}]", n.join(", ")).unwrap();
        }
        self.text.push('\n');
        self
    }

    /// Parses (through the real parser and validation) and panics with the error text.
    pub fn desc(&self) -> SceneDesc {
        match parse_scene(&self.text, Path::new("test-scene.toml")) {
            Ok((desc, _warnings)) => desc,
            Err(e) => panic!("test scene does not load: {e}\n--- scene ---\n{}", self.text),
        }
    }

    /// The flat scene with the scene's own render settings.
    pub fn flat(&self) -> FlatScene {
        let desc = self.desc();
        FlatScene::build(&desc, &desc.render)
    }
}

/// Renders with `threads` threads and asserts that no pixel is NaN or infinite.
pub fn render_with(flat: &FlatScene, threads: usize, specialise: bool) -> CpuRender {
    let r = render_cpu(flat, &CpuOptions { threads, specialise }, RenderControl::default()).expect("render");
    assert_eq!(r.image.pixels.len(), flat.pixel_count());
    if let Some((i, p)) = r.image.pixels.iter().enumerate().find(|(_, p)| !p.is_finite()) {
        panic!("pixel {i} is not finite: {p}");
    }
    r
}

/// Single-threaded, specialised render; every pixel finite.
pub fn render(flat: &FlatScene) -> CpuRender {
    render_with(flat, 1, true)
}

/// The per-term breakdown of the centre sample of pixel (x, y), checked for consistency.
pub fn probe(flat: &FlatScene, x: u32, y: u32) -> Breakdown {
    let b = probe_pixel(flat, x, y, 0);
    assert!(b.total.is_finite(), "probe ({x}, {y}) total {}", b.total);
    b
}

/// The camera ray through the centre of pixel (x, y) (y downwards), re-derived from the stored
/// camera vectors: direction ∝ forward + ndc_x·right + ndc_y·up with pixel centres at
/// (x + 0.5, y + 0.5) (the documented camera model).
pub fn primary_ray(flat: &FlatScene, x: u32, y: u32) -> (DVec3, DVec3) {
    let (w, h) = (f64::from(flat.header.width), f64::from(flat.header.height));
    let c = &flat.camera;
    let ndc_x = 2.0 * (f64::from(x) + 0.5) / w - 1.0;
    let ndc_y = 1.0 - 2.0 * (f64::from(y) + 0.5) / h;
    let d = w3(c.forward) + ndc_x * w3(c.right) + ndc_y * w3(c.up);
    (w3(c.position), d.normalize())
}

/// Nearest ray/sphere hit with t > 0 and its discriminant relative to r² (how far from the
/// silhouette the ray is), by the textbook quadratic for a unit direction.
pub fn sphere_hit(o: DVec3, d: DVec3, center: DVec3, radius: f64) -> Option<(f64, f64)> {
    let oc = o - center;
    let b = oc.dot(d);
    let c = oc.dot(oc) - radius * radius;
    let disc = b * b - c;
    if disc < 0.0 {
        return None;
    }
    let s = disc.sqrt();
    let t = if -b - s > 0.0 { -b - s } else { -b + s };
    (t > 0.0).then_some((t, disc / (radius * radius)))
}

/// Ray/plane hit for the plane n·x = k.
pub fn plane_hit(o: DVec3, d: DVec3, n: DVec3, k: f64) -> Option<f64> {
    let t = (k - n.dot(o)) / n.dot(d);
    (t.is_finite() && t > 0.0).then_some(t)
}

/// Blinn: max(N·H, 0)^n with H = (L+V)/|L+V|, 0 where N·L ≤ 0; x^0 = 1.
pub fn blinn(n: DVec3, l: DVec3, v: DVec3, shininess: f64) -> f64 {
    if n.dot(l) <= 0.0 {
        return 0.0;
    }
    let h = (l + v).normalize();
    pow0(n.dot(h).max(0.0), shininess)
}

/// Phong: max(R·V, 0)^n with R = 2(N·L)N − L, 0 where N·L ≤ 0; x^0 = 1.
pub fn phong(n: DVec3, l: DVec3, v: DVec3, shininess: f64) -> f64 {
    let ndl = n.dot(l);
    if ndl <= 0.0 {
        return 0.0;
    }
    let r = 2.0 * ndl * n - l;
    pow0(r.dot(v).max(0.0), shininess)
}

/// x^n with x^0 = 1 (also 0^0).
pub fn pow0(x: f64, n: f64) -> f64 {
    if n == 0.0 { 1.0 } else { x.powf(n) }
}

/// Per channel |got − want| ≤ rel·max(|want|, 1e-6) (the floor keeps exact zeros meaningful
/// without demanding bit equality of sums of tiny terms).
pub fn assert_rel(got: DVec3, want: DVec3, rel: f64, what: &str) {
    for i in 0..3 {
        let (g, w) = (got[i], want[i]);
        let tol = rel * w.abs().max(1e-6);
        assert!(
            g.is_finite() && (g - w).abs() <= tol,
            "{what}: channel {i}: got {g:e}, expected {w:e} (diff {:e} > tol {tol:e}); got {got}, expected {want}",
            (g - w).abs()
        );
    }
}

/// DVec3 from an array (short form for expectations).
pub fn dv(a: [f64; 3]) -> DVec3 {
    DVec3::from(a)
}
