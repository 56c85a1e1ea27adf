//! The flat layout's textures: one texel buffer (linear RGBA f32, each image once however many
//! materials use it) and a table of `GpuTexture`s pointing into it, built from the materials'
//! image textures and checkers.

use std::sync::Arc;

use glint_scene::{CheckerDesc, Filter, Rgb, TextureDesc, TextureImage, UvTransform, Wrap};
use glint_types::layout::{GpuTexture, NO_TEXTURE};

/// The texture table and texel buffer under construction.
#[derive(Debug, Default)]
pub(crate) struct TextureTable {
    pub textures: Vec<GpuTexture>,
    pub texels: Vec<[f32; 4]>,
    /// Each texture's UV transform rows in f64, as `textures` stores them in f32
    /// (`FlatScene::texture_transforms`).
    pub transforms: Vec<[[f64; 3]; 2]>,
    /// Images already in `texels`, with their first texel.
    stored: Vec<(Arc<TextureImage>, u32)>,
}

fn row(m: [f64; 3]) -> [f32; 4] {
    [m[0] as f32, m[1] as f32, m[2] as f32, 0.0]
}

impl TextureTable {
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
        self.transforms.push([u, v]);
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
            // In world space (frame origin 0) the origin's coordinates are the offsets.
            planar_u: [row(u)[2]; 4],
            planar_v: [row(v)[2]; 4],
        });
        self.textures.len() as u32 - 1
    }
}
