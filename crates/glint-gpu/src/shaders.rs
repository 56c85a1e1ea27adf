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
pub const SHADER_MODULES: [(&str, &str, &str); 15] = [
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
            Self { features, stack_size: depth + 1, probe: false, bvh: true, bvh_stack: bvh_stack_size(scene), path }
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
        defs.insert("MAX_TREE_NODES".into(), ShaderDefValue::UInt(MAX_TREE_NODES));
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
            "{}{} stack {}{}{}",
            if self.path { "path: " } else { "" },
            names.join("|"),
            self.stack_size,
            if self.bvh { format!(" bvh {}", self.bvh_stack) } else { String::new() },
            if self.probe { " probe" } else { "" }
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::binding::Binding;
    use glint_io::{BUILTIN_SCENES, parse_scene};

    /// Every built-in scene's variant under each integrator.
    fn builtin_keys() -> Vec<(String, ShaderKey)> {
        BUILTIN_SCENES
            .iter()
            .flat_map(|b| {
                // Generated scenes at a small resolution: the features, not the size, pick the variant.
                let (desc, _) = b.load(b.is_generated().then_some(4)).expect("built-in scene loads");
                glint_scene::Integrator::ALL.map(|integrator| {
                    let settings = glint_scene::RenderSettings { integrator, ..desc.render.clone() };
                    let flat = FlatScene::build(&desc, &settings);
                    (format!("{} ({})", b.name, integrator.name()), ShaderKey::for_scene(&flat, true))
                })
            })
            .collect()
    }

    fn compose_or_report(key: &ShaderKey) -> naga::Module {
        match compose(key).and_then(|m| validate(&m).map(|_| m)) {
            Ok(m) => m,
            Err(e) => panic!("shader variant [{}] is invalid:\n{e}", key.describe()),
        }
    }

    #[test]
    fn full_shader_and_every_builtin_variant_validate() {
        compose_or_report(&ShaderKey::full());
        compose_or_report(&ShaderKey { path: true, ..ShaderKey::full() });
        for (name, key) in builtin_keys() {
            eprintln!("{name}: {}", key.describe());
            compose_or_report(&key);
        }
    }

    #[test]
    fn probe_variants_validate() {
        compose_or_report(&ShaderKey { probe: true, ..ShaderKey::full() });
        for (_, key) in builtin_keys() {
            compose_or_report(&ShaderKey { probe: true, path: false, ..key });
        }
    }

    #[test]
    fn every_single_feature_and_its_absence_validate() {
        // Each feature alone, and all features but one: catches an #ifdef block that only
        // compiles next to some other feature.
        for bit in 0..feature::NAMES.len() {
            for features in [1u32 << bit, feature::ALL & !(1 << bit)] {
                for (bvh, path) in [(false, false), (true, false), (false, true), (true, true)] {
                    compose_or_report(&ShaderKey { features, stack_size: 4, probe: false, bvh, bvh_stack: 16, path });
                }
            }
        }
    }

    #[test]
    fn storage_buffer_count_matches_the_composed_module() {
        let mut keys = vec![ShaderKey::full(), ShaderKey { bvh: false, ..ShaderKey::full() }];
        keys.push(ShaderKey { path: true, ..ShaderKey::full() });
        keys.extend(builtin_keys().into_iter().map(|(_, k)| k));
        for key in keys {
            // The probe records Whitted's tree only (GpuTracer::probe).
            for probe in if key.path { &[false][..] } else { &[false, true][..] } {
                let probe = *probe;
                let key = ShaderKey { probe, ..key };
                let module = compose_or_report(&key);
                let storage = module
                    .global_variables
                    .iter()
                    .filter(|(_, g)| g.binding.is_some() && matches!(g.space, naga::AddressSpace::Storage { .. }))
                    .count();
                assert_eq!(key.storage_buffers() as usize, storage, "[{}]", key.describe());
                let error = key.check_storage_limit(storage as u32 - 1).expect_err("one buffer too many");
                assert!(error.to_string().contains("max_storage_buffers_per_shader_stage"), "{error}");
                assert_eq!(key.check_storage_limit(storage as u32).ok(), Some(key));
            }
        }
    }

    /// sample.wgsl and bsdf.wgsl, with every function called once from an entry point, compose
    /// and validate: path.wgsl calls only the warps and lobes a scene's features compile in, so
    /// this is where the others are validated.
    #[test]
    fn the_path_tracers_modules_validate_with_every_function_called() {
        let entry = "\
#import glint::sample::{frame_x, frame_y, to_world, spherical_direction, concentric_disk, cosine_hemisphere, cosine_hemisphere_pdf, power_cosine, power_cosine_pdf, beckmann_normal, beckmann_normal_pdf, reflect_about, reflected_pdf, cone_versin, uniform_cone, uniform_cone_pdf, uniform_sphere, uniform_sphere_pdf, uniform_triangle, area_to_solid_angle, power_heuristic}
#import glint::bsdf::{lambert_brdf, blinn_normalisation, blinn_brdf, phong_brdf, cook_torrance_brdf, sample_blinn, blinn_pdf, sample_phong, phong_pdf, sample_cook_torrance, cook_torrance_pdf}
@group(3) @binding(0) var<storage, read_write> io: array<f32, 8>;
@compute @workgroup_size(1)
fn main() {
    let u = vec2<f32>(io[0], io[1]);
    let n = normalize(vec3<f32>(io[2], io[3], 1.0));
    let v = vec3<f32>(0.0, 0.0, 1.0);
    var s = frame_x(n).x + frame_y(n).y + to_world(n, v).z + spherical_direction(0.5, 0.5, io[4]).x;
    s += concentric_disk(u).x + cosine_hemisphere(u).z + cosine_hemisphere_pdf(n.z);
    s += power_cosine(u, 8.0).z + power_cosine_pdf(n.z, 8.0) + beckmann_normal(u, 0.3).z + beckmann_normal_pdf(n.z, 0.3);
    s += reflect_about(v, n).x + reflected_pdf(1.0, n.z) + uniform_cone(u, cone_versin(0.1)).z + uniform_cone_pdf(0.1);
    s += uniform_sphere(u).z + uniform_sphere_pdf() + uniform_triangle(u).x + area_to_solid_angle(1.0, 2.0, n.z) + power_heuristic(1.0, 2.0);
    s += lambert_brdf(v, n) + blinn_normalisation(2.0) + blinn_brdf(v, n, 8.0) + phong_brdf(v, n, 8.0) + cook_torrance_brdf(v, n, 0.3, 1.5, 0u);
    s += sample_blinn(v, u, 8.0).z + blinn_pdf(v, n, 8.0) + sample_phong(v, u, 8.0).z + phong_pdf(v, n, 8.0);
    s += sample_cook_torrance(v, u, 0.3).z + cook_torrance_pdf(v, n, 0.3);
    io[5] = s;
}
";
        let module = compose_entry(&ShaderKey::full(), entry).unwrap_or_else(|e| panic!("{e}"));
        validate(&module).unwrap_or_else(|e| panic!("{e}"));
        let names = function_names(&module);
        for f in ["power_heuristic", "uniform_triangle", "cook_torrance_brdf", "sample_phong", "half_vector"] {
            assert!(names.iter().any(|n| n == f), "{f} is not in the composed module: {names:?}");
        }
    }

    #[test]
    fn every_ifdef_names_a_def_the_host_sets() {
        // A misspelt #ifdef would compile its code out of every variant, silently.
        let defs = ShaderKey { probe: true, ..ShaderKey::full() }.shader_defs();
        let sources = SHADER_MODULES
            .iter()
            .map(|(_, file, source)| (*file, *source))
            .chain([("trace.wgsl", TRACE_WGSL), ("raycast.wgsl", RAYCAST_WGSL)]);
        let mut checked = 0;
        for (file, source) in sources {
            for line in source.lines() {
                let t = line.trim_start();
                if let Some(name) = t.strip_prefix("#ifdef ").or_else(|| t.strip_prefix("#ifndef ")) {
                    assert!(defs.contains_key(name.trim()), "{file}: `{t}` names no shader def of ShaderKey");
                    checked += 1;
                }
            }
        }
        assert!(checked > feature::NAMES.len(), "only {checked} #ifdef lines found");
    }

    /// Function names of a composed module without naga_oil's module decoration.
    fn function_names(module: &naga::Module) -> Vec<String> {
        module.functions.iter().filter_map(|(_, f)| f.name.as_deref()).map(|n| undecorated(n).to_string()).collect()
    }

    #[test]
    fn specialised_module_lacks_what_the_scene_does_not_use() {
        let text = "[render]\nwidth = 8\nheight = 8\nmax_depth = 5\n\
            [camera]\nposition = [0.0, 0.0, -5.0]\nlook_at = [0.0, 0.0, 0.0]\n\
            [materials.m]\nkd = 0.8\n\
            [[lights]]\ntype = \"directional\"\ndirection = [0.0, -1.0, 1.0]\n\
            [[objects]]\ntype = \"sphere\"\ncenter = [0.0, 0.0, 0.0]\nradius = 1.0\nmaterial = \"m\"\n";
        let (desc, _) = parse_scene(text, std::path::Path::new("opaque.toml")).expect("scene parses");
        let flat = FlatScene::build(&desc, &desc.render);
        let key = ShaderKey::for_scene(&flat, true);
        assert_eq!(key.stack_size, 1, "nothing reflects: no ray tree to walk");
        let module = compose_or_report(&key);
        let names = function_names(&module);
        for absent in [
            "intersect_triangle",
            "ray_shear",
            "triangle_shading_normal",
            "intersect_plane",
            "spot_factor",
            "smooth_spot_factor",
            "attenuation_factor",
            "inverse_square_factor",
            "refract_dir",
            "reflect_dir",
            "push_ray",
            "strata_rows",
            "sample_texture",
            "planar_uv",
            "triangle_uv",
            "wrap_texel",
        ] {
            assert!(!names.iter().any(|n| n == absent), "specialised module still has {absent}: {names:?}");
        }
        for present in ["intersect_sphere", "shade_local", "light_sample", "trace_ray"] {
            assert!(names.iter().any(|n| n == present), "specialised module lacks {present}: {names:?}");
        }
        let bindings: Vec<u32> =
            module.global_variables.iter().filter_map(|(_, g)| g.binding.as_ref().map(|b| b.binding)).collect();
        let untextured = [Binding::Uvs, Binding::Texels, Binding::Textures].map(Binding::number);
        for absent in [Binding::Planes.number(), Binding::Triangles.number()].into_iter().chain(untextured) {
            assert!(!bindings.contains(&absent), "binding {absent} should be gone: {bindings:?}");
        }
        let full = compose_or_report(&ShaderKey::full());
        let full_names = function_names(&full);
        for f in [
            "intersect_triangle",
            "spot_factor",
            "smooth_spot_factor",
            "inverse_square_factor",
            "refract_dir",
            "push_ray",
            "sample_texture",
            "triangle_uv",
        ] {
            assert!(full_names.iter().any(|n| n == f), "the full shader should have {f}");
        }
        let full_bindings: Vec<u32> =
            full.global_variables.iter().filter_map(|(_, g)| g.binding.as_ref().map(|b| b.binding)).collect();
        assert!(untextured.iter().all(|b| full_bindings.contains(b)), "the full shader binds the textures");
        // Textures on spheres and planes only: texels and table, no texture coordinates.
        let planar = ShaderKey {
            features: feature::TEXTURES | feature::SPHERES,
            stack_size: 1,
            probe: false,
            bvh: false,
            bvh_stack: 8,
            path: false,
        };
        let planar = compose_or_report(&planar);
        let planar_bindings: Vec<u32> =
            planar.global_variables.iter().filter_map(|(_, g)| g.binding.as_ref().map(|b| b.binding)).collect();
        assert!(
            planar_bindings.contains(&Binding::Texels.number()) && !planar_bindings.contains(&Binding::Uvs.number())
        );
        assert!(full_names.iter().any(|n| n == "slab_ray"), "the full shader walks the BVH");
        let brute = compose_or_report(&ShaderKey { bvh: false, ..ShaderKey::full() });
        let brute_names = function_names(&brute);
        assert!(!brute_names.iter().any(|n| n == "slab_ray"), "brute force has no BVH walk: {brute_names:?}");
        let brute_bindings: Vec<u32> =
            brute.global_variables.iter().filter_map(|(_, g)| g.binding.as_ref().map(|b| b.binding)).collect();
        assert!(!brute_bindings.contains(&Binding::BvhNodes.number()), "brute force binds no BVH");
        let (small, big) = (module_stats(&module), module_stats(&full));
        eprintln!("opaque sphere scene: {} statements, full shader: {}", small.statements, big.statements);
        assert!(small.statements * 10 < big.statements * 7, "specialisation removed less than 30 %");
    }

    /// A sphere under one point and one spot light with the given extra fields.
    fn lit_sphere_key(point: &str, spot: &str) -> ShaderKey {
        let text = format!(
            "[camera]\nposition = [0.0, 0.0, -5.0]\nlook_at = [0.0, 0.0, 0.0]\n\
             [materials.m]\nkd = 0.8\n\
             [[lights]]\ntype = \"point\"\nposition = [0.0, 3.0, -3.0]\n{point}\n\
             [[lights]]\ntype = \"spot\"\nposition = [0.0, 3.0, 0.0]\ndirection = [0.0, -1.0, 0.0]\n{spot}\n\
             [[objects]]\ntype = \"sphere\"\ncenter = [0.0, 0.0, 0.0]\nradius = 1.0\nmaterial = \"m\"\n"
        );
        let (desc, _) = parse_scene(&text, std::path::Path::new("lights.toml")).expect("scene parses");
        ShaderKey::for_scene(&FlatScene::build(&desc, &desc.render), true)
    }

    #[test]
    fn gltf_light_models_are_compiled_only_for_scenes_that_use_them() {
        let opengl = lit_sphere_key("attenuation = { c = 1.0, q = 0.5 }", "exponent = 4.0\ncutoff = 30.0");
        assert_eq!(opengl.features & (feature::INVERSE_SQUARE | feature::SMOOTH_SPOT), 0, "[{}]", opengl.describe());
        let names = function_names(&compose_or_report(&opengl));
        for present in ["attenuation_factor", "spot_factor"] {
            assert!(names.iter().any(|n| n == present), "OpenGL lights need {present}: {names:?}");
        }
        for absent in ["inverse_square_factor", "smooth_spot_factor"] {
            assert!(!names.iter().any(|n| n == absent), "no glTF light, yet the module has {absent}: {names:?}");
        }

        let gltf = lit_sphere_key(
            "attenuation = { model = \"inverse_square\", range = 20.0 }",
            "falloff = \"smooth\"\ninner_cone = 10.0\nouter_cone = 30.0",
        );
        let both = feature::INVERSE_SQUARE | feature::SMOOTH_SPOT;
        assert_eq!(gltf.features & both, both, "[{}]", gltf.describe());
        assert_eq!(gltf.features & feature::ATTENUATION, 0, "no polynomial attenuation: [{}]", gltf.describe());
        let names = function_names(&compose_or_report(&gltf));
        for present in ["inverse_square_factor", "smooth_spot_factor"] {
            assert!(names.iter().any(|n| n == present), "glTF lights need {present}: {names:?}");
        }
        assert!(!names.iter().any(|n| n == "attenuation_factor"), "no polynomial attenuation to compute: {names:?}");
    }
}
