//! Materials: the seed's coefficients per RGB, the specular lobe, and their textures.

use glint_types::{Fresnel, Integrator, SpecularModel};
use serde::{Deserialize, Serialize};

use crate::rgb::Rgb;
use crate::texture::TextureDesc;

/// The Beckmann roughness m of a material that does not set it: the lobe width of the default
/// shininess 32, since (N·H)^n ≈ exp(−n·α²/2) and the Beckmann lobe ≈ exp(−α²/m²) near the
/// peak give m = √(2/n) = 0.25.
pub const DEFAULT_ROUGHNESS: f64 = 0.25;

fn default_roughness() -> f64 {
    DEFAULT_ROUGHNESS
}

fn is_default_fresnel(f: &Fresnel) -> bool {
    *f == Fresnel::default()
}

fn is_default_roughness(m: &f64) -> bool {
    *m == DEFAULT_ROUGHNESS
}

#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct MaterialDesc {
    pub ka: Rgb,
    pub kd: Rgb,
    pub ks: Rgb,
    /// Specular exponent n, in [0, 1e6].
    pub shininess: f64,
    pub specular_model: SpecularModel,
    /// Beckmann roughness m (RMS slope of the microfacets) of the Cook–Torrance lobe, in
    /// [1e-3, 1]; kept, unused, under the other models.
    #[serde(default = "default_roughness", skip_serializing_if = "is_default_roughness")]
    pub roughness: f64,
    /// The Cook–Torrance lobe's Fresnel factor; kept, unused, under the other models.
    #[serde(skip_serializing_if = "is_default_fresnel")]
    pub fresnel: Fresnel,
    pub kr: Rgb,
    pub kt: Rgb,
    pub ior: f64,
    pub emission: Rgb,
    /// A two-colour checker (k_d and `checker.kd`) in planar coordinates: stored as a 2×2
    /// texture, so it colours k_a as well as k_d, as `texture` does.
    #[serde(skip_serializing_if = "Option::is_none", deserialize_with = "crate::tables::option_table")]
    pub checker: Option<CheckerDesc>,
    /// Base-colour texture: its colour multiplies k_a and k_d (POV-Ray's pigment, OpenGL's
    /// ambient-and-diffuse colour material, glTF's base colour × factor).
    #[serde(skip_serializing_if = "Option::is_none", deserialize_with = "crate::tables::option_table")]
    pub texture: Option<TextureDesc>,
    /// Emission texture: its colour multiplies E_m.
    #[serde(skip_serializing_if = "Option::is_none", deserialize_with = "crate::tables::option_table")]
    pub emission_texture: Option<TextureDesc>,
}

impl Default for MaterialDesc {
    fn default() -> Self {
        Self {
            ka: Rgb::splat(1.0),
            kd: Rgb::splat(0.8),
            ks: Rgb::splat(0.0),
            shininess: 32.0,
            specular_model: SpecularModel::Blinn,
            roughness: DEFAULT_ROUGHNESS,
            fresnel: Fresnel::Exact,
            kr: Rgb::splat(0.0),
            kt: Rgb::splat(0.0),
            ior: 1.5,
            emission: Rgb::splat(0.0),
            checker: None,
            texture: None,
            emission_texture: None,
        }
    }
}

#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CheckerDesc {
    /// The second colour of the checker (the first is the material's k_d).
    pub kd: Rgb,
    /// Edge length of one square in scene units, in [1e-9, 1e9] (`ranges::CHECKER_SIZE`).
    pub size: f64,
}

impl MaterialDesc {
    /// The most a surface of it multiplies radiance by, per bounce (its largest channel): where
    /// it exceeds 1, radiance grows with depth. Whitted's tree adds k_d and k_s once per light,
    /// so only k_r + k_t multiply along its rays; a path meets every lobe bounce after bounce
    /// (each lobe's albedo at most its k, the checker's k_d where it is brighter).
    pub fn gain(&self, integrator: Integrator) -> f64 {
        let kd = self.checker.as_ref().map_or(self.kd, |c| Rgb(std::array::from_fn(|k| self.kd.0[k].max(c.kd.0[k]))));
        let channel = |k: usize| match integrator {
            Integrator::Whitted => self.kr.0[k] + self.kt.0[k],
            Integrator::Path => kd.0[k] + self.ks.0[k] + self.kr.0[k] + self.kt.0[k],
        };
        (0..3).map(channel).fold(0.0, f64::max)
    }
}

/// The textures of one material, with the field name each has in a scene file.
pub fn material_textures(m: &MaterialDesc) -> [(&'static str, Option<&TextureDesc>); 2] {
    [("texture", m.texture.as_ref()), ("emission_texture", m.emission_texture.as_ref())]
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The largest channel wherever it lies: a gain held only in blue was missed when two
    /// channels were read (a mutation no test told), and with it the warnings built on it.
    #[test]
    fn the_gain_is_the_largest_channel_in_any_channel() {
        let permutations = [[0, 1, 2], [0, 2, 1], [1, 0, 2], [1, 2, 0], [2, 0, 1], [2, 1, 0]];
        let at = |values: [f64; 3], p: [usize; 3]| Rgb(std::array::from_fn(|k| values[p[k]]));
        for p in permutations {
            let path =
                MaterialDesc { kd: at([0.25, 0.25, 0.5], p), ks: at([0.0, 0.0, 0.75], p), ..MaterialDesc::default() };
            assert_eq!(path.gain(Integrator::Path), 1.25, "{p:?}");
            let whitted =
                MaterialDesc { kr: at([0.0, 0.0, 0.5], p), kt: at([0.0, 0.0, 0.75], p), ..MaterialDesc::default() };
            assert_eq!(whitted.gain(Integrator::Whitted), 1.25, "{p:?}");
        }
    }
}
