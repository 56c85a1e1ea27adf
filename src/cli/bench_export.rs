//! `glint bench rays --export DIR`: the benchmark's mesh, both ray sets and the CPU's hits as
//! raw little-endian arrays, for an outside tracer to cast the same rays at the same triangles
//! and compare (`crates/glint-core/benches/embree_rays.cpp`, Intel Embree: the anchor the
//! issue's targets are stated against, measured on the same machine in the same session).
//!
//! Files, each a plain array (no header; counts follow from the sizes):
//! - `vertices.f32x4`: the flat scene's vertex positions (x, y, z, 1);
//! - `triangles.u32x3`: each triangle's three vertex indices, in the flat scene's (leaf) order;
//! - `primary.rays`, `incoherent.rays`: `RayRecord`s (origin, t_min; direction, t_max; f32);
//! - `primary.hits`, `incoherent.hits`: the CPU's `HitRecord` per ray (kind, 3 for a triangle
//!   and 0 for a miss; triangle index; t as f32; 0).

use std::path::Path;

use anyhow::{Context, bail};
use glint_core::FlatScene;
use glint_core::cpu::raycast::{HitRecord, RayRecord};
use glint_core::rays::RaySet;
use glint_io::atomic::write_file_atomically;

use crate::cli::units::counted;

/// Before the benchmark runs: an error unless the exported mesh is the whole scene, and
/// `dir` made if missing (so a path that cannot be a folder fails before minutes of work).
pub fn prepare(dir: &Path, flat: &FlatScene) -> anyhow::Result<()> {
    if !flat.spheres.is_empty() || !flat.planes.is_empty() {
        bail!(
            "--export: the scene has {} and {}; the exported mesh holds triangles only, so an outside tracer \
             would not see them (bumpy has none)",
            counted(flat.spheres.len(), "sphere"),
            counted(flat.planes.len(), "plane")
        );
    }
    super::output_path::create_folder("--export", dir)
}

/// Writes the files above into `dir` (`prepare`d), each atomically.
pub fn export(dir: &Path, flat: &FlatScene, sets: &[(RaySet, &[RayRecord], &[HitRecord])]) -> anyhow::Result<()> {
    let write = |name: &str, bytes: &[u8]| {
        let path = dir.join(name);
        write_file_atomically(&path, bytes).with_context(|| format!("--export: cannot write {}", path.display()))
    };
    write("vertices.f32x4", bytemuck::cast_slice(&flat.vertices[..]))?;
    let indices: Vec<[u32; 3]> = flat.triangles.iter().map(|t| [t.va, t.vb, t.vc]).collect();
    write("triangles.u32x3", bytemuck::cast_slice(&indices))?;
    for (set, rays, hits) in sets {
        write(&format!("{}.rays", set.name()), bytemuck::cast_slice(rays))?;
        write(&format!("{}.hits", set.name()), bytemuck::cast_slice(hits))?;
    }
    Ok(())
}
