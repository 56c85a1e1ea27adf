//! What the tracers rely on in a flat scene: known tags, indices in range, finite numbers.

// What the parent module declares for its children.
use glint_types::Integrator;

use super::{
    EpsilonMode, Filter, FlatScene, LightTags, MESH_HAS_COLOURS, MESH_HAS_NORMALS, MESH_HAS_UVS, MaterialTags,
    NO_TEXTURE, UnknownTag, Wrap,
};

impl FlatScene {
    /// Decodes every stored tag the tracers switch on (the integrator, the ε strategy, each
    /// light's kind, attenuation model and spot falloff, each material's specular model and
    /// Fresnel), so that both refuse a scene holding a value no kind has instead of tracing it
    /// as another. Also checks that every index both tracers then follow without a check is in
    /// range: each triangle's vertices and mesh, each object's material, each texture's texels.
    pub fn check_tags(&self) -> Result<(), UnknownTag> {
        EpsilonMode::try_from(self.header.epsilon_mode)?;
        // The GPU has no error to raise: an unknown integrator ran as Whitted's, an unknown
        // specular model as Blinn's and an unknown Fresnel as the exact one (a code review).
        Integrator::try_from(self.header.integrator)?;
        for l in &self.lights {
            LightTags::decode(l)?;
        }
        for m in &self.materials {
            MaterialTags::decode(m)?;
        }
        let materials = self.materials.len();
        let material_of = |what: &'static str, m: u32| {
            if (m as usize) < materials { Ok(()) } else { Err(UnknownTag { what, value: m }) }
        };
        for s in self.spheres.iter() {
            material_of("sphere material index", s.material)?;
        }
        for p in self.planes.iter() {
            material_of("plane material index", p.material)?;
        }
        for m in self.meshes.iter() {
            material_of("mesh material index", m.material)?;
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
        let colours = self.meshes.iter().any(|m| m.flags & MESH_HAS_COLOURS != 0);
        if colours && self.colours.len() != vertices {
            return Err(UnknownTag { what: "vertex colour count (one per vertex)", value: self.colours.len() as u32 });
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
        if bad(&[c.anchor, c.forward, c.right, c.up].concat()) {
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
        let colours = self.colours.iter();
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
            .or_else(|| first_bad("colours", colours))
            .or_else(|| first_bad("textures", tx))
            .or_else(|| first_bad("texels", texels))
    }
}
