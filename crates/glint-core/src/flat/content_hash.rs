//! A fingerprint of everything a render reads: the flat scene's header (image size, samples,
//! depth, ε, seed, integrator), camera, materials, lights, geometry, texture texels and names.
//! Model and texture files enter by their content, as the tracers see it, so two machines that
//! loaded the same scene from the same files get the same hash, and a changed file changes it.
//! Tiles rendered on many machines carry it, and `glint merge` joins only tiles that agree.

use sha2::{Digest, Sha256};

use super::FlatScene;

impl FlatScene {
    /// SHA-256 of the scene as the tracers read it, in hex. The BVH is left out: it is made
    /// from the geometry.
    pub fn content_hash(&self) -> String {
        let mut h = Sha256::new();
        let mut part = |name: &str, bytes: &[u8]| {
            h.update((name.len() as u64).to_le_bytes());
            h.update(name.as_bytes());
            h.update((bytes.len() as u64).to_le_bytes());
            h.update(bytes);
        };
        part("header", bytemuck::bytes_of(&self.header));
        part("camera", bytemuck::bytes_of(&self.camera));
        part("materials", bytemuck::cast_slice(&self.materials));
        part("lights", bytemuck::cast_slice(&self.lights));
        part("spheres", bytemuck::cast_slice(&self.spheres));
        part("planes", bytemuck::cast_slice(&self.planes));
        part("triangles", bytemuck::cast_slice(&self.triangles));
        part("vertices", bytemuck::cast_slice(&self.vertices));
        part("normals", bytemuck::cast_slice(&self.normals));
        part("uvs", bytemuck::cast_slice(&self.uvs));
        part("colours", bytemuck::cast_slice(&self.colours));
        part("meshes", bytemuck::cast_slice(&self.meshes));
        part("textures", bytemuck::cast_slice(&self.textures));
        part("texels", bytemuck::cast_slice(&self.texels));
        for name in self.object_names.iter().chain(&self.material_names) {
            part("name", name.as_bytes());
        }
        h.finalize().iter().map(|b| format!("{b:02x}")).collect()
    }
}

#[cfg(test)]
mod tests {
    use glint_io::builtin;

    use crate::FlatScene;

    #[test]
    fn the_hash_follows_what_is_rendered_and_nothing_else() {
        let (desc, _) = builtin("whitted").expect("built-in").load(None).expect("loads");
        let flat = FlatScene::build(&desc, &desc.render);
        assert_eq!(flat.content_hash(), FlatScene::build(&desc, &desc.render).content_hash(), "not stable");
        assert_eq!(flat.content_hash().len(), 64);
        let mut settings = desc.render.clone();
        settings.spp += 1;
        assert_ne!(flat.content_hash(), FlatScene::build(&desc, &settings).content_hash(), "spp");
        let mut moved = desc.clone();
        moved.camera.position[0] += 0.5;
        assert_ne!(flat.content_hash(), FlatScene::build(&moved, &desc.render).content_hash(), "camera");
        let mut tinted = desc.clone();
        tinted.materials.values_mut().next().expect("a material").kd.0[0] *= 0.5;
        assert_ne!(flat.content_hash(), FlatScene::build(&tinted, &desc.render).content_hash(), "material");
    }
}
