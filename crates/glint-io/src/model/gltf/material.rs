//! glTF materials (metallic-roughness, specular-glossiness and the KHR material extensions)
//! mapped onto the seed's coefficients, as docs/models.md tabulates.

use crate::model::widen;
use glint_scene::MaterialSource;
use glint_scene::{FieldIssue, MAX_INTENSITY, MAX_IOR, MAX_SHININESS, MaterialDesc, Rgb, format_number};

/// Below this roughness a surface is treated as smooth enough to mirror: it traces
/// reflection rays with k_r = its specular colour (F0). Rougher surfaces keep the highlight
/// only: a Whitted tracer has no glossy reflection.
pub const MIRROR_ROUGHNESS: f64 = 0.1;

/// The normal-incidence reflectance of a dielectric (ior 1.5), glTF's F0 for metallic = 0.
const DIELECTRIC_F0: f64 = 0.04;

/// The Blinn exponent of a roughness: n = 2/α² − 2 with α = roughness² (Walter et al.'s
/// Beckmann–Phong correspondence as glTF viewers use it), capped at `MAX_SHININESS`.
pub fn blinn_exponent(roughness: f64) -> f64 {
    let alpha = roughness.clamp(0.0, 1.0).powi(2);
    if alpha <= 0.0 { MAX_SHININESS } else { (2.0 / (alpha * alpha) - 2.0).clamp(0.0, MAX_SHININESS) }
}

fn lerp(a: f64, b: f64, t: f64) -> f64 {
    a + (b - a) * t
}

/// The factors glTF bounds to [0, 1], each read through `unit`: one outside (a negative or
/// non-finite colour, a metallic factor of 2) is clamped with a warning naming the glTF field,
/// where the coefficients it maps to would have been refused under Glint's own names.
struct Factors<'a> {
    field: &'a str,
    warnings: &'a mut Vec<FieldIssue>,
}

impl Factors<'_> {
    fn unit(&mut self, name: &str, value: f32) -> f64 {
        let v = widen(value);
        if (0.0..=1.0).contains(&v) {
            return v;
        }
        let kept = if v.is_nan() { 0.0 } else { v.clamp(0.0, 1.0) };
        let problem = format!("{name} = {v} is outside [0, 1], as glTF bounds it; {kept} is used");
        self.warnings.push(FieldIssue { field: self.field.to_string(), problem });
        kept
    }

    fn rgb(&mut self, name: &str, c: [f32; 3]) -> Rgb {
        const CHANNEL: [&str; 3] = ["r", "g", "b"];
        Rgb(std::array::from_fn(|k| self.unit(&format!("{name}.{}", CHANNEL[k]), c[k])))
    }
}

/// A material's coefficients, and what of it could not be mapped as warnings under `field`.
pub(super) fn map_material(m: &::gltf::Material<'_>, field: &str, warnings: &mut Vec<FieldIssue>) -> MaterialDesc {
    let mut factors = Factors { field, warnings };
    if m.unlit() {
        // KHR_materials_unlit: the surface shows its base colour whatever the light, which in
        // the seed's model is an emitter with no reflection terms. The base texture becomes
        // the emission texture (`load_gltf`); every other property is ignored, as the
        // extension asks.
        let b = m.pbr_metallic_roughness().base_color_factor();
        let black = Rgb::splat(0.0);
        return MaterialDesc {
            ka: black,
            kd: black,
            ks: black,
            emission: factors.rgb("baseColorFactor", [b[0], b[1], b[2]]),
            ..MaterialDesc::default()
        };
    }
    // `dielectric_f0`: the largest channel of the specular reflectance the diffuse lobe shares
    // the light with (both extensions keep 1 − its largest channel for the diffuse).
    let (base, f0, roughness, dielectric_f0) = match m.pbr_specular_glossiness() {
        Some(sg) => {
            let d = sg.diffuse_factor();
            // Specular-glossiness gives k_d and F0 directly; roughness = 1 − glossiness.
            let specular = factors.rgb("specularFactor", sg.specular_factor());
            (
                factors.rgb("diffuseFactor", [d[0], d[1], d[2]]),
                specular,
                1.0 - factors.unit("glossinessFactor", sg.glossiness_factor()),
                specular.max_channel(),
            )
        }
        None => {
            let pbr = m.pbr_metallic_roughness();
            let b = pbr.base_color_factor();
            let base = factors.rgb("baseColorFactor", [b[0], b[1], b[2]]);
            let metallic = factors.unit("metallicFactor", pbr.metallic_factor());
            // KHR_materials_specular scales the dielectric F0 (colour and strength).
            let (strength, tint) = match m.specular() {
                Some(s) => (factors.unit("specularFactor", s.specular_factor()), s.specular_color_factor().map(widen)),
                None => (1.0, [1.0; 3]),
            };
            let dielectric_f0: [f64; 3] = std::array::from_fn(|k| (DIELECTRIC_F0 * tint[k]).min(1.0) * strength);
            let f0 = Rgb(std::array::from_fn(|k| lerp(dielectric_f0[k], base.0[k], metallic)));
            let diffuse = Rgb(base.0.map(|c| c * (1.0 - metallic)));
            (diffuse, f0, factors.unit("roughnessFactor", pbr.roughness_factor()), Rgb(dielectric_f0).max_channel())
        }
    };
    let transmission = m.transmission().map_or(0.0, |t| factors.unit("transmissionFactor", t.transmission_factor()));
    // Clamped as the other factors are (a factor of 2 was an error, against docs/models.md).
    let emissive = factors.rgb("emissiveFactor", m.emissive_factor());
    let mut warn = |problem: String| warnings.push(FieldIssue { field: field.to_string(), problem });
    let kr = if roughness < MIRROR_ROUGHNESS { f0 } else { Rgb::splat(0.0) };
    // Transmission replaces the diffuse part and is tinted by it (KHR_materials_transmission);
    // what a smooth surface mirrors it does not transmit (F0: 0.04 of a glass), so that
    // k_r + k_t stays within 1 (a plain glass mapped to 1.04, which validation warned of).
    // glTF mixes the diffuse with the specular lobe by the Fresnel term, keeping 1 − max(F0) at
    // normal incidence for the diffuse (KHR_materials_specular and pbrSpecularGlossiness say
    // so): a white rough plastic mapped to k_d + k_s = 1.04 returned more light than it
    // received under paths.
    let kd = Rgb(std::array::from_fn(|k| base.0[k] * (1.0 - transmission) * (1.0 - dielectric_f0)));
    let kt = Rgb(std::array::from_fn(|k| base.0[k] * transmission * (1.0 - kr.0[k])));
    let ior = match m.ior().map(widen) {
        None => 1.5,
        Some(ior) if (1.0..=MAX_IOR).contains(&ior) => ior,
        Some(ior) => {
            warn(format!("KHR_materials_ior ior {ior} is outside [1, {MAX_IOR}]; using 1.5"));
            1.5
        }
    };
    let strength = m.emissive_strength().map_or(1.0, widen);
    let emission = Rgb(emissive.0.map(|e| e * strength));
    if m.alpha_mode() == ::gltf::material::AlphaMode::Blend {
        warn("alphaMode BLEND is traced as opaque (use KHR_materials_transmission for glass)".into());
    }
    MaterialDesc {
        ka: kd,
        kd,
        ks: f0,
        shininess: blinn_exponent(roughness),
        kr,
        kt,
        ior,
        emission,
        ..MaterialDesc::default()
    }
}

/// The material as the file wrote it: the factors of its workflow and of the KHR extensions
/// `map_material` reads (those the file leaves out are absent).
pub(super) fn source(m: &::gltf::Material<'_>) -> MaterialSource {
    let mut fields: Vec<(&'static str, Vec<f64>)> = Vec::new();
    if m.unlit() {
        // All that an unlit material's colour is made of (`map_material`).
        let base = m.pbr_metallic_roughness().base_color_factor();
        return MaterialSource {
            format: "glTF (KHR_materials_unlit)",
            fields: vec![("baseColorFactor", base.map(widen).to_vec())],
        };
    }
    match m.pbr_specular_glossiness() {
        Some(sg) => {
            fields.push(("diffuseFactor", sg.diffuse_factor().map(widen).to_vec()));
            fields.push(("specularFactor", sg.specular_factor().map(widen).to_vec()));
            fields.push(("glossinessFactor", vec![widen(sg.glossiness_factor())]));
        }
        None => {
            let pbr = m.pbr_metallic_roughness();
            fields.push(("baseColorFactor", pbr.base_color_factor().map(widen).to_vec()));
            fields.push(("metallicFactor", vec![widen(pbr.metallic_factor())]));
            fields.push(("roughnessFactor", vec![widen(pbr.roughness_factor())]));
            if let Some(s) = m.specular() {
                fields.push(("specularFactor", vec![widen(s.specular_factor())]));
                fields.push(("specularColorFactor", s.specular_color_factor().map(widen).to_vec()));
            }
        }
    }
    if let Some(ior) = m.ior() {
        fields.push(("ior", vec![widen(ior)]));
    }
    if let Some(t) = m.transmission() {
        fields.push(("transmissionFactor", vec![widen(t.transmission_factor())]));
    }
    let emissive = m.emissive_factor();
    if emissive != [0.0; 3] {
        fields.push(("emissiveFactor", emissive.map(widen).to_vec()));
    }
    if let Some(strength) = m.emissive_strength() {
        fields.push(("emissiveStrength", vec![widen(strength)]));
    }
    MaterialSource { format: "glTF", fields }
}

/// The material of primitives that name none: a neutral grey plastic (glTF's own default is
/// a rough white metal, which a Phong model renders as a flat specular glare).
pub fn default_material() -> MaterialDesc {
    MaterialDesc {
        ka: Rgb::splat(0.8),
        kd: Rgb::splat(0.8),
        ks: Rgb::splat(DIELECTRIC_F0),
        shininess: blinn_exponent(0.5),
        ..MaterialDesc::default()
    }
}

/// An emission the scene cannot hold (beyond `MAX_INTENSITY`) named by the file's own fields:
/// validation would name Glint's `materials.X.emission`, which the file does not have.
pub(super) fn check_emission(
    m: &::gltf::Material<'_>,
    index: usize,
    desc: &MaterialDesc,
) -> Result<(), (String, String)> {
    let strength = m.emissive_strength().map_or(1.0, widen);
    let [r, g, b] = m.emissive_factor().map(|c| format_number(widen(c)));
    if strength.is_nan() || strength < 0.0 {
        return Err((
            format!("materials[{index}].extensions.KHR_materials_emissive_strength.emissiveStrength"),
            format!("{} is negative; it must be ≥ 0", format_number(strength)),
        ));
    }
    let brightest = desc.emission.max_channel();
    if brightest.is_finite() && brightest <= MAX_INTENSITY {
        return Ok(());
    }
    Err((
        format!("materials[{index}].emissiveFactor"),
        format!(
            "({r}, {g}, {b}) × KHR_materials_emissive_strength {} reaches {}, beyond the {MAX_INTENSITY:e} an \
             emission may have",
            format_number(strength),
            format_number(brightest),
        ),
    ))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn roughness_maps_to_a_blinn_exponent() {
        assert_eq!(blinn_exponent(0.0), MAX_SHININESS);
        assert_eq!(blinn_exponent(1.0), 0.0);
        assert!((blinn_exponent(0.5) - 30.0).abs() < 1e-12, "α = 0.25: 2/0.0625 − 2 = 30");
    }
}
