//! glTF textures: the image (a bufferView, or a URI through the one resolver) decoded once
//! however many materials use it, its sampler's wrap and filter, and KHR_texture_transform.

use crate::texture::decode_texture;
use std::path::Path;
use std::sync::Arc;

use ::gltf::texture::{MagFilter, WrappingMode};

use super::accessor::{Buffers, view_bytes};
use crate::uri::{MAX_RESOURCE_BYTES, resolve_uri};
use glint_scene::{ColorSpace, Filter, TextureDesc, TextureImage, UvTransform, Wrap};

/// Decoded images by glTF image index.
#[derive(Debug, Default)]
pub(super) struct Images(Vec<Option<Arc<TextureImage>>>);

fn wrap(mode: WrappingMode) -> Wrap {
    match mode {
        WrappingMode::Repeat => Wrap::Repeat,
        WrappingMode::ClampToEdge => Wrap::ClampToEdge,
        WrappingMode::MirroredRepeat => Wrap::MirroredRepeat,
    }
}

/// The texture an `Info` names, with the texture-coordinate set it reads (the transform's
/// `texCoord` overriding the info's); an error is (JSON path, problem).
pub(super) fn texture(
    info: &::gltf::texture::Info<'_>,
    buffers: &Buffers,
    file: &Path,
    images: &mut Images,
) -> Result<(TextureDesc, u32), (String, String)> {
    let texture = info.texture();
    let source = texture.source();
    let index = source.index();
    let field = format!("images[{index}]");
    if images.0.len() < index + 1 {
        images.0.resize(index + 1, None);
    }
    let (path, image) = match &images.0[index] {
        Some(image) => (source_name(&source, index), Arc::clone(image)),
        None => {
            let bytes = match source.source() {
                ::gltf::image::Source::View { view, .. } => {
                    view_bytes(&view, buffers).map_err(|p| (field.clone(), p))?.to_vec()
                }
                ::gltf::image::Source::Uri { uri, .. } => {
                    resolve_uri(file, uri, MAX_RESOURCE_BYTES).map_err(|e| (format!("{field}.uri"), e.to_string()))?
                }
            };
            let image = Arc::new(decode_texture(&bytes, ColorSpace::Srgb).map_err(|e| (field.clone(), e.to_string()))?);
            images.0[index] = Some(Arc::clone(&image));
            (source_name(&source, index), image)
        }
    };
    let sampler = texture.sampler();
    let mut desc = TextureDesc::decoded(path, image);
    desc.wrap_s = wrap(sampler.wrap_s());
    desc.wrap_t = wrap(sampler.wrap_t());
    desc.filter = match sampler.mag_filter() {
        Some(MagFilter::Nearest) => Filter::Nearest,
        Some(MagFilter::Linear) | None => Filter::Bilinear,
    };
    let mut set = info.tex_coord();
    if let Some(t) = info.texture_transform() {
        desc.transform = Some(UvTransform {
            offset: t.offset().map(f64::from),
            rotation: f64::from(t.rotation()),
            scale: t.scale().map(f64::from),
        });
        set = t.tex_coord().unwrap_or(set);
    }
    Ok((desc, set))
}

/// What a saved scene names for the image: its URI, or its place in the file.
fn source_name(image: &::gltf::Image<'_>, index: usize) -> String {
    match image.source() {
        ::gltf::image::Source::Uri { uri, .. } if !uri.starts_with("data:") => uri.to_string(),
        _ => format!("images[{index}]"),
    }
}
