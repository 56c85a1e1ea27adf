//! "Fit ambient" (issue 33): the global I_a that brings Whitted's image closest to the
//! path-traced one lowers the error against it, and Whitted's image is affine in I_a as the fit
//! assumes.

use glint_core::ambient_fit::fit_ambient;
use glint_core::{CpuOptions, FlatScene, RenderControl, render_cpu};
use glint_io::load_scene;
use glint_scene::{Integrator, Rgb};

#[test]
fn the_fitted_ambient_lowers_whitteds_error_against_the_path_traced_image() {
    for name in ["cornell-gi", "cornell"] {
        let desc = load_scene(name).expect("built-in scene").desc;
        let mut settings = desc.render.clone();
        (settings.width, settings.height, settings.max_depth) = (40, 30, 8);
        let reference_settings =
            glint_scene::RenderSettings { integrator: Integrator::Path, spp: 256, ..settings.clone() };
        let options = CpuOptions::default();
        let reference = render_cpu(&FlatScene::build(&desc, &reference_settings), &options, RenderControl::default())
            .expect("path-traced reference")
            .image;
        let fit = fit_ambient(&desc, &settings, &reference, &options).expect("fit");
        eprintln!("{name}: {fit:?}");
        assert!(fit.determined, "{name}: {fit:?}");
        assert!(fit.ambient.iter().all(|a| *a > 0.0), "{name}: the indirect light needs some ambient: {fit:?}");
        assert!(fit.rmse_fitted < fit.rmse_without, "{name}: {fit:?}");
        assert!(fit.rmse_fitted <= fit.rmse_as_written, "{name}: {fit:?}");

        // The fit's model, W0 + I_a·(W1 − W0), is the render at I_a itself.
        let mut fitted = desc.clone();
        fitted.world.ambient = Rgb(fit.ambient);
        let direct = render_cpu(
            &FlatScene::build(
                &fitted,
                &glint_scene::RenderSettings { integrator: Integrator::Whitted, ..settings.clone() },
            ),
            &options,
            RenderControl::default(),
        )
        .expect("Whitted at the fitted ambient");
        let sum: f64 = direct.image.pixels.iter().zip(&reference.pixels).map(|(p, q)| (*p - *q).length_squared()).sum();
        let rmse = (sum / (3 * reference.pixels.len()) as f64).sqrt();
        assert!(
            (rmse - fit.rmse_fitted).abs() <= 1e-9 * rmse.max(1.0),
            "{name}: rendered {rmse}, fitted {}",
            fit.rmse_fitted
        );
        // The figures at any I_a written follow from the fit's moments: as written, fitted,
        // without (the viewer's "as written" after an I_a edit, without a render).
        // To 1e-7: a render stores its I_a as f32 (0.1 is 0.100000001), the moments take it exact.
        let close = |a: f64, b: f64| (a - b).abs() <= 1e-7 * a.abs().max(b.abs()).max(1e-12);
        let (rmse, adds) = fit.at(desc.world.ambient.0);
        assert!(close(rmse, fit.rmse_as_written) && close(adds, fit.adds_as_written), "{name}: {rmse} {adds} {fit:?}");
        let (rmse, adds) = fit.at(fit.ambient);
        assert!(close(rmse, fit.rmse_fitted) && close(adds, fit.adds_fitted), "{name}: {rmse} {adds} {fit:?}");
        assert!(close(fit.at([0.0; 3]).0, fit.rmse_without) && fit.at([0.0; 3]).1 == 0.0, "{name}");
    }
}

#[test]
fn without_k_a_no_ambient_fits_better_than_another_and_the_fit_says_so() {
    let mut desc = load_scene("cornell").expect("built-in scene").desc;
    for m in desc.materials.values_mut() {
        m.ka = Rgb([0.0; 3]);
    }
    let mut settings = desc.render.clone();
    (settings.width, settings.height) = (16, 12);
    let reference = render_cpu(
        &FlatScene::build(&desc, &glint_scene::RenderSettings { integrator: Integrator::Path, ..settings.clone() }),
        &CpuOptions::default(),
        RenderControl::default(),
    )
    .expect("path-traced reference")
    .image;
    let fit = fit_ambient(&desc, &settings, &reference, &CpuOptions::default()).expect("fit");
    assert!(!fit.determined, "{fit:?}");
    assert_eq!(fit.rmse_fitted, fit.rmse_without, "{fit:?}");
}
