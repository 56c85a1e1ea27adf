//! Turning a validated scene description into the flat layout both tracers read.

use std::sync::Arc;

use glam::DVec3;

use crate::bvh::{self, BvhNodes};
use crate::cpu::{LightTags, MaterialTags, shade};

use crate::layout::{
    GpuCamera, GpuLight, GpuMaterial, GpuMesh, GpuPlane, GpuSphere, GpuTexture, GpuTriangle, LIGHT_CASTS_SHADOWS,
    MESH_HAS_NORMALS, MESH_HAS_UVS, NO_TEXTURE, SceneHeader, UnknownTag, feature, origin_power,
};
use crate::scene::{
    Attenuation, AttenuationModel, EpsilonMode, Filter, LightDesc, LightKind, MaterialDesc, MeshDesc, NO_CONE_CUTOFF,
    ObjectDesc, PlaneDesc, RenderSettings, Rgb, SceneDesc, SpecularModel, SphereDesc, SpotFalloff, Wrap,
};
use crate::texture_table::TextureTable;

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
    pub meshes: Arc<[GpuMesh]>,
    /// The texture table the materials' texture indices point into.
    pub textures: Vec<GpuTexture>,
    /// Every texture's texels, linear RGBA, row by row from the top (`GpuTexture::offset`).
    pub texels: Vec<[f32; 4]>,
    /// The BVH over spheres and triangles (`bvh::build`; root first, empty without them).
    pub bvh_nodes: BvhNodes,
    /// The primitive references its leaves point into (`bvh::PrimRef`).
    pub bvh_prims: Arc<[u32]>,
    /// Object names by object id (scene order; unnamed objects get `kind #index`).
    pub object_names: Arc<[String]>,
    pub material_names: Vec<String>,
}

fn vec4(v: DVec3, w: f32) -> [f32; 4] {
    [v.x as f32, v.y as f32, v.z as f32, w]
}

fn rgb4(c: Rgb) -> [f32; 4] {
    [c.0[0] as f32, c.0[1] as f32, c.0[2] as f32, 0.0]
}

/// The primitives of a scene by kind, with an object id and name per scene object.
#[derive(Debug, Default)]
struct Primitives {
    spheres: Vec<GpuSphere>,
    planes: Vec<GpuPlane>,
    triangles: Vec<GpuTriangle>,
    vertices: Vec<[f32; 4]>,
    normals: Vec<[f32; 4]>,
    uvs: Vec<[f32; 2]>,
    meshes: Vec<GpuMesh>,
    object_names: Vec<String>,
}

/// The geometry of a flat scene by identity: two are equal when they share the same data (a
/// scene and the scenes `rebuild` made from it), never by comparing a million triangles. It
/// holds the data alive, so an address cannot be reused by other data while it is kept.
#[derive(Clone, Debug)]
pub struct GeometryId(Geometry);

impl PartialEq for GeometryId {
    fn eq(&self, o: &Self) -> bool {
        let (a, b) = (&self.0, &o.0);
        Arc::ptr_eq(&a.spheres, &b.spheres)
            && Arc::ptr_eq(&a.planes, &b.planes)
            && Arc::ptr_eq(&a.triangles, &b.triangles)
            && Arc::ptr_eq(&a.vertices, &b.vertices)
            && Arc::ptr_eq(&a.normals, &b.normals)
            && Arc::ptr_eq(&a.uvs, &b.uvs)
            && Arc::ptr_eq(&a.meshes, &b.meshes)
            && a.bvh_nodes.ptr_eq(&b.bvh_nodes)
            && Arc::ptr_eq(&a.bvh_prims, &b.bvh_prims)
    }
}

/// The shared part of a flat scene: the primitives, their object names and the BVH.
#[derive(Clone, Debug)]
struct Geometry {
    spheres: Arc<[GpuSphere]>,
    planes: Arc<[GpuPlane]>,
    triangles: Arc<[GpuTriangle]>,
    vertices: Arc<[[f32; 4]]>,
    normals: Arc<[[f32; 4]]>,
    uvs: Arc<[[f32; 2]]>,
    meshes: Arc<[GpuMesh]>,
    object_names: Arc<[String]>,
    bvh_nodes: BvhNodes,
    bvh_prims: Arc<[u32]>,
}

impl Geometry {
    fn new(p: Primitives, bvh: bvh::Bvh) -> Self {
        Self {
            spheres: p.spheres.into(),
            planes: p.planes.into(),
            triangles: p.triangles.into(),
            vertices: p.vertices.into(),
            normals: p.normals.into(),
            uvs: p.uvs.into(),
            meshes: p.meshes.into(),
            object_names: p.object_names.into(),
            bvh_nodes: BvhNodes::new(&bvh.nodes),
            bvh_prims: bvh.prims.into(),
        }
    }
}

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
            meshes: self.meshes.clone(),
            object_names: self.object_names.clone(),
            bvh_nodes: self.bvh_nodes.clone(),
            bvh_prims: self.bvh_prims.clone(),
        }
    }

    /// Everything but the geometry, around it.
    fn assemble(desc: &SceneDesc, settings: &RenderSettings, material_names: Vec<String>, geometry: Geometry) -> Self {
        let mut table = TextureTable::default();
        let materials = desc.materials.values().map(|m| flat_material(m, &mut table)).collect();
        let lights = desc.traced_lights().map(flat_light).collect();
        let mut flat = Self {
            header: flat_header(desc, settings, &geometry, material_names.len()),
            camera: Self::camera_for(desc, settings),
            materials,
            lights,
            spheres: geometry.spheres,
            planes: geometry.planes,
            triangles: geometry.triangles,
            vertices: geometry.vertices,
            normals: geometry.normals,
            uvs: geometry.uvs,
            meshes: geometry.meshes,
            textures: table.textures,
            texels: table.texels,
            bvh_nodes: geometry.bvh_nodes,
            bvh_prims: geometry.bvh_prims,
            object_names: geometry.object_names,
            material_names,
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

    /// The features this scene needs, from the flat data itself (only materials that some
    /// object uses count) and the tags of each light and material.
    fn scene_features(&self, light_tags: &[LightTags], material_tags: &[MaterialTags]) -> u32 {
        let mut f = 0;
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
            if nonzero(l.ambient) {
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
            if nonzero(m.ks) && any_specular_light {
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
        }
        if self.header.spp > 1 {
            f |= feature::JITTER;
        }
        // Only secondary rays leave a primitive: without shadow or child rays there is nothing
        // to skip.
        // Only child rays are attenuated; the f32 coefficients decide, as the tracers read them.
        if feature::recurses(f) && self.header.global_attenuation != [1.0, 0.0, 0.0, 0.0] {
            f |= feature::GLOBAL_ATTENUATION;
        }
        if self.header.epsilon_mode == crate::layout::EPS_SKIP_CONVEX
            && (f & feature::SHADOWS != 0 || feature::recurses(f))
        {
            f |= feature::SKIP_CONVEX;
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

    /// Decodes every stored tag the tracers switch on (the ε strategy, each light's kind,
    /// attenuation model and spot falloff), so
    /// that both refuse a scene holding a value no kind has instead of tracing it as another.
    /// Also checks that every triangle's vertex and mesh indices are in range, which both
    /// tracers then index without a check.
    pub fn check_tags(&self) -> Result<(), UnknownTag> {
        EpsilonMode::try_from(self.header.epsilon_mode)?;
        for l in &self.lights {
            LightTags::decode(l)?;
        }
        let (vertices, meshes) = (self.vertices.len(), self.meshes.len());
        for t in self.triangles.iter() {
            for v in [t.va, t.vb, t.vc] {
                if v as usize >= vertices {
                    return Err(UnknownTag { what: "triangle vertex index", value: v });
                }
            }
            if t.mesh as usize >= meshes {
                return Err(UnknownTag { what: "triangle mesh index", value: t.mesh });
            }
        }
        let normals = self.meshes.iter().any(|m| m.flags & MESH_HAS_NORMALS != 0);
        if normals && self.normals.len() != vertices {
            return Err(UnknownTag { what: "normal count (one per vertex)", value: self.normals.len() as u32 });
        }
        let uvs = self.meshes.iter().any(|m| m.flags & MESH_HAS_UVS != 0);
        if uvs && self.uvs.len() != vertices {
            return Err(UnknownTag { what: "texture coordinate count (one per vertex)", value: self.uvs.len() as u32 });
        }
        for m in &self.materials {
            for t in [m.diffuse_texture, m.emission_texture] {
                if t != NO_TEXTURE && t as usize >= self.textures.len() {
                    return Err(UnknownTag { what: "material texture index", value: t });
                }
            }
        }
        for t in &self.textures {
            Wrap::try_from(t.wrap_s)?;
            Wrap::try_from(t.wrap_t)?;
            Filter::try_from(t.filter_mode)?;
            let end = u64::from(t.offset) + u64::from(t.width) * u64::from(t.height);
            if t.width == 0 || t.height == 0 || end > self.texels.len() as u64 {
                return Err(UnknownTag { what: "texture texel range", value: t.offset });
            }
        }
        Ok(())
    }

    /// The first float field holding a NaN or an infinity (e.g. `spheres[0].center_radius`).
    /// Validation keeps them out of scenes built from a description; the fields are public, so
    /// the GPU tracer checks again before upload and never receives non-finite data.
    pub fn first_non_finite(&self) -> Option<String> {
        let bad = |v: &[f32]| v.iter().any(|x| !x.is_finite());
        let h = &self.header;
        for (name, v) in [
            ("header.epsilon", &[h.epsilon][..]),
            ("header.bailout", &[h.bailout]),
            ("header.ambient", &h.ambient),
            ("header.background", &h.background),
            ("header.global_attenuation", &h.global_attenuation),
            ("header.frame", &h.frame),
        ] {
            if bad(v) {
                return Some(name.into());
            }
        }
        let c = &self.camera;
        if bad(&[c.position, c.forward, c.right, c.up].concat()) {
            return Some("camera".into());
        }
        let m = self
            .materials
            .iter()
            .map(|m| [&[m.ka, m.kd, m.ks, m.kr, m.kt, m.emission].concat()[..], &[m.shininess, m.ior]].concat());
        let l = self.lights.iter().map(|l| {
            [
                &[l.position, l.direction, l.diffuse, l.specular, l.ambient, l.attenuation].concat()[..],
                &[l.spot_exponent, l.spot_versin_cutoff, l.range, l.spot_versin_inner],
            ]
            .concat()
        });
        let s = self.spheres.iter().map(|s| s.center_radius);
        let p = self.planes.iter().map(|p| p.normal_offset);
        let v = self.vertices.iter();
        let n = self.normals.iter();
        let uv = self.uvs.iter();
        let tx = self.textures.iter().map(|t| [t.transform_u, t.transform_v].concat());
        let texels = self.texels.iter();
        // Generic over the item so that the large arrays are scanned in place, not copied.
        fn first_bad<V: AsRef<[f32]>>(kind: &str, items: impl Iterator<Item = V>) -> Option<String> {
            let mut items = items;
            items.position(|v| v.as_ref().iter().any(|x| !x.is_finite())).map(|i| format!("{kind}[{i}]"))
        }
        first_bad("materials", m)
            .or_else(|| first_bad("lights", l))
            .or_else(|| first_bad("spheres", s))
            .or_else(|| first_bad("planes", p))
            .or_else(|| first_bad("vertices", v))
            .or_else(|| first_bad("normals", n))
            .or_else(|| first_bad("uvs", uv))
            .or_else(|| first_bad("textures", tx))
            .or_else(|| first_bad("texels", texels))
    }
}

impl FlatScene {
    /// Ray-generation vectors of the pinhole camera, computed in f64 and stored once in f32
    /// (what `build` stores; the viewer's light gizmos project with it).
    pub fn camera_for(desc: &SceneDesc, settings: &RenderSettings) -> GpuCamera {
        let c = &desc.camera;
        let pos = DVec3::from(c.position);
        let forward = (DVec3::from(c.look_at) - pos).normalize();
        let right = forward.cross(DVec3::from(c.up)).normalize();
        let up = right.cross(forward);
        let half_h = (c.fov_y.to_radians() * 0.5).tan();
        let half_w = half_h * f64::from(settings.width) / f64::from(settings.height);
        GpuCamera {
            position: vec4(pos, 1.0),
            forward: vec4(forward, 0.0),
            right: vec4(right * half_w, 0.0),
            up: vec4(up * half_h, 0.0),
        }
    }
}

/// A material in the flat layout, its textures added to `table`. A checker is a texture of
/// k_d and its second colour over a white k_d, so that k_d · texel is exactly either colour.
fn flat_material(m: &MaterialDesc, table: &mut TextureTable) -> GpuMaterial {
    let (kd, diffuse_texture) = match (&m.checker, &m.texture) {
        (Some(c), _) => (rgb4(Rgb::one()), table.add_checker(m.kd, c)),
        (None, Some(t)) => (rgb4(m.kd), table.add(t)),
        (None, None) => (rgb4(m.kd), NO_TEXTURE),
    };
    GpuMaterial {
        ka: rgb4(m.ka),
        kd,
        ks: rgb4(m.ks),
        kr: rgb4(m.kr),
        kt: rgb4(m.kt),
        emission: rgb4(m.emission),
        shininess: m.shininess as f32,
        ior: m.ior as f32,
        specular_model: m.specular_model as u32,
        diffuse_texture,
        emission_texture: m.emission_texture.as_ref().map_or(NO_TEXTURE, |t| table.add(t)),
        roughness: m.roughness as f32,
        fresnel: m.fresnel as u32,
        pad: 0,
    }
}

/// cos(angle) of a cone half-angle in [0, 90] degrees, as sin(90° − angle): exact at both ends
/// (1 and 0), where cos(90°.to_radians()) would be 6e-17 and leave a point exactly at 90°
/// outside a closed cone.
/// 1 − cos of a cone's half-angle, as 2·sin²(θ/2): no cancellation for small cones, and exact
/// at 0° (0), 90° (1, where sin² 45° rounds to 1/2) and 180° (2).
fn cone_versin(degrees: f64) -> f64 {
    let s = (degrees / 2.0).to_radians().sin();
    2.0 * s * s
}

/// A light in the flat layout: unit direction, the attenuation model with its parameters, the
/// spot cone as versines (1 − cos).
fn flat_light(l: &LightDesc) -> GpuLight {
    let position = l.position.map_or(DVec3::ZERO, DVec3::from);
    let direction = l.direction.map_or(DVec3::ZERO, |d| DVec3::from(d).normalize());
    let (attenuation, range) = match l.attenuation {
        Attenuation::Polynomial { c, l, q } => ([c as f32, l as f32, q as f32, 0.0], 0.0),
        Attenuation::InverseSquare { range } => ([1.0, 0.0, 0.0, 0.0], range.map_or(0.0, |r| r as f32)),
    };
    // (s, versine of the cutoff or outer cone, versine of the inner cone)
    let (spot_exponent, versin_cutoff, versin_inner) = match (l.kind, l.falloff) {
        (LightKind::Spot, SpotFalloff::Power) if l.cutoff < NO_CONE_CUTOFF => {
            (l.exponent as f32, cone_versin(l.cutoff), 0.0)
        }
        (LightKind::Spot, SpotFalloff::Power) => (l.exponent as f32, shade::NO_CONE_VERSIN, 0.0),
        (LightKind::Spot, SpotFalloff::Smooth) => {
            let (inner, outer) = l.cone_angles();
            (0.0, cone_versin(outer), cone_versin(inner))
        }
        (LightKind::Point | LightKind::Directional, _) => (0.0, shade::NO_CONE_VERSIN, 0.0),
    };
    let spot_falloff = match l.kind {
        LightKind::Spot => l.falloff,
        LightKind::Point | LightKind::Directional => SpotFalloff::Power,
    };
    GpuLight {
        position: vec4(position, 1.0),
        direction: vec4(direction, 0.0),
        diffuse: rgb4(l.diffuse),
        specular: rgb4(l.specular),
        ambient: rgb4(l.ambient),
        attenuation,
        kind: l.kind as u32,
        flags: if l.casts_shadows { LIGHT_CASTS_SHADOWS } else { 0 },
        spot_exponent,
        spot_versin_cutoff: versin_cutoff as f32,
        attenuation_model: l.attenuation.model() as u32,
        spot_falloff: spot_falloff as u32,
        range,
        spot_versin_inner: versin_inner as f32,
    }
}

/// Every object's primitives, in scene order (the object id is the index in `desc.objects`).
fn flat_primitives(desc: &SceneDesc, material_names: &[String]) -> Primitives {
    let material_index = |name: &str| material_names.iter().position(|m| m == name).unwrap_or(0) as u32;
    let mut out = Primitives::default();
    for (id, object) in desc.objects.iter().enumerate() {
        let object_id = id as u32;
        let material = material_index(object.material());
        out.object_names.push(if object.name().is_empty() {
            format!("{} #{id}", object.kind_name())
        } else {
            object.name().to_string()
        });
        match object {
            ObjectDesc::Sphere(SphereDesc { center, radius, .. }) => out.spheres.push(GpuSphere {
                center_radius: vec4(DVec3::from(*center), *radius as f32),
                material,
                object_id,
                power: origin_power(vec4(DVec3::from(*center), *radius as f32)),
                pad: 0,
            }),
            ObjectDesc::Plane(PlaneDesc { point, normal, .. }) => {
                let n = DVec3::from(*normal).normalize();
                out.planes.push(GpuPlane {
                    normal_offset: vec4(n, n.dot(DVec3::from(*point)) as f32),
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
    out
}

/// A mesh's triangles, leaving out those of zero area in the stored (f32) data, so that they
/// are never hit, as validation promises: in the ray's sheared frame their edge functions are
/// rounding noise, and one on a line through the eye would be "hit" by a quarter of all camera
/// rays, with a 0/0 normal.
fn mesh_triangles(mesh: &MeshDesc, material: u32, object_id: u32, out: &mut Primitives) {
    let MeshDesc { vertices, triangles: tris, normals, uvs, .. } = mesh;
    let first = out.vertices.len() as u32;
    out.vertices.extend(vertices.iter().map(|&v| vec4(DVec3::from(v), 1.0)));
    // Every vertex gets a normal slot, so that one index reaches both; zero without normals.
    match normals {
        Some(n) => out.normals.extend(n.iter().map(|&n| vec4(DVec3::from(n).normalize(), 0.0))),
        None => out.normals.extend(std::iter::repeat_n([0.0; 4], vertices.len())),
    }
    match uvs {
        Some(uv) => out.uvs.extend(uv.iter().map(|&[u, v]| [u as f32, v as f32])),
        None => out.uvs.extend(std::iter::repeat_n([0.0; 2], vertices.len())),
    }
    let mesh_index = out.meshes.len() as u32;
    out.meshes.push(GpuMesh {
        material,
        object_id,
        flags: if normals.is_some() { MESH_HAS_NORMALS } else { 0 } | if uvs.is_some() { MESH_HAS_UVS } else { 0 },
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
        ambient: rgb4(desc.world.ambient),
        background: rgb4(desc.world.background),
        global_attenuation: {
            let g = desc.world.global_attenuation;
            [g.c as f32, g.l as f32, g.q as f32, 0.0]
        },
        frame: crate::rebase::WORLD_FRAME,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::builtin;

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
}
