//! Texture fixtures: PNG files written by the tests, and a scene using every texture path (a
//! bilinear mirrored texture with a UV transform on a quad with vertex UVs, a nearest clamped
//! one with an emission texture on a sphere in planar coordinates, and a checker floor).

use std::path::Path;

use crate::scene::SceneText;

/// Writes an 8-bit RGBA PNG (`rgba`: width · height · 4 bytes, rows from the top).
pub fn write_png(path: &Path, width: u32, height: u32, rgba: &[u8]) {
    let file = std::fs::File::create(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    let mut encoder = png::Encoder::new(std::io::BufWriter::new(file), width, height);
    encoder.set_color(png::ColorType::Rgba);
    encoder.set_depth(png::BitDepth::Eight);
    encoder.write_header().and_then(|mut w| w.write_image_data(rgba)).expect("PNG written");
}

/// A 4×4 texture of distinct colours (`tex.png`) and a 2×2 glow (`glow.png`) in `dir`.
pub fn write_fixture_textures(dir: &Path) {
    let tex: Vec<u8> = (0..16u8).flat_map(|i| [i * 16, 255 - i * 12, (i % 4) * 80, 255]).collect();
    write_png(&dir.join("tex.png"), 4, 4, &tex);
    write_png(&dir.join("glow.png"), 2, 2, &[255, 64, 0, 255, 0, 0, 0, 255, 0, 0, 0, 255, 32, 128, 255, 255]);
}

/// The textured scene (its textures written into `dir`, where its scene file must be).
pub fn textured_scene(dir: &Path, width: u32, height: u32) -> SceneText {
    textured_scene_moved(dir, width, height, 2, [0.0; 3])
}

/// `textured_scene` moved by `o`, rendered to `max_depth`.
pub fn textured_scene_moved(dir: &Path, width: u32, height: u32, max_depth: u32, o: [f64; 3]) -> SceneText {
    write_fixture_textures(dir);
    let p = |v: [f64; 3]| [v[0] + o[0], v[1] + o[1], v[2] + o[2]];
    let quad = [p([-1.5, -0.2, 1.0]), p([1.5, -0.2, 1.0]), p([1.5, 2.2, 1.0]), p([-1.5, 2.2, 1.0])];
    let uvs = [[0.0, 2.0], [3.0, 2.0], [3.0, -0.5], [0.0, -0.5]];
    let render = format!("max_depth = {max_depth}");
    SceneText::new(width, height, &render, p([0.3, 1.2, -3.5]), p([0.0, 0.6, 0.0]), [0.0, 1.0, 0.0], 50.0)
        .world([0.2; 3], [0.1, 0.1, 0.15])
        .material(
            "poster",
            "ka = 0.5\nkd = [0.9, 0.8, 0.7]\nks = 0.2\nshininess = 16.0\n\
             texture = { path = \"tex.png\", wrap_s = \"repeat\", wrap_t = \"mirrored_repeat\", \
             filter = \"bilinear\", transform = { offset = [0.1, 0.2], rotation = 0.3, scale = [1.25, 0.75] } }",
        )
        .material(
            "ball",
            "ka = 0.3\nkd = 0.7\nks = 0.3\nemission = 0.5\n\
             texture = { path = \"tex.png\", wrap_s = \"clamp_to_edge\", wrap_t = \"clamp_to_edge\", filter = \"nearest\", \
             transform = { offset = [0.5, 0.5], scale = [0.5, 0.5] } }\n\
             emission_texture = { path = \"glow.png\", filter = \"nearest\" }",
        )
        .material("floor", "ka = 0.3\nkd = [0.7, 0.6, 0.5]\nkr = 0.2\nchecker = { kd = [0.2, 0.25, 0.3], size = 0.5 }")
        .light("point", &format!("position = {}\ndiffuse = 0.8\nspecular = 0.6", crate::scene::arr(p([-2.0, 4.0, -3.0]))))
        .plane(p([0.0, -0.2, 0.0]), [0.0, 1.0, 0.0], "floor")
        .sphere(p([0.9, 0.35, 0.2]), 0.55, "ball")
        .textured_mesh(&quad, &[[0, 1, 2], [0, 2, 3]], &uvs, "poster")
}
