//! Where the viewer edits a field that a validation message names: the tab, the trail of
//! labels down to the control, and what to select there. Messages are written in the scene
//! file's terms (`lights[0].casts_shadows`); a viewer user looks for "Casts shadows" under
//! the light's name in the Lights tab.

use crate::document::Document;
use crate::layout::Tab;

/// What a place selects when shown.
#[derive(Clone, Debug, PartialEq)]
pub enum Focus {
    Nothing,
    Light(usize),
    Material(String),
    /// An object and its material.
    Object(usize),
}

#[derive(Clone, Debug, PartialEq)]
pub struct Place {
    pub tab: Tab,
    /// Labels from the tab down to the control, as the panels write them.
    pub trail: Vec<String>,
    pub focus: Focus,
}

impl Place {
    /// A tab alone, nothing selected: where a field not found in the scene points.
    fn tab(tab: Tab, name: &str) -> Self {
        Self { tab, trail: vec![name.to_string()], focus: Focus::Nothing }
    }

    /// The trail as read: "Lights › key › Casts shadows".
    pub fn text(&self) -> String {
        self.trail.join(" › ")
    }
}

/// The place of `field` (a dotted path as `FieldIssue::field` writes it) in the panels.
pub fn place(field: &str, doc: &Document) -> Place {
    if let Some(rest) = field.strip_prefix("lights[") {
        if let Some((index, tail)) = indexed(rest).filter(|(i, _)| *i < doc.desc.lights.len()) {
            let mut trail = vec!["Lights".to_string(), doc.light_label(index)];
            let spot = doc.desc.lights[index].kind == glint_scene::LightKind::Spot;
            trail.extend(light_control(first_part(tail), spot).map(String::from));
            return Place { tab: Tab::Lights, trail, focus: Focus::Light(index) };
        }
        return Place::tab(Tab::Lights, "Lights");
    }
    if let Some(rest) = field.strip_prefix("objects[") {
        if let Some((index, _)) = indexed(rest).filter(|(i, _)| *i < doc.desc.objects.len()) {
            // Geometry has no control: the object is selected, its material shown.
            let trail = vec!["Materials".to_string(), doc.object_label(index)];
            return Place { tab: Tab::Materials, trail, focus: Focus::Object(index) };
        }
        return Place::tab(Tab::Materials, "Materials");
    }
    if let Some(rest) = field.strip_prefix("materials.") {
        // Names may hold dots: the longest name the path starts with.
        let named = doc
            .desc
            .materials
            .keys()
            .filter(|n| rest == n.as_str() || rest.strip_prefix(n.as_str()).is_some_and(|t| t.starts_with('.')))
            .max_by_key(|n| n.len());
        if let Some(name) = named {
            let tail = rest[name.len()..].trim_start_matches('.');
            let mut trail = vec!["Materials".to_string(), name.clone()];
            trail.extend(material_control(tail).map(String::from));
            return Place { tab: Tab::Materials, trail, focus: Focus::Material(name.clone()) };
        }
        return Place::tab(Tab::Materials, "Materials");
    }
    let (section, control) = match field.split_once('.') {
        Some(("camera", tail)) => ("Camera", camera_control(first_part(tail))),
        Some(("world", tail)) => ("World", world_control(first_part(tail))),
        Some(("render", tail)) => ("Render", render_control(first_part(tail))),
        _ => match field {
            "camera" => ("Camera", None),
            "world" => ("World", None),
            "render" => ("Render", None),
            "lights" => return Place::tab(Tab::Lights, "Lights"),
            "materials" => return Place::tab(Tab::Materials, "Materials"),
            _ => return Place::tab(Tab::Scene, "Scene"),
        },
    };
    let mut trail = vec!["Scene".to_string(), section.to_string()];
    trail.extend(control.map(String::from));
    Place { tab: Tab::Scene, trail, focus: Focus::Nothing }
}

/// `3].casts_shadows` → (3, "casts_shadows").
fn indexed(rest: &str) -> Option<(usize, &str)> {
    let (index, tail) = rest.split_once(']')?;
    Some((index.parse().ok()?, tail.trim_start_matches('.')))
}

fn first_part(tail: &str) -> &str {
    tail.split(['.', '[']).next().unwrap_or(tail)
}

fn light_control(field: &str, spot: bool) -> Option<&'static str> {
    Some(match field {
        "direction" if spot => "Spot axis",
        "kind" => "Type",
        "position" => "Position",
        "direction" => "Direction",
        "diffuse" => "I_d",
        "specular" => "I_s",
        "ambient" => "I_a,j",
        "attenuation" => "Attenuation",
        "range" => "Range",
        "falloff" => "Falloff",
        "exponent" => "Spot exponent",
        "cutoff" => "Cutoff",
        "inner_cone" => "Inner cone",
        "outer_cone" => "Outer cone",
        "casts_shadows" => "Casts shadows",
        _ => return None,
    })
}

fn material_control(tail: &str) -> Option<&'static str> {
    Some(match tail {
        "ka" => "k_a",
        "kd" => "k_d",
        "ks" => "k_s",
        "shininess" => "Shininess n",
        "specular_model" => "Specular model",
        "roughness" => "Roughness m",
        "fresnel" => "Fresnel",
        "kr" => "k_r",
        "kt" => "k_t",
        "ior" => "Index of refraction",
        "emission" => "E_m",
        "checker.kd" => "Checker k_d",
        "checker.size" => "Checker size",
        _ if tail.starts_with("checker") => "Checker",
        _ if tail.starts_with("emission_texture") => "Emission texture (× E_m)",
        _ if tail.starts_with("texture") => "Texture (× k_a, k_d)",
        _ => return None,
    })
}

fn camera_control(field: &str) -> Option<&'static str> {
    Some(match field {
        "projection" => "Projection",
        "fov_y" => "Field of view",
        "view_height" => "View height",
        // Moved by dragging the view, or set back by this button.
        "position" | "look_at" | "up" => "Reset camera",
        _ => return None,
    })
}

fn world_control(field: &str) -> Option<&'static str> {
    Some(match field {
        "ambient" => "Ambient I_a",
        "background" => "Background",
        "global_attenuation" => "Global attenuation of k_r·I_r, k_t·I_t",
        _ => return None,
    })
}

fn render_control(field: &str) -> Option<&'static str> {
    Some(match field {
        "integrator" => "Integrator",
        "indirect" => "Indirect light",
        "max_depth" => "Max depth",
        "bailout" => "Bailout",
        "epsilon" => "Epsilon",
        "epsilon_mode" => "Epsilon strategy",
        "spp" => "Samples per pixel",
        "width" => "Width",
        "height" => "Height",
        _ => return None,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn doc() -> Document {
        Document::from_loaded(glint_io::load_scene("spotlights").expect("built-in"))
    }

    #[test]
    fn a_light_field_names_the_light_and_its_control() {
        let doc = doc();
        let p = place("lights[1].casts_shadows", &doc);
        assert_eq!(p.tab, Tab::Lights);
        assert_eq!(p.focus, Focus::Light(1));
        assert_eq!(p.text(), format!("Lights › {} › Casts shadows", doc.light_label(1)));
        assert_eq!(place("lights[1].attenuation.q", &doc).trail.last().map(String::as_str), Some("Attenuation"));
    }

    #[test]
    fn a_field_out_of_the_scene_falls_back_to_its_tab() {
        let doc = doc();
        let p = place("lights[99].position", &doc);
        assert_eq!((p.tab, &p.focus, p.text()), (Tab::Lights, &Focus::Nothing, "Lights".to_string()));
        assert_eq!(place("materials.nonesuch.kd", &doc).text(), "Materials");
        assert_eq!(place("objects[x].center", &doc).text(), "Materials");
        assert_eq!(place("seed", &doc).text(), "Scene");
    }

    #[test]
    fn render_and_world_fields_name_their_section() {
        let doc = doc();
        assert_eq!(place("render.max_depth", &doc).text(), "Scene › Render › Max depth");
        assert_eq!(
            place("world.global_attenuation.c", &doc).text(),
            "Scene › World › Global attenuation of k_r·I_r, k_t·I_t"
        );
        assert_eq!(place("camera.fov_y", &doc).text(), "Scene › Camera › Field of view");
        assert_eq!(place("render.seed", &doc).text(), "Scene › Render");
    }

    #[test]
    fn a_material_name_with_dots_is_matched_whole() {
        let mut doc = doc();
        let m = doc.desc.materials.values().next().cloned().expect("a material");
        doc.desc.materials.insert("glass.v2".into(), m.clone());
        doc.desc.materials.insert("glass".into(), m);
        let p = place("materials.glass.v2.checker.size", &doc);
        assert_eq!(p.focus, Focus::Material("glass.v2".into()));
        assert_eq!(p.text(), "Materials › glass.v2 › Checker size");
        assert_eq!(place("materials.glass.ior", &doc).text(), "Materials › glass › Index of refraction");
    }
}
