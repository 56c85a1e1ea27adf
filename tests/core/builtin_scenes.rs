//! The built-in scenes do what their comments promise a lesson.

use glint_core::{CpuOptions, FlatScene, RenderControl, render_cpu};
use glint_io::load_scene;
use glint_scene::{RenderSettings, Rgb};

/// `lights`: each of the three lights reaches its own bay alone. With one light left, and no
/// ambient or background light, the image columns of the other bays are black: the middle bay
/// projects within 0.376–0.624 of the width, so the outer thirds are side bays' (or nothing).
#[test]
fn each_light_of_the_lights_scene_stays_in_its_bay() {
    let desc = load_scene("lights").expect("built-in scene").desc;
    let settings = RenderSettings { width: 180, height: 72, ..desc.render.clone() };
    let (w, h) = (settings.width as usize, settings.height as usize);
    let lit_columns = |light: usize| -> Vec<usize> {
        let mut one = desc.clone();
        one.lights = vec![desc.lights[light].clone()];
        one.world.ambient = Rgb::splat(0.0);
        one.world.background = Rgb::splat(0.0);
        let image = render_cpu(&FlatScene::build(&one, &settings), &CpuOptions::default(), RenderControl::default())
            .expect("render")
            .image;
        (0..w).filter(|&x| (0..h).any(|y| image.pixels[y * w + x].max_element() > 0.0)).collect()
    };
    let (left, middle, right) = (0..w / 3, 45 * w / 100..55 * w / 100, 2 * w / 3..w);
    // Screen left is +x, the point light's bay; the spot is screen right.
    for (light, own, others) in
        [(0, &left, [&middle, &right]), (1, &middle, [&left, &right]), (2, &right, [&left, &middle])]
    {
        let lit = lit_columns(light);
        assert!(lit.iter().any(|x| own.contains(x)), "light {light} lights nothing of its own bay");
        for other in others {
            let strays: Vec<&usize> = lit.iter().filter(|x| other.contains(x)).collect();
            assert!(strays.is_empty(), "light {light} reaches columns {strays:?} of another bay");
        }
    }
}
