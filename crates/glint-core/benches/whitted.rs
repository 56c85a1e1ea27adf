//! The built-in `whitted` scene on the CPU reference tracer: 1280×720, 1 spp, depth 5,
//! bailout 0 (every child ray traced), 2 threads.
//!
//! Run with `cargo bench -p glint-core --bench whitted`. Throughput is reported in rays
//! (camera + shadow + reflection + refraction) per second; criterion prints it as Melem/s,
//! which is Mrays/s.

use std::hint::black_box;
use std::time::Duration;

use criterion::{Criterion, SamplingMode, Throughput, criterion_group, criterion_main};
use glint_core::{CpuOptions, FlatScene, RenderControl, render_cpu};
use glint_io::load_scene;

fn whitted(c: &mut Criterion) {
    let loaded = load_scene("whitted").expect("the built-in whitted scene loads");
    let mut settings = loaded.desc.render.clone();
    settings.width = 1280;
    settings.height = 720;
    settings.spp = 1;
    settings.max_depth = 5;
    settings.bailout = 0.0;
    let flat = FlatScene::build(&loaded.desc, &settings);
    let options = CpuOptions { threads: 2, ..CpuOptions::default() };

    // The ray count is deterministic: take it from one render outside the timed loop.
    let counts = render_cpu(&flat, &options, RenderControl::default()).expect("render").counts;
    let rays = counts.total();
    eprintln!(
        "whitted: {rays} rays per render ({} camera, {} shadow, {} reflection, {} refraction); thrpt Melem/s = Mrays/s",
        counts.camera, counts.shadow, counts.reflection, counts.refraction
    );

    let mut group = c.benchmark_group("whitted");
    // One render takes a few hundred milliseconds: flat sampling (the same iteration count in
    // every sample) keeps the whole benchmark around 15 s instead of linear sampling's
    // 55 iterations minimum.
    group.sampling_mode(SamplingMode::Flat);
    group.sample_size(10);
    group.warm_up_time(Duration::from_secs(2));
    group.measurement_time(Duration::from_secs(10));
    group.throughput(Throughput::Elements(rays));
    group.bench_function("cpu_1280x720_1spp_depth5_bailout0_2threads", |b| {
        b.iter(|| render_cpu(black_box(&flat), &options, RenderControl::default()).expect("render"));
    });
    group.finish();
}

criterion_group!(benches, whitted);
criterion_main!(benches);
