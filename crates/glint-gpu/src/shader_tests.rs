//! The shader variants: every built-in scene's key composes, validates and binds what its
//! features need (tests of `shaders.rs`, kept apart for its length).

use glint_core::FlatScene;
use glint_io::{BUILTIN_SCENES, parse_scene};
use glint_types::layout::feature;

use crate::binding::Binding;
use crate::shaders::*;

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
                compose_or_report(&ShaderKey {
                    features,
                    stack_size: 4,
                    bvh,
                    bvh_stack: 16,
                    path,
                    ..ShaderKey::full()
                });
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
        ..ShaderKey::full()
    };
    let planar = compose_or_report(&planar);
    let planar_bindings: Vec<u32> =
        planar.global_variables.iter().filter_map(|(_, g)| g.binding.as_ref().map(|b| b.binding)).collect();
    assert!(planar_bindings.contains(&Binding::Texels.number()) && !planar_bindings.contains(&Binding::Uvs.number()));
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
