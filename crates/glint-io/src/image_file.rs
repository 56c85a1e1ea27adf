//! Rendered images written to files (8-bit sRGB PNG with metadata, linear f32 OpenEXR), each
//! atomically, and the metadata read back from a PNG.

use std::io::{BufWriter, Write};
use std::path::Path;

use glint_core::image::HdrImage;

use crate::atomic::write_atomically;
use crate::exr_file::{PIXELS_SHA256, write_exr_region};

pub use crate::error::ImageWriteError;

/// Refuses an image with pixels no file can hold as they are (see `HdrImage::unrepresentable`).
fn check_representable(path: &Path, image: &HdrImage) -> Result<(), ImageWriteError> {
    match image.unrepresentable() {
        Some(found) => Err(ImageWriteError::Unrepresentable { path: path.to_owned(), found }),
        None => Ok(()),
    }
}

/// 8-bit sRGB PNG with `metadata` as tEXt chunks.
pub fn write_png(path: &Path, image: &HdrImage, metadata: &[(String, String)]) -> Result<(), ImageWriteError> {
    check_representable(path, image)?;
    write_png_rgb8(path, image.width, image.height, &image.to_srgb8(), metadata)
}

/// SHA-256 of 8-bit RGB pixels as a PNG holds them (R, G, B, one byte each, row by row), in
/// hex: the EXR's `pixel_digest` for the bytes this format stores.
pub fn rgb8_digest(rgb: &[u8]) -> String {
    use sha2::{Digest, Sha256};
    Sha256::digest(rgb).iter().map(|b| format!("{b:02x}")).collect()
}

/// An already encoded 8-bit RGB buffer as PNG with tEXt metadata and its pixels' digest
/// (`PIXELS_SHA256`, of `rgb8_digest`, in place of any `metadata` gives): a render's PNG and a
/// merge's differ in their time and rays, so the digest is what tells that their pixels agree.
pub fn write_png_rgb8(
    path: &Path,
    width: u32,
    height: u32,
    rgb: &[u8],
    metadata: &[(String, String)],
) -> Result<(), ImageWriteError> {
    write_atomically(path, |file| {
        let io = |error| ImageWriteError::Io { path: path.to_owned(), error };
        let png_err = |e: png::EncodingError| ImageWriteError::Png { path: path.to_owned(), message: e.to_string() };
        let mut out = BufWriter::new(file);
        let mut encoder = png::Encoder::new(&mut out, width, height);
        encoder.set_color(png::ColorType::Rgb);
        encoder.set_depth(png::BitDepth::Eight);
        encoder.set_source_srgb(png::SrgbRenderingIntent::Perceptual);
        // fdeflate's PNG-tuned fast mode. On the 1280×720 Whitted render it encodes in 10 ms
        // instead of zlib's default level's 55 ms (5.4×), for a file a third larger (177 kB
        // against 133 kB): the encoding was a fifth of the whole command's wall time.
        encoder.set_compression(png::Compression::Fast);
        let digest = (PIXELS_SHA256.to_string(), rgb8_digest(rgb));
        let metadata = metadata.iter().filter(|(k, _)| k != PIXELS_SHA256).chain(std::iter::once(&digest));
        for (key, value) in metadata {
            // tEXt holds Latin-1 only: a scene named 日本.toml (its path is `glint:source`)
            // failed to write at all. UTF-8 goes in iTXt, where a value needs it.
            if value.chars().all(|c| u32::from(c) < 256) {
                encoder.add_text_chunk(key.clone(), value.clone()).map_err(png_err)?;
            } else {
                encoder.add_itxt_chunk(key.clone(), value.clone()).map_err(png_err)?;
            }
        }
        let mut writer = encoder.write_header().map_err(png_err)?;
        writer.write_image_data(rgb).map_err(png_err)?;
        writer.finish().map_err(png_err)?;
        out.flush().map_err(io)
    })
}

/// Linear f32 OpenEXR with `metadata` as text attributes (the values a PNG's text chunks hold).
pub fn write_exr(path: &Path, image: &HdrImage, metadata: &[(String, String)]) -> Result<(), ImageWriteError> {
    write_exr_tile(path, image, (image.width, image.height), (0, 0), metadata)
}

/// `write_exr` of `image` as the data window at `origin` of a `display`-sized image (a tile of
/// `glint render --tile`).
pub fn write_exr_tile(
    path: &Path,
    image: &HdrImage,
    display: (u32, u32),
    origin: (u32, u32),
    metadata: &[(String, String)],
) -> Result<(), ImageWriteError> {
    check_representable(path, image)?;
    let pixel = |x: usize, y: usize| image.pixels[y * image.width as usize + x].to_array().map(|v| v as f32);
    write_exr_region(path, display, origin, (image.width, image.height), pixel, metadata)
}

/// PNG or EXR by the file extension.
pub fn write_image(path: &Path, image: &HdrImage, metadata: &[(String, String)]) -> Result<(), ImageWriteError> {
    match path.extension().and_then(|e| e.to_str()).map(str::to_ascii_lowercase).as_deref() {
        Some("png") => write_png(path, image, metadata),
        Some("exr") => write_exr(path, image, metadata),
        _ => Err(ImageWriteError::Format { path: path.to_owned() }),
    }
}

/// The text chunks of a PNG file: tEXt, then iTXt (where `write_png` puts a value that is not
/// Latin-1, a viewer's "Whitted − GI" say).
pub fn read_png_text(path: &Path) -> Result<Vec<(String, String)>, std::io::Error> {
    let decoder = png::Decoder::new(std::io::BufReader::new(std::fs::File::open(path)?));
    let reader = decoder.read_info().map_err(std::io::Error::other)?;
    let info = reader.info();
    let latin1 = info.uncompressed_latin1_text.iter().map(|t| Ok((t.keyword.clone(), t.text.clone())));
    let utf8 = info.utf8_text.iter().map(|t| Ok((t.keyword.clone(), t.get_text().map_err(std::io::Error::other)?)));
    latin1.chain(utf8).collect()
}

#[cfg(test)]
mod tests {
    use glint_core::glam::DVec3;
    use glint_core::image::Unrepresentable;

    use super::*;

    #[test]
    fn a_png_carries_the_digest_of_its_pixels_as_stored() {
        let dir = std::env::temp_dir().join(format!("glint-io-png-digest-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let path = dir.join("d.png");
        let rgb: Vec<u8> = (0..2 * 3 * 3).map(|v| (v * 13) as u8).collect();
        let stale = vec![("glint:spp".to_string(), "4".to_string()), (PIXELS_SHA256.to_string(), "0".repeat(64))];
        write_png_rgb8(&path, 3, 2, &rgb, &stale).unwrap();
        let text = read_png_text(&path).unwrap();
        let digests: Vec<&str> = text.iter().filter(|(k, _)| k == PIXELS_SHA256).map(|(_, v)| v.as_str()).collect();
        // The bytes' SHA-256 (as `sha256sum` gives it of the raw RGB), one, not a stale one given.
        use sha2::{Digest, Sha256};
        let expected: String = Sha256::digest(&rgb).iter().map(|b| format!("{b:02x}")).collect();
        assert_eq!(digests, [expected.as_str()]);
        assert!(text.contains(&("glint:spp".to_string(), "4".to_string())), "{text:?}");
        std::fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn radiance_beyond_f32_is_never_written() {
        // Finite in f64, +inf once stored as f32: before, the EXR held +inf and the PNG white.
        let dir = std::env::temp_dir().join(format!("glint-core-image-overflow-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let mut image = HdrImage::new(4, 2);
        image.pixels[5] = DVec3::new(1.0, 1e45, 0.0);
        image.pixels[7] = DVec3::splat(f64::NAN);
        let found = image.unrepresentable().expect("two bad pixels");
        assert_eq!(found, Unrepresentable { count: 2, first: (1, 1), largest: 1e45, nan: 1 });
        for name in ["out.exr", "out.png"] {
            let path = dir.join(name);
            let error = write_image(&path, &image, &[]).expect_err("refused");
            assert_eq!(
                error.to_string(),
                format!(
                    "{}: not written: 2 pixels have radiance that is not a finite f32 number (1 of them NaN; \
                     largest 1e45, first at pixel (1, 1))",
                    path.display()
                )
            );
        }
        assert_eq!(std::fs::read_dir(&dir).unwrap().count(), 0, "nothing written");
        image.pixels[5] = DVec3::ZERO;
        let nan_only = image.unrepresentable().expect("a NaN pixel");
        assert_eq!(nan_only.to_string(), "1 pixel is NaN (first at pixel (3, 1))");
        image.pixels[5] = DVec3::splat(f64::from(f32::MAX));
        image.pixels[7] = DVec3::ZERO;
        assert_eq!(image.unrepresentable(), None, "f32::MAX itself is representable");
        std::fs::remove_dir_all(dir).unwrap();
    }
}
