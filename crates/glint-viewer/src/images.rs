//! CPU-side images as egui textures (the CPU reference and the difference heat map), and the
//! composites that "Save image" writes.

use glint_core::HdrImage;
use glint_core::compare::srgb8;

/// A texture that is replaced in place when its pixels change.
#[derive(Default)]
pub struct CpuTexture {
    pub handle: Option<egui::TextureHandle>,
    pub size: (u32, u32),
}

impl std::fmt::Debug for CpuTexture {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("CpuTexture").field("size", &self.size).finish_non_exhaustive()
    }
}

impl CpuTexture {
    pub fn set_rgba(&mut self, ctx: &egui::Context, name: &str, width: u32, height: u32, rgba: &[u8]) {
        let image = egui::ColorImage::from_rgba_unmultiplied([width as usize, height as usize], rgba);
        self.set(ctx, name, image, (width, height));
    }

    pub fn set_rgb(&mut self, ctx: &egui::Context, name: &str, width: u32, height: u32, rgb: &[u8]) {
        let image = egui::ColorImage::from_rgb([width as usize, height as usize], rgb);
        self.set(ctx, name, image, (width, height));
    }

    fn set(&mut self, ctx: &egui::Context, name: &str, image: egui::ColorImage, size: (u32, u32)) {
        // Nearest filtering: the pixels of a reference image should stay pixels when magnified.
        let options = egui::TextureOptions::NEAREST;
        match &mut self.handle {
            Some(h) => h.set(image, options),
            None => self.handle = Some(ctx.load_texture(name, image, options)),
        }
        self.size = size;
    }

    pub fn id(&self) -> Option<egui::TextureId> {
        self.handle.as_ref().map(egui::TextureHandle::id)
    }
}

/// Images placed left to right on one canvas (8-bit RGB, same height).
pub fn side_by_side(parts: &[(u32, u32, &[u8])]) -> (u32, u32, Vec<u8>) {
    let width: u32 = parts.iter().map(|p| p.0).sum();
    let height = parts.iter().map(|p| p.1).max().unwrap_or(0);
    let mut out = vec![0u8; width as usize * height as usize * 3];
    let mut x0 = 0usize;
    for &(w, h, rgb) in parts {
        for y in 0..h as usize {
            let src = &rgb[y * w as usize * 3..(y + 1) * w as usize * 3];
            let dst = (y * width as usize + x0) * 3;
            out[dst..dst + src.len()].copy_from_slice(src);
        }
        x0 += w as usize;
    }
    (width, height, out)
}

/// Linear images placed left to right (for EXR export of several views).
pub fn side_by_side_hdr(parts: &[&HdrImage]) -> HdrImage {
    let width: u32 = parts.iter().map(|p| p.width).sum();
    let height = parts.iter().map(|p| p.height).max().unwrap_or(0);
    let mut out = HdrImage::new(width, height);
    let mut x0 = 0u32;
    for p in parts {
        for y in 0..p.height {
            for x in 0..p.width {
                let i = ((y * width) + x0 + x) as usize;
                out.pixels[i] = p.get(x, y);
                out.first_hit[i] = p.first_hit[(y * p.width + x) as usize];
            }
        }
        x0 += p.width;
    }
    out
}

/// |GPU − CPU| per channel as a linear image (the EXR form of the difference view).
pub fn abs_difference(cpu: &HdrImage, gpu: &HdrImage) -> HdrImage {
    let mut out = cpu.clone();
    for (o, g) in out.pixels.iter_mut().zip(&gpu.pixels) {
        *o = (*g - *o).abs();
    }
    out
}

pub fn srgb(image: &HdrImage) -> Vec<u8> {
    srgb8(image)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn side_by_side_places_each_part_at_its_offset() {
        let a = [1u8, 1, 1, 2, 2, 2];
        let b = [9u8, 9, 9, 8, 8, 8];
        let (w, h, out) = side_by_side(&[(1, 2, &a), (1, 2, &b)]);
        assert_eq!((w, h), (2, 2));
        assert_eq!(out, vec![1, 1, 1, 9, 9, 9, 2, 2, 2, 8, 8, 8]);
    }
}
