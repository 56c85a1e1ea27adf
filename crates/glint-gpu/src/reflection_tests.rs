//! What the GPU tracer shares with glint-core beyond the vocabulary (glint-types checks the
//! layout, the BVH's records included, against `shaders/layout.wgsl`): the binding table and
//! the constants the two tracers' functions share. No "keep in sync" comments.

use glint_core::cpu::{FAR, intersect, offset, path, primitive, sample, shade};
use glint_types::layout::NO_HIT;
use naga_oil::compose::Composer;

use crate::binding::Binding;
use crate::layout_check::literal_value;
use crate::shaders::ShaderKey;

const LAYOUT_WGSL: &str = include_str!("../../../shaders/layout.wgsl");

/// `sources` joined as one plain WGSL module: without naga_oil's directives (import path and
/// imports), which only name what the files give each other.
fn plain_module(sources: &[&str]) -> naga::Module {
    let source: String = sources
        .iter()
        .flat_map(|s| s.lines())
        .filter(|l| !l.trim_start().starts_with('#'))
        .collect::<Vec<_>>()
        .join("\n");
    naga::front::wgsl::parse_str(&source).unwrap_or_else(|e| panic!("{}", e.emit_to_string(&source)))
}

pub(crate) fn layout_module() -> naga::Module {
    plain_module(&[LAYOUT_WGSL])
}

#[test]
fn binding_table_matches_bindings_wgsl_both_ways() {
    let module = plain_module(&[LAYOUT_WGSL, include_str!("../../../shaders/bindings.wgsl")]);
    let mut wgsl = Vec::new();
    for (_, var) in module.global_variables.iter() {
        let Some(rb) = &var.binding else { continue };
        let name = var.name.as_deref().expect("bindings are named");
        let found = Binding::of_global(rb.group, rb.binding, name).unwrap_or_else(|e| panic!("bindings.wgsl: {e}"));
        wgsl.push(found);
    }
    for b in Binding::ALL {
        assert!(wgsl.contains(&b), "{b:?} (@binding({}) {}) is not in bindings.wgsl", b.number(), b.wgsl_name());
    }
    assert_eq!(wgsl.len(), Binding::ALL.len(), "bindings.wgsl declares a binding twice: {wgsl:?}");
}

#[test]
fn shared_tracer_constants_match_rust() {
    // Constants the two tracers must share exactly. (offset.rs's FLOAT_SCALE and SHADOW_REL
    // differ on purpose: each is scaled to its tracer's precision.) A probe module imports
    // each one and stores it, so naga cannot fold it away before we read it.
    let expected: [(&str, &str, f64); 16] = [
        ("glint::intersect", "PRIM_NONE", f64::from(intersect::PRIM_NONE)),
        ("glint::intersect", "PRIM_SPHERE", f64::from(intersect::PRIM_SPHERE)),
        ("glint::intersect", "PRIM_PLANE", f64::from(intersect::PRIM_PLANE)),
        ("glint::intersect", "PRIM_TRIANGLE", f64::from(intersect::PRIM_TRIANGLE)),
        ("glint::primitive", "PLANE_PARALLEL_COS", primitive::PLANE_PARALLEL_COS),
        ("glint::primitive", "FORM_MARGIN", primitive::FORM_MARGIN),
        ("glint::ray", "FAR", FAR),
        ("glint::shade", "MIN_LIGHT_DISTANCE", shade::MIN_LIGHT_DISTANCE),
        ("glint::shade", "MIN_HALF_LENGTH", shade::MIN_HALF_LENGTH),
        ("glint::shade", "MIN_ATTENUATION_DENOMINATOR", shade::MIN_ATTENUATION_DENOMINATOR),
        ("glint::shade", "MIN_GRAZING_COS", shade::MIN_GRAZING_COS),
        ("glint::sample", "MAX_SQUARED_PDF", sample::MAX_SQUARED_PDF),
        ("glint::offset", "ORIGIN", offset::ORIGIN),
        ("glint::offset", "INT_SCALE", offset::INT_SCALE),
        ("glint::scene_data", "NO_HIT", f64::from(NO_HIT)),
        ("glint::bvh", "BVH_STACK_SIZE", f64::from(crate::shaders::BVH_STACK_SIZE)),
    ];
    let mut probe = String::new();
    for (path, name, _) in &expected {
        probe.push_str(&format!("#import {path}::{{{name}}}\n"));
    }
    probe.push_str("@group(0) @binding(0) var<storage, read_write> probe_out: array<f32, 16>;\n");
    probe.push_str("@compute @workgroup_size(1)\nfn main() {\n");
    for (i, (_, name, _)) in expected.iter().enumerate() {
        probe.push_str(&format!("    probe_out[{i}] = f32({name});\n"));
    }
    probe.push_str("}\n");
    let module = compose_probe(&probe);
    for (path, name, value) in expected {
        let decorated = Composer::decorated_name(Some(path), name);
        let c = module
            .constants
            .iter()
            .find(|(_, c)| c.name.as_deref() == Some(decorated.as_str()))
            .unwrap_or_else(|| panic!("{path}::{name} not found in the probe module"))
            .1;
        let wgsl = literal_value(&module, c.init);
        // u32 constants must be equal; f32 ones equal to the Rust value rounded to f32.
        assert!(wgsl == value || wgsl == f64::from(value as f32), "{path}::{name}: WGSL {wgsl} != Rust {value}");
    }
}

#[test]
fn the_path_tracers_constants_match_rust() {
    // path.wgsl is an entry point, which no probe can import: its constants are read from the
    // composed path tracer itself (a review found them unchecked).
    let key = ShaderKey { path: true, ..ShaderKey::full() };
    let module = crate::shaders::compose(&key).unwrap_or_else(|e| panic!("{e}"));
    for (name, value) in [
        ("DIMS_PER_BOUNCE", f64::from(path::DIMS_PER_BOUNCE)),
        ("FIRST_PATH_DIM", f64::from(path::FIRST_PATH_DIM)),
        ("ROULETTE_FROM", f64::from(path::ROULETTE_FROM)),
        ("MAX_SURVIVAL", path::MAX_SURVIVAL),
    ] {
        let c = module
            .constants
            .iter()
            .find(|(_, c)| c.name.as_deref().map(crate::shaders::undecorated) == Some(name))
            .unwrap_or_else(|| panic!("path.wgsl's {name} not found in the composed module"))
            .1;
        let wgsl = literal_value(&module, c.init);
        assert!(wgsl == value || wgsl == f64::from(value as f32), "{name}: WGSL {wgsl} != Rust {value}");
    }
}

fn compose_probe(source: &str) -> naga::Module {
    use naga_oil::compose::{ComposableModuleDescriptor, NagaModuleDescriptor};
    let mut composer = Composer::default();
    for (path, file, text) in crate::shaders::SHADER_MODULES {
        let added = composer.add_composable_module(ComposableModuleDescriptor {
            source: text,
            file_path: file,
            as_name: Some(path.to_string()),
            shader_defs: ShaderKey::full().shader_defs(),
            ..Default::default()
        });
        if let Err(e) = added {
            panic!("{}", e.emit_to_string(&composer));
        }
    }
    let module = composer.make_naga_module(NagaModuleDescriptor {
        source,
        file_path: "probe.wgsl",
        shader_defs: ShaderKey::full().shader_defs(),
        ..Default::default()
    });
    module.unwrap_or_else(|e| panic!("{}", e.emit_to_string(&composer)))
}
