//! Turning a validated scene description into the flat layout both tracers read.

use std::sync::Arc;

use glam::DVec3;

use crate::bvh::{self, BvhNodes};
use glint_types::{Integrator, LightTags, MaterialTags};

use crate::texture_table::TextureTable;
use glint_scene::{
    Attenuation, AttenuationModel, EpsilonMode, Filter, LightDesc, LightKind, MaterialDesc, MeshDesc, NO_CONE_CUTOFF,
    ObjectDesc, PlaneDesc, RenderSettings, Rgb, SceneDesc, SpecularModel, SphereDesc, SpotFalloff, Wrap,
};
use glint_types::layout::{
    GpuCamera, GpuLight, GpuMaterial, GpuMesh, GpuPlane, GpuSphere, GpuTexture, GpuTriangle, INTEGRATOR_PATH,
    LIGHT_CASTS_SHADOWS, MESH_HAS_COLOURS, MESH_HAS_NORMALS, MESH_HAS_UVS, NO_CONE_VERSIN, NO_TEXTURE, SceneHeader,
    UnknownTag, feature, origin_power,
};

/// A scene in the GPU-ready layout, plus the names the UI and reports show. The geometry (the
/// primitives and the BVH) is shared, not copied, between scenes `rebuild` makes from one
/// another: a clone costs nothing over a million triangles, and the GPU tracer keeps the
/// buffers of geometry it has uploaded before (`Arc::ptr_eq`).
#[derive(Clone, Debug, PartialEq)]
pub struct FlatScene {
    pub header: SceneHeader,
    pub camera: GpuCamera,
    pub materials: Vec<GpuMaterial>,
    pub lights: Vec<GpuLight>,
    pub spheres: Arc<[GpuSphere]>,
    pub planes: Arc<[GpuPlane]>,
    /// The triangles of every mesh, in the BVH's leaf order (`bvh::reorder_triangles`).
    pub triangles: Arc<[GpuTriangle]>,
    /// Vertex positions of every mesh (xyz, w = 1), indexed by the triangles.
    pub vertices: Arc<[[f32; 4]]>,
    /// Unit vertex normals beside `vertices` (w = 0; zero for a mesh without normals), or
    /// empty when no mesh has them.
    pub normals: Arc<[[f32; 4]]>,
    /// Texture coordinates beside `vertices` (zero for a mesh without them), or empty when no
    /// mesh has them.
    pub uvs: Arc<[[f32; 2]]>,
    /// Linear vertex colours beside `vertices` (rgb, w = 1; white for a mesh without them), or
    /// empty when no mesh has them.
    pub colours: Arc<[[f32; 4]]>,
    pub meshes: Arc<[GpuMesh]>,
    /// The texture table the materials' texture indices point into.
    pub textures: Vec<GpuTexture>,
    /// Every texture's texels, linear RGBA, row by row from the top (`GpuTexture::offset`).
    pub texels: Vec<[f32; 4]>,
    /// The BVH over spheres and triangles (`bvh::build`; root first, empty without them).
    pub bvh_nodes: BvhNodes,
    /// The primitive references its leaves point into (`bvh::PrimRef`).
    pub bvh_prims: Arc<[u32]>,
    /// The referenced triangles' corners in reference order, for the CPU walk.
    pub leaf_corners: LeafCorners,
    /// Object names by object id (scene order; unnamed objects get `kind #index`).
    pub object_names: Arc<[String]>,
    pub material_names: Vec<String>,
    /// The world box around the bounded geometry, as the description gives it
    /// (`glint_scene::bounded_box`): what the storage origin and the camera judge a far box by,
    /// kept so that `rebuild` judges a moved camera without walking the vertices again.
    pub bounds: Option<(DVec3, DVec3)>,
    /// The origin the build stored the positions relative to (`glint_scene::storage_origin`);
    /// the header's frame is moved from it when the GPU rebases (`rebase::rebased`).
    pub storage_origin: DVec3,
}

fn rgb4(c: Rgb) -> [f32; 4] {
    [c.0[0] as f32, c.0[1] as f32, c.0[2] as f32, 0.0]
}

mod camera;
mod checks;
mod content_hash;
mod frame;
mod geometry;
mod leaf_corners;
mod lights_materials;

pub use camera::{SceneBox, WorldCamera, camera_eye};
pub(crate) use camera::{anchor_of, telephoto};
pub(crate) use frame::move_texture_origins;
pub use geometry::GeometryId;
use geometry::{Geometry, flat_primitives};
pub use leaf_corners::{Corners, GPU_LEAF_BYTES_PER_PRIM, GpuLeafAb, GpuLeafC, LeafCorners, fill_gpu_leaves};
use lights_materials::{flat_light, flat_material};

impl FlatScene {
    /// Builds the flat layout. The scene must have passed validation (`scene::validate`);
    /// settings are taken from `settings`, not from `desc.render`, so callers can override them.
    ///
    /// One step per part of the layout: materials, lights, primitives, the BVH over the bounded
    /// primitives, camera, header, and last the feature set, computed from the flat data itself.
    pub fn build(desc: &SceneDesc, settings: &RenderSettings) -> Self {
        let material_names: Vec<String> = desc.materials.keys().cloned().collect();
        let mut primitives = flat_primitives(desc, &material_names);
        let mut bvh = bvh::build(&bvh::Bounded {
            spheres: &primitives.spheres,
            triangles: &primitives.triangles,
            vertices: &primitives.vertices,
        });
        bvh::reorder_triangles(&mut bvh, &mut primitives.triangles);
        Self::assemble(desc, settings, material_names, Geometry::new(primitives, bvh))
    }

    /// `build` for a description whose objects and material names are those this scene was
    /// built from (only settings, camera, lights, world or material values differ): the
    /// primitives and the BVH are copied instead of rebuilt — the viewer's case while the
    /// camera or a light is dragged over a million triangles. Identical to `build`.
    pub fn rebuild(&self, desc: &SceneDesc, settings: &RenderSettings) -> Self {
        // A camera turned towards or away from a far box can move the storage origin
        // (`glint_scene::storage_origin`): then every position is stored anew.
        if DVec3::from(glint_scene::storage_origin_within(desc, self.bounds)) != self.storage_origin {
            return Self::build(desc, settings);
        }
        Self::assemble(desc, settings, self.material_names.clone(), self.geometry())
    }

    /// The identity of this scene's geometry (see `GeometryId`).
    pub fn geometry_id(&self) -> GeometryId {
        GeometryId(self.geometry())
    }

    /// The shared part, shared again (no data is copied).
    fn geometry(&self) -> Geometry {
        Geometry {
            spheres: self.spheres.clone(),
            planes: self.planes.clone(),
            triangles: self.triangles.clone(),
            vertices: self.vertices.clone(),
            normals: self.normals.clone(),
            uvs: self.uvs.clone(),
            colours: self.colours.clone(),
            meshes: self.meshes.clone(),
            object_names: self.object_names.clone(),
            bvh_nodes: self.bvh_nodes.clone(),
            bvh_prims: self.bvh_prims.clone(),
            leaf_corners: self.leaf_corners.clone(),
            // The positions are stored in the frame, whether `build` or `rebase` put them there.
            frame: self.header.frame,
            bounds: self.bounds,
            storage_origin: self.storage_origin,
        }
    }

    /// Everything but the geometry, around it.
    fn assemble(desc: &SceneDesc, settings: &RenderSettings, material_names: Vec<String>, geometry: Geometry) -> Self {
        let origin = wide(geometry.frame);
        let mut table = TextureTable::new(origin);
        let materials = desc.materials.values().map(|m| flat_material(m, &mut table)).collect();
        let lights = desc.traced_lights().map(|l| flat_light(l, origin)).collect();
        // A far box the camera cannot see is not what it looks at, nor what the scene is stored
        // around (`glint_scene::storage_origin`): the camera is judged as over planes alone.
        let seen = scene_box(&geometry.bvh_nodes).filter(|_| !glint_scene::far_box_out_of_sight(desc, geometry.bounds));
        let camera = Self::world_camera(desc, settings).stored(origin, seen, &geometry.planes);
        let mut flat = Self {
            header: flat_header(desc, settings, &geometry, material_names.len()),
            camera,
            materials,
            lights,
            spheres: geometry.spheres,
            planes: geometry.planes,
            triangles: geometry.triangles,
            vertices: geometry.vertices,
            normals: geometry.normals,
            uvs: geometry.uvs,
            colours: geometry.colours,
            meshes: geometry.meshes,
            textures: table.textures,
            texels: table.texels,
            bvh_nodes: geometry.bvh_nodes,
            bvh_prims: geometry.bvh_prims,
            leaf_corners: geometry.leaf_corners,
            object_names: geometry.object_names,
            material_names,
            bounds: geometry.bounds,
            storage_origin: geometry.storage_origin,
        };
        let light_tags: Vec<LightTags> = desc
            .traced_lights()
            .map(|l| LightTags { kind: l.kind, attenuation: l.attenuation.model(), falloff: l.falloff })
            .collect();
        let material_tags: Vec<MaterialTags> =
            desc.materials.values().map(|m| MaterialTags { specular: m.specular_model, fresnel: m.fresnel }).collect();
        flat.header.features = flat.scene_features(&light_tags, &material_tags);
        flat
    }

    /// The features this scene needs under its integrator, from the flat data itself (only
    /// materials that some object uses count) and the tags of each light and material. Paths
    /// differ from Whitted's tree in four: no ambient term; a glossy lobe reflects light from
    /// every direction, not only specular lights; f_att(t) weighs emitters' light at every
    /// bounce, and every path leaves surfaces (ε's primitive skip).
    fn scene_features(&self, light_tags: &[LightTags], material_tags: &[MaterialTags]) -> u32 {
        let mut f = 0;
        let path = self.header.integrator == INTEGRATOR_PATH;
        let mut used = vec![false; self.materials.len()];
        for m in self.spheres.iter().map(|s| s.material).chain(self.planes.iter().map(|p| p.material)) {
            used[m as usize] = true;
        }
        for m in self.meshes.iter() {
            used[m.material as usize] = true;
        }
        let nonzero = |c: [f32; 4]| c[..3].iter().any(|&v| v != 0.0);
        let any_geometry = !(self.spheres.is_empty() && self.planes.is_empty() && self.triangles.is_empty());
        let mut any_specular_light = false;
        for (l, &LightTags { kind, attenuation: model, falloff }) in self.lights.iter().zip(light_tags) {
            f |= match kind {
                LightKind::Point => feature::POINT_LIGHTS,
                LightKind::Directional => feature::DIRECTIONAL_LIGHTS,
                LightKind::Spot => feature::SPOT_LIGHTS,
            };
            f |= match (kind, model) {
                (LightKind::Point | LightKind::Spot, AttenuationModel::Polynomial) => {
                    if l.attenuation != [1.0, 0.0, 0.0, 0.0] { feature::ATTENUATION } else { 0 }
                }
                (LightKind::Point | LightKind::Spot, AttenuationModel::InverseSquare) => feature::INVERSE_SQUARE,
                (LightKind::Directional, _) => 0,
            };
            f |= match (kind, falloff) {
                (LightKind::Spot, SpotFalloff::Smooth) => feature::SMOOTH_SPOT,
                (LightKind::Spot, SpotFalloff::Power) | (LightKind::Point | LightKind::Directional, _) => 0,
            };
            if l.flags & LIGHT_CASTS_SHADOWS != 0 && any_geometry {
                f |= feature::SHADOWS;
            }
            if nonzero(l.ambient) && !path {
                f |= feature::LIGHT_AMBIENT;
            }
            any_specular_light |= nonzero(l.specular);
        }
        for ((m, tags), _) in self.materials.iter().zip(material_tags).zip(&used).filter(|(_, u)| **u) {
            if nonzero(m.kr) {
                f |= feature::REFLECTION;
            }
            if nonzero(m.kt) {
                f |= feature::TRANSMISSION;
            }
            if nonzero(m.emission) {
                f |= feature::EMISSION;
            }
            if m.diffuse_texture != NO_TEXTURE || m.emission_texture != NO_TEXTURE {
                f |= feature::TEXTURES;
            }
            if nonzero(m.ks) && (any_specular_light || path) {
                f |= feature::SPECULAR;
                f |= match tags.specular {
                    SpecularModel::Blinn => feature::BLINN,
                    SpecularModel::Phong => feature::PHONG,
                    SpecularModel::CookTorrance => feature::COOK_TORRANCE,
                };
            }
        }
        if f & feature::TRANSMISSION != 0 && f & feature::SHADOWS != 0 {
            f |= feature::FILTERED_SHADOWS;
        }
        if self.header.max_depth == 0 {
            // No child rays: reflection and refraction code is not needed (k_t still filters
            // shadows through FILTERED_SHADOWS).
            f &= !(feature::REFLECTION | feature::TRANSMISSION);
        }
        if !self.spheres.is_empty() {
            f |= feature::SPHERES;
        }
        if !self.planes.is_empty() {
            f |= feature::PLANES;
        }
        if !self.triangles.is_empty() {
            f |= feature::TRIANGLES;
            if self.meshes.iter().any(|m| m.flags & MESH_HAS_COLOURS != 0) {
                f |= feature::VERTEX_COLOURS;
            }
        }
        // A path's pixel is the mean over its area, whatever spp: one sample at the centre would
        // make renders of other seeds average to the centres' image (aliased edges), as the
        // viewer's and the report's do. Whitted's single sample is the pixel's centre.
        if self.header.spp > 1 || path {
            f |= feature::JITTER;
        }
        // Only secondary rays leave a primitive: without shadow or child rays there is nothing
        // to skip.
        // Only child rays are attenuated; the f32 coefficients decide, as the tracers read them.
        if (feature::recurses(f) || path) && self.header.global_attenuation != [1.0, 0.0, 0.0, 0.0] {
            f |= feature::GLOBAL_ATTENUATION;
        }
        // `robust` skips the primitive left as well: its offset is sized for the hit point's
        // rounding, not for the next test's (a ray sheared off a large triangle through a
        // coordinate plane re-met it 5e-5 away on the GPU, under an offset of 2^-16).
        let mode = self.header.epsilon_mode;
        if (mode == glint_types::layout::EPS_SKIP_CONVEX || mode == glint_types::layout::EPS_ROBUST)
            && (f & feature::SHADOWS != 0 || feature::recurses(f) || path)
        {
            f |= feature::SKIP_LEFT;
        }
        f
    }

    /// The bounded primitives the BVH is built over, as stored.
    pub fn bounded(&self) -> bvh::Bounded<'_> {
        bvh::Bounded { spheres: &self.spheres, triangles: &self.triangles, vertices: &self.vertices }
    }

    pub fn pixel_count(&self) -> usize {
        self.header.width as usize * self.header.height as usize
    }
}

/// The box around the bounded geometry (the BVH's root), `None` without any.
pub(crate) fn scene_box(nodes: &BvhNodes) -> Option<SceneBox> {
    let root = nodes.first()?;
    let (lo, hi) = (DVec3::from(root.min.map(f64::from)), DVec3::from(root.max.map(f64::from)));
    Some(SceneBox { centre: (lo + hi) * 0.5, side: (hi - lo).max_element() })
}

/// The xyz of a stored vector, widened exactly to f64 (`vec4`'s inverse up to rounding).
fn wide(v: [f32; 4]) -> DVec3 {
    DVec3::new(v[0].into(), v[1].into(), v[2].into())
}

fn vec4(v: DVec3, w: f32) -> [f32; 4] {
    [v.x as f32, v.y as f32, v.z as f32, w]
}

/// The header: image and sampling settings, counts, and the world's ambient and background.
/// (`features` is filled in last, from the finished layout.)
fn flat_header(desc: &SceneDesc, settings: &RenderSettings, p: &Geometry, material_count: usize) -> SceneHeader {
    SceneHeader {
        width: settings.width,
        height: settings.height,
        spp: settings.spp,
        max_depth: settings.max_depth,
        sphere_count: p.spheres.len() as u32,
        plane_count: p.planes.len() as u32,
        triangle_count: p.triangles.len() as u32,
        vertex_count: p.vertices.len() as u32,
        mesh_count: p.meshes.len() as u32,
        light_count: desc.traced_lights().count() as u32,
        material_count: material_count as u32,
        features: 0,
        epsilon_mode: settings.epsilon_mode as u32,
        seed: settings.seed,
        epsilon: settings.epsilon as f32,
        bailout: settings.bailout as f32,
        integrator: settings.integrator.into(),
        // Whitted's tree reads no such setting: a file's `indirect = false` (warned of) makes no
        // other scene of it, and no other scene hash.
        indirect: u32::from(settings.indirect || settings.integrator == Integrator::Whitted),
        omit_kinds: 0,
        pad_b: 0,
        ambient: rgb4(desc.world.ambient),
        background: rgb4(desc.world.background),
        global_attenuation: {
            let g = desc.world.global_attenuation;
            [g.c as f32, g.l as f32, g.q as f32, 0.0]
        },
        frame: p.frame,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use glint_io::builtin;

    #[test]
    fn rebuild_with_another_camera_light_and_material_value_equals_build() {
        let (desc, _) = builtin("bumpy-glass").expect("built-in").load(Some(12)).expect("loads");
        let old = FlatScene::build(&desc, &desc.render);
        let mut edited = desc.clone();
        edited.camera.position[0] += 0.5;
        edited.lights[0].diffuse = Rgb([0.3, 0.2, 0.1]);
        if let Some(m) = edited.materials.values_mut().next() {
            m.shininess += 3.0;
        }
        let mut settings = edited.render.clone();
        (settings.width, settings.height, settings.max_depth) = (33, 17, 2);
        let rebuilt = old.rebuild(&edited, &settings);
        assert_eq!(rebuilt, FlatScene::build(&edited, &settings));
        assert_ne!(rebuilt.camera, old.camera);
    }

    #[test]
    fn rebuild_after_turning_away_from_a_far_box_stores_the_scene_as_build_does() {
        // A sphere 3e5 away and a floor under the eye: looking at the sphere, the scene is
        // stored around it; turned down to the floor, around the eye (stiff case 26).
        let text = "[camera]\nposition = [0.0, 0.01, 0.0]\nlook_at = [0.0, 0.01, 1.0]\n[materials.m]\nkd = 0.5\n\
                    [[objects]]\ntype = \"plane\"\npoint = [0.0, 0.0, 0.0]\nnormal = [0.0, 1.0, 0.0]\nmaterial = \"m\"\n\
                    [[objects]]\ntype = \"sphere\"\ncenter = [0.0, 1.0, 3e5]\nradius = 1.0\nmaterial = \"m\"\n";
        let (desc, _) = glint_io::parse_scene(text, std::path::Path::new("t.toml")).expect("scene");
        let old = FlatScene::build(&desc, &desc.render);
        let mut turned = desc.clone();
        turned.camera.look_at = [0.0, 0.0, -1.0];
        let rebuilt = old.rebuild(&turned, &turned.render);
        assert_ne!(rebuilt.header.frame, old.header.frame, "the origin moved to the eye");
        assert_eq!(rebuilt, FlatScene::build(&turned, &turned.render));
    }
}
