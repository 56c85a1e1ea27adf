//! The exact CPU reference tracer (f64). Each module is the twin of a WGSL file in `shaders/`
//! with the same function names, as vello pairs `cpu/*.rs` with `shader/*.wgsl`.

pub mod bsdf;
pub mod bvh;
pub mod camera;
pub mod emitter;
pub mod intersect;
pub mod offset;
pub mod path;
pub mod primitive;
pub mod ray_tree;
pub mod raycast;
pub mod rng;
pub mod sample;
pub mod shade;
pub mod surface;
pub mod texture;
pub mod trace;
pub mod walk;

use std::ops::AddAssign;

use glam::DVec3;
use glint_types::{LightTags, MaterialTags};

use crate::flat::{Corners, FlatScene};
use glint_scene::{EpsilonMode, Filter, Integrator, Wrap};
use glint_types::layout::{UnknownTag, feature};

/// The default of `TraceContext::max_rays_per_sample`: 2^22 rays, about 3 s of one core. A
/// depth-5 tree through glass (63 hits) with 10,000 lights traces 630,000 rays; a tree
/// beyond 2^22 is one that doubles for more than 20 levels, which the bailout did not stop.
pub const DEFAULT_MAX_RAYS_PER_SAMPLE: u64 = 1 << 22;

/// Largest ray parameter; also the reach of shadow rays towards directional lights. Finite
/// so that the f32 tracer never computes with infinities.
pub const FAR: f64 = 1e30;

/// A ray with a unit direction.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Ray {
    pub origin: DVec3,
    pub dir: DVec3,
}

/// Widens a stored `vec4<f32>` (xyz) to f64: exact.
#[inline]
pub fn v3(a: [f32; 4]) -> DVec3 {
    DVec3::new(f64::from(a[0]), f64::from(a[1]), f64::from(a[2]))
}

/// Rays traced, by kind.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RayCounts {
    pub camera: u64,
    pub shadow: u64,
    pub reflection: u64,
    pub refraction: u64,
    /// Child rays not traced because their path weight fell below the bailout.
    pub bailout_saved: u64,
    /// Camera samples whose ray tree reached `TraceContext::max_rays_per_sample` (the CPU
    /// stops the render at the first: `render::CpuRenderError::RayCap`).
    pub capped_samples: u64,
}

impl RayCounts {
    pub fn total(&self) -> u64 {
        self.camera + self.shadow + self.reflection + self.refraction
    }
}

impl AddAssign for RayCounts {
    fn add_assign(&mut self, o: Self) {
        self.camera += o.camera;
        self.shadow += o.shadow;
        self.reflection += o.reflection;
        self.refraction += o.refraction;
        self.bailout_saved += o.bailout_saved;
        self.capped_samples += o.capped_samples;
    }
}

/// How the CPU tracer is asked to find the primitives a ray meets. The image is bit-identical
/// whichever it uses.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Accel {
    /// The BVH for scenes with at least `bvh::AUTO_MIN_PRIMITIVES` spheres and triangles,
    /// brute force below (where it is faster): the default.
    #[default]
    Auto,
    /// Always through the scene's BVH (`FlatScene::bvh_nodes`), planes tested apart.
    Bvh,
    /// Every primitive against every ray (brute force).
    None,
}

impl Accel {
    /// Every choice with its `--accel` name.
    pub const CHOICES: [(&'static str, Self); 3] = [("auto", Self::Auto), ("bvh", Self::Bvh), ("none", Self::None)];

    pub fn name(self) -> &'static str {
        match self {
            Self::Auto => "auto",
            Self::Bvh => "bvh",
            Self::None => "none",
        }
    }

    /// How a ray of `scene` is traced under this choice.
    pub fn traversal(self, scene: &FlatScene) -> Traversal {
        match self {
            Self::Auto if scene.spheres.len() + scene.triangles.len() >= crate::bvh::AUTO_MIN_PRIMITIVES => {
                Traversal::Bvh
            }
            Self::Auto | Self::None => Traversal::BruteForce,
            Self::Bvh => Traversal::Bvh,
        }
    }
}

/// How the tracer finds the primitives a ray meets, decided once per render (`Accel::traversal`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Traversal {
    Bvh,
    BruteForce,
}

/// Everything the tracer functions read: the flat scene, its header widened once, its tags
/// decoded once, and the feature set whose work the tracer does.
#[derive(Clone, Debug)]
pub struct TraceContext<'a> {
    pub scene: &'a FlatScene,
    /// The features the tracer runs: the scene's own (specialised, the default) or
    /// `feature::ALL` (unspecialised). Passed beside the scene, never written into it.
    pub features: u32,
    /// BVH or brute force (`Accel::Auto`'s choice unless set with `with_accel`).
    pub traversal: Traversal,
    pub max_depth: u32,
    /// Whitted's ray tree or Monte Carlo paths (`SceneHeader::integrator`).
    pub integrator: Integrator,
    /// Paths follow the non-delta lobes (`SceneHeader::indirect`); paths only.
    pub indirect: bool,
    /// The kinds of light paths leave out (`SceneHeader::omit_kinds`); paths only.
    pub omit_kinds: u32,
    pub epsilon: f64,
    pub epsilon_mode: EpsilonMode,
    pub bailout: f64,
    /// Rays one camera sample's tree may trace (camera, shadow, reflection, refraction rays)
    /// before its remaining children are cut and the sample counted in
    /// `RayCounts::capped_samples`: the bound on the work of a pixel.
    pub max_rays_per_sample: u64,
    /// The tags of each light, in light order.
    pub light_tags: Vec<LightTags>,
    /// The tags of each material, in material order.
    pub material_tags: Vec<MaterialTags>,
    /// The caller's stop flag, read each time a tree would trace another child: a sample's tree
    /// of 1e12 rays (under a raised `max_rays_per_sample`) ran for minutes after a SIGTERM,
    /// which the render loop sees between pixels only. A stopped tree's image is discarded.
    pub cancel: Option<&'a std::sync::atomic::AtomicBool>,
    /// The wrap modes (u, v) and filter of each texture, in table order.
    pub texture_modes: Vec<([Wrap; 2], Filter)>,
    /// The BVH walk's leaf-order triangle corners, if they were made from this scene's arrays
    /// (`LeafCorners::for_arrays`; checked once here, not per ray).
    pub leaf_corners: Option<&'a [Corners]>,
}

impl<'a> TraceContext<'a> {
    /// The specialised tracer: exactly the scene's features.
    pub fn new(scene: &'a FlatScene) -> Result<Self, UnknownTag> {
        Self::with_features(scene, scene.header.features)
    }

    /// The tracer running `features` (the scene's own, or `feature::ALL` for every feature's
    /// code path: the image is bit-identical either way).
    pub fn with_features(scene: &'a FlatScene, features: u32) -> Result<Self, UnknownTag> {
        // Every index the tracer follows unchecked, as the GPU's upload checks it.
        scene.check_tags()?;
        let h = &scene.header;
        Ok(Self {
            scene,
            features,
            traversal: Accel::default().traversal(scene),
            max_depth: h.max_depth,
            integrator: Integrator::try_from(h.integrator)?,
            indirect: h.indirect != 0,
            omit_kinds: h.omit_kinds,
            epsilon: f64::from(h.epsilon),
            epsilon_mode: EpsilonMode::try_from(h.epsilon_mode)?,
            bailout: f64::from(h.bailout),
            max_rays_per_sample: DEFAULT_MAX_RAYS_PER_SAMPLE,
            cancel: None,
            light_tags: scene.lights.iter().map(LightTags::decode).collect::<Result<_, _>>()?,
            material_tags: scene.materials.iter().map(MaterialTags::decode).collect::<Result<_, _>>()?,
            texture_modes: scene
                .textures
                .iter()
                .map(|t| Ok(([Wrap::try_from(t.wrap_s)?, Wrap::try_from(t.wrap_t)?], Filter::try_from(t.filter_mode)?)))
                .collect::<Result<_, UnknownTag>>()?,
            leaf_corners: scene.leaf_corners.for_arrays(&scene.vertices, &scene.triangles, &scene.bvh_prims),
        })
    }

    /// The same context, finding primitives with `accel`.
    pub fn with_accel(self, accel: Accel) -> Self {
        Self { traversal: accel.traversal(self.scene), ..self }
    }

    /// The same context, cutting a camera sample's tree at `cap` rays.
    pub fn with_ray_cap(self, cap: u64) -> Self {
        Self { max_rays_per_sample: cap, ..self }
    }

    /// The same context, its trees cut short once `cancel` is raised.
    pub fn with_cancel(self, cancel: Option<&'a std::sync::atomic::AtomicBool>) -> Self {
        Self { cancel, ..self }
    }

    /// Whether a camera sample's tree, whose own rays are `counts`, has traced its
    /// `max_rays_per_sample`: then no further child is traced and the sample is marked capped.
    /// A raised stop flag cuts it too, unmarked (the render is then cancelled, not capped).
    #[inline]
    pub fn cap_reached(&self, counts: &mut RayCounts) -> bool {
        let reached = counts.total() >= self.max_rays_per_sample;
        if reached {
            counts.capped_samples = 1;
        }
        reached || self.cancel.is_some_and(|c| c.load(std::sync::atomic::Ordering::Relaxed))
    }

    /// Whether any of the `bits` is in the feature set.
    #[inline]
    pub fn has(&self, bits: u32) -> bool {
        self.features & bits != 0
    }
}

const _: () = assert!(feature::ALL.count_ones() as usize == feature::NAMES.len());
