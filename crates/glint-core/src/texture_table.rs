//! The flat layout's textures: one texel buffer (linear RGBA f32, each image once however many
//! materials use it) and a table of `GpuTexture`s pointing into it, built from the materials'
//! image textures and checkers, with their planar origins placed in the frame the scene is
//! stored in.

use std::sync::Arc;

use glam::DVec3;

use glint_scene::{CheckerDesc, Filter, Rgb, TextureDesc, TextureImage, UvTransform, Wrap};
use glint_types::layout::{GpuTexture, NO_TEXTURE};

/// The texture table and texel buffer under construction.
#[derive(Debug)]
pub(crate) struct TextureTable {
    pub textures: Vec<GpuTexture>,
    pub texels: Vec<[f32; 4]>,
    /// Images already in `texels`, with their first texel.
    stored: Vec<(Arc<TextureImage>, u32)>,
    /// The frame's origin in world space (the storage origin), where `planar_origins` are placed.
    origin: DVec3,
}

fn row(m: [f64; 3]) -> [f32; 4] {
    [m[0] as f32, m[1] as f32, m[2] as f32, 0.0]
}

impl TextureTable {
    /// An empty table for a scene stored relative to `origin` (world space).
    pub fn new(origin: DVec3) -> Self {
        Self { textures: Vec::new(), texels: Vec::new(), stored: Vec::new(), origin }
    }

    /// The table entry of an image texture, its image stored once. A texture without an image
    /// (never passes validation) gets `NO_TEXTURE`.
    pub fn add(&mut self, t: &TextureDesc) -> u32 {
        let Some(image) = &t.image else { return NO_TEXTURE };
        let offset = match self.stored.iter().find(|(i, _)| Arc::ptr_eq(i, image)) {
            Some(&(_, offset)) => offset,
            None => {
                let offset = self.texels.len() as u32;
                self.texels.extend_from_slice(image.texels());
                self.stored.push((Arc::clone(image), offset));
                offset
            }
        };
        let transform = t.transform.unwrap_or_default();
        self.push(offset, image.width(), image.height(), [t.wrap_s, t.wrap_t], t.filter, &transform)
    }

    /// The checker as a 2×2 nearest, repeating texture of k_d and the second colour, one texel
    /// per square: planar coordinates scaled by 1 / (2 · size) (one repeat is two squares).
    pub fn add_checker(&mut self, kd: Rgb, checker: &CheckerDesc) -> u32 {
        let texel = |c: Rgb| [c.0[0] as f32, c.0[1] as f32, c.0[2] as f32, 1.0];
        let offset = self.texels.len() as u32;
        self.texels.extend_from_slice(&[texel(kd), texel(checker.kd), texel(checker.kd), texel(kd)]);
        let scale = 0.5 / checker.size;
        let transform = UvTransform { offset: [0.0; 2], rotation: 0.0, scale: [scale; 2] };
        self.push(offset, 2, 2, [Wrap::Repeat; 2], Filter::Nearest, &transform)
    }

    fn push(&mut self, offset: u32, width: u32, height: u32, wrap: [Wrap; 2], filter: Filter, t: &UvTransform) -> u32 {
        let [u, v] = t.matrix();
        let (planar_u, planar_v) = (planar_origins(u, wrap[0], self.origin), planar_origins(v, wrap[1], self.origin));
        self.textures.push(GpuTexture {
            offset,
            width,
            height,
            wrap_s: wrap[0] as u32,
            wrap_t: wrap[1] as u32,
            filter_mode: filter as u32,
            pad_a: 0,
            pad_b: 0,
            transform_u: row(u),
            transform_v: row(v),
            planar_u,
            planar_v,
        });
        self.textures.len() as u32 - 1
    }
}

/// A texture's planar origins (`GpuTexture::planar_u` or `planar_v`, for the transform `row`)
/// in the frame whose origin is `origin`: the transformed planar coordinates of that origin
/// across each axis, in f64 from the f64 transform (the f32 one's rounding times the origin's
/// distance is a shift of the pattern: a checker of size 0.3 moved by 9e6 of its periods was
/// half a period off), folded towards 0 by the wrap mode's period (`fold`). Planar coordinates
/// are then taken relative to the frame, small, and a texel edge 1e6 units from the world
/// origin stays where it is (its f32 world coordinate was off by 1/16 there). At the world
/// origin they are the offsets, exact. A rebase moves them (`flat::move_texture_origins`).
fn planar_origins(row: [f64; 3], wrap: Wrap, origin: DVec3) -> [f32; 4] {
    let offset = row[2] as f32;
    if origin == DVec3::ZERO {
        return [offset; 4];
    }
    let across = [(origin.y, origin.z), (origin.x, origin.z), (origin.x, origin.y)];
    let [a, b, c] = across.map(|(a, b)| fold(row[0] * a + row[1] * b + row[2], wrap as u32) as f32);
    [a, b, c, offset]
}

/// `u` less the whole number of its wrap mode's periods nearest it, into [−period/2,
/// period/2]: the same texel, a number near 0. Not [0, period): an origin just below a square's
/// edge (u = −1e-9, a 1e9 checker's edge at the frame's origin) folded to 1 − 1e-9, which f32
/// rounds to 1, and 1 + the point's own tiny coordinate is 1 again: every point near the edge
/// took one side of it. Clamped coordinates have no period and stay.
pub(crate) fn fold(u: f64, wrap: u32) -> f64 {
    match Wrap::try_from(wrap) {
        Ok(Wrap::Repeat) => u - u.round(),
        Ok(Wrap::MirroredRepeat) => u - 2.0 * (u * 0.5).round(),
        Ok(Wrap::ClampToEdge) | Err(_) => u,
    }
}
