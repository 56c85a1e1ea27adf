//! The exact CPU reference tracer (f64). Each module is the twin of a WGSL file in `shaders/`
//! with the same function names, as vello pairs `cpu/*.rs` with `shader/*.wgsl`.

pub mod camera;
pub mod intersect;
pub mod offset;
pub mod probe;
pub mod rng;
pub mod shade;
pub mod trace;

use std::ops::AddAssign;

use glam::DVec3;

use crate::flat::FlatScene;
use crate::layout::feature;

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
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct RayCounts {
    pub camera: u64,
    pub shadow: u64,
    pub reflection: u64,
    pub refraction: u64,
    /// Child rays not traced because their path weight fell below the bailout.
    pub bailout_saved: u64,
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
    }
}

/// Everything the tracer functions read: the flat scene and its header widened once.
#[derive(Clone, Copy, Debug)]
pub struct TraceContext<'a> {
    pub scene: &'a FlatScene,
    pub features: u32,
    pub max_depth: u32,
    pub epsilon: f64,
    pub epsilon_mode: u32,
    pub bailout: f64,
}

impl<'a> TraceContext<'a> {
    pub fn new(scene: &'a FlatScene) -> Self {
        let h = &scene.header;
        Self {
            scene,
            features: h.features,
            max_depth: h.max_depth,
            epsilon: f64::from(h.epsilon),
            epsilon_mode: h.epsilon_mode,
            bailout: f64::from(h.bailout),
        }
    }

    /// Whether any of the `bits` is in the scene's feature set.
    #[inline]
    pub fn has(&self, bits: u32) -> bool {
        self.features & bits != 0
    }
}

const _: () = assert!(feature::ALL.count_ones() as usize == feature::NAMES.len());
