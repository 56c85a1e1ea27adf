//! The generated built-in scenes `bumpy` and `bumpy-glass`: a displaced UV sphere of 4·N²
//! triangles over a ground quad, made in code at any resolution N so that the acceleration
//! structure can be measured from a few hundred to millions of triangles without a large file.
//!
//! Provenance: the displaced sphere of the ray-benchmark issue (θ = π·i/N, φ = 2π·k/(2N),
//! r = 1 + 0.08·sin 13θ·sin 11φ + 0.03·sin(57θ + 3φ)); the high-frequency term makes the
//! triangles too small to share a leaf box with many neighbours, as in a scanned mesh. Materials,
//! lights and camera are our own.

use std::collections::BTreeMap;
use std::f64::consts::PI;

use super::camera::CameraDesc;
use super::desc::{ObjectDesc, RenderSettings, SceneDesc, SphereDesc, WorldDesc};
use super::light::LightDesc;
use super::material::{CheckerDesc, MaterialDesc};
use super::mesh::MeshDesc;
use super::rgb::Rgb;
use glint_types::LightKind;

/// The sphere in the descriptions (`glint render --list`, the viewer).
const SPHERE: &str = "displaced UV sphere of 4·N² triangles (--resolution N, default 500)";

/// Height of the ground quad.
pub const GROUND_Y: f64 = -1.2;
/// Half the side of the ground quad (it spans ±10 in x and z).
pub const GROUND_HALF: f64 = 10.0;

/// The radius of the displaced sphere at polar angle θ and azimuth φ.
pub fn bumpy_radius(theta: f64, phi: f64) -> f64 {
    1.0 + 0.08 * (13.0 * theta).sin() * (11.0 * phi).sin() + 0.03 * (57.0 * theta + 3.0 * phi).sin()
}

/// Vertex (i, k) of the grid: θ = π·i/N, φ = 2π·k/(2N), at r(θ, φ)·(sinθ·cosφ, cosθ, sinθ·sinφ).
pub fn bumpy_vertex(n: u32, i: u32, k: u32) -> [f64; 3] {
    let theta = PI * f64::from(i) / f64::from(n);
    let phi = 2.0 * PI * f64::from(k) / f64::from(2 * n);
    let r = bumpy_radius(theta, phi);
    [r * theta.sin() * phi.cos(), r * theta.cos(), r * theta.sin() * phi.sin()]
}

/// The displaced sphere: (N+1)·(2N+1) vertices and 4·N² triangles, two per grid cell.
///
/// The issue lists a cell's triangles as (a, c, b) and (b, c, d), with a = i·(2N+1)+k, b = a+1,
/// c = a+2N+1, d = c+1. With θ growing downwards and φ towards +z that order turns clockwise
/// seen from outside, so its normal cross(c − a, b − a) points into the sphere; the scene
/// format's front is counter-clockwise (docs/scene-format.md), and refraction in
/// `bumpy-glass` enters through the front. The same triangles are therefore stored as
/// (a, b, c) and (b, d, c): outward by the right-hand rule.
pub fn bumpy_sphere(n: u32) -> (Vec<[f64; 3]>, Vec<[u32; 3]>) {
    let row = 2 * n + 1;
    let mut vertices = Vec::with_capacity(((n + 1) * row) as usize);
    for i in 0..=n {
        for k in 0..row {
            vertices.push(bumpy_vertex(n, i, k));
        }
    }
    let mut triangles = Vec::with_capacity((4 * n * n) as usize);
    for i in 0..n {
        for k in 0..2 * n {
            let a = i * row + k;
            let (b, c) = (a + 1, a + row);
            let d = c + 1;
            triangles.push([a, b, c]);
            triangles.push([b, d, c]);
        }
    }
    (vertices, triangles)
}

/// The vertices and triangles of the generated scenes' meshes at resolution `n` (the sphere's
/// and the ground quad's), without making them: what a memory check before generating counts.
pub fn bumpy_mesh_size(n: u32) -> (u64, u64) {
    let n = u64::from(n);
    ((n + 1) * (2 * n + 1) + 4, 4 * n * n + 2)
}

/// The ground: a quad at y = −1.2 spanning ±10 in x and z, two triangles facing up.
pub fn ground_quad() -> (Vec<[f64; 3]>, Vec<[u32; 3]>) {
    let (y, h) = (GROUND_Y, GROUND_HALF);
    (vec![[-h, y, -h], [h, y, -h], [h, y, h], [-h, y, h]], vec![[0, 2, 1], [0, 3, 2]])
}

fn rgb(r: f64, g: f64, b: f64) -> Rgb {
    Rgb([r, g, b])
}

fn mesh(mesh: (Vec<[f64; 3]>, Vec<[u32; 3]>), material: &str, name: &str) -> ObjectDesc {
    ObjectDesc::Mesh(MeshDesc::new(mesh.0, mesh.1, material, name))
}

/// The part both variants share: camera, world, lights and the ground; `sphere_material` is
/// the displaced sphere's.
fn base(n: u32, sphere_material: (&str, MaterialDesc)) -> SceneDesc {
    let ground = MaterialDesc {
        ka: Rgb::splat(0.4),
        kd: rgb(0.75, 0.75, 0.72),
        ks: Rgb::splat(0.05),
        shininess: 10.0,
        checker: Some(CheckerDesc { kd: rgb(0.3, 0.32, 0.36), size: 1.0 }),
        ..MaterialDesc::default()
    };
    let mut key = LightDesc::new(LightKind::Point, [-3.0, 5.0, 4.0], [0.0, -1.0, 0.0]);
    key.diffuse = Rgb::splat(0.9);
    key.specular = Rgb::splat(0.9);
    key.name = "key".into();
    let mut fill = LightDesc::new(LightKind::Directional, [0.0; 3], [0.6, -0.8, -0.4]);
    fill.diffuse = rgb(0.25, 0.28, 0.35);
    fill.specular = Rgb::splat(0.2);
    fill.name = "fill".into();
    let (name, material) = sphere_material;
    SceneDesc {
        description: String::new(),
        provenance: "Glint ray-benchmark issue: displaced UV sphere (generated, resolution N)".into(),
        render: RenderSettings { width: 960, height: 540, ..RenderSettings::default() },
        // The benchmark's eye point, looking slightly down at the sphere's centre.
        camera: CameraDesc::perspective([0.0, 0.3, 3.0], [0.0, -0.05, 0.0], [0.0, 1.0, 0.0], 55.0),
        world: WorldDesc { ambient: Rgb::splat(0.12), background: rgb(0.55, 0.65, 0.8), ..WorldDesc::default() },
        materials: BTreeMap::from([("ground".to_string(), ground), (name.to_string(), material)]),
        lights: vec![key, fill],
        objects: vec![mesh(bumpy_sphere(n), name, "bumpy sphere"), mesh(ground_quad(), "ground", "ground")],
    }
}

/// `bumpy`: the displaced sphere in an opaque, glossy clay over a checkered ground.
pub fn bumpy(n: u32) -> SceneDesc {
    let clay = MaterialDesc {
        ka: rgb(0.8, 0.5, 0.35),
        kd: rgb(0.8, 0.48, 0.32),
        ks: Rgb::splat(0.35),
        shininess: 48.0,
        ..MaterialDesc::default()
    };
    let mut desc = base(n, ("clay", clay));
    desc.description = format!("{SPHERE}, clay, over a checkered ground quad (generated)");
    desc
}

/// `bumpy-glass`: the displaced sphere in glass, with a mirror ball beside it, so that
/// refraction through the bumps and reflection both show (Whitted's two effects).
pub fn bumpy_glass(n: u32) -> SceneDesc {
    let glass = MaterialDesc {
        ka: Rgb::splat(0.0),
        kd: Rgb::splat(0.02),
        ks: Rgb::splat(0.8),
        shininess: 300.0,
        kr: Rgb::splat(0.08),
        kt: rgb(0.88, 0.92, 0.9),
        ior: 1.5,
        ..MaterialDesc::default()
    };
    let mirror = MaterialDesc {
        ka: Rgb::splat(0.05),
        kd: Rgb::splat(0.05),
        ks: Rgb::splat(0.7),
        shininess: 200.0,
        kr: Rgb::splat(0.85),
        ..MaterialDesc::default()
    };
    let mut desc = base(n, ("glass", glass));
    desc.materials.insert("mirror".into(), mirror);
    desc.objects.push(ObjectDesc::Sphere(SphereDesc {
        center: [1.7, -0.65, -1.2],
        radius: 0.55,
        material: "mirror".into(),
        name: "mirror ball".into(),
    }));
    desc.render.max_depth = 6;
    desc.description = format!("{SPHERE}, glass, and a mirror ball over a checkered ground (generated)");
    desc
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::validate;

    fn sub(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
        [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
    }

    fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
        [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]
    }

    fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
        a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
    }

    #[test]
    fn counts_follow_the_resolution() {
        for n in [2, 3, 20, 57] {
            let (v, t) = bumpy_sphere(n);
            assert_eq!(v.len(), ((n + 1) * (2 * n + 1)) as usize, "N = {n}");
            assert_eq!(t.len(), (4 * n * n) as usize, "N = {n}");
            assert!(t.iter().flatten().all(|&k| (k as usize) < v.len()), "N = {n}: index out of range");
            let desc = bumpy(n);
            let triangles: usize = desc
                .objects
                .iter()
                .map(|o| match o {
                    ObjectDesc::Mesh(m) => m.triangles.len(),
                    _ => 0,
                })
                .sum();
            assert_eq!(triangles, (4 * n * n + 2) as usize, "sphere and ground quad, N = {n}");
        }
    }

    #[test]
    fn vertices_follow_the_formula() {
        let n = 20;
        let (v, _) = bumpy_sphere(n);
        let row = 2 * n + 1;
        // The poles, the equator and an arbitrary vertex, written out by hand.
        let at = |i: u32, k: u32| v[(i * row + k) as usize];
        let north = at(0, 7);
        let phi = 2.0 * PI * 7.0 / 40.0;
        assert!(north[0].abs() < 1e-15 && north[2].abs() < 1e-15);
        assert!((north[1] - (1.0 + 0.03 * (3.0 * phi).sin())).abs() < 1e-15, "{north:?}");
        let eq = at(10, 0);
        let r = 1.0 + 0.08 * (13.0 * PI / 2.0).sin() * 0.0 + 0.03 * (57.0 * PI / 2.0).sin();
        assert!((eq[0] - r).abs() < 1e-14 && eq[1].abs() < 1e-14 && eq[2].abs() < 1e-15, "{eq:?} vs r = {r}");
        let (theta, phi) = (PI * 3.0 / 20.0, 2.0 * PI * 11.0 / 40.0);
        let r = 1.0 + 0.08 * (13.0 * theta).sin() * (11.0 * phi).sin() + 0.03 * (57.0 * theta + 3.0 * phi).sin();
        let want = [r * theta.sin() * phi.cos(), r * theta.cos(), r * theta.sin() * phi.sin()];
        let got = at(3, 11);
        assert!((0..3).all(|c| (got[c] - want[c]).abs() < 1e-14), "{got:?} vs {want:?}");
        // The displacement stays within its amplitudes.
        for p in &v {
            let len = dot(*p, *p).sqrt();
            assert!((1.0 - 0.111..=1.0 + 0.111).contains(&len), "{p:?}");
        }
    }

    #[test]
    fn triangles_are_the_issue_cells_wound_outward() {
        let n = 30;
        let (v, t) = bumpy_sphere(n);
        let row = 2 * n + 1;
        // Cell (i, k) holds the issue's (a, c, b) and (b, c, d) as (a, b, c) and (b, d, c).
        let (i, k) = (4, 9);
        let a = i * row + k;
        let cell = (i * 2 * n + k) as usize * 2;
        assert_eq!(t[cell], [a, a + 1, a + row]);
        assert_eq!(t[cell + 1], [a + 1, a + row + 1, a + row]);
        // Away from the poles every normal cross(b − a, c − a) points away from the centre.
        let mut checked = 0;
        for tri in &t {
            let [a, b, c] = tri.map(|k| v[k as usize]);
            let ng = cross(sub(b, a), sub(c, a));
            let centroid = [(a[0] + b[0] + c[0]) / 3.0, (a[1] + b[1] + c[1]) / 3.0, (a[2] + b[2] + c[2]) / 3.0];
            if centroid[1].abs() < 0.9 {
                assert!(dot(ng, centroid) > 0.0, "inward triangle {tri:?}");
                checked += 1;
            }
        }
        assert!(checked > t.len() / 2, "only {checked} triangles checked");
        let (gv, gt) = ground_quad();
        for tri in gt {
            let [a, b, c] = tri.map(|k| gv[k as usize]);
            assert!(cross(sub(b, a), sub(c, a))[1] > 0.0, "the ground faces up");
        }
    }

    #[test]
    fn both_variants_validate() {
        for desc in [bumpy(12), bumpy_glass(12)] {
            let report = validate(&desc);
            assert!(report.errors.is_empty(), "{:?}", report.errors);
        }
    }
}
