//! The acceleration structure alone, as `glint bench rays` measures it, on the generated
//! `bumpy` scene at N = 200 (160,002 triangles, so that it runs in seconds): the BVH build (with
//! the CPU walk's wide nodes), and the closest hit of the primary and the incoherent ray sets
//! (1280×720 rays each) on 2 threads.
//!
//! Run with `cargo bench -p glint-core --bench rays`. Throughput is in triangles (build) and in
//! rays (casts) per second; criterion prints them as Melem/s.

use std::hint::black_box;
use std::time::Duration;

use criterion::{Criterion, SamplingMode, Throughput, criterion_group, criterion_main};
use glint_core::cpu::TraceContext;
use glint_core::cpu::raycast::cast_rays;
use glint_core::rays::RaySet;
use glint_core::{FlatScene, bvh};
use glint_io::{LoadOptions, load_scene_with};

const RESOLUTION: u32 = 200;
const THREADS: usize = 2;

fn rays(c: &mut Criterion) {
    let loaded = load_scene_with("bumpy", &LoadOptions { resolution: Some(RESOLUTION), ..LoadOptions::default() })
        .expect("the generated bumpy scene loads");
    let flat = FlatScene::build(&loaded.desc, &loaded.desc.render);
    let pool = rayon::ThreadPoolBuilder::new().num_threads(THREADS).build().expect("a thread pool");
    let ctx = TraceContext::new(&flat).expect("a valid flat scene");

    let mut group = c.benchmark_group(format!("bumpy{RESOLUTION}"));
    // Each iteration takes 0.05–1 s: flat sampling and 10 samples keep the whole run near a minute.
    group.sampling_mode(SamplingMode::Flat);
    group.sample_size(10);
    group.warm_up_time(Duration::from_secs(1));
    group.measurement_time(Duration::from_secs(12));

    group.throughput(Throughput::Elements((flat.spheres.len() + flat.triangles.len()) as u64));
    // The build with the collapse into the CPU walk's wide nodes, as `glint bench rays` times it.
    group.bench_function("bvh_build_2threads", |b| {
        b.iter(|| pool.install(|| bvh::BvhNodes::build_for_cpu(black_box(&flat.bounded()))));
    });
    for set in RaySet::ALL {
        let rays = set.rays();
        group.throughput(Throughput::Elements(rays.len() as u64));
        group.bench_function(format!("{}_1280x720_2threads", set.name()), |b| {
            b.iter(|| pool.install(|| cast_rays(&ctx, black_box(&rays))));
        });
    }
    group.finish();
}

criterion_group!(benches, rays);
criterion_main!(benches);
