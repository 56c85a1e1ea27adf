//! What the render of a scene under its own integrator reads, its objects aside: an edit that
//! leaves it the same leaves that render as it is. Paths have no ambient term (I_a, k_a and
//! the lights' I_a,j stand in for the indirect light they compute: `glint_core::cpu::path`),
//! so applying a fitted I_a in the Whitted vs GI view renders Whitted's side again and lets
//! the paths go on converging, where it started them over.

use std::collections::BTreeMap;

use glint_scene::{CameraDesc, LightDesc, MaterialDesc, RenderSettings, Rgb, SceneDesc, WorldDesc};

/// The scene's part of it: camera, world, materials and lights, the ambient terms left out
/// under paths. The error history keys its points by it too.
#[derive(Clone, Debug, PartialEq)]
pub struct SceneInputs {
    camera: CameraDesc,
    world: WorldDesc,
    materials: BTreeMap<String, MaterialDesc>,
    lights: Vec<LightDesc>,
}

impl SceneInputs {
    pub fn of(desc: &SceneDesc) -> Self {
        let mut inputs = Self::as_written(desc);
        if !desc.render.integrator.is_whitted() {
            inputs.world.ambient = Rgb::default();
            inputs.materials.values_mut().for_each(|m| m.ka = Rgb::default());
            inputs.lights.iter_mut().for_each(|l| l.ambient = Rgb::default());
        }
        inputs
    }

    /// Every term as `desc` writes it.
    fn as_written(desc: &SceneDesc) -> Self {
        Self {
            camera: desc.camera.clone(),
            world: desc.world.clone(),
            materials: desc.materials.clone(),
            lights: desc.lights.clone(),
        }
    }
}

#[derive(Clone, Debug, PartialEq)]
pub struct RenderInputs {
    render: RenderSettings,
    scene: SceneInputs,
    omit_kinds: u32,
}

impl RenderInputs {
    /// What the render of `desc` (the kinds of path-traced light in `omit_kinds` left out) reads.
    pub fn of(desc: &SceneDesc, omit_kinds: u32) -> Self {
        Self { render: desc.render.clone(), scene: SceneInputs::of(desc), omit_kinds }
    }
}

/// What the ambient fit reads (`glint_core::ambient_fit`): the scene and the render settings it
/// renders Whitted and the paths at, its objects aside, but not the world's I_a, which the fit
/// does not depend on (the figures "as written" follow from its moments at any I_a).
#[derive(Clone, Debug, PartialEq)]
pub struct FitInputs {
    render: RenderSettings,
    scene: SceneInputs,
}

impl FitInputs {
    pub fn of(desc: &SceneDesc) -> Self {
        let mut scene = SceneInputs::as_written(desc);
        scene.world.ambient = Rgb::default();
        // The fit renders both integrators itself, with every kind of light.
        let render =
            RenderSettings { integrator: glint_scene::Integrator::Whitted, indirect: true, ..desc.render.clone() };
        Self { render, scene }
    }
}
