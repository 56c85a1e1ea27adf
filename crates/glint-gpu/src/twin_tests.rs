//! Each WGSL file has a CPU twin module with the same function names (vello's layout). This
//! test reads both and fails when one side gains a function the other lacks, unless it is
//! listed below with the reason it exists on one side only.

use std::collections::BTreeSet;

const TWINS: [(&str, &str, &str, &str); 8] = [
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
        "intersect.wgsl",
        include_str!("../../../shaders/intersect.wgsl"),
        "cpu/intersect.rs",
        include_str!("../../glint-core/src/cpu/intersect.rs"),
    ),
    (
        "offset.wgsl",
        include_str!("../../../shaders/offset.wgsl"),
        "cpu/offset.rs",
        include_str!("../../glint-core/src/cpu/offset.rs"),
    ),
    (
        "shade.wgsl",
        include_str!("../../../shaders/shade.wgsl"),
        "cpu/shade.rs",
        include_str!("../../glint-core/src/cpu/shade.rs"),
    ),
    (
        "trace.wgsl",
        include_str!("../../../shaders/trace.wgsl"),
        "cpu/trace.rs",
        include_str!("../../glint-core/src/cpu/trace.rs"),
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
const GPU_ONLY: [(&str, &str, &str); 6] = [
    ("trace.wgsl", "push_ray", "the explicit ray stack: WGSL has no recursion"),
    ("trace.wgsl", "add_stat", "64-bit ray counters built from u32 atomics"),
    ("trace.wgsl", "main", "the compute entry point; the CPU's loop is render::render_cpu"),
    (
        "trace.wgsl",
        "accumulate_sample",
        "one sample per dispatch, summed in the output buffer in the order of the CPU's render_pixel",
    ),
    ("trace.wgsl", "driver_cut_loops", "detects lavapipe's silent loop cut-off, which the CPU does not have"),
    ("present.wgsl", "main", "the compute entry point; the CPU converts pixel by pixel where it writes a PNG"),
];

/// Functions only the CPU side has, and why.
const CPU_ONLY: [(&str, &str, &str); 3] = [
    ("cpu/mod.rs", "*", "Rust plumbing: widening (v3), counters, the trace context"),
    ("cpu/trace.rs", "render_pixel", "the GPU sums a pixel's samples across dispatches (accumulate_sample)"),
    ("image.rs", "*", "file output (PNG, EXR, metadata) has no place on the GPU"),
];

/// Names declared with `fn` in a source text, before its test module.
fn functions(source: &str) -> BTreeSet<String> {
    let code = source.split("#[cfg(test)]").next().unwrap_or(source);
    let mut names = BTreeSet::new();
    for line in code.lines() {
        let t = line.trim_start();
        let t = t.strip_prefix("pub ").unwrap_or(t);
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
