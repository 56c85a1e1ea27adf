//! A flat scene's frame (`SceneHeader::frame`): the origin its positions are stored
//! relative to, which planar texture coordinates are taken from.

use glam::DVec3;

use super::{FlatScene, wide};
use crate::texture_table::fold;

impl FlatScene {
    /// Where the stored coordinates have their origin, in world space (`SceneHeader::frame`:
    /// the storage origin as built, the GPU's frame once rebased). A stored point p is the
    /// world point p + `frame_origin()`.
    pub fn frame_origin(&self) -> DVec3 {
        wide(self.header.frame)
    }
}

/// Each texture's planar origins moved with the frame, from `from` to `to` (world space): the
/// planar coordinates of the shift, with the f32 transform the tracers apply to every stored
/// point, added to the origins placed at `from`. A point's coordinates are then those it has in
/// the frame `from`, to f32's rounding of the sum: the GPU, rebased, reads the pattern the CPU
/// reads where the scene is stored (placed anew at `to` with the f64 transform, the two
/// differed by its rounding times the shift: 7.7e-3 at a checker edge of a scene 3e3 out).
pub(crate) fn move_texture_origins(out: &mut FlatScene, from: DVec3, to: DVec3) {
    let d = to - from;
    if d == DVec3::ZERO {
        return;
    }
    let across = [(d.y, d.z), (d.x, d.z), (d.x, d.y)];
    for tex in &mut out.textures {
        for (k, &(a, b)) in across.iter().enumerate() {
            let moved = |row: [f32; 4], at: f32, wrap: u32| {
                fold(f64::from(row[0]) * a + f64::from(row[1]) * b + f64::from(at), wrap) as f32
            };
            tex.planar_u[k] = moved(tex.transform_u, tex.planar_u[k], tex.wrap_s);
            tex.planar_v[k] = moved(tex.transform_v, tex.planar_v[k], tex.wrap_t);
        }
    }
}
