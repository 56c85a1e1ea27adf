//! Vertex colours on the CPU reference: what they multiply (k_a and k_d, exactly, and
//! nothing else), what they leave alone (a scene without them: no feature, no buffer), and
//! the bad values validation refuses.

use glam::DVec3;
use glint_core::FlatScene;
use glint_scene::{MeshDesc, ObjectDesc};
use glint_test_support::scene::{SceneText, vertex_colour_scene};
use glint_types::layout::feature;

use super::render::render_cpu_checked;

/// A quad facing the camera under a white point light and the ambient term, with `material`'s
/// fields, and `colour` on every vertex when given.
fn quad(material: &str, colour: Option<[f64; 3]>) -> FlatScene {
    let vertices = [[-1.0, -1.0, 0.0], [1.0, -1.0, 0.0], [1.0, 1.0, 0.0], [-1.0, 1.0, 0.0]];
    let tris = [[0, 1, 2], [0, 2, 3]];
    let s = SceneText::new(48, 48, "max_depth = 0", [0.3, 0.2, 3.0], [0.0; 3], [0.0, 1.0, 0.0], 50.0)
        .world([0.2; 3], [0.0; 3])
        .material("m", material)
        .light("point", "position = [1.0, 2.0, 2.0]\ndiffuse = 1.0\nspecular = 1.0");
    match colour {
        Some(c) => s.coloured_mesh(&vertices, &tris, &[c; 4], "m"),
        None => s.mesh(&vertices, &tris, None, "m"),
    }
    .flat()
}

#[test]
fn a_vertex_colour_multiplies_k_a_and_k_d_and_nothing_else() {
    let lambert = "ka = 1.0\nkd = 0.8\nks = 0.0";
    let colour = DVec3::new(0.25, 0.5, 1.0);
    let plain = render_cpu_checked(&quad(lambert, None), 0, true).image;
    let tinted = render_cpu_checked(&quad(lambert, Some(colour.to_array())), 0, true).image;
    let mut hits = 0;
    for (a, b) in plain.pixels.iter().zip(&tinted.pixels).filter(|(a, _)| a.max_element() > 0.0) {
        // The interpolated colour is c·((1 − u − v) + u + v): c to within a few ulps.
        let rel = ((*b - *a * colour).abs() / (*a * colour)).max_element();
        assert!(rel < 1e-14, "{b} is not {a} × {colour} (relative {rel:e})");
        hits += 1;
    }
    assert!(hits > 1000, "only {hits} pixels hit the quad");
    // Black vertices leave the highlight alone, as k_a = k_d = 0 would.
    let glossy = "ka = 1.0\nkd = 0.8\nks = 0.5\nshininess = 20.0";
    let black = render_cpu_checked(&quad(glossy, Some([0.0; 3])), 0, true).image;
    let unlit = render_cpu_checked(&quad("ka = 0.0\nkd = 0.0\nks = 0.5\nshininess = 20.0", None), 0, true).image;
    assert_eq!(black.pixels, unlit.pixels, "black vertex colours left more than the highlight");
    assert!(black.pixels.iter().any(|p| p.max_element() > 0.1), "no highlight to compare");
}

#[test]
fn only_a_scene_with_vertex_colours_stores_them_and_specialises_for_them() {
    let with = vertex_colour_scene(16, 12, true).flat();
    assert!(with.header.features & feature::VERTEX_COLOURS != 0);
    assert_eq!(with.colours.len(), with.vertices.len(), "one colour a vertex, white where a mesh has none");
    assert!(with.colours.iter().filter(|c| **c == [1.0; 4]).count() >= 3, "the uncoloured triangle is white");
    let without = vertex_colour_scene(16, 12, false).flat();
    assert_eq!((without.header.features & feature::VERTEX_COLOURS, without.colours.len()), (0, 0));
    // A saved scene keeps them, and `colors` reads as `colours`.
    let desc = vertex_colour_scene(16, 12, true).desc();
    let saved = glint_io::to_toml(&desc).expect("TOML");
    assert!(saved.contains("colours = ["), "{saved}");
    let (again, _) = glint_io::parse_scene(&saved, std::path::Path::new("saved.toml")).expect("reads back");
    assert_eq!(again.objects, desc.objects);
    let american = saved.replace("colours = [", "colors = [");
    assert_eq!(
        glint_io::parse_scene(&american, std::path::Path::new("us.toml")).expect("reads").0.objects,
        desc.objects
    );
    // The colours change the image (and its content hash, which tiles carry).
    let (a, b) = (render_cpu_checked(&with, 0, true).image, render_cpu_checked(&without, 0, true).image);
    assert!(a.pixels != b.pixels && with.content_hash() != without.content_hash());
    // All white is no colour: left out, and the image is the uncoloured one bit for bit.
    let lambert = "ka = 1.0\nkd = 0.8\nks = 0.3";
    let white = quad(lambert, Some([1.0; 3]));
    assert_eq!((white.header.features & feature::VERTEX_COLOURS, white.colours.len()), (0, 0));
    let plain = render_cpu_checked(&quad(lambert, None), 0, true).image;
    assert_eq!(render_cpu_checked(&white, 0, true).image.pixels, plain.pixels);
}

#[test]
fn bad_vertex_colours_are_errors_naming_the_field() {
    let mut desc = vertex_colour_scene(16, 12, true).desc();
    let last = desc.objects.len() - 1;
    let ObjectDesc::Mesh(MeshDesc { colours: Some(colours), .. }) = &mut desc.objects[last] else {
        panic!("the quad is the last object")
    };
    colours[1] = [0.5, -0.1, 0.0];
    colours.pop();
    let report = glint_scene::validate(&desc);
    let text: Vec<String> = report.errors.iter().map(|e| format!("{}: {}", e.field, e.problem)).collect();
    let named = |field: &str, words: &str| text.iter().any(|e| e.contains(field) && e.contains(words));
    assert!(named(&format!("objects[{last}].colours"), "has 3 entries; it needs one per vertex (4)"), "{text:?}");
    assert!(named(&format!("objects[{last}].colours[1]"), "channel g = -0.1"), "{text:?}");
    // 8-bit colours written as 0–255 are allowed, as k_d > 1 is, but named.
    let mut desc = vertex_colour_scene(16, 12, true).desc();
    let ObjectDesc::Mesh(MeshDesc { colours: Some(colours), .. }) = &mut desc.objects[last] else {
        panic!("the quad is the last object")
    };
    colours[2] = [255.0, 128.0, 0.0];
    let report = glint_scene::validate(&desc);
    assert!(report.errors.is_empty(), "{:?}", report.errors);
    let warned = report.warnings.iter().find(|w| w.field == format!("objects[{last}].colours")).expect("warned");
    assert!(warned.problem.contains("reach 255") && warned.problem.contains("dividing by 255"), "{}", warned.problem);
}
