//! Texture images read from files: PNG and JPEG decoded to the linear RGBA texels of a
//! `TextureImage`, and the textures a scene file names, read relative to it.

use std::path::Path;
use std::sync::Arc;

use glint_scene::{ColorSpace, SceneDesc, TextureError, TextureImage, check_size, srgb_to_linear};

use crate::uri::{MAX_RESOURCE_BYTES, resolve_uri};
use glint_scene::FieldIssue;

/// Decodes a PNG or JPEG file's bytes, converting sRGB colour channels to linear once
/// (alpha stays linear). The size is checked from the header, before decoding.
pub fn decode_texture(bytes: &[u8], color: ColorSpace) -> Result<TextureImage, TextureError> {
    let reader = image::ImageReader::new(std::io::Cursor::new(bytes))
        .with_guessed_format()
        .map_err(|e| TextureError::Decode(e.to_string()))?;
    match reader.format() {
        Some(image::ImageFormat::Png | image::ImageFormat::Jpeg) => {}
        _ => return Err(TextureError::Format),
    }
    if reader.format() == Some(image::ImageFormat::Jpeg)
        && let Some(end) = jpeg_cut_short(bytes)
    {
        return Err(TextureError::Decode(format!(
            "the JPEG ends at byte {end}, before its end-of-image marker: the file is cut short"
        )));
    }
    // A PNG's size is read from its IHDR here: the decoder answered a header claiming
    // 2^31 × 2^31 texels with "Memory limit exceeded" before the size could be named.
    if reader.format() == Some(image::ImageFormat::Png)
        && let Some(ihdr) = bytes.get(12..24).filter(|h| h.starts_with(b"IHDR"))
    {
        let side = |at: usize| u32::from_be_bytes([ihdr[at], ihdr[at + 1], ihdr[at + 2], ihdr[at + 3]]);
        check_size(side(4), side(8))?;
    }
    let (width, height) = reader.into_dimensions().map_err(|e| TextureError::Decode(e.to_string()))?;
    check_size(width, height)?;
    let reader = image::ImageReader::new(std::io::Cursor::new(bytes))
        .with_guessed_format()
        .map_err(|e| TextureError::Decode(e.to_string()))?;
    let decoded = reader.decode().map_err(|e| TextureError::Decode(e.to_string()))?;
    // Channels as exact fractions of their 8- or 16-bit maximum, in f64, then linear.
    let convert = |p: [f64; 4]| {
        let colour = |c: f64| match color {
            ColorSpace::Srgb => srgb_to_linear(c) as f32,
            ColorSpace::Linear => c as f32,
        };
        [colour(p[0]), colour(p[1]), colour(p[2]), p[3] as f32]
    };
    let sixteen_bit = decoded.color().bytes_per_pixel() > decoded.color().channel_count();
    let texels = if sixteen_bit {
        decoded.into_rgba16().pixels().map(|p| convert(p.0.map(|c| f64::from(c) / 65535.0))).collect()
    } else {
        decoded.into_rgba8().pixels().map(|p| convert(p.0.map(|c| f64::from(c) / 255.0))).collect()
    };
    TextureImage::from_linear_rgba(width, height, texels)
}

/// Decodes every texture of `desc` whose image is not filled yet, reading its path relative to
/// `file` (the scene file) through `resolve_uri`. Each image file is decoded once, however many
/// textures name it. Every failure is reported, naming `materials.NAME.FIELD.path`; the caller
/// names the file (this module imports no error of the scene's, which imports the models that
/// decode textures here).
pub fn load_textures(desc: &mut SceneDesc, file: &Path) -> Result<(), Vec<FieldIssue>> {
    let mut decoded: Vec<(String, Arc<TextureImage>)> = Vec::new();
    let mut issues = Vec::new();
    for (name, m) in &mut desc.materials {
        for (field, texture) in [("texture", &mut m.texture), ("emission_texture", &mut m.emission_texture)] {
            let Some(t) = texture.as_mut().filter(|t| t.image.is_none()) else { continue };
            if let Some((_, image)) = decoded.iter().find(|(p, _)| *p == t.path) {
                t.image = Some(Arc::clone(image));
                continue;
            }
            let image = resolve_uri(file, &t.path, MAX_RESOURCE_BYTES)
                .map_err(|e| e.to_string())
                .and_then(|bytes| decode_texture(&bytes, ColorSpace::Srgb).map_err(|e| e.to_string()));
            match image {
                Ok(image) => {
                    let image = Arc::new(image);
                    decoded.push((t.path.clone(), Arc::clone(&image)));
                    t.image = Some(image);
                }
                Err(problem) => {
                    issues.push(FieldIssue { field: format!("materials.{name}.{field}.path"), problem });
                }
            }
        }
    }
    if issues.is_empty() { Ok(()) } else { Err(issues) }
}

/// The length of a JPEG that ends before its end-of-image marker, `None` if it has one (or is
/// not laid out as JPEG markers, which the decoder then names). The decoder fills a file cut
/// short with grey rows and no error (a tester's texture cut at 3,000 of 9,287 bytes rendered
/// flat grey). The marker segments are walked from the start, so that an EXIF thumbnail's own
/// end marker, inside its APP1 segment, is skipped with it; a scan's data runs to the next
/// marker that is neither a stuffed 0xFF00 nor a restart marker.
fn jpeg_cut_short(bytes: &[u8]) -> Option<usize> {
    let cut = Some(bytes.len());
    let mut at = 2; // after the start-of-image marker
    loop {
        if *bytes.get(at)? != 0xFF {
            return None;
        }
        while bytes.get(at) == Some(&0xFF) {
            at += 1;
        }
        let marker = *bytes.get(at)?;
        at += 1;
        match marker {
            0xD9 => return None,
            0x01 | 0xD0..=0xD7 => continue,
            _ => {}
        }
        let Some(length) = bytes.get(at..at + 2) else { return cut };
        at += usize::from(u16::from_be_bytes([length[0], length[1]]));
        if at > bytes.len() {
            return cut;
        }
        if marker == 0xDA {
            loop {
                match bytes.get(at..at + 2) {
                    None => return cut,
                    Some([0xFF, 0x00 | 0xD0..=0xD7]) => at += 2,
                    Some([0xFF, next]) if *next != 0xFF => break,
                    Some(_) => at += 1,
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn png(width: u32, height: u32, rgba: &[u8]) -> Vec<u8> {
        let mut out = Vec::new();
        let mut encoder = png::Encoder::new(&mut out, width, height);
        encoder.set_color(png::ColorType::Rgba);
        encoder.set_depth(png::BitDepth::Eight);
        encoder.write_header().unwrap().write_image_data(rgba).unwrap();
        out
    }

    #[test]
    fn srgb_is_converted_once_and_alpha_stays() {
        let bytes = png(2, 1, &[0, 128, 255, 128, 255, 255, 255, 0]);
        let t = decode_texture(&bytes, ColorSpace::Srgb).expect("decodes");
        assert_eq!((t.width(), t.height()), (2, 1));
        let want = srgb_to_linear(128.0 / 255.0) as f32;
        assert_eq!(t.texels()[0], [0.0, want, 1.0, (128.0_f64 / 255.0) as f32]);
        assert_eq!(t.texels()[1], [1.0, 1.0, 1.0, 0.0]);
        let linear = decode_texture(&bytes, ColorSpace::Linear).expect("decodes");
        assert_eq!(linear.texels()[0][1], (128.0_f64 / 255.0) as f32);
    }

    #[test]
    fn a_jpeg_cut_short_is_refused_and_a_whole_one_decodes() {
        let mut image = image::RgbImage::new(32, 24);
        image.pixels_mut().enumerate().for_each(|(i, p)| *p = image::Rgb([(i * 7) as u8, (i * 3) as u8, 90]));
        let mut whole = Vec::new();
        image::codecs::jpeg::JpegEncoder::new_with_quality(&mut whole, 90).encode_image(&image).expect("encodes");
        assert_eq!(jpeg_cut_short(&whole), None);
        assert!(decode_texture(&whole, ColorSpace::Srgb).is_ok());
        // Bytes after the end marker (a trailer some writers append) are not a cut.
        let mut trailed = whole.clone();
        trailed.extend_from_slice(b"trailer");
        assert_eq!(jpeg_cut_short(&trailed), None);
        for keep in [whole.len() - 2, whole.len() / 2, 200] {
            let cut = &whole[..keep];
            assert_eq!(jpeg_cut_short(cut), Some(keep), "cut at {keep}");
            let said = decode_texture(cut, ColorSpace::Srgb).expect_err("a JPEG cut short").to_string();
            assert!(said.contains(&format!("the JPEG ends at byte {keep}, before its end-of-image marker")), "{said}");
        }
    }

    #[test]
    fn other_formats_garbage_and_huge_headers_are_clear_errors() {
        assert!(matches!(decode_texture(b"not an image", ColorSpace::Srgb), Err(TextureError::Format)));
        let mut bytes = png(1, 1, &[0, 0, 0, 255]);
        bytes.truncate(bytes.len() - 20);
        assert!(decode_texture(&bytes, ColorSpace::Srgb).is_err());
        // A valid 1×1 PNG whose header claims 20000×20000 texels (CRC fixed): refused from
        // the header, before anything is decoded.
        // PNG's largest, 2^31 − 1 a side, too: named by its size, not the decoder's memory limit.
        for side in [20000u32, (1 << 31) - 1] {
            let mut huge = png(1, 1, &[0, 0, 0, 255]);
            huge[16..20].copy_from_slice(&side.to_be_bytes());
            huge[20..24].copy_from_slice(&side.to_be_bytes());
            let crc = crc32(&huge[12..29]);
            huge[29..33].copy_from_slice(&crc.to_be_bytes());
            let e = decode_texture(&huge, ColorSpace::Srgb).unwrap_err();
            assert!(matches!(e, TextureError::TooLarge { width, height } if width == side && height == side), "{e}");
        }
        let e = TextureImage::from_linear_rgba(2, 2, vec![[0.0; 4]; 3]).unwrap_err();
        assert_eq!(e.to_string(), "3 texels given for a 2x2 image");
    }

    /// PNG's chunk CRC (ISO 3309), bit by bit.
    fn crc32(bytes: &[u8]) -> u32 {
        let mut crc = u32::MAX;
        for &b in bytes {
            crc ^= u32::from(b);
            for _ in 0..8 {
                crc = if crc & 1 != 0 { (crc >> 1) ^ 0xEDB8_8320 } else { crc >> 1 };
            }
        }
        !crc
    }
}
