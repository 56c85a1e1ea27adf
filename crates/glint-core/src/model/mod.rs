//! Model files (glTF 2.0, OBJ/MTL): their import, and the lab scene a model opens in.

pub mod obj;
pub mod uri;

pub use obj::{ObjError, ObjModel, load_obj};
pub use uri::{MAX_RESOURCE_BYTES, UriError, resolve_uri};

use crate::scene::{
    CameraDesc, LightDesc, LightKind, MaterialDesc, ObjectDesc, PlaneDesc, RenderSettings, Rgb, SceneDesc, WorldDesc,
};

/// The material of the ground under an opened model.
pub const GROUND_MATERIAL: &str = "glint-ground";

/// A scene around an imported model (a file has no lab of its own): a camera that frames its
/// bounding box from the front, above and to the right, a key light and a fill light, and a
/// grey ground under it so that its shadows show.
pub fn scene_around(model: ObjModel, description: String) -> SceneDesc {
    let mut lo = [f64::INFINITY; 3];
    let mut hi = [f64::NEG_INFINITY; 3];
    for v in model.meshes.iter().flat_map(|m| &m.vertices) {
        for k in 0..3 {
            lo[k] = lo[k].min(v[k]);
            hi[k] = hi[k].max(v[k]);
        }
    }
    let center: [f64; 3] = std::array::from_fn(|k| 0.5 * (lo[k] + hi[k]));
    let radius = (0..3).map(|k| (hi[k] - lo[k]).powi(2)).sum::<f64>().sqrt().max(1e-6) * 0.5;
    let at = |d: [f64; 3], s: f64| std::array::from_fn(|k| center[k] + d[k] * s * radius);
    let mut materials = model.materials;
    materials.insert(
        GROUND_MATERIAL.into(),
        MaterialDesc { ka: Rgb::splat(0.5), kd: Rgb::splat(0.5), ..MaterialDesc::default() },
    );
    let mut objects: Vec<ObjectDesc> = model.meshes.into_iter().map(ObjectDesc::Mesh).collect();
    objects.push(ObjectDesc::Plane(PlaneDesc {
        point: [center[0], lo[1], center[2]],
        normal: [0.0, 1.0, 0.0],
        material: GROUND_MATERIAL.into(),
        name: "ground".into(),
    }));
    let light = |kind, position, direction, intensity| LightDesc {
        diffuse: Rgb::splat(intensity),
        specular: Rgb::splat(intensity),
        ..LightDesc::new(kind, position, direction)
    };
    SceneDesc {
        description,
        provenance: String::new(),
        render: RenderSettings::default(),
        camera: CameraDesc { position: at([0.45, 0.35, 0.82], 2.6), look_at: center, up: [0.0, 1.0, 0.0], fov_y: 40.0 },
        world: WorldDesc { ambient: Rgb::splat(0.1), background: Rgb([0.2, 0.25, 0.3]) },
        materials,
        lights: vec![
            light(LightKind::Point, at([-0.8, 1.6, 1.2], 3.0), [0.0; 3], 0.8),
            light(LightKind::Directional, [0.0; 3], [0.4, -1.0, -0.3], 0.3),
        ],
        objects,
    }
}
