//! Materials and their textures.

// What the parent module declares for its children.
use super::{MaterialDesc, Report, TextureDesc, material_textures, num, ranges};

pub(super) fn validate_material(path: &str, m: &MaterialDesc, r: &mut Report) {
    for (field, v) in [("ka", m.ka), ("kd", m.kd), ("ks", m.ks), ("kr", m.kr), ("kt", m.kt)] {
        r.colour(&format!("{path}.{field}"), v);
    }
    r.colour(&format!("{path}.emission"), m.emission);
    r.finite_in(&format!("{path}.shininess"), m.shininess, ranges::SHININESS);
    r.finite_in(&format!("{path}.roughness"), m.roughness, ranges::ROUGHNESS);
    if !ranges::IOR.contains(m.ior) {
        let (lo, hi) = (ranges::IOR.min, ranges::IOR.max);
        let why = ranges::IOR.why_outside(m.ior);
        r.error(format!("{path}.ior"), format!("{} is outside the allowed range ({lo}, {hi}]{why}", num(m.ior)));
    }
    if let Some(ch) = &m.checker {
        r.colour(&format!("{path}.checker.kd"), ch.kd);
        r.finite_in(&format!("{path}.checker.size"), ch.size, ranges::CHECKER_SIZE);
        if m.texture.is_some() {
            r.error(format!("{path}.checker"), "a material has a checker or a texture, not both");
        }
    }
    for (field, texture) in material_textures(m) {
        if let Some(t) = texture {
            validate_texture(&format!("{path}.{field}"), t, r);
        }
    }
    // A coefficient is the fraction of a light's term a surface returns; an 8-bit colour typed
    // as one (kd = 255) rendered without a word.
    let checker = m.checker.as_ref().map(|c| ("checker.kd", c.kd));
    for (field, v) in [("ka", m.ka), ("kd", m.kd), ("ks", m.ks)].into_iter().chain(checker) {
        let most = v.max_channel();
        if most > 1.0 && most.is_finite() {
            let eight_bit = if most > 2.0 && most <= 255.0 { " (an 8-bit colour? divide it by 255)" } else { "" };
            r.warn(
                format!("{path}.{field}"),
                format!(
                    "{} is above 1: the coefficient is the fraction of the light's term the surface returns, in \
                     [0, 1]{eight_bit}",
                    num(most)
                ),
            );
        }
    }
    // Whitted's gain: k_r + k_t in the largest channel.
    let sum = m.gain(glint_types::Integrator::Whitted);
    if sum > 1.0 {
        r.warn(
            format!("{path}.kr + kt"),
            format!("k_r + k_t = {} > 1: the surface returns more light than it receives", num(sum)),
        );
    }
}

/// A texture's transform, and that its image was decoded (`load_textures`, or an importer).
fn validate_texture(path: &str, t: &TextureDesc, r: &mut Report) {
    if t.image.is_none() {
        r.error(
            format!("{path}.path"),
            format!("`{}` was not decoded (scene descriptions built in code call scene::load_textures)", t.path),
        );
    }
    if let Some(tr) = &t.transform {
        for (axis, v) in ["u", "v"].iter().zip(tr.offset) {
            r.finite_in(&format!("{path}.transform.offset.{axis}"), v, ranges::COORD);
        }
        for (axis, v) in ["u", "v"].iter().zip(tr.scale) {
            r.finite_in(&format!("{path}.transform.scale.{axis}"), v, ranges::COORD);
        }
        r.finite_in(&format!("{path}.transform.rotation"), tr.rotation, ranges::COORD);
    }
}
