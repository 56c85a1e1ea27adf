//! The images of docs/tour.md (the seed's "Basic Ray Tracing Deficiencies", shown on built-in
//! scenes): each is Whitted's image beside the path tracer's of the same scene and view, CPU,
//! deterministic. `GLINT_WRITE_TOUR=1 cargo test --test core tour` writes them; without it the
//! test renders them again and fails when a committed image no longer matches, pixel for pixel.

use std::path::PathBuf;

use glint_core::ambient_fit::fit_ambient;
use glint_core::image::linear_f32_to_srgb8;
use glint_core::{CpuOptions, FlatScene, HdrImage, RenderControl, render_cpu};
use glint_io::load_scene;
use glint_scene::{Integrator, RenderSettings, Rgb, SceneDesc};

const WIDTH: u32 = 160;
const HEIGHT: u32 = 120;
const PATHS: u32 = 64;

/// How a stop sets Whitted's ambient term from the scene, its settings and the paths' image.
type AmbientOf<'a> = &'a dyn Fn(&SceneDesc, &RenderSettings, &HdrImage) -> Rgb;

fn render(desc: &SceneDesc, settings: &RenderSettings) -> HdrImage {
    render_cpu(&FlatScene::build(desc, settings), &CpuOptions::default(), RenderControl::default())
        .expect("render")
        .image
}

/// Whitted's image (with `ambient`, if given) beside the path tracer's, as 8-bit sRGB rows.
fn pair(scene: &str, ambient: Option<AmbientOf>) -> Vec<u8> {
    let mut desc = load_scene(scene).expect("built-in scene").desc;
    let base = RenderSettings { width: WIDTH, height: HEIGHT, max_depth: 8, ..desc.render.clone() };
    let paths = render(&desc, &RenderSettings { integrator: Integrator::Path, spp: PATHS, ..base.clone() });
    let whitted_settings = RenderSettings { integrator: Integrator::Whitted, spp: 4, ..base };
    if let Some(fit) = ambient {
        desc.world.ambient = fit(&desc, &whitted_settings, &paths);
    }
    let whitted = render(&desc, &whitted_settings);
    let mut rgb = Vec::with_capacity((2 * WIDTH * HEIGHT * 3) as usize);
    for y in 0..HEIGHT {
        for image in [&whitted, &paths] {
            for x in 0..WIDTH {
                rgb.extend(image.get(x, y).to_array().map(|v| linear_f32_to_srgb8(v as f32)));
            }
        }
    }
    rgb
}

#[test]
fn the_tours_images_are_what_the_tracers_render() {
    let fitted = |desc: &SceneDesc, settings: &RenderSettings, paths: &HdrImage| {
        Rgb(fit_ambient(desc, settings, paths, &CpuOptions::default()).expect("fit").ambient)
    };
    let stops: [(&str, &str, Option<AmbientOf>); 3] = [
        ("tour-highlights.png", "highlights", None),
        ("tour-cornell.png", "cornell", None),
        ("tour-cornell-gi-fitted.png", "cornell-gi", Some(&fitted)),
    ];
    let folder = PathBuf::from(concat!(env!("CARGO_MANIFEST_DIR"), "/docs/images"));
    let write = std::env::var("GLINT_WRITE_TOUR").is_ok_and(|v| v == "1");
    for (file, scene, ambient) in stops {
        let rgb = pair(scene, ambient);
        let path = folder.join(file);
        if write {
            let metadata = [("glint:scene".to_string(), scene.to_string())];
            glint_io::image_file::write_png_rgb8(&path, 2 * WIDTH, HEIGHT, &rgb, &metadata).expect("write");
            continue;
        }
        let committed = image::open(&path)
            .unwrap_or_else(|e| {
                panic!("{}: {e} (GLINT_WRITE_TOUR=1 cargo test --test core tour writes it)", path.display())
            })
            .into_rgb8();
        assert_eq!(committed.dimensions(), (2 * WIDTH, HEIGHT), "{file}");
        assert!(
            committed.into_raw() == rgb,
            "{file} is no longer what the tracers render: GLINT_WRITE_TOUR=1 cargo test --test core tour"
        );
    }
}
