//! A flat scene's frame (`SceneHeader::frame`): the origin its positions are stored
//! relative to, which planar texture coordinates are taken from.

use glam::DVec3;

use super::{FlatScene, wide};
use glint_scene::Wrap;

impl FlatScene {
    /// Where the stored coordinates have their origin, in world space (`SceneHeader::frame`:
    /// the storage origin as built, the GPU's frame once rebased). A stored point p is the
    /// world point p + `frame_origin()`.
    pub fn frame_origin(&self) -> DVec3 {
        wide(self.header.frame)
    }
}

/// Each texture's planar origins (`GpuTexture::planar_u`, `planar_v`) for `frame`, the frame
/// the scene is built in (its storage origin): the transformed planar coordinates of the
/// frame's origin, across each axis, in f64 (with the f64 transform,
/// `FlatScene::texture_transforms`: the stored f32 one's rounding times the origin's distance is
/// a shift of the pattern), folded towards 0 by the wrap mode's period (`fold`). Planar
/// coordinates are then taken relative to the frame, small, and a texel edge 1e6 units from the
/// world origin stays where it is (its f32 world coordinate was off by 1/16 there). At the world
/// origin they are the offsets, exact. A rebase moves them (`move_texture_origins`).
pub(crate) fn place_texture_origins(out: &mut FlatScene, frame: [f32; 4]) {
    let f = wide(frame);
    let across = [(f.y, f.z), (f.x, f.z), (f.x, f.y)];
    let at_world_origin = f == DVec3::ZERO;
    for (i, tex) in out.textures.iter_mut().enumerate() {
        // A texture put in without its f64 rows (a test's table) is placed with its f32 ones,
        // not left unplaced.
        let widened = |r: [f32; 4]| [f64::from(r[0]), f64::from(r[1]), f64::from(r[2])];
        let [u, v] =
            out.texture_transforms.get(i).copied().unwrap_or([widened(tex.transform_u), widened(tex.transform_v)]);
        for (k, &(a, b)) in across.iter().enumerate() {
            let at = |stored: [f32; 4], row: [f64; 3], wrap: u32| {
                if at_world_origin {
                    return stored[2];
                }
                fold(row[0] * a + row[1] * b + row[2], wrap) as f32
            };
            tex.planar_u[k] = at(tex.transform_u, u, tex.wrap_s);
            tex.planar_v[k] = at(tex.transform_v, v, tex.wrap_t);
        }
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

/// `u` less the whole number of its wrap mode's periods nearest it, into [−period/2,
/// period/2]: the same texel, a number near 0. Not [0, period): an origin just below a square's
/// edge (u = −1e-9, a 1e9 checker's edge at the frame's origin) folded to 1 − 1e-9, which f32
/// rounds to 1, and 1 + the point's own tiny coordinate is 1 again: every point near the edge
/// took one side of it. Clamped coordinates have no period and stay.
fn fold(u: f64, wrap: u32) -> f64 {
    match Wrap::try_from(wrap) {
        Ok(Wrap::Repeat) => u - u.round(),
        Ok(Wrap::MirroredRepeat) => u - 2.0 * (u * 0.5).round(),
        Ok(Wrap::ClampToEdge) | Err(_) => u,
    }
}
