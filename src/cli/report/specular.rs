//! The seed's claim measured: "other models (e.g., Cook and Torrance) are available — more
//! accurate model at the cost of higher computation expense". Every material of a scene is set
//! to each specular model in turn (its roughness and Fresnel choice as the material has them),
//! and the three are rendered with the same settings on each backend: the same rays (the
//! specular lobe decides no ray), so any difference in time is the lobe's arithmetic and, on
//! the GPU, the specialised shader of the model.

use anyhow::Context;
use glint_core::{Backend, FlatScene};
use glint_io::LoadedScene;
use glint_scene::{EpsilonMode, RenderSettings, SpecularModel};
use indicatif::ProgressBar;

use super::plan::{Bailout, Config};
use super::sweep::{Engines, SpecularRow, render, settings_for, timed_passes};

/// Samples per pixel and depth of the measurement: enough work per render (16 samples of a
/// depth-5 tree per pixel) that the timer's resolution and a frame's fixed costs do not count.
pub const SPP: u32 = 16;
pub const DEPTH: u32 = 5;

/// The configuration every model is rendered with on `backend`.
pub fn config(backend: Backend) -> Config {
    Config {
        backend,
        spp: SPP,
        depth: DEPTH,
        bailout: Bailout::Per255,
        specialise: true,
        epsilon_mode: EpsilonMode::Robust,
    }
}

/// Renders per scene: a warm-up and `runs` timed renders of each model on each backend.
pub fn renders(backends: &[Backend], runs: u32) -> usize {
    SpecularModel::ALL.len() * backends.len() * (1 + runs as usize)
}

/// `desc` with every material's specular model set to `model`.
fn forced(loaded: &LoadedScene, model: SpecularModel) -> glint_scene::SceneDesc {
    let mut desc = loaded.desc.clone();
    for m in desc.materials.values_mut() {
        m.specular_model = model;
    }
    desc
}

/// A warm-up pass over every (model, backend), then `runs` timed passes over all of them, as
/// the main sweep does, so that a load change hits every model alike.
pub fn measure(
    engines: &mut Engines,
    loaded: &LoadedScene,
    base: &RenderSettings,
    backends: &[Backend],
    runs: u32,
    bar: &ProgressBar,
) -> anyhow::Result<Vec<SpecularRow>> {
    let name = &loaded.name;
    let mut jobs: Vec<(SpecularModel, Config, FlatScene)> = Vec::new();
    for &backend in backends {
        let config = config(backend);
        for model in SpecularModel::ALL {
            jobs.push((model, config, FlatScene::build(&forced(loaded, model), &settings_for(base, &config))));
        }
    }
    let mut rows = Vec::with_capacity(jobs.len());
    for (model, config, flat) in &jobs {
        bar.set_message(format!("{name}: specular models: warm-up: {} {}", config.backend.name(), model.label()));
        let warm = render(engines, flat, config).with_context(|| format!("{name}: {} {config:?}", model.label()))?;
        rows.push(SpecularRow {
            model: *model,
            config: *config,
            times: Vec::new(),
            counts: warm.counts,
            gpu: warm.gpu,
            shard: None,
        });
        bar.inc(1);
    }
    let timed: Vec<(&FlatScene, Config)> = jobs.iter().map(|(_, c, f)| (f, *c)).collect();
    let what = format!("{name}: specular models");
    for (row, times) in rows.iter_mut().zip(timed_passes(engines, &timed, &|_| base.integrator, runs, bar, &what)?) {
        row.times = times;
    }
    Ok(rows)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_model_is_forced_on_every_material_and_decides_the_feature_bits() {
        use glint_types::layout::feature;
        let loaded = glint_io::load_scene("highlights").expect("built-in scene");
        let settings = settings_for(&loaded.desc.render, &config(Backend::Cpu));
        for (model, bit) in [
            (SpecularModel::Blinn, feature::BLINN),
            (SpecularModel::Phong, feature::PHONG),
            (SpecularModel::CookTorrance, feature::COOK_TORRANCE),
        ] {
            let desc = forced(&loaded, model);
            assert!(desc.materials.values().all(|m| m.specular_model == model));
            let lobes = FlatScene::build(&desc, &settings).header.features
                & (feature::BLINN | feature::PHONG | feature::COOK_TORRANCE);
            assert_eq!(lobes, bit, "{model:?}");
        }
    }
}
