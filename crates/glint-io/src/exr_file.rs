//! Linear f32 OpenEXR files with Glint's metadata as header attributes, written and read with
//! the `exr` crate: a whole image, or one tile of it whose data window is the tile and whose
//! display window is the whole image (the OpenEXR convention for a part of a picture, as
//! pbrt-v4's `--pixelbounds` writes it), so that `glint merge` can place it.

use std::io::BufWriter;
use std::path::{Path, PathBuf};

use exr::meta::attribute::{AttributeValue, SampleType, Text};
use exr::prelude::{
    Encoding, Image, IntegerBounds, Layer, LayerAttributes, ReadChannels, ReadLayers, SpecificChannels, Vec2,
    WritableImage,
};
use sha2::{Digest, Sha256};

use crate::atomic::write_atomically;
use crate::error::ImageWriteError;
use crate::exr_order::sort_attributes;

/// The attribute every EXR glint writes holds its pixels' digest in (`pixel_digest`): a tile
/// whose pixel bytes were damaged in an uncompressed chunk (one no checksum guards) read as
/// finite values, and `glint merge` passed them on.
pub const PIXELS_SHA256: &str = "glint:pixels_sha256";

/// SHA-256 of RGB pixels as f32 little-endian bytes, row by row, in hex.
pub fn pixel_digest(rgb: impl IntoIterator<Item = [f32; 3]>) -> String {
    let mut h = Sha256::new();
    for p in rgb {
        for c in p {
            h.update(c.to_le_bytes());
        }
    }
    h.finalize().iter().map(|b| format!("{b:02x}")).collect()
}

/// Where an EXR file's pixels lie in the whole image, and its text attributes.
#[derive(Clone, Debug, PartialEq)]
pub struct ExrHeader {
    /// The whole image's size (the display window).
    pub display: (u32, u32),
    /// The data window's top-left corner in the whole image.
    pub origin: (u32, u32),
    pub width: u32,
    pub height: u32,
    /// The text attributes of the header, in name order.
    pub attributes: Vec<(String, String)>,
    /// Why the RGB values read may not be the f32 values rendered, if they may not: a colour
    /// channel stored as another sample type (a tile re-encoded as half floats), or a
    /// compression that is lossy for f32 (PXR24, DWAA/B). `read_exr`, which converts every
    /// channel to f32 as it reads, judges the compression alone.
    pub inexact: Option<String>,
}

impl ExrHeader {
    /// The text attribute `name`, if the file has it.
    pub fn attribute(&self, name: &str) -> Option<&str> {
        self.attributes.iter().find(|(k, _)| k == name).map(|(_, v)| v.as_str())
    }
}

/// The pixels an EXR file holds, with its header.
#[derive(Clone, Debug, PartialEq)]
pub struct ExrPixels {
    pub header: ExrHeader,
    /// Linear RGB, row by row over the data window.
    pub rgb: Vec<[f32; 3]>,
}

impl ExrPixels {
    /// Whether the pixels are the ones the file's digest was made of: `None` for a file
    /// without one (not glint's, or a glint's before digests).
    pub fn digest_holds(&self) -> Option<bool> {
        // Hex in either case: a digest rewritten in capitals is the same digest.
        self.header.attribute(PIXELS_SHA256).map(|d| d.eq_ignore_ascii_case(&pixel_digest(self.rgb.iter().copied())))
    }
}

#[derive(Debug, thiserror::Error)]
pub enum ExrReadError {
    #[error("{path}: not a readable RGB OpenEXR file: {message}")]
    Decode { path: PathBuf, message: String },
    #[error("{path}: its data window {window} does not lie inside its display window ({width}x{height} at the origin)")]
    Window { path: PathBuf, window: String, width: i64, height: i64 },
}

/// An attribute value as EXR text holds it: its UTF-8 bytes (EXR's strings are bytes, which
/// OpenEXR's tools print as they are). As Latin-1, every other character had become '?': the
/// path of a scene named 日本.toml read back as ??.toml.
fn exr_text(value: &str) -> Text {
    Text::from_slice_unchecked(value.as_bytes())
}

/// An attribute's text: UTF-8 where its bytes are, else Latin-1 (another writer's, or a glint
/// before UTF-8, whose é is one byte).
fn text_value(t: &Text) -> String {
    std::str::from_utf8(t.bytes()).map_or_else(|_| t.to_string(), str::to_owned)
}

/// Writes the `width`×`height` pixels `pixel(x, y)` (coordinates within the data window) as
/// the data window at `origin` of a `display`-sized image, with `metadata` as text attributes
/// and the pixels' digest (`PIXELS_SHA256`, in place of any `metadata` gives), atomically. The
/// pixels are generated as they are written, never held twice.
pub fn write_exr_region(
    path: &Path,
    display: (u32, u32),
    origin: (u32, u32),
    size: (u32, u32),
    pixel: impl Fn(usize, usize) -> [f32; 3] + Sync,
    metadata: &[(String, String)],
) -> Result<(), ImageWriteError> {
    let exr_error = |message: String| ImageWriteError::Exr { path: path.to_owned(), message };
    let attributes =
        LayerAttributes { layer_position: Vec2(origin.0 as i32, origin.1 as i32), ..LayerAttributes::default() };
    let layer = Layer::new(
        (size.0 as usize, size.1 as usize),
        attributes,
        Encoding::SMALL_LOSSLESS,
        SpecificChannels::rgb(|p: Vec2<usize>| {
            let [r, g, b] = pixel(p.x(), p.y());
            (r, g, b)
        }),
    );
    let rows = (0..size.1 as usize).flat_map(|y| (0..size.0 as usize).map(move |x| (x, y)));
    let digest = pixel_digest(rows.map(|(x, y)| pixel(x, y)));
    let mut metadata: Vec<(String, String)> = metadata.iter().filter(|(k, _)| k != PIXELS_SHA256).cloned().collect();
    metadata.push((PIXELS_SHA256.into(), digest));
    let mut image = Image::from_layer(layer);
    image.attributes.display_window = IntegerBounds::new((0, 0), (display.0 as usize, display.1 as usize));
    for (key, value) in &metadata {
        image.attributes.other.insert(exr_text(key), AttributeValue::Text(exr_text(value)));
    }
    write_atomically(path, |file| {
        image.write().to_buffered(BufWriter::new(&mut *file)).map_err(|e| exr_error(e.to_string()))?;
        // The names as the file holds them (Latin-1, `exr_text`), not as UTF-8.
        let names: Vec<Vec<u8>> = metadata.iter().map(|(key, _)| exr_text(key).as_slice().to_vec()).collect();
        sort_attributes(file, &names).map_err(|e| exr_error(e.to_string()))
    })
}

/// The header of an EXR file alone, without its pixels: where its data window lies in the
/// display window, and its text attributes.
pub fn read_exr_header(path: &Path) -> Result<ExrHeader, ExrReadError> {
    let meta = exr::meta::MetaData::read_from_file(path, false)
        .map_err(|e| ExrReadError::Decode { path: path.to_owned(), message: e.to_string() })?;
    let header = meta
        .headers
        .first()
        .ok_or_else(|| ExrReadError::Decode { path: path.to_owned(), message: "the file has no layer".into() })?;
    let other = header.shared_attributes.other.iter().chain(&header.own_attributes.other);
    let mut read = exr_header(
        path,
        header.shared_attributes.display_window,
        header.own_attributes.layer_position,
        header.layer_size,
        other,
    )?;
    let colour = header.channels.list.iter().filter(|c| ["R", "G", "B"].contains(&c.name.to_string().as_str()));
    read.inexact = match colour.into_iter().find(|c| c.sample_type != SampleType::F32) {
        Some(c) => Some(format!("its channel {} holds {:?} samples, not 32-bit floats", c.name, c.sample_type)),
        None => lossy_for_f32(header.compression),
    };
    Ok(read)
}

/// Why `compression` may change 32-bit float samples, if it may.
fn lossy_for_f32(compression: exr::compression::Compression) -> Option<String> {
    (!compression.is_lossless_for(SampleType::F32)).then(|| format!("its {compression} is lossy for 32-bit floats"))
}

fn exr_header<'a>(
    path: &Path,
    display: IntegerBounds,
    position: Vec2<i32>,
    size: Vec2<usize>,
    other: impl Iterator<Item = (&'a Text, &'a AttributeValue)>,
) -> Result<ExrHeader, ExrReadError> {
    let (x0, y0) = (i64::from(position.x()), i64::from(position.y()));
    let (w, h) = (size.width() as i64, size.height() as i64);
    let (dx, dy) = (i64::from(display.position.x()), i64::from(display.position.y()));
    let (dw, dh) = (display.size.width() as i64, display.size.height() as i64);
    if dx != 0 || dy != 0 || x0 < 0 || y0 < 0 || x0 + w > dw || y0 + h > dh {
        return Err(ExrReadError::Window {
            path: path.to_owned(),
            window: format!("{w}x{h} at ({x0}, {y0})"),
            width: dw,
            height: dh,
        });
    }
    let mut attributes: Vec<(String, String)> = other
        .filter_map(|(k, v)| match v {
            AttributeValue::Text(t) => Some((text_value(k), text_value(t))),
            _ => None,
        })
        .collect();
    attributes.sort();
    Ok(ExrHeader {
        display: (dw as u32, dh as u32),
        origin: (x0 as u32, y0 as u32),
        width: w as u32,
        height: h as u32,
        attributes,
        inexact: None,
    })
}

/// Reads an RGB OpenEXR file: its data window's pixels (as f32) and its header.
pub fn read_exr(path: &Path) -> Result<ExrPixels, ExrReadError> {
    let image = exr::prelude::read()
        .no_deep_data()
        .largest_resolution_level()
        .rgb_channels(
            |size: Vec2<usize>, _| (size.width(), vec![[0f32; 3]; size.width() * size.height()]),
            |(width, pixels): &mut (usize, Vec<[f32; 3]>), p: Vec2<usize>, (r, g, b): (f32, f32, f32)| {
                pixels[p.y() * *width + p.x()] = [r, g, b];
            },
        )
        .first_valid_layer()
        .all_attributes()
        .from_file(path)
        .map_err(|e| ExrReadError::Decode { path: path.to_owned(), message: e.to_string() })?;
    let layer = image.layer_data;
    let other = image.attributes.other.iter().chain(&layer.attributes.other);
    let mut header =
        exr_header(path, image.attributes.display_window, layer.attributes.layer_position, layer.size, other)?;
    header.inexact = lossy_for_f32(layer.encoding.compression);
    Ok(ExrPixels { header, rgb: layer.channel_data.pixels.1 })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_pixel_digest_is_written_and_tells_a_changed_pixel() {
        let dir = tempfile::tempdir().expect("temp dir");
        let path = dir.path().join("t.exr");
        let value = |x: usize, y: usize| [x as f32 * 0.25, y as f32, 1e-3];
        let stale = vec![(PIXELS_SHA256.to_string(), "0".repeat(64))];
        write_exr_region(&path, (9, 7), (1, 2), (4, 3), value, &stale).expect("write");
        let mut read = read_exr(&path).expect("read");
        assert_eq!(read.digest_holds(), Some(true), "the digest of the pixels written, not the one given");
        assert_eq!(read.header.attributes.iter().filter(|(k, _)| k == PIXELS_SHA256).count(), 1);
        // Any bit of any channel.
        read.rgb[5][2] = f32::from_bits(read.rgb[5][2].to_bits() ^ 1);
        assert_eq!(read.digest_holds(), Some(false));
        read.header.attributes.retain(|(k, _)| k != PIXELS_SHA256);
        assert_eq!(read.digest_holds(), None);
        // Row order counts: the same values elsewhere are another image.
        assert_ne!(pixel_digest([[1.0, 0.0, 0.0], [0.0; 3]]), pixel_digest([[0.0; 3], [1.0, 0.0, 0.0]]));
    }

    #[test]
    fn text_attributes_keep_every_character_and_read_latin1_of_other_writers() {
        for value in ["whitted", "José", "日本.toml", "w\u{fffd}.toml"] {
            assert_eq!(text_value(&exr_text(value)), value);
        }
        // One byte 0xE9 (Latin-1 é) is not UTF-8: read as Latin-1.
        assert_eq!(text_value(&Text::from_slice_unchecked(&[b'J', b'o', b's', 0xe9])), "José");
    }
}
