//! Image textures of a scene description: where the image comes from and how it is sampled
//! (the glTF sampler's wrap modes and filters, `KHR_texture_transform`'s UV transform), and the
//! decoded image itself, which both tracers read from the flat layout's texel buffer.

use std::fmt;
use std::sync::Arc;

use glint_types::{Filter, Wrap};
use serde::{Deserialize, Serialize};

/// `KHR_texture_transform`: uv' = T(offset) · R(rotation) · S(scale) · uv, in that order.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct UvTransform {
    #[serde(deserialize_with = "crate::exact_len::array")]
    pub offset: [f64; 2],
    /// Radians, counter-clockwise in UV space, as `KHR_texture_transform` writes it.
    pub rotation: f64,
    #[serde(deserialize_with = "crate::exact_len::array")]
    pub scale: [f64; 2],
}

impl Default for UvTransform {
    fn default() -> Self {
        Self { offset: [0.0; 2], rotation: 0.0, scale: [1.0; 2] }
    }
}

impl UvTransform {
    /// The 2×3 matrix [T·R·S] as two rows (u' = row0 · (u, v, 1), v' = row1 · (u, v, 1)),
    /// computed in f64 (KHR_texture_transform's rotation matrix is [cos sin; −sin cos]).
    pub fn matrix(&self) -> [[f64; 3]; 2] {
        let (s, c) = self.rotation.sin_cos();
        let [sx, sy] = self.scale;
        let [ox, oy] = self.offset;
        [[c * sx, s * sy, ox], [-s * sx, c * sy, oy]]
    }
}

/// An image texture: a file (relative to the scene file) and how it is sampled. Texture
/// coordinates follow glTF: (0, 0) is the top-left corner of the image, v grows downwards.
#[derive(Clone, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct TextureDesc {
    /// A PNG or JPEG file, relative to the scene file and inside its folder (read through
    /// `model::uri::resolve_uri`: absolute paths and escapes are refused).
    pub path: String,
    #[serde(default)]
    pub wrap_s: Wrap,
    #[serde(default)]
    pub wrap_t: Wrap,
    #[serde(default)]
    pub filter: Filter,
    #[serde(default, skip_serializing_if = "Option::is_none", deserialize_with = "crate::tables::option_table")]
    pub transform: Option<UvTransform>,
    /// The decoded image: filled when a scene file is loaded (`load_textures`), or by an
    /// importer that decoded it itself (`TextureImage::decode`); never written to a file.
    #[serde(skip)]
    pub image: Option<Arc<TextureImage>>,
}

impl TextureDesc {
    /// A texture of an already decoded image with glTF's default sampler (repeat, bilinear)
    /// and no transform; `path` is what a saved scene names.
    pub fn decoded(path: impl Into<String>, image: Arc<TextureImage>) -> Self {
        Self {
            path: path.into(),
            wrap_s: Wrap::Repeat,
            wrap_t: Wrap::Repeat,
            filter: Filter::Bilinear,
            transform: None,
            image: Some(image),
        }
    }
}

impl fmt::Debug for TextureDesc {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("TextureDesc")
            .field("path", &self.path)
            .field("wrap_s", &self.wrap_s)
            .field("wrap_t", &self.wrap_t)
            .field("filter", &self.filter)
            .field("transform", &self.transform)
            .field("image", &self.image)
            .finish()
    }
}

/// Equal when the sampling is equal and the images are the same (one shared decode, or equal
/// texels).
impl PartialEq for TextureDesc {
    fn eq(&self, o: &Self) -> bool {
        let same_image = match (&self.image, &o.image) {
            (Some(a), Some(b)) => Arc::ptr_eq(a, b) || a == b,
            (None, None) => true,
            (Some(_), None) | (None, Some(_)) => false,
        };
        self.path == o.path
            && self.wrap_s == o.wrap_s
            && self.wrap_t == o.wrap_t
            && self.filter == o.filter
            && self.transform == o.transform
            && same_image
    }
}

/// How the bytes of an image encode colour.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ColorSpace {
    /// sRGB-encoded (colour textures: glTF base colour and emissive, MTL map_Kd and map_Ke).
    Srgb,
    /// Linear values, used as they are.
    Linear,
}

/// Largest texture side, in texels.
pub const MAX_TEXTURE_SIDE: u32 = 16384;
/// Most texels of one texture (4096²): 256 MiB as linear RGBA f32, twice the 128 MiB a storage
/// buffer binding is guaranteed; larger images are refused before they are decoded.
pub const MAX_TEXTURE_TEXELS: u64 = 1 << 24;

/// Why an image did not become a texture.
#[derive(Debug, thiserror::Error)]
pub enum TextureError {
    #[error("not a PNG or JPEG image (the formats Glint reads)")]
    Format,
    #[error(
        "{width}x{height} texels is more than a texture may have ({MAX_TEXTURE_SIDE} per side, {MAX_TEXTURE_TEXELS} in all)"
    )]
    TooLarge { width: u32, height: u32 },
    #[error("an image needs at least one texel")]
    Empty,
    #[error("{texels} texels given for a {width}x{height} image")]
    Length { width: u32, height: u32, texels: usize },
    #[error("cannot decode the image: {0}")]
    Decode(String),
}

/// A decoded texture: linear RGBA (alpha as stored), row 0 the top row of the image, stored in
/// f32 exactly as the GPU reads it.
#[derive(Clone, PartialEq)]
pub struct TextureImage {
    width: u32,
    height: u32,
    texels: Vec<[f32; 4]>,
}

impl fmt::Debug for TextureImage {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "TextureImage({}x{})", self.width, self.height)
    }
}

/// The sRGB transfer function's inverse (IEC 61966-2-1), in f64.
pub fn srgb_to_linear(c: f64) -> f64 {
    if c <= 0.04045 { c / 12.92 } else { ((c + 0.055) / 1.055).powf(2.4) }
}

pub fn check_size(width: u32, height: u32) -> Result<(), TextureError> {
    if width == 0 || height == 0 {
        return Err(TextureError::Empty);
    }
    if width > MAX_TEXTURE_SIDE
        || height > MAX_TEXTURE_SIDE
        || u64::from(width) * u64::from(height) > MAX_TEXTURE_TEXELS
    {
        return Err(TextureError::TooLarge { width, height });
    }
    Ok(())
}

impl TextureImage {
    /// An image of linear RGBA texels, row by row from the top.
    pub fn from_linear_rgba(width: u32, height: u32, texels: Vec<[f32; 4]>) -> Result<Self, TextureError> {
        check_size(width, height)?;
        if texels.len() as u64 != u64::from(width) * u64::from(height) {
            return Err(TextureError::Length { width, height, texels: texels.len() });
        }
        if texels.iter().flatten().any(|c| !c.is_finite()) {
            return Err(TextureError::Decode("a texel is not a finite number".into()));
        }
        Ok(Self { width, height, texels })
    }

    pub fn width(&self) -> u32 {
        self.width
    }

    pub fn height(&self) -> u32 {
        self.height
    }

    /// Linear RGBA texels, row by row from the top.
    pub fn texels(&self) -> &[[f32; 4]] {
        &self.texels
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn transform_is_translation_rotation_scale() {
        let t = UvTransform { offset: [0.5, 0.25], rotation: std::f64::consts::FRAC_PI_2, scale: [2.0, 3.0] };
        let m = t.matrix();
        let apply = |u: f64, v: f64| [0, 1].map(|r| m[r][0] * u + m[r][1] * v + m[r][2]);
        // S: (1, 0) → (2, 0); R(90°) with KHR's [cos sin; −sin cos]: → (0, −2); T: → (0.5, −1.75).
        let [u, v] = apply(1.0, 0.0);
        assert!((u - 0.5).abs() < 1e-15 && (v + 1.75).abs() < 1e-15, "{u} {v}");
    }
}
