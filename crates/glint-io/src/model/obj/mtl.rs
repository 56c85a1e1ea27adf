//! MTL materials mapped onto the seed's model, as `docs/models.md` tabulates: the coefficients
//! (`map_material`), the statements as the file wrote them (`source`), the scene's names
//! (`material_names`), and what the importer reads before tobj does (`expand_colours`) or
//! leaves out (`unread_statements`).

use std::path::Path;

use super::mtl_file::MtlFile;
use super::mtl_images::{Images, Source, TextureError, material_files};
use super::text;
use glint_scene::{FieldIssue, MaterialDesc, MaterialSource, Model, Rgb};

/// The material of faces that name none (MTL's defaults for Kd, no highlight).
pub const DEFAULT_MATERIAL: &str = "obj-default";

/// The OBJ's (`obj`) MTL materials put into `out` with their warnings and textures, under the
/// names `material_names` gives (returned, in the materials' order); `files` are the MTL
/// files as read.
pub(super) fn add_materials(
    obj: &Path,
    materials: &[tobj::Material],
    files: &[MtlFile],
    out: &mut Model,
) -> Result<Vec<String>, TextureError> {
    out.warnings.extend(unread_statements(materials));
    let names = material_names(materials);
    let files = material_files(files, materials.len());
    let mut images = Images::default();
    // Per file and name, how many materials of that name came before (a file may define one
    // name twice: its second's texture error named the first's line).
    let mut before: std::collections::HashMap<(Option<&str>, &str), usize> = std::collections::HashMap::new();
    for ((m, name), file) in materials.iter().zip(&names).zip(&files) {
        let key = (file.map(|f| f.uri.as_str()), m.name.as_str());
        let count = before.entry(key).or_default();
        let nth = *count;
        *count += 1;
        let mut material = map_material(m, name, &mut out.warnings);
        let at = Source { obj, mtl: *file, material: name, mtl_name: &m.name, nth };
        if let Some(map) = m.diffuse_texture.as_deref() {
            material.texture = Some(images.texture(&at, map, "texture", &mut out.warnings)?);
        }
        if let Some(map) = m.unknown_param.get("map_Ke") {
            material.emission_texture = Some(images.texture(&at, map, "emission_texture", &mut out.warnings)?);
            // Ke multiplies map_Ke; without Ke the map alone is the emission.
            if m.emissive.is_none() {
                material.emission = Rgb::splat(1.0);
            }
        }
        out.materials.insert(name.clone(), material);
        out.sources.insert(name.clone(), source(m));
    }
    Ok(names)
}

/// The MTL statements this importer reads; any other is named in one warning.
const READ_STATEMENTS: [&str; 11] = ["Ka", "Kd", "Ks", "Ke", "Ns", "Ni", "d", "Tr", "illum", "map_Kd", "map_Ke"];

/// One warning naming the MTL statements the materials hold that Glint does not read (bump and
/// specular maps, `Tf`, …), each with how many materials hold it: the model renders without them.
fn unread_statements(materials: &[tobj::Material]) -> Option<FieldIssue> {
    let mut unread: std::collections::BTreeMap<&str, usize> = std::collections::BTreeMap::new();
    for m in materials {
        let maps = [
            ("map_Ka", &m.ambient_texture),
            ("map_Ks", &m.specular_texture),
            ("map_Bump", &m.normal_texture),
            ("map_Ns", &m.shininess_texture),
            ("map_d", &m.dissolve_texture),
        ];
        let tobj_fields = maps.into_iter().filter(|(_, v)| v.is_some()).map(|(k, _)| k);
        // tobj keeps `#word …` (no space after the #) as a statement: it is a comment.
        let others =
            m.unknown_param.keys().map(String::as_str).filter(|k| !READ_STATEMENTS.contains(k) && !k.starts_with('#'));
        for statement in tobj_fields.chain(others) {
            *unread.entry(statement).or_default() += 1;
        }
    }
    crate::model::left_out("mtllib", "statements Glint does not read", &unread)
}

/// The first number of the MTL statements Glint reads that cannot be read (its line, why):
/// not a finite f32 (tobj reads f32), or a colour channel below 0 or above `MAX_INTENSITY`.
/// Checked as the file wrote them: mapped, a `Kd nan` was refused as the scene material's `ka`
/// and `kd` (k_a defaults to k_d), and `d nan` clamped "to NaN".
pub(super) fn bad_number(text: &[u8]) -> Option<(usize, String)> {
    for (n, raw) in text.split(|&b| b == b'\n').enumerate() {
        let Ok(line) = std::str::from_utf8(raw) else { continue };
        let mut words = line.split_whitespace();
        let (key, colour) = match words.next() {
            Some(key @ ("Ka" | "Kd" | "Ks" | "Ke")) => (key, true),
            Some(key @ ("Ns" | "Ni" | "d" | "Tr")) => (key, false),
            // tobj reads an illum as a byte and a map's last word as its file: any other made
            // its "material parse error", which dropped every material of the file, with no
            // line (a tester's `illum 2.5`, `illum -1`, a bare `map_Kd`).
            Some("illum") => {
                let values: Vec<&str> = words.collect();
                if values.len() != 1 || values[0].parse::<u8>().is_err() {
                    return Some((
                        n + 1,
                        format!("`{}`: `illum` takes one whole number, an illumination model in 0..=10", line.trim()),
                    ));
                }
                continue;
            }
            Some(map) if is_map_statement(map) && words.next().is_none() => {
                return Some((n + 1, format!("`{}`: names no image file", line.trim())));
            }
            _ => continue,
        };
        let values: Vec<&str> = words.collect();
        // A word where a number belongs, or a count a scalar has not, made tobj's "material
        // parse error" with no line (a tester). `Tr` is Glint's to read (tobj keeps it as
        // text), and its own warning names a bad one; `Kd spectral file`, `Kd xyz x y z` and
        // `d -halo factor` are forms Glint does not read, left to tobj.
        if key != "Tr" {
            if values.first().is_some_and(|v| matches!(*v, "spectral" | "xyz" | "-halo")) {
                continue;
            }
            if !colour && values.len() != 1 {
                return Some((n + 1, format!("`{}`: `{key}` takes one number; {} given", line.trim(), values.len())));
            }
            if let Some(word) = values.iter().find(|w| w.parse::<f64>().is_err()) {
                return Some((n + 1, format!("`{}`: `{word}` is not a number", line.trim())));
            }
        }
        for word in values.into_iter().take_while(|w| w.parse::<f64>().is_ok()) {
            let value = word.parse::<f32>().unwrap_or(f32::NAN);
            let problem = if let Some(problem) = text::not_finite(word, value) {
                problem
            } else if colour && !(0.0..=glint_scene::MAX_INTENSITY).contains(&f64::from(value)) {
                format!("{word} is outside a colour channel's [0, {:e}]", glint_scene::MAX_INTENSITY)
            } else {
                continue;
            };
            return Some((n + 1, format!("`{}`: {problem}", line.trim())));
        }
    }
    None
}

/// The colour lines (`Ka`, `Kd`, `Ks`, `Ke`) with more than three numbers, as (line, text):
/// tobj reads the first three, as Assimp does, and dropped the rest without a word (a
/// tester's `Kd 0.8 0.1 0.1 0.5`, an alpha perhaps).
pub(super) fn long_colours(text: &[u8]) -> Vec<(usize, String)> {
    let mut out = Vec::new();
    for (n, raw) in text.split(|&b| b == b'\n').enumerate() {
        let Ok(line) = std::str::from_utf8(raw) else { continue };
        let mut words = line.split_whitespace();
        if matches!(words.next(), Some("Ka" | "Kd" | "Ks" | "Ke"))
            && words.take_while(|w| w.parse::<f64>().is_ok()).count() > 3
        {
            out.push((n + 1, line.trim().to_string()));
        }
    }
    out
}

/// Whether `key` is an MTL texture statement (its last word a file).
fn is_map_statement(key: &str) -> bool {
    key.starts_with("map_") || matches!(key, "bump" | "disp" | "decal" | "refl" | "norm")
}

/// MTL text with every `Ka`/`Kd`/`Ks`/`Ke r` line written as `… r r r`: the MTL format lets g
/// and b default to r, and tobj panics on fewer than three numbers. A colour line with none or
/// two numbers is an error naming the line. tobj reads line by line, so the lines are checked
/// one by one; a line that is not UTF-8 is kept for tobj to refuse.
pub(super) fn expand_colours(text: &[u8]) -> Result<Vec<u8>, String> {
    let mut out = Vec::with_capacity(text.len() + 64);
    for (n, raw) in text.split(|&b| b == b'\n').enumerate() {
        if n > 0 {
            out.push(b'\n');
        }
        let Ok(line) = std::str::from_utf8(raw) else {
            out.extend_from_slice(raw);
            continue;
        };
        let mut words = line.split_whitespace();
        if let Some(key @ ("Ka" | "Kd" | "Ks" | "Ke")) = words.next() {
            let values: Vec<&str> = words.collect();
            // `Kd spectral …` and `Kd xyz …` start with a word: tobj refuses those itself.
            if values.first().is_none_or(|v| v.parse::<f32>().is_ok()) {
                match values.iter().take_while(|v| v.parse::<f32>().is_ok()).count() {
                    1 if values.len() == 1 => {
                        out.extend_from_slice(format!("{key} {0} {0} {0}", values[0]).as_bytes());
                        continue;
                    }
                    3.. => {}
                    _ => {
                        return Err(format!(
                            "{}: `{key}` takes r [g b] (one number, or three), not `{}`",
                            n + 1,
                            line.trim()
                        ));
                    }
                }
            }
        }
        out.extend_from_slice(raw);
    }
    Ok(out)
}

/// Each material's name in the scene: MTL names may hold any character, and the scene format's
/// keys are kept readable (other characters become `_`; the nameless material is `unnamed`); a
/// name that two materials would share gets its index (`name-3`).
fn material_names(materials: &[tobj::Material]) -> Vec<String> {
    let mut names: Vec<String> = Vec::with_capacity(materials.len());
    for (k, m) in materials.iter().enumerate() {
        let raw = if m.name == text::NAMELESS { "" } else { &m.name };
        let cleaned: String =
            raw.chars().map(|c| if c.is_alphanumeric() || "-_.".contains(c) { c } else { '_' }).collect();
        let name = if cleaned.is_empty() { "unnamed".to_string() } else { cleaned };
        names.push(if names.contains(&name) || name == DEFAULT_MATERIAL { format!("{name}-{k}") } else { name });
    }
    names
}

pub(super) fn default_material() -> MaterialDesc {
    MaterialDesc { ka: Rgb::splat(0.8), kd: Rgb::splat(0.8), ks: Rgb::splat(0.0), ..MaterialDesc::default() }
}

fn rgb(c: [f64; 3]) -> Rgb {
    Rgb(c)
}

/// The MTL statements `map_material` reads, as the file wrote them (absent ones left out).
fn source(m: &tobj::Material) -> MaterialSource {
    let colour = |c: Option<[f64; 3]>| c.map(|c| c.to_vec());
    let number = |x: Option<f64>| x.map(|x| vec![x]);
    let fields = [
        ("Ka", colour(m.ambient)),
        ("Kd", colour(m.diffuse)),
        ("Ks", colour(m.specular)),
        ("Ke", colour(m.emissive)),
        ("Ns", number(m.shininess)),
        ("Ni", number(m.optical_density)),
        ("d", number(m.dissolve)),
        ("Tr", number(m.unknown_param.get("Tr").and_then(|t| t.trim().parse().ok()))),
        ("illum", m.illumination_model.map(|i| vec![f64::from(i)])),
    ];
    MaterialSource { format: "MTL", fields: fields.into_iter().filter_map(|(k, v)| Some((k, v?))).collect() }
}

/// The MTL fields onto the seed's coefficients (docs/models.md): Kd → k_d, Ka → k_a (k_d when
/// absent), Ks → k_s from illum 2 on, Ns → n, Ke → E_m, Ni → ior; illum 3 and 5 trace
/// reflection rays with k_r = Ks, illum 4, 6 and 7 also refraction rays with k_t = 1 − d.
/// MTL's opacity: `d`, else 1 − `Tr` (the transparency many exporters write instead), else 1.
fn dissolve(m: &tobj::Material, warn: &mut impl FnMut(&str, String)) -> f64 {
    match (m.dissolve, m.unknown_param.get("Tr")) {
        (Some(d), _) => d,
        (None, Some(tr)) => match tr.trim().parse::<f64>() {
            Ok(t) if t.is_finite() => 1.0 - t,
            _ => {
                warn("Tr", format!("`Tr {tr}` is not a number; the material is opaque"));
                1.0
            }
        },
        (None, None) => 1.0,
    }
}

fn map_material(m: &tobj::Material, name: &str, warnings: &mut Vec<FieldIssue>) -> MaterialDesc {
    let kd = m.diffuse.map_or(Rgb::splat(0.8), rgb);
    let ks = m.specular.map_or(Rgb::splat(0.0), rgb);
    let illum = m.illumination_model.unwrap_or(2);
    let mut warn = |field: &str, problem: String| {
        warnings.push(FieldIssue { field: format!("materials.{name}.{field}"), problem });
    };
    let opacity = dissolve(m, &mut warn);
    if !(0.0..=1.0).contains(&opacity) {
        // Named as the file wrote it: `Tr`'s own text, not 1 − opacity back in f64.
        let (field, written) = match (m.dissolve, m.unknown_param.get("Tr")) {
            (Some(d), _) => ("d", format!("d {d}")),
            (None, Some(tr)) => ("Tr", format!("Tr {}", tr.trim())),
            (None, None) => ("d", format!("d {opacity}")),
        };
        let problem = if field == "d" { "an opacity" } else { "a transparency" };
        warn(
            field,
            format!("`{written}` is {problem} outside [0, 1]; the opacity is clamped to {}", opacity.clamp(0.0, 1.0)),
        );
    }
    let transmission = Rgb::splat(1.0 - opacity.clamp(0.0, 1.0));
    let (ks_local, kr, kt) = match illum {
        0 | 1 => (Rgb::splat(0.0), Rgb::splat(0.0), Rgb::splat(0.0)),
        2 => (ks, Rgb::splat(0.0), Rgb::splat(0.0)),
        3 | 5 => (ks, ks, Rgb::splat(0.0)),
        4 | 6 | 7 => (ks, ks, transmission),
        8..=10 => {
            warn("illum", format!("illum {illum} (no ray tracing) is traced as illum 2"));
            (ks, Rgb::splat(0.0), Rgb::splat(0.0))
        }
        other => {
            warn("illum", format!("illum {other} is outside 0..=10; traced as illum 2"));
            (ks, Rgb::splat(0.0), Rgb::splat(0.0))
        }
    };
    let ior = match m.optical_density {
        Some(ni) if (1.0..=glint_scene::MAX_IOR).contains(&ni) => ni,
        Some(ni) => {
            warn("ior", format!("Ni {ni} is outside [1, {}]; using 1.5", glint_scene::MAX_IOR));
            1.5
        }
        None => 1.5,
    };
    let shininess = m.shininess.unwrap_or(0.0).clamp(0.0, glint_scene::MAX_SHININESS);
    if let Some(ns) = m.shininess.filter(|ns| *ns != shininess) {
        warn("Ns", format!("Ns {ns} is outside [0, {}]; using {shininess}", glint_scene::MAX_SHININESS));
    }
    // Exporters write `Ns 0` for a rough surface; Phong's (H·N)^n is then 1 wherever light
    // falls, and k_s is added over the whole lit side (a tester's red cube came out pink).
    if shininess < 1.0 && ks_local.0.iter().any(|&k| k > 0.0) {
        let written = m.shininess.map_or("no `Ns` (n = 0)".to_string(), |ns| format!("`Ns {ns}`"));
        warn(
            "Ns",
            format!(
                "{written} with Ks > 0 and illum {illum}: (H·N)^n is about 1 wherever the light falls at n < 1, so \
                 k_s is a glare over the whole lit side, not a highlight; raise Ns or lower Ks"
            ),
        );
    }
    MaterialDesc {
        ka: m.ambient.map_or(kd, rgb),
        kd,
        ks: ks_local,
        shininess,
        kr,
        kt,
        ior,
        emission: m.emissive.map_or(Rgb::splat(0.0), rgb),
        ..MaterialDesc::default()
    }
}
