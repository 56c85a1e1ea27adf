//! Shader composition with naga_oil: the WGSL files of `shaders/` joined by `#import`, with
//! `#ifdef` shader defs chosen from the scene's feature set, so that a specialised shader
//! really lacks the code and bindings the scene does not need (WGSL `override` constants
//! would leave them in).

use std::collections::HashMap;

use glint_core::cpu::Traversal;
use glint_core::{Accel, FlatScene};
use glint_types::layout::{INTEGRATOR_PATH, feature};
use naga_oil::compose::{ComposableModuleDescriptor, Composer, NagaModuleDescriptor, ShaderDefValue};

use crate::error::GpuError;

/// Deepest ray tree the GPU stack holds when the shader is not specialised; deeper trees that
/// branch raise `STATUS_STACK_OVERFLOW`.
pub const GPU_STACK_LIMIT: u32 = 64;

/// Entries of the BVH traversal stack when the shader is not specialised (bvh.wgsl's
/// `BVH_STACK_SIZE`); a deeper tree that needs more raises `STATUS_BVH_STACK_OVERFLOW`.
pub const BVH_STACK_LIMIT: u32 = 64;

/// The BVH stack a scene's tree needs (`BvhNodes::depth` + 1 entries), in steps of 8 so that
/// trees of similar depth share a variant, at most `BVH_STACK_LIMIT`. Sized to the tree
/// rather than the limit because WGSL zero-fills a function's arrays on every call: on
/// lavapipe the 64-entry stacks cost a seventh of bumpy's GPU render.
pub fn bvh_stack_size(scene: &FlatScene) -> u32 {
    (scene.bvh_nodes.depth() + 1).next_multiple_of(8).min(BVH_STACK_LIMIT)
}

/// lavapipe's loop budget: once an invocation group has run this many loop iterations in all,
/// it ends every loop after its current iteration, silently (docs/numerics.md, "GPU loop
/// bounds"). The GPU tracer's own loop bounds derive from it.
pub const LAVAPIPE_LOOP_BUDGET: u32 = 65_535;

/// Most primitives of one kind the GPU walks per ray, checked on upload: one walk alone must
/// fit in lavapipe's budget.
pub const GPU_PRIMITIVE_LIMIT: u32 = LAVAPIPE_LOOP_BUDGET;

/// Entries of the BVH traversal stack (`BVH_STACK_SIZE` in `shaders/bvh.wgsl`); a traversal
/// that needs more raises `STATUS_BVH_STACK_OVERFLOW`.
pub const BVH_STACK_SIZE: u32 = 64;

/// Bound of the shader's ray-tree walk per sample (shader def `MAX_TREE_NODES`); reaching it
/// raises `STATUS_LOOP_LIMIT`. The budget rounded down to thousands.
pub const MAX_TREE_NODES: u32 = LAVAPIPE_LOOP_BUDGET / 1_000 * 1_000;

/// The modules in dependency order: (import path, file name, source).
pub const SHADER_MODULES: [(&str, &str, &str); 16] = [
    ("glint::scene_data", "layout.wgsl", include_str!("../../../shaders/layout.wgsl")),
    ("glint::bindings", "bindings.wgsl", include_str!("../../../shaders/bindings.wgsl")),
    ("glint::ray", "ray.wgsl", include_str!("../../../shaders/ray.wgsl")),
    ("glint::rng", "rng.wgsl", include_str!("../../../shaders/rng.wgsl")),
    ("glint::camera", "camera.wgsl", include_str!("../../../shaders/camera.wgsl")),
    ("glint::primitive", "primitive.wgsl", include_str!("../../../shaders/primitive.wgsl")),
    ("glint::intersect", "intersect.wgsl", include_str!("../../../shaders/intersect.wgsl")),
    ("glint::bvh", "bvh.wgsl", include_str!("../../../shaders/bvh.wgsl")),
    ("glint::offset", "offset.wgsl", include_str!("../../../shaders/offset.wgsl")),
    ("glint::texture", "texture.wgsl", include_str!("../../../shaders/texture.wgsl")),
    ("glint::shade", "shade.wgsl", include_str!("../../../shaders/shade.wgsl")),
    ("glint::surface", "surface.wgsl", include_str!("../../../shaders/surface.wgsl")),
    ("glint::probe", "probe.wgsl", include_str!("../../../shaders/probe.wgsl")),
    // The path tracer's warps and BRDFs (path.wgsl imports them).
    ("glint::sample", "sample.wgsl", include_str!("../../../shaders/sample.wgsl")),
    ("glint::bsdf", "bsdf.wgsl", include_str!("../../../shaders/bsdf.wgsl")),
    ("glint::emitter", "emitter.wgsl", include_str!("../../../shaders/emitter.wgsl")),
];

/// The path tracer's entry module (its `start` and bounce `main` kernels).
pub const PATH_WGSL: &str = include_str!("../../../shaders/path.wgsl");

/// The entry module.
pub const TRACE_WGSL: &str = include_str!("../../../shaders/trace.wgsl");

/// The ray-cast kernel's entry module (`glint bench rays`): bvh.wgsl's closest hit for a
/// buffer of rays. An entry module as trace.wgsl, so not in `SHADER_MODULES`, which lists the
/// modules entries import.
pub const RAYCAST_WGSL: &str = include_str!("../../../shaders/raycast.wgsl");

/// Everything that selects a shader variant: the feature bits compiled in, and the stack size.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct ShaderKey {
    pub features: u32,
    pub stack_size: u32,
    /// The pixel-probe variant: renders one sample and records its breakdown.
    pub probe: bool,
    /// Find hits through the BVH (shader def `BVH`) instead of testing every primitive.
    pub bvh: bool,
    /// Entries of the BVH traversal stack (shader def `BVH_STACK_SIZE`).
    pub bvh_stack: u32,
    /// The path tracer (path.wgsl) instead of Whitted's (trace.wgsl), as the scene's header says.
    pub path: bool,
    /// Bound of the ray-tree walk per sample (shader def `MAX_TREE_NODES`): `MAX_TREE_NODES`,
    /// below lavapipe's loop budget, but for tests that reach it there (`GpuOptions::tree_nodes`).
    pub tree_nodes: u32,
}

impl ShaderKey {
    /// The variant for `scene`: exactly its features, or all of them when not specialising.
    pub fn for_scene(scene: &FlatScene, specialise: bool) -> Self {
        let path = scene.header.integrator == INTEGRATOR_PATH;
        if specialise {
            let features = scene.header.features;
            // Paths keep no stack: each bounce is a dispatch.
            let depth =
                if feature::recurses(features) && !path { scene.header.max_depth.min(GPU_STACK_LIMIT - 1) } else { 0 };
            Self {
                features,
                stack_size: depth + 1,
                probe: false,
                bvh: true,
                bvh_stack: bvh_stack_size(scene),
                path,
                tree_nodes: MAX_TREE_NODES,
            }
        } else {
            Self { path, ..Self::full() }
        }
    }

    /// The unspecialised shader: every feature, the largest stack.
    pub fn full() -> Self {
        Self {
            features: feature::ALL,
            stack_size: GPU_STACK_LIMIT,
            probe: false,
            bvh: true,
            bvh_stack: BVH_STACK_LIMIT,
            path: false,
            tree_nodes: MAX_TREE_NODES,
        }
    }

    /// The same variant with brute force or the BVH, as `accel` decides for this scene (the
    /// CPU's rule, `Accel::traversal`); a scene without bounded primitives has no BVH to walk
    /// and keeps brute force's (plane) loops.
    pub fn with_accel(self, scene: &FlatScene, accel: Accel) -> Self {
        let bvh = accel.traversal(scene) == Traversal::Bvh && !scene.bvh_nodes.is_empty();
        Self { bvh, ..self }
    }

    /// The storage buffers the variant binds (a test checks this against the composed module):
    /// materials, lights, output and stats always, one per sphere or plane kind compiled in,
    /// four for triangles (triangles, vertices, normals, meshes), the probe record and tree, the
    /// BVH's nodes and leaf words (with triangles, a second array of them for the third corner),
    /// and for textures the texels and the table, with texture coordinates when
    /// there are triangles; vertex colours with triangles; the path tracer's paths, and its
    /// emitters where a material emits.
    pub fn storage_buffers(&self) -> u32 {
        let on = |f: u32| u32::from(self.features & f != 0);
        4 + u32::from(self.path) * (1 + on(feature::EMISSION))
            + on(feature::SPHERES)
            + on(feature::PLANES)
            + 4 * on(feature::TRIANGLES)
            + 2 * u32::from(self.probe)
            + if self.bvh { 2 + on(feature::TRIANGLES) } else { 0 }
            + 2 * on(feature::TEXTURES)
            + on(feature::TEXTURES) * on(feature::TRIANGLES)
            + on(feature::VERTEX_COLOURS) * on(feature::TRIANGLES)
    }

    /// The variant, if this device binds as many storage buffers per stage as it needs (wgpu's
    /// default limit is 8; `context.rs` and the viewer ask for the adapter's own), else an
    /// error naming the limit.
    pub fn check_storage_limit(self, max_storage_buffers: u32) -> Result<Self, GpuError> {
        let needed = self.storage_buffers();
        if needed > max_storage_buffers {
            return Err(GpuError::TooManyStorageBuffers {
                variant: self.describe(),
                needed,
                limit: max_storage_buffers,
            });
        }
        Ok(self)
    }

    /// naga_oil shader defs: one boolean per feature present, `RECURSION` when the variant
    /// walks a ray tree, `STACK_SIZE`, `MAX_TREE_NODES`, `PROBE`, `BVH`.
    pub fn shader_defs(&self) -> HashMap<String, ShaderDefValue> {
        let mut defs: HashMap<String, ShaderDefValue> = feature::NAMES
            .iter()
            .enumerate()
            .filter(|(bit, _)| self.features & (1 << bit) != 0)
            .map(|(_, name)| ((*name).to_string(), ShaderDefValue::Bool(true)))
            .collect();
        if feature::recurses(self.features) {
            defs.insert("RECURSION".into(), ShaderDefValue::Bool(true));
        }
        defs.insert("STACK_SIZE".into(), ShaderDefValue::UInt(self.stack_size));
        defs.insert("MAX_TREE_NODES".into(), ShaderDefValue::UInt(self.tree_nodes.max(1)));
        defs.insert("BVH_STACK_SIZE".into(), ShaderDefValue::UInt(self.bvh_stack.max(1)));
        if self.probe {
            defs.insert("PROBE".into(), ShaderDefValue::Bool(true));
        }
        if self.bvh {
            defs.insert("BVH".into(), ShaderDefValue::Bool(true));
        }
        defs
    }

    /// Short readable form for logs and reports, e.g. `SPHERES|PLANES|… stack 6`.
    pub fn describe(&self) -> String {
        let names: Vec<&str> = feature::NAMES
            .iter()
            .enumerate()
            .filter(|(bit, _)| self.features & (1 << bit) != 0)
            .map(|(_, n)| *n)
            .collect();
        format!(
            "{}{} stack {}{}{}{}",
            if self.path { "path: " } else { "" },
            names.join("|"),
            self.stack_size,
            if self.bvh { format!(" bvh {}", self.bvh_stack) } else { String::new() },
            if self.probe { " probe" } else { "" },
            if self.tree_nodes == MAX_TREE_NODES { String::new() } else { format!(" tree nodes {}", self.tree_nodes) }
        )
    }
}

/// Composes the tracer for `key` (Whitted's or the path tracer); errors carry naga's readable
/// report.
pub fn compose(key: &ShaderKey) -> Result<naga::Module, GpuError> {
    compose_entry(key, if key.path { PATH_WGSL } else { TRACE_WGSL })
}

/// Composes `entry` (the source of an entry module, as `trace.wgsl`) with the modules of
/// `shaders/` for `key`.
pub fn compose_entry(key: &ShaderKey, entry: &str) -> Result<naga::Module, GpuError> {
    let mut composer = Composer::default();
    for (path, file, source) in SHADER_MODULES {
        let added = composer.add_composable_module(ComposableModuleDescriptor {
            source,
            file_path: file,
            as_name: Some(path.to_string()),
            ..Default::default()
        });
        if let Err(e) = added {
            return Err(GpuError::Compose(e.emit_to_string(&composer)));
        }
    }
    let module = composer.make_naga_module(NagaModuleDescriptor {
        source: entry,
        file_path: if entry == PATH_WGSL { "path.wgsl" } else { "trace.wgsl" },
        shader_defs: key.shader_defs(),
        ..Default::default()
    });
    module.map_err(|e| GpuError::Compose(e.emit_to_string(&composer)))
}

/// A name in a composed module without naga_oil's module decoration.
pub fn undecorated(name: &str) -> &str {
    name.split("X_naga_oil_mod_").next().unwrap_or(name)
}

/// Validates a composed module again with naga's validator (all checks), as a build step would.
pub fn validate(module: &naga::Module) -> Result<naga::valid::ModuleInfo, GpuError> {
    naga::valid::Validator::new(naga::valid::ValidationFlags::all(), naga::valid::Capabilities::default())
        .validate(module)
        .map_err(|e| GpuError::Validation(e.emit_to_string("")))
}

/// Size of a shader in naga IR: what specialisation removes.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct ModuleStats {
    pub functions: usize,
    pub statements: usize,
    pub expressions: usize,
    pub bindings: usize,
}

pub fn module_stats(module: &naga::Module) -> ModuleStats {
    fn count(block: &naga::Block) -> usize {
        use naga::Statement as S;
        block
            .iter()
            .map(|s| {
                1 + match s {
                    S::Block(b) => count(b),
                    S::If { accept, reject, .. } => count(accept) + count(reject),
                    S::Switch { cases, .. } => cases.iter().map(|c| count(&c.body)).sum(),
                    S::Loop { body, continuing, .. } => count(body) + count(continuing),
                    _ => 0,
                }
            })
            .sum()
    }
    let functions = module.functions.iter().map(|(_, f)| f).chain(module.entry_points.iter().map(|e| &e.function));
    let mut stats = ModuleStats {
        functions: module.functions.len() + module.entry_points.len(),
        bindings: module.global_variables.iter().filter(|(_, g)| g.binding.is_some()).count(),
        ..Default::default()
    };
    for f in functions {
        stats.statements += count(&f.body);
        stats.expressions += f.expressions.len();
    }
    stats
}
