//! Each WGSL file has a CPU twin module with the same function and struct names (vello's
//! layout), and a struct both sides have has the same fields in the same order. These tests
//! read both sides and fail when one gains a function or struct the other lacks (unless it is
//! listed below with the reason it exists on one side only), when a struct's fields drift
//! apart, or when a struct lives in another CPU module than its WGSL twin's.

use std::collections::{BTreeMap, BTreeSet};

const TWINS: [(&str, &str, &str, &str); 18] = [
    (
        "bsdf.wgsl",
        include_str!("../../../shaders/bsdf.wgsl"),
        "cpu/bsdf.rs",
        include_str!("../../glint-core/src/cpu/bsdf.rs"),
    ),
    (
        "emitter.wgsl",
        include_str!("../../../shaders/emitter.wgsl"),
        "cpu/emitter.rs",
        include_str!("../../glint-core/src/cpu/emitter.rs"),
    ),
    (
        "sample.wgsl",
        include_str!("../../../shaders/sample.wgsl"),
        "cpu/sample.rs",
        include_str!("../../glint-core/src/cpu/sample.rs"),
    ),
    (
        "rng.wgsl",
        include_str!("../../../shaders/rng.wgsl"),
        "cpu/rng.rs",
        include_str!("../../glint-core/src/cpu/rng.rs"),
    ),
    (
        "camera.wgsl",
        include_str!("../../../shaders/camera.wgsl"),
        "cpu/camera.rs",
        include_str!("../../glint-core/src/cpu/camera.rs"),
    ),
    (
        "primitive.wgsl",
        include_str!("../../../shaders/primitive.wgsl"),
        "cpu/primitive.rs",
        include_str!("../../glint-core/src/cpu/primitive.rs"),
    ),
    (
        "intersect.wgsl",
        include_str!("../../../shaders/intersect.wgsl"),
        "cpu/intersect.rs",
        include_str!("../../glint-core/src/cpu/intersect.rs"),
    ),
    (
        "bvh.wgsl",
        include_str!("../../../shaders/bvh.wgsl"),
        "cpu/bvh/mod.rs",
        include_str!("../../glint-core/src/cpu/bvh/mod.rs"),
    ),
    (
        "offset.wgsl",
        include_str!("../../../shaders/offset.wgsl"),
        "cpu/offset.rs",
        include_str!("../../glint-core/src/cpu/offset.rs"),
    ),
    (
        "texture.wgsl",
        include_str!("../../../shaders/texture.wgsl"),
        "cpu/texture.rs",
        include_str!("../../glint-core/src/cpu/texture.rs"),
    ),
    (
        "shade.wgsl",
        include_str!("../../../shaders/shade.wgsl"),
        "cpu/shade.rs",
        include_str!("../../glint-core/src/cpu/shade.rs"),
    ),
    (
        "path.wgsl",
        include_str!("../../../shaders/path.wgsl"),
        "cpu/path.rs",
        include_str!("../../glint-core/src/cpu/path.rs"),
    ),
    (
        "surface.wgsl",
        include_str!("../../../shaders/surface.wgsl"),
        "cpu/surface.rs",
        include_str!("../../glint-core/src/cpu/surface.rs"),
    ),
    (
        "trace.wgsl",
        include_str!("../../../shaders/trace.wgsl"),
        "cpu/trace.rs",
        include_str!("../../glint-core/src/cpu/trace.rs"),
    ),
    (
        "probe.wgsl",
        include_str!("../../../shaders/probe.wgsl"),
        "cpu/ray_tree.rs",
        include_str!("../../glint-core/src/cpu/ray_tree.rs"),
    ),
    (
        "raycast.wgsl",
        include_str!("../../../shaders/raycast.wgsl"),
        "cpu/raycast.rs",
        include_str!("../../glint-core/src/cpu/raycast.rs"),
    ),
    (
        "ray.wgsl",
        include_str!("../../../shaders/ray.wgsl"),
        "cpu/mod.rs",
        include_str!("../../glint-core/src/cpu/mod.rs"),
    ),
    (
        "present.wgsl",
        include_str!("../../../shaders/present.wgsl"),
        "image.rs",
        include_str!("../../glint-core/src/image.rs"),
    ),
];

/// Functions only the GPU side has, and why.
const GPU_ONLY: [(&str, &str, &str); 45] = [
    ("bvh.wgsl", "load_node", "the root in two vec4 loads; the CPU reads the shared BvhNode where it lies"),
    (
        "bvh.wgsl",
        "load_pair",
        "a node's children in two vec4 loads; the CPU walks the wide nodes, not the GPU's quantized pairs",
    ),
    ("bvh.wgsl", "pair_boxes", "glint_core::bvh::pair_boxes, beside the builder of the GPU form, whose tests use it"),
    ("bvh.wgsl", "pair_refs", "glint_core::bvh::pair_refs, beside the builder of the GPU form, whose tests use it"),
    (
        "bvh.wgsl",
        "leaf_head",
        "a leaf reference and its triangle's first corner in one vec4 load; the CPU reads bvh_prims and leaf_triangle",
    ),
    (
        "bvh.wgsl",
        "node_ref",
        "the GPU walk carries a tested child's first index and count in a register, not its index to load again",
    ),
    ("bvh.wgsl", "ref_count", "reads node_ref's count"),
    ("bvh.wgsl", "ref_first", "reads node_ref's first child or primitive"),
    ("bvh.wgsl", "root_node", "the CPU tests the root in traverse before it runs the walk"),
    (
        "bvh.wgsl",
        "nearer_child",
        "the CPU sorts a wide node's entered children and pushes all but the nearest inside Walk::run; WGSL passes \
         its NodeStack by pointer",
    ),
    (
        "bvh.wgsl",
        "pop_node",
        "the CPU pops its Vec and skips a passed entry inside Walk::run; WGSL passes its NodeStack by pointer",
    ),
    (
        "bvh.wgsl",
        "next_leaf",
        "the interior steps of the walk in a loop of their own, so that a SIMD group's leaf tests run together; the CPU walks one ray at a time",
    ),
    ("bvh.wgsl", "slab_ray", "the CPU's SlabRay::new: WGSL has no methods"),
    (
        "bvh.wgsl",
        "box_pad",
        "the GPU pads each box by its own magnitude (its 1e-5 of the root's made far geometry cost the walk its culling); the CPU pads once per ray against the root (cpu/bvh/mod.rs box_scale)",
    ),
    ("trace.wgsl", "push_ray", "the explicit ray stack: WGSL has no recursion"),
    (
        "trace.wgsl",
        "weigh",
        "the weight carried down the stack walk times a k or a radiance, a zero staying zero; the CPU multiplies k·I(child) on return",
    ),
    ("ray.wgsl", "add_stat", "64-bit ray counters built from u32 atomics"),
    ("ray.wgsl", "flush_counts", "an invocation's counters into the statistics buffer; the CPU adds RayCounts"),
    ("trace.wgsl", "main", "the compute entry point; the CPU's loop is render::render_cpu"),
    (
        "trace.wgsl",
        "accumulate_sample",
        "one sample per dispatch, summed in the output buffer in the order of the CPU's render_pixel",
    ),
    ("probe.wgsl", "probe_alloc", "the probe's fixed-capacity tree buffer; the CPU's RayTree is a Vec"),
    ("probe.wgsl", "probe_clear", "resets a node of the probe's reused tree buffer; the CPU pushes fresh RayNodes"),
    (
        "probe.wgsl",
        "probe_cut",
        "the probe's cut children go down the stack walk; the CPU records them where shade_hit decides",
    ),
    // The hooks of trace.wgsl's walk: cpu/trace.rs calls the recorder inline instead.
    ("probe.wgsl", "probe_start", "empties the reused tree buffer; the CPU's probe_tree starts a RayTree::default()"),
    ("probe.wgsl", "probe_root", "the camera ray's link; the CPU's render_sample opens the camera node itself"),
    (
        "probe.wgsl",
        "probe_enter",
        "opens the node of each ray the stack walk takes up, a cut one too; the CPU opens a child where shade_hit \
         spawns or cuts it",
    ),
    (
        "probe.wgsl",
        "probe_attenuation",
        "f_att at a node's hit, known before its shading; the CPU's trace_ray passes it to close",
    ),
    (
        "probe.wgsl",
        "probe_shade_begin",
        "switches ray.wgsl's breakdown record on for shade_hit; the CPU passes shade_hit a Breakdown",
    ),
    (
        "probe.wgsl",
        "probe_shade_end",
        "closes the shaded node and keeps the first hit's breakdown; the CPU's trace_ray and render_sample call close",
    ),
    (
        "probe.wgsl",
        "probe_hit",
        "the hit's breakdown fields and its shadow rays; the CPU's shade_hit fills its Breakdown inline",
    ),
    ("probe.wgsl", "probe_factors", "k_r, k_t and total internal reflection into the breakdown; the CPU's shade_hit"),
    (
        "probe.wgsl",
        "probe_child",
        "the link of the child the walk follows next; the CPU's shade_hit builds the child's RayNode where it recurses",
    ),
    ("probe.wgsl", "probe_push", "the links beside the explicit ray stack: WGSL has no recursion"),
    ("probe.wgsl", "probe_pop", "the links beside the explicit ray stack: WGSL has no recursion"),
    (
        "probe.wgsl",
        "probe_gathered",
        "sums the walk's weighted terms by the camera hit's branch; the CPU's shade_hit takes I_r and I_t on return",
    ),
    ("probe.wgsl", "probe_finish", "writes the first hit's breakdown to probe_out; the CPU returns its Breakdown"),
    ("ray.wgsl", "driver_cut_loops", "detects lavapipe's silent loop cut-off, which the CPU does not have"),
    ("present.wgsl", "main", "the compute entry point; the CPU converts pixel by pixel where it writes a PNG"),
    ("raycast.wgsl", "main", "the compute entry point, one ray per invocation; the CPU's loop is cast_rays"),
    ("path.wgsl", "start", "the entry point that starts a tile's paths; the CPU's path_sample calls start_path"),
    ("path.wgsl", "main", "the entry point of one bounce over a tile's paths; the CPU's path_sample loops path_bounce"),
    ("path.wgsl", "load_path", "a path from the buffer between dispatches (GpuPathState); the CPU keeps it in a local"),
    (
        "path.wgsl",
        "store_path",
        "a path into the buffer between dispatches (GpuPathState); the CPU keeps it in a local",
    ),
    ("path.wgsl", "path_alive", "reads the stored path's flag; the CPU's path_sample loops while path_bounce says so"),
    ("path.wgsl", "finish_path", "an ended path into the output, sample by sample as the CPU's path_pixel sums them"),
];

/// Functions only the CPU side has, and why.
const CPU_ONLY: [(&str, &str, &str); 24] = [
    ("cpu/raycast.rs", "from_hit", "HitRecord from the CPU's Option<Hit>; cast_ray writes the vec4 in place"),
    ("cpu/raycast.rs", "is_hit", "a record read on the host (the benchmark's hit counts)"),
    ("cpu/bvh/mod.rs", "new", "SlabRay::new; WGSL builds it in slab_ray (no methods)"),
    (
        "cpu/bvh/mod.rs",
        "box_scale",
        "the root's magnitude for the CPU's once-per-ray padding (1e-9 of it costs nothing); the GPU pads per box (bvh.wgsl box_pad)",
    ),
    ("cpu/bvh/mod.rs", "prefetch", "a CPU cache hint for the nodes and leaves the walk takes next; WGSL has none"),
    (
        "cpu/bvh/mod.rs",
        "run",
        "traverse's loop over the wide nodes (bvh::WideNode) with its reused per-thread stack; the GPU walks \
         the binary nodes they are collapsed from, with its stack in a local array",
    ),
    (
        "cpu/bvh/mod.rs",
        "traverse",
        "the stack walk over a visitor closure: WGSL has no closures, so closest_hit and \
         shadow_transmittance each hold the same walk",
    ),
    (
        "cpu/shade.rs",
        "sum_of_terms",
        "adds up a Breakdown, the host-side probe record (the GPU probe record becomes one too)",
    ),
    ("cpu/mod.rs", "*", "Rust plumbing: widening (v3), counters, the trace context"),
    ("cpu/raycast.rs", "cast_rays", "the rayon loop over the buffer; the GPU's is the dispatch (main)"),
    ("cpu/trace.rs", "render_pixel", "the GPU sums a pixel's samples across dispatches (accumulate_sample)"),
    ("image.rs", "*", "the HDR image, its sRGB encoding and metadata: host output, no place on the GPU"),
    ("cpu/ray_tree.rs", "new", "RayNode::new; WGSL has no methods: probe.wgsl's open writes the node's fields"),
    ("cpu/ray_tree.rs", "name", "Cut's names in the host's reports"),
    ("cpu/ray_tree.rs", "hit", "RayNode::hit reads t on the host; the GPU flags NODE_HIT in close"),
    ("cpu/ray_tree.rs", "children", "a recorded tree read on the host (reports and tests)"),
    ("cpu/ray_tree.rs", "radiance_of", "a recorded tree read on the host: its radiance recomputed from the nodes"),
    ("cpu/ray_tree.rs", "count", "a recorded tree read on the host (reports and tests)"),
    (
        "cpu/ray_tree.rs",
        "translate",
        "a recorded tree moved on the host into world space (both probes, after reading back)",
    ),
    (
        "cpu/path.rs",
        "path_sample",
        "a path's bounces in a loop; the GPU dispatches its bounce kernel (main) per bounce",
    ),
    ("cpu/path.rs", "path_pixel", "the GPU sums a pixel's samples across dispatches (finish_path)"),
    ("cpu/emitter.rs", "of", "Emitters::of, the host's list; the GPU reads the emitter buffer it makes"),
    ("cpu/emitter.rs", "of_scene", "Emitters::of_scene, the host's list; the GPU reads the emitter buffer it makes"),
    ("cpu/emitter.rs", "gpu_words", "the emitter buffer the host uploads"),
];

/// Structs only the GPU side has, and why.
const GPU_ONLY_STRUCTS: [(&str, &str, &str); 9] = [
    ("bvh.wgsl", "NodeStack", "the CPU walk's Vec<Pending>: WGSL has no Vec, so a fixed array with its length"),
    ("primitive.wgsl", "MaybeT", "WGSL has no Option: a flag beside the value"),
    ("primitive.wgsl", "SphereRoots", "WGSL has no Option<(f64, f64)>: a flag beside the roots"),
    ("primitive.wgsl", "TriangleHit", "WGSL has no Option<(t, bu, bv)>: a flag beside the hit"),
    ("trace.wgsl", "SampleResult", "the CPU returns the pair (radiance, object)"),
    ("trace.wgsl", "StackEntry", "the explicit ray stack: WGSL has no recursion"),
    ("trace.wgsl", "Shaded", "a hit's radiance and the next ray of the stack walk, kept in registers"),
    ("probe.wgsl", "ProbeLink", "how a stacked ray joins the probe's tree; the CPU passes it down the recursion"),
    ("emitter.wgsl", "SphereCone", "WGSL has no Option<(axis, versine)>: a flag beside the cone"),
];

/// Structs only the CPU side has, and why.
const CPU_ONLY_STRUCTS: [(&str, &str, &str); 11] = [
    ("cpu/raycast.rs", "RayRecord", "a ray of the buffer as the host writes it; WGSL reads two vec4<f32>"),
    ("cpu/raycast.rs", "HitRecord", "a hit of the buffer as the host reads it; WGSL writes one vec4<u32>"),
    (
        "cpu/bvh/mod.rs",
        "Pending",
        "an entry of the CPU walk's stack, a wide node or a leaf with its entry distance; NodeStack's on the GPU",
    ),
    ("cpu/bvh/mod.rs", "Walk", "what the CPU's loop over the wide nodes reads; WGSL reads bindings"),
    (
        "cpu/bvh/mod.rs",
        "Crossing",
        "the CPU sorts shadow crossings into brute force's order to be bit-identical; the f32 GPU \
         multiplies in visiting order",
    ),
    ("cpu/mod.rs", "TraceContext", "the scene and its decoded header; WGSL reads them from bindings"),
    ("cpu/emitter.rs", "Emitters", "the host's emitter list; the GPU reads the buffer of its gpu_words"),
    ("cpu/shade.rs", "Breakdown", "the CPU probe's record; the GPU probe writes ProbeRecord (layout.rs)"),
    ("image.rs", "*", "host images and their metadata have no place on the GPU"),
    ("cpu/ray_tree.rs", "RayNode", "the host's node; the GPU writes a ProbeNode (layout.rs), decoded into one"),
    ("cpu/ray_tree.rs", "RayTree", "the host's tree, a Vec of nodes; the GPU writes a ProbeTree (layout.rs)"),
];

/// Fields only the CPU side of a twin struct has, and why (left out before the comparison).
const CPU_ONLY_FIELDS: [(&str, &str, &str, &str); 3] = [
    (
        "cpu/mod.rs",
        "RayCounts",
        "capped_samples",
        "the CPU's per-sample ray cap (--max-rays-per-sample); the GPU's bound is its tree walk's, raised as a status bit",
    ),
    (
        "cpu/shade.rs",
        "LightTerm",
        "shadow_ray",
        "set by the probe around light_term on both sides; the GPU probe stores it in ProbeLight::shadow_ray",
    ),
    (
        "cpu/shade.rs",
        "LightTerm",
        "angles",
        "set by the probe beside light_term on both sides (light_angles); the GPU probe stores them in ProbeLight",
    ),
];

/// Structs declared in a source text before its test module, with their field names in order.
/// WGSL fields are `name: type,`; Rust fields `pub name: Type,` (attributes and comments skipped;
/// tuple and unit structs have no named fields).
fn structs(source: &str) -> BTreeMap<String, Vec<String>> {
    let code = source.split("#[cfg(test)]").next().unwrap_or(source);
    let mut out = BTreeMap::new();
    let mut current: Option<(String, Vec<String>)> = None;
    for line in code.lines() {
        let t = line.trim();
        if let Some((name, fields)) = current.as_mut() {
            if t.starts_with('}') {
                out.insert(std::mem::take(name), std::mem::take(fields));
                current = None;
            } else if !(t.starts_with("//") || t.starts_with("#[") || t.is_empty()) {
                let t = without_visibility(t);
                let field: String = t.chars().take_while(|c| c.is_alphanumeric() || *c == '_').collect();
                if t[field.len()..].trim_start().starts_with(':') {
                    fields.push(field);
                }
            }
            continue;
        }
        let t = without_visibility(t);
        if let Some(rest) = t.strip_prefix("struct ")
            && rest.trim_end().ends_with('{')
        {
            let name: String = rest.chars().take_while(|c| c.is_alphanumeric() || *c == '_').collect();
            current = Some((name, Vec::new()));
        }
    }
    out
}

#[test]
fn every_shader_struct_has_a_cpu_twin_with_the_same_fields_in_the_same_module() {
    let cpu_structs: Vec<(&str, BTreeMap<String, Vec<String>>)> =
        TWINS.iter().map(|(_, _, cpu_file, cpu)| (*cpu_file, structs(cpu))).collect();
    let mut problems = Vec::new();
    let mut compared = 0;
    for (wgsl_file, wgsl, cpu_file, cpu) in TWINS {
        let (gpu_structs, mut own) = (structs(wgsl), structs(cpu));
        for (_, name, field, _) in CPU_ONLY_FIELDS.iter().filter(|(file, ..)| *file == cpu_file) {
            let fields = own.get_mut(*name).unwrap_or_else(|| panic!("{cpu_file} has no struct {name}"));
            let before = fields.len();
            fields.retain(|f| f != field);
            assert_eq!(fields.len() + 1, before, "{cpu_file}: {name} has no field {field} (CPU_ONLY_FIELDS)");
        }
        for (name, gpu_fields) in &gpu_structs {
            match own.get(name) {
                Some(cpu_fields) if cpu_fields == gpu_fields => compared += 1,
                Some(cpu_fields) => problems.push(format!(
                    "struct {name}: fields differ, {wgsl_file} {gpu_fields:?} vs {cpu_file} {cpu_fields:?}"
                )),
                None => {
                    if let Some((elsewhere, _)) = cpu_structs.iter().find(|(_, s)| s.contains_key(name)) {
                        problems.push(format!(
                            "struct {name} is in {elsewhere}, its WGSL twin in {wgsl_file}: move it to {cpu_file}"
                        ));
                    } else if !GPU_ONLY_STRUCTS.iter().any(|(file, n, _)| *file == wgsl_file && n == name) {
                        problems.push(format!("{wgsl_file}: struct {name} has no twin in {cpu_file}"));
                    }
                }
            }
        }
        for name in own.keys().filter(|n| !gpu_structs.contains_key(*n)) {
            let in_some_wgsl = TWINS.iter().any(|(_, w, _, _)| structs(w).contains_key(name));
            let listed = CPU_ONLY_STRUCTS.iter().any(|(file, n, _)| *file == cpu_file && (*n == "*" || n == name));
            if !in_some_wgsl && !listed {
                problems.push(format!("{cpu_file}: struct {name} has no twin in {wgsl_file}"));
            }
        }
    }
    // A listed exception whose struct is gone (moved, renamed) would excuse nothing and mislead.
    for (file, name, _) in GPU_ONLY_STRUCTS {
        let found = TWINS.iter().any(|(w, wgsl, _, _)| *w == file && structs(wgsl).contains_key(name));
        if !found {
            problems.push(format!("GPU_ONLY_STRUCTS lists {file}: {name}, which {file} does not have"));
        }
    }
    for (file, name, _) in CPU_ONLY_STRUCTS.iter().filter(|(_, n, _)| *n != "*") {
        if !cpu_structs.iter().any(|(f, s)| f == file && s.contains_key(*name)) {
            problems.push(format!("CPU_ONLY_STRUCTS lists {file}: {name}, which {file} does not have"));
        }
    }
    assert!(problems.is_empty(), "CPU/WGSL struct twins differ:\n{}", problems.join("\n"));
    assert!(compared >= 7, "only {compared} struct pairs compared: is the parser still reading both sides?");
}

#[test]
fn struct_parser_reads_fields_of_both_languages() {
    let wgsl = "struct A {\n    x: f32,\n    // c\n    y: vec3<f32>,\n}\n";
    let rust = "/// d\n#[derive(Debug)]\npub struct A {\n    /// x\n    pub x: f64,\n    #[serde(skip)]\n    pub y: DVec3,\n}\npub struct T(u32);\n";
    let want = BTreeMap::from([("A".to_string(), vec!["x".to_string(), "y".to_string()])]);
    assert_eq!(structs(wgsl), want);
    assert_eq!(structs(rust), want);
    // Restricted visibility (a module's items shared with its siblings) reads the same.
    assert_eq!(structs(&rust.replace("pub struct A", "pub(super) struct A").replace("pub y", "pub(crate) y")), want);
}

/// A Rust line without its leading visibility (`pub`, `pub(super)`, `pub(crate)`).
fn without_visibility(t: &str) -> &str {
    ["pub ", "pub(super) ", "pub(crate) "].iter().find_map(|p| t.strip_prefix(p)).unwrap_or(t)
}

/// Names declared with `fn` in a source text, before its test module.
fn functions(source: &str) -> BTreeSet<String> {
    let code = source.split("#[cfg(test)]").next().unwrap_or(source);
    let mut names = BTreeSet::new();
    for line in code.lines() {
        let t = line.trim_start();
        let t = without_visibility(t);
        if let Some(rest) = t.strip_prefix("fn ") {
            let name: String = rest.chars().take_while(|c| c.is_alphanumeric() || *c == '_').collect();
            names.insert(name);
        }
    }
    names
}

#[test]
fn every_shader_function_has_a_cpu_twin_and_back() {
    let mut problems = Vec::new();
    for (wgsl_file, wgsl, cpu_file, cpu) in TWINS {
        let (gpu_fns, cpu_fns) = (functions(wgsl), functions(cpu));
        // One side may have none (ray.wgsl: only structs); the other's then lack twins below.
        assert!(!gpu_fns.is_empty() || !cpu_fns.is_empty(), "no functions parsed from {wgsl_file} nor {cpu_file}");
        for f in gpu_fns.difference(&cpu_fns) {
            if !GPU_ONLY.iter().any(|(file, name, _)| *file == wgsl_file && name == f) {
                problems.push(format!("{wgsl_file}: fn {f} has no twin in {cpu_file}"));
            }
        }
        for f in cpu_fns.difference(&gpu_fns) {
            if !CPU_ONLY.iter().any(|(file, name, _)| *file == cpu_file && (*name == "*" || name == f)) {
                problems.push(format!("{cpu_file}: fn {f} has no twin in {wgsl_file}"));
            }
        }
    }
    assert!(problems.is_empty(), "CPU/WGSL twins differ:\n{}", problems.join("\n"));
}
