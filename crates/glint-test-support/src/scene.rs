//! Scene text for tests: a TOML builder that goes through the real parser and validation, so
//! that every test scene is a scene a user could write.

use std::fmt::Write as _;
use std::path::Path;

use glint_core::FlatScene;
use glint_io::parse_scene;
use glint_scene::{MeshDesc, ObjectDesc, SceneDesc};

/// Widens a stored `[f32; 4]` (xyz) exactly to f64: the tracer's own `v3`, under the name the
/// tests use.
pub use glint_core::cpu::v3 as w3;

/// A TOML array `[x, y, z]` that round-trips the f64 values exactly (`{:?}` is the shortest
/// representation that reads back to the same number, and always a TOML float).
pub fn arr(v: [f64; 3]) -> String {
    format!("[{:?}, {:?}, {:?}]", v[0], v[1], v[2])
}

/// A TOML float.
pub fn num(v: f64) -> String {
    format!("{v:?}")
}

/// Parses and validates scene text (panicking with the error and the text) and builds the flat
/// scene with the scene's own render settings.
pub fn flat_from_toml(text: &str) -> FlatScene {
    let (desc, _) = parse_scene(text, Path::new("test.toml")).unwrap_or_else(|e| panic!("{e}\n{text}"));
    FlatScene::build(&desc, &desc.render)
}

/// A checkered floor, a red sphere, a point light (and a directional one if `directional`)
/// and, optionally, a sphere of ideal glass of the given ior (k_t = 1, every other coefficient
/// 0). ε = 0: the robust offset alone moves secondary origins (by a few hundred ULPs), so a
/// straight-through ray continues on a line displaced by ~1e-13, far below a 1e-9 tolerance.
pub fn glass_scene(glass_ior: Option<f64>, directional: bool) -> SceneText {
    const Y: [f64; 3] = [0.0, 1.0, 0.0];
    let s = SceneText::new(48, 36, "max_depth = 4\nepsilon = 0.0\nbailout = 0.0", [0.1, 1.2, -3.0], [0.1, 0.5, 1.0], Y, 50.0)
        .world([0.125; 3], [0.25, 0.5, 0.75])
        .material(
            "floor",
            "ka = 0.5\nkd = [0.75, 0.25, 0.25]\nks = 0.5\nshininess = 10.0\nchecker = { kd = [0.25, 0.75, 0.25], size = 0.5 }",
        )
        .material("red", "ka = 0.5\nkd = [0.8, 0.1, 0.1]\nks = 0.5\nshininess = 30.0")
        .light("point", "position = [-2.0, 4.0, -1.0]\ndiffuse = 0.75\nspecular = 0.75");
    let s = if directional {
        s.light("directional", "direction = [0.5, -1.0, 0.25]\ndiffuse = 0.25\nspecular = 0.25")
    } else {
        s
    };
    let s = s.plane([0.0; 3], Y, "floor").sphere([0.8, 0.5, 2.0], 0.5, "red");
    match glass_ior {
        Some(ior) => s
            .material("glass", &format!("ka = 0.0\nkd = 0.0\nks = 0.0\nkr = 0.0\nkt = 1.0\nior = {}", num(ior)))
            .sphere([-0.3, 0.6, 0.5], 0.6, "glass"),
        None => s,
    }
}

/// The slab's emissive sky (above) and ground (below), and its glass's k_r and k_t.
pub const SLAB_SKY: [f64; 3] = [0.25, 0.5, 1.0];
pub const SLAB_GROUND: [f64; 3] = [1.0, 0.5, 0.125];
pub const SLAB_KR: f64 = 0.25;
pub const SLAB_KT: f64 = 0.5;

/// The camera is inside glass of index `ior`: the half-space y < 1 below the plane y = 1
/// (normal +y, so a ray going up leaves the glass). Above, an emissive sky (y = 6); below, an
/// emissive ground (y = −6). The camera looks up at `deg` from the normal.
pub fn slab(ior: f64, deg: f64) -> SceneText {
    const Y: [f64; 3] = [0.0, 1.0, 0.0];
    const Z: [f64; 3] = [0.0, 0.0, 1.0];
    let a = deg.to_radians();
    SceneText::pinhole("max_depth = 2\nbailout = 0.0", [0.0; 3], [a.sin(), a.cos(), 0.0], Z)
        .world([0.5; 3], [0.0; 3])
        .material(
            "glass",
            &format!("ka = 0.0\nkd = 0.0\nks = 0.0\nkr = {}\nkt = {}\nior = {}", num(SLAB_KR), num(SLAB_KT), num(ior)),
        )
        .material("sky", &format!("ka = 0.0\nkd = 0.0\nks = 0.0\nemission = {SLAB_SKY:?}"))
        .material("ground", &format!("ka = 0.0\nkd = 0.0\nks = 0.0\nemission = {SLAB_GROUND:?}"))
        .plane([0.0, 1.0, 0.0], Y, "glass")
        .plane([0.0, 6.0, 0.0], [0.0, -1.0, 0.0], "sky")
        .plane([0.0, -6.0, 0.0], Y, "ground")
}

/// The camera inside a glass slab, 10° off its normal, at depth 65: every hit defers a
/// refracted ray, one more than the GPU's 64-entry stack holds (tests/stiff case 15), so a GPU
/// render raises `STATUS_STACK_OVERFLOW`.
pub fn stack_overflow_slab() -> String {
    let a = 10.0_f64.to_radians();
    SceneText::pinhole("max_depth = 65\nbailout = 0.0", [0.0; 3], [a.sin(), a.cos(), 0.0], [0.0, 0.0, 1.0])
        .world([0.0; 3], [0.25; 3])
        .material("glass", "ka = 0.0\nkd = 0.0\nks = 0.0\nkr = 0.9\nkt = 0.5\nior = 1.5\nemission = 0.0625")
        .plane([0.0, 1.0, 0.0], [0.0, 1.0, 0.0], "glass")
        .plane([0.0, -1.0, 0.0], [0.0, -1.0, 0.0], "glass")
        .text
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

    /// `[world]` with the global attenuation (c, l, q) of reflected and transmitted terms.
    pub fn world_attenuated(mut self, ambient: [f64; 3], background: [f64; 3], [c, l, q]: [f64; 3]) -> Self {
        writeln!(
            self.text,
            "[world]\nambient = {}\nbackground = {}\nglobal_attenuation = {{ c = {}, l = {}, q = {} }}\n",
            arr(ambient),
            arr(background),
            num(c),
            num(l),
            num(q)
        )
        .unwrap();
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
    pub fn triangles(self, tris: &[[[f64; 3]; 3]], normals: Option<&[[f64; 3]]>, material: &str) -> Self {
        let vertices: Vec<[f64; 3]> = tris.iter().flatten().copied().collect();
        let indices: Vec<[u32; 3]> = (0..tris.len() as u32).map(|i| [3 * i, 3 * i + 1, 3 * i + 2]).collect();
        self.mesh(&vertices, &indices, normals, material)
    }

    /// An indexed mesh: shared vertices are written once, as a modeller would export them.
    pub fn mesh(
        mut self,
        vertices: &[[f64; 3]],
        triangles: &[[u32; 3]],
        normals: Option<&[[f64; 3]]>,
        material: &str,
    ) -> Self {
        let vertices: Vec<String> = vertices.iter().map(|v| arr(*v)).collect();
        let indices: Vec<String> = triangles.iter().map(|t| format!("[{}, {}, {}]", t[0], t[1], t[2])).collect();
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

    /// An indexed mesh with texture coordinates per vertex.
    pub fn textured_mesh(
        mut self,
        vertices: &[[f64; 3]],
        triangles: &[[u32; 3]],
        uvs: &[[f64; 2]],
        material: &str,
    ) -> Self {
        self = self.mesh(vertices, triangles, None, material);
        self.text.pop();
        let uvs: Vec<String> = uvs.iter().map(|uv| format!("[{:?}, {:?}]", uv[0], uv[1])).collect();
        writeln!(self.text, "uvs = [{}]\n", uvs.join(", ")).unwrap();
        self
    }

    /// An indexed mesh with a linear colour per vertex.
    pub fn coloured_mesh(
        mut self,
        vertices: &[[f64; 3]],
        triangles: &[[u32; 3]],
        colours: &[[f64; 3]],
        material: &str,
    ) -> Self {
        self = self.mesh(vertices, triangles, None, material);
        self.text.pop();
        let colours: Vec<String> = colours.iter().map(|c| arr(*c)).collect();
        writeln!(self.text, "colours = [{}]\n", colours.join(", ")).unwrap();
        self
    }

    /// Writes the scene as `dir/scene.toml` and loads it from there (texture paths are
    /// relative to it), panicking with the error text.
    pub fn desc_in(&self, dir: &Path) -> SceneDesc {
        let file = dir.join("scene.toml");
        std::fs::write(&file, &self.text).expect("scene file written");
        match glint_io::load_scene(&file) {
            Ok(loaded) => loaded.desc,
            Err(e) => panic!("test scene does not load: {e}\n--- scene ---\n{}", self.text),
        }
    }

    /// `desc_in`, as a flat scene with the scene's own render settings.
    pub fn flat_in(&self, dir: &Path) -> FlatScene {
        let desc = self.desc_in(dir);
        FlatScene::build(&desc, &desc.render)
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

/// Vertex colours where every path that reads them shows: a quad with a red, green, blue and
/// white corner (diffuse, ambient and a white highlight), an uncoloured triangle beside it, a
/// mirror floor that reflects both and a glass sphere in front, under a point light that casts
/// shadows; `colours` = false writes the same quad without its colours.
pub fn vertex_colour_scene(width: u32, height: u32, colours: bool) -> SceneText {
    let quad = [[-1.5, 0.0, 0.0], [0.5, 0.0, 0.0], [0.5, 2.0, 0.0], [-1.5, 2.0, 0.0]];
    let corners = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0], [1.0, 1.0, 1.0]];
    let tris = [[0, 1, 2], [0, 2, 3]];
    let s = SceneText::new(width, height, "max_depth = 3", [0.0, 1.6, 5.0], [0.0, 0.8, 0.0], [0.0, 1.0, 0.0], 40.0)
        .world([0.2; 3], [0.05, 0.05, 0.1])
        .material("paint", "ka = 1.0\nkd = 0.8\nks = 0.5\nshininess = 40.0")
        .material("mirror", "ka = 0.2\nkd = 0.3\nkr = 0.5")
        .material("glass", "ka = 0.0\nkd = 0.0\nks = 0.5\nshininess = 80.0\nkt = 0.9\nior = 1.5")
        .light("point", "position = [2.0, 4.0, 4.0]\ndiffuse = 1.0\nspecular = 1.0")
        .plane([0.0, -0.01, 0.0], [0.0, 1.0, 0.0], "mirror")
        .sphere([0.9, 0.4, 1.2], 0.4, "glass")
        .mesh(&[[0.7, 0.0, -0.2], [1.9, 0.0, -0.2], [1.3, 1.4, -0.2]], &[[0, 1, 2]], None, "paint");
    if colours { s.coloured_mesh(&quad, &tris, &corners, "paint") } else { s.mesh(&quad, &tris, None, "paint") }
}

/// `mesh_scene` for meshes too large to go through scene text: the same scene with the mesh
/// appended to the parsed description (every index in range, as validation would require).
pub fn large_mesh_desc(w: u32, h: u32, mesh: (Vec<[f64; 3]>, Vec<[u32; 3]>)) -> SceneDesc {
    let mut desc = mesh_scene(w, h, (vec![[0.0; 3], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]], vec![[0, 1, 2]])).desc();
    let last = desc.objects.len() - 1;
    desc.objects[last] = ObjectDesc::Mesh(MeshDesc::new(mesh.0, mesh.1, "clay", "large mesh"));
    desc
}

/// A UV sphere of 4·n² triangles (rings θ = π·i/n, segments φ = 2π·k/(2n)), radius `r` around
/// `c`, with a small bump so that not every triangle is a plain facet.
pub fn uv_sphere(n: u32, c: [f64; 3], r: f64) -> (Vec<[f64; 3]>, Vec<[u32; 3]>) {
    let m = 2 * n;
    let mut v = Vec::new();
    for i in 0..=n {
        let th = std::f64::consts::PI * f64::from(i) / f64::from(n);
        for k in 0..=m {
            let ph = 2.0 * std::f64::consts::PI * f64::from(k) / f64::from(m);
            let rr = r * (1.0 + 0.05 * (7.0 * th).sin() * (5.0 * ph).sin());
            v.push([c[0] + rr * th.sin() * ph.cos(), c[1] + rr * th.cos(), c[2] + rr * th.sin() * ph.sin()]);
        }
    }
    let mut t = Vec::new();
    for i in 0..n {
        for k in 0..m {
            let a = i * (m + 1) + k;
            let (b, cc) = (a + 1, a + m + 1);
            t.push([a, cc, b]);
            t.push([b, cc, cc + 1]);
        }
    }
    (v, t)
}

/// A lamp (a sphere 0.1 across, E_m = 5) 0.02 above a white floor (k_d = 0.8), seen from
/// nearby, 32×24, with `render` the `[render]` table's lines: at depth 0 a path counts the lamp's
/// light samples alone, at depth 1 it weighs them against the paths that meet the lamp; the
/// same expectation, which both tracers' MIS tests hold them to (a reviewer's scene).
pub fn lamp_over_a_floor(render: &str) -> SceneText {
    SceneText::new(32, 24, render, [0.0, 0.5, -0.6], [0.0; 3], [0.0, 1.0, 0.0], 40.0)
        .world([0.0; 3], [0.0; 3])
        .material("white", "ka = 0.0\nkd = 0.8")
        .material("lamp", "ka = 0.0\nkd = 0.0\nemission = 5.0")
        .plane([0.0; 3], [0.0, 1.0, 0.0], "white")
        .sphere([0.0, 0.07, 0.0], 0.05, "lamp")
}

/// A closed box of white emitting walls seen from inside (the cube [−1, 1]³, its 12 triangles
/// wound to face inwards, their emitting side): k_d = 0.5 and E_m = 1, so its radiance is
/// Σ 0.5^k = 2 (1 − 0.5^(d+1)) to path depth d. `render` is the `[render]` table's lines.
pub fn emissive_box(width: u32, height: u32, render: &str) -> SceneText {
    let (mut vertices, mut triangles) = (Vec::new(), Vec::new());
    for axis in 0..3 {
        for side in [-1.0, 1.0] {
            let (u, v) = ((axis + 1) % 3, (axis + 2) % 3);
            let base = vertices.len() as u32;
            for (a, b) in [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)] {
                let mut p = [0.0; 3];
                (p[axis], p[u], p[v]) = (side, a, b);
                vertices.push(p);
            }
            // Counter-clockwise in (u, v) faces +axis (e_u × e_v = e_axis); inwards is −side.
            let quad = if side > 0.0 { [[0, 2, 1], [0, 3, 2]] } else { [[0, 1, 2], [0, 2, 3]] };
            triangles.extend(quad.map(|t| t.map(|i| base + i)));
        }
    }
    SceneText::new(width, height, render, [0.0, 0.0, -0.5], [0.0, 0.0, 0.5], [0.0, 1.0, 0.0], 60.0)
        .world([0.0; 3], [0.0; 3])
        .material(
            "wall",
            "ka = [0.0, 0.0, 0.0]\nkd = [0.5, 0.5, 0.5]\nks = [0.0, 0.0, 0.0]\nemission = [1.0, 1.0, 1.0]",
        )
        .mesh(&vertices, &triangles, None, "wall")
}

/// A lit scene with a ground plane, a mirror sphere and one mesh.
pub fn mesh_scene(w: u32, h: u32, mesh: (Vec<[f64; 3]>, Vec<[u32; 3]>)) -> SceneText {
    SceneText::new(w, h, "max_depth = 2", [0.3, 1.1, -3.2], [0.0, 0.2, 0.0], [0.0, 1.0, 0.0], 45.0)
        .world([0.1; 3], [0.2, 0.3, 0.4])
        .material("ground", "ka = 0.2\nkd = 0.6\nks = 0.2\nchecker = { kd = [0.2, 0.2, 0.2], size = 0.5 }")
        .material("clay", "ka = 0.2\nkd = [0.7, 0.5, 0.3]\nks = 0.4\nshininess = 20.0")
        .material("mirror", "ka = 0.0\nkd = 0.1\nks = 0.3\nkr = 0.6")
        .light("point", "position = [-2.0, 4.0, -3.0]\ndiffuse = 0.8\nspecular = 0.6")
        .light("directional", "direction = [0.3, -1.0, 0.2]\ndiffuse = 0.3\nspecular = 0.2")
        .plane([0.0, -1.2, 0.0], [0.0, 1.0, 0.0], "ground")
        .sphere([1.3, -0.6, 0.6], 0.6, "mirror")
        .mesh(&mesh.0, &mesh.1, None, "clay")
}

/// `desc` moved by `by`: the camera (eye and look-at point), point and spot lights, and every
/// object's positions (sphere centres, plane points, mesh and placed model vertices, and a
/// model's own lights). Directions are unchanged.
pub fn translate(desc: &mut SceneDesc, by: [f64; 3]) {
    let shift = |p: &mut [f64; 3]| (0..3).for_each(|k| p[k] += by[k]);
    shift(&mut desc.camera.position);
    shift(&mut desc.camera.look_at);
    desc.lights.iter_mut().filter_map(|l| l.position.as_mut()).for_each(shift);
    for object in &mut desc.objects {
        match object {
            ObjectDesc::Sphere(s) => shift(&mut s.center),
            ObjectDesc::Plane(p) => shift(&mut p.point),
            ObjectDesc::Mesh(m) => m.vertices.iter_mut().for_each(shift),
            ObjectDesc::Model(m) => {
                if let Some(loaded) = m.loaded.as_mut().map(std::sync::Arc::make_mut) {
                    loaded.meshes.iter_mut().flat_map(|mesh| &mut mesh.vertices).for_each(shift);
                    loaded.lights.iter_mut().filter_map(|l| l.position.as_mut()).for_each(shift);
                }
            }
        }
    }
}
