//! The shared geometry of a flat scene: primitives by kind, and its identity.

// What the parent module declares for its children.
use super::{
    Arc, BvhNodes, DVec3, GpuMesh, GpuPlane, GpuSphere, GpuTriangle, LeafCorners, MESH_HAS_COLOURS, MESH_HAS_NORMALS,
    MESH_HAS_UVS, MeshDesc, ObjectDesc, PlaneDesc, SceneDesc, SphereDesc, bvh, origin_power, vec4,
};
use glint_scene::{bounded_box, storage_origin_within};
use glint_types::layout::WORLD_FRAME;

/// The primitives of a scene by kind, with an object id and name per scene object.
#[derive(Debug, Default)]
pub(super) struct Primitives {
    pub(super) spheres: Vec<GpuSphere>,
    pub(super) planes: Vec<GpuPlane>,
    pub(super) triangles: Vec<GpuTriangle>,
    pub(super) vertices: Vec<[f32; 4]>,
    pub(super) normals: Vec<[f32; 4]>,
    pub(super) uvs: Vec<[f32; 2]>,
    pub(super) colours: Vec<[f32; 4]>,
    pub(super) meshes: Vec<GpuMesh>,
    pub(super) object_names: Vec<String>,
    /// The origin the positions are stored relative to (`glint_scene::storage_origin`).
    pub(super) origin: DVec3,
    /// The world box around the bounded geometry it was judged by (`glint_scene::bounded_box`).
    pub(super) bounds: Option<(DVec3, DVec3)>,
}

/// The geometry of a flat scene by identity: two are equal when they share the same data (a
/// scene and the scenes `rebuild` made from it), never by comparing a million triangles. It
/// holds the data alive, so an address cannot be reused by other data while it is kept.
#[derive(Clone, Debug)]
pub struct GeometryId(pub(super) Geometry);

impl PartialEq for GeometryId {
    fn eq(&self, o: &Self) -> bool {
        let (a, b) = (&self.0, &o.0);
        Arc::ptr_eq(&a.spheres, &b.spheres)
            && Arc::ptr_eq(&a.planes, &b.planes)
            && Arc::ptr_eq(&a.triangles, &b.triangles)
            && Arc::ptr_eq(&a.vertices, &b.vertices)
            && Arc::ptr_eq(&a.normals, &b.normals)
            && Arc::ptr_eq(&a.uvs, &b.uvs)
            && Arc::ptr_eq(&a.colours, &b.colours)
            && Arc::ptr_eq(&a.meshes, &b.meshes)
            && a.bvh_nodes.ptr_eq(&b.bvh_nodes)
            && Arc::ptr_eq(&a.bvh_prims, &b.bvh_prims)
            && a.leaf_corners.ptr_eq(&b.leaf_corners)
    }
}

/// The shared part of a flat scene: the primitives, their object names and the BVH.
#[derive(Clone, Debug)]
pub(super) struct Geometry {
    pub(super) spheres: Arc<[GpuSphere]>,
    pub(super) planes: Arc<[GpuPlane]>,
    pub(super) triangles: Arc<[GpuTriangle]>,
    pub(super) vertices: Arc<[[f32; 4]]>,
    pub(super) normals: Arc<[[f32; 4]]>,
    pub(super) uvs: Arc<[[f32; 2]]>,
    pub(super) colours: Arc<[[f32; 4]]>,
    pub(super) meshes: Arc<[GpuMesh]>,
    pub(super) object_names: Arc<[String]>,
    pub(super) bvh_nodes: BvhNodes,
    pub(super) bvh_prims: Arc<[u32]>,
    pub(super) leaf_corners: LeafCorners,
    /// The frame the positions are stored in (`SceneHeader::frame`: the origin, exact in f32,
    /// and the offsets' length scale).
    pub(super) frame: [f32; 4],
    pub(super) bounds: Option<(DVec3, DVec3)>,
    /// The storage origin `bounds` gave at the build (`frame` moves when the GPU rebases).
    pub(super) storage_origin: DVec3,
}

impl Geometry {
    pub(super) fn new(p: Primitives, bvh: bvh::Bvh) -> Self {
        let triangles: Arc<[GpuTriangle]> = p.triangles.into();
        let vertices: Arc<[[f32; 4]]> = p.vertices.into();
        let bvh_prims: Arc<[u32]> = bvh.prims.into();
        let leaf_corners = LeafCorners::new(&vertices, &triangles, &bvh_prims);
        Self {
            spheres: p.spheres.into(),
            planes: p.planes.into(),
            triangles,
            vertices,
            normals: p.normals.into(),
            uvs: p.uvs.into(),
            colours: p.colours.into(),
            meshes: p.meshes.into(),
            object_names: p.object_names.into(),
            bvh_nodes: BvhNodes::new(&bvh.nodes),
            bvh_prims,
            leaf_corners,
            frame: [p.origin.x as f32, p.origin.y as f32, p.origin.z as f32, WORLD_FRAME[3]],
            bounds: p.bounds,
            storage_origin: p.origin,
        }
    }
}

/// Every object's primitives, in scene order (the object id is the index in `desc.objects`),
/// their positions relative to the scene's storage origin (each difference taken in f64 and
/// rounded once).
pub(super) fn flat_primitives(desc: &SceneDesc, material_names: &[String]) -> Primitives {
    let material_index = |name: &str| material_names.iter().position(|m| m == name).unwrap_or(0) as u32;
    let bounds = bounded_box(desc);
    let origin = DVec3::from(storage_origin_within(desc, bounds));
    let mut out = Primitives { origin, bounds, ..Primitives::default() };
    for (id, object) in desc.objects.iter().enumerate() {
        let object_id = id as u32;
        let material = material_index(object.material());
        out.object_names.push(if object.name().is_empty() {
            format!("{} #{id}", object.kind_name())
        } else {
            object.name().to_string()
        });
        match object {
            ObjectDesc::Sphere(SphereDesc { center, radius, .. }) => {
                let center_radius = vec4(DVec3::from(*center) - origin, *radius as f32);
                out.spheres.push(GpuSphere {
                    center_radius,
                    material,
                    object_id,
                    power: origin_power(center_radius),
                    pad: 0,
                });
            }
            ObjectDesc::Plane(PlaneDesc { point, normal, .. }) => {
                let n = DVec3::from(*normal).normalize();
                out.planes.push(GpuPlane {
                    normal_offset: vec4(n, n.dot(DVec3::from(*point) - origin) as f32),
                    material,
                    object_id,
                    pad: [0; 2],
                });
            }
            ObjectDesc::Mesh(mesh) => mesh_triangles(mesh, material, object_id, &mut out),
            // One object, one mesh record per imported mesh (each with its own material).
            ObjectDesc::Model(model) => {
                for mesh in model.loaded.iter().flat_map(|m| &m.meshes) {
                    mesh_triangles(mesh, material_index(&mesh.material), object_id, &mut out);
                }
            }
        }
    }
    if out.meshes.iter().all(|m| m.flags & MESH_HAS_NORMALS == 0) {
        out.normals = Vec::new();
    }
    if out.meshes.iter().all(|m| m.flags & MESH_HAS_UVS == 0) {
        out.uvs = Vec::new();
    }
    if out.meshes.iter().all(|m| m.flags & MESH_HAS_COLOURS == 0) {
        out.colours = Vec::new();
    }
    out
}

/// A mesh's triangles, leaving out those of zero area in the stored (f32) data, so that they
/// are never hit, as validation promises: in the ray's sheared frame their edge functions are
/// rounding noise, and one on a line through the eye would be "hit" by a quarter of all camera
/// rays, with a 0/0 normal.
fn mesh_triangles(mesh: &MeshDesc, material: u32, object_id: u32, out: &mut Primitives) {
    let MeshDesc { vertices, triangles: tris, normals, uvs, colours, .. } = mesh;
    // White everywhere is no colour (exporters write COLOR_0 so): left out, it costs neither
    // a buffer nor a multiplication, and k_a and k_d stay exact (an interpolated 1 may not be).
    let colours = colours.as_ref().filter(|c| c.iter().any(|c| *c != [1.0; 3]));
    let first = out.vertices.len() as u32;
    out.vertices.extend(vertices.iter().map(|&v| vec4(DVec3::from(v) - out.origin, 1.0)));
    // Every vertex gets a normal slot, so that one index reaches both; zero without normals.
    match normals {
        Some(n) => out.normals.extend(n.iter().map(|&n| vec4(DVec3::from(n).normalize(), 0.0))),
        None => out.normals.extend(std::iter::repeat_n([0.0; 4], vertices.len())),
    }
    match uvs {
        Some(uv) => out.uvs.extend(uv.iter().map(|&[u, v]| [u as f32, v as f32])),
        None => out.uvs.extend(std::iter::repeat_n([0.0; 2], vertices.len())),
    }
    match colours {
        Some(c) => out.colours.extend(c.iter().map(|&[r, g, b]| [r as f32, g as f32, b as f32, 1.0])),
        None => out.colours.extend(std::iter::repeat_n([1.0; 4], vertices.len())),
    }
    let mesh_index = out.meshes.len() as u32;
    out.meshes.push(GpuMesh {
        material,
        object_id,
        flags: if normals.is_some() { MESH_HAS_NORMALS } else { 0 }
            | if uvs.is_some() { MESH_HAS_UVS } else { 0 }
            | if colours.is_some() { MESH_HAS_COLOURS } else { 0 },
        pad: 0,
    });
    let stored = &out.vertices;
    let at = |k: u32| DVec3::from_array([0, 1, 2].map(|c| f64::from(stored[(first + k) as usize][c])));
    for t in tris {
        let [a, b, c] = t.map(at);
        if (b - a).cross(c - a) == DVec3::ZERO {
            continue;
        }
        out.triangles.push(GpuTriangle {
            va: first + t[0],
            vb: first + t[1],
            vc: first + t[2],
            mesh: mesh_index,
            order: out.triangles.len() as u32,
        });
    }
}
