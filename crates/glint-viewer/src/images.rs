//! CPU-side images as egui textures (the CPU reference and the difference heat map), and the
//! composites that "Save image" writes.

use glint_core::HdrImage;

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
        let image = within_texture_side(image, ctx.input(|i| i.max_texture_side));
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

/// `image`, or every k-th pixel of it where a side exceeds what the window's textures hold
/// (`max_side`, the device's; a render may be up to 16384 a side): shown in the same place, as
/// the sampler's nearest filtering would minify it, where the whole image made the window's
/// device fail. Probes and saved images read the render itself, not this.
pub fn within_texture_side(image: egui::ColorImage, max_side: usize) -> egui::ColorImage {
    let [width, height] = image.size;
    let k = width.max(height).div_ceil(max_side.max(1));
    if k <= 1 {
        return image;
    }
    let size = [width.div_ceil(k), height.div_ceil(k)];
    let pixels = (0..size[1])
        .flat_map(|y| (0..size[0]).map(move |x| (x * k, y * k)))
        .map(|(x, y)| image.pixels[y * width + x])
        .collect();
    egui::ColorImage::new(size, pixels)
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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn an_image_wider_than_the_textures_is_shown_by_every_kth_pixel() {
        let (width, height) = (9000, 3);
        let pixels = (0..width * height).map(|i| egui::Color32::from_gray((i % 251) as u8)).collect();
        let image = egui::ColorImage::new([width, height], pixels);
        let small = within_texture_side(image.clone(), 8192);
        assert_eq!(small.size, [4500, 2]);
        assert_eq!(small.pixels[4500 + 7], image.pixels[2 * width + 14]);
        assert_eq!(within_texture_side(image.clone(), 9000).size, [9000, 3], "one that fits is kept");
    }

    #[test]
    fn side_by_side_places_each_part_at_its_offset() {
        let a = [1u8, 1, 1, 2, 2, 2];
        let b = [9u8, 9, 9, 8, 8, 8];
        let (w, h, out) = side_by_side(&[(1, 2, &a), (1, 2, &b)]);
        assert_eq!((w, h), (2, 2));
        assert_eq!(out, vec![1, 1, 1, 9, 9, 9, 2, 2, 2, 8, 8, 8]);
    }
}
