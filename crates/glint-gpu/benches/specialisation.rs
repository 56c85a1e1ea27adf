//! What specialisation buys, per built-in scene: shader size (naga statements), pipeline
//! creation time, and render time of the specialised and the full tracer, on the GPU and on
//! the CPU. Run with `cargo bench -p glint-gpu --bench specialisation`; for cold pipeline
//! times disable the driver's shader cache (`MESA_SHADER_CACHE_DISABLE=true` for Mesa).

use std::time::Duration;

use glint_core::{CpuOptions, FlatScene, RenderControl, render_cpu};
use glint_gpu::shaders::{ShaderKey, compose, module_stats};
use glint_gpu::{AdapterRequest, GpuContext, GpuOptions, GpuTracer};
use glint_io::{BUILTIN_SCENES, load_scene};

const RUNS: usize = 3;

fn median(mut v: Vec<Duration>) -> f64 {
    v.sort();
    v[v.len() / 2].as_secs_f64() * 1e3
}

fn gpu_times(flat: &FlatScene, specialise: bool) -> (f64, f64) {
    // A fresh tracer, so the pipeline is created (and, on lavapipe, compiled) again.
    let ctx = GpuContext::new(&AdapterRequest { name: None, prefer_cpu: false }).expect("a GPU adapter");
    let tracer = GpuTracer::new(ctx);
    let options = GpuOptions { specialise, ..GpuOptions::default() };
    let first = tracer.render(flat, &options).expect("GPU render");
    let times = (0..RUNS).map(|_| tracer.render(flat, &options).expect("GPU render").render_time).collect();
    (first.pipeline_time.as_secs_f64() * 1e3, median(times))
}

fn cpu_time(flat: &FlatScene, specialise: bool) -> f64 {
    let options = CpuOptions { threads: 0, specialise, ..CpuOptions::default() };
    render_cpu(flat, &options, RenderControl::default()).expect("CPU render");
    median((0..RUNS).map(|_| render_cpu(flat, &options, RenderControl::default()).expect("CPU").elapsed).collect())
}

fn main() {
    let adapter = GpuContext::new(&AdapterRequest::default()).expect("a GPU adapter").adapter;
    let cache = std::env::var("MESA_SHADER_CACHE_DISABLE").unwrap_or_else(|_| "unset".into());
    println!("specialised vs full tracer; GPU: {adapter}; MESA_SHADER_CACHE_DISABLE={cache}; median of {RUNS}");
    println!(
        "{:<11} {:>9} {:>9} | {:>9} {:>9} | {:>9} {:>9} {:>6} | {:>9} {:>9} {:>6}",
        "scene", "stmts sp", "full", "pipe ms", "full", "gpu ms", "full", "gain", "cpu ms", "full", "gain"
    );
    let full_statements = module_stats(&compose(&ShaderKey::full()).expect("full shader")).statements;
    // The scene files: the generated scenes measure the BVH (`glint bench rays`), not shading.
    for b in BUILTIN_SCENES.iter().filter(|b| !b.is_generated()) {
        let loaded = load_scene(b.name).expect("built-in");
        let flat = FlatScene::build(&loaded.desc, &loaded.desc.render);
        let key = ShaderKey::for_scene(&flat, true);
        let statements = module_stats(&compose(&key).expect("variant")).statements;
        let (pipe_s, gpu_s) = gpu_times(&flat, true);
        let (pipe_f, gpu_f) = gpu_times(&flat, false);
        let (cpu_s, cpu_f) = (cpu_time(&flat, true), cpu_time(&flat, false));
        println!(
            "{:<11} {statements:>9} {full_statements:>9} | {pipe_s:>9.1} {pipe_f:>9.1} | {gpu_s:>9.1} {gpu_f:>9.1} {:>5.2}x | {cpu_s:>9.1} {cpu_f:>9.1} {:>5.2}x",
            b.name,
            gpu_f / gpu_s,
            cpu_f / cpu_s
        );
    }
}
