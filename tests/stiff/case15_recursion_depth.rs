//! Case 15: recursion depth 0, 1, 64, 1000, and the GPU's bounds on the ray tree.
//!
//! - Two facing mirrors (k_r = 1/2) with the default bailout 1/255: depth 0, 1, 64 and 1000 all
//!   terminate; 64 and 1000 give bit-identical images and ray counts on each backend (the path
//!   weight 2^-k falls below the bailout after 8 bounces).
//! - Perfect mirrors (k_r = 1) without bailout at depth 1000: a chain of 1001 hits per pixel on
//!   both backends (the CPU recursion 1000 deep, the GPU walk 1001 iterations), each adding its
//!   emission E: I = 1001·E.
//! - The GPU's ray stack holds GPU_STACK_LIMIT = 64 deferred rays. A ray tree that branches at
//!   every level (glass, camera in a slab, near the normal: each hit defers its refracted ray
//!   and follows the mirror ray) fits exactly at depth 64 — status 0 and the CPU's image — and
//!   overflows at depth 65: the GPU must raise STATUS_STACK_OVERFLOW, never drop rays silently.
//! - Its tree walk is bounded by 65,000 nodes per sample (lavapipe cuts longer loops silently
//!   after 65,535 iterations): a tree that branches fully (ten parallel glass plates, depth 18)
//!   has more nodes, and the GPU must raise STATUS_LOOP_LIMIT.
//! - lavapipe allows 65,535 loop iterations in all per invocation group (every loop of the
//!   shader counts) and then ends each loop after one iteration, silently. A canary loop at the
//!   end of the shader sees it: one camera ray over 40,000 triangles (plus its shadow ray) must
//!   raise STATUS_DRIVER_LOOP_CUTOFF there, and on a driver without the budget give the CPU's
//!   image with status 0. Samples go in separate dispatches, so 64 spp never adds to it.

use std::time::Instant;

use glint_core::Accel;
use glint_gpu::{GPU_STACK_LIMIT, GpuOptions};
use glint_types::layout::{STATUS_DRIVER_LOOP_CUTOFF, STATUS_LOOP_LIMIT, STATUS_STACK_OVERFLOW};

use crate::gpu::{BothOptions, render_both, render_both_with};
use crate::scene::{SceneText, num};
use crate::{Y, Z};

const E: f64 = 0.0625;

fn mirrors(depth: u32, kr: f64, bailout: f64, size: u32) -> SceneText {
    SceneText::new(
        size,
        size,
        &format!("max_depth = {depth}\nbailout = {}", num(bailout)),
        [0.2, 0.1, 1.0],
        [1.0, 0.5, 4.0],
        Y,
        60.0,
    )
    .world([0.125; 3], [0.0; 3])
    .material("mirror", &format!("ka = 0.5\nkd = 0.5\nks = 0.0\nkr = {}\nemission = {}", num(kr), num(E)))
    .light("point", "position = [0.0, 3.0, 1.0]")
    .plane([0.0; 3], Z, "mirror")
    .plane([0.0, 0.0, 4.0], [0.0, 0.0, -1.0], "mirror")
}

#[test]
fn depths_0_1_64_1000_terminate_and_the_bailout_makes_64_equal_1000() {
    let mut out = String::new();
    say!(out, "case 15: facing mirrors k_r = 1/2, bailout 1/255 (16x16)");
    let mut runs = Vec::new();
    for depth in [0, 1, 64, 1000] {
        let start = Instant::now();
        let both =
            render_both("stiff/case15", &format!("mirrors-depth{depth}"), &mirrors(depth, 0.5, 1.0 / 255.0, 16).flat());
        say!(
            out,
            "  depth {depth:>4}: {:>5} rays, {:>4} saved by the bailout, {:.0} ms on both backends",
            both.cpu.counts.total(),
            both.cpu.counts.bailout_saved,
            start.elapsed().as_secs_f64() * 1e3
        );
        runs.push(both);
    }
    let (d64, d1000) = (&runs[2], &runs[3]);
    assert_eq!(d64.cpu.image, d1000.cpu.image, "CPU: depth 64 and 1000 differ");
    assert_eq!(d64.cpu.counts, d1000.cpu.counts, "CPU: depth 64 and 1000 trace different rays");
    if let (Some(a), Some(b)) = (&d64.gpu, &d1000.gpu) {
        assert_eq!(a.image, b.image, "GPU: depth 64 and 1000 differ");
        assert_eq!(a.counts, b.counts, "GPU: depth 64 and 1000 trace different rays");
    }
    assert!(runs[1].cpu.counts.reflection > 0 && runs[0].cpu.counts.reflection == 0);
    eprint!("{out}");
}

#[test]
fn perfect_mirrors_at_depth_1000_without_bailout() {
    // Emission only (k_a = k_d = 0, no light): each of the 1001 hits adds E.
    let flat = SceneText::new(4, 4, "max_depth = 1000\nbailout = 0.0", [0.2, 0.1, 1.0], [1.0, 0.5, 4.0], Y, 60.0)
        .world([0.125; 3], [0.0; 3])
        .material("mirror", &format!("ka = 0.0\nkd = 0.0\nks = 0.0\nkr = 1.0\nemission = {}", num(E)))
        .plane([0.0; 3], Z, "mirror")
        .plane([0.0, 0.0, 4.0], [0.0, 0.0, -1.0], "mirror")
        .flat();
    let both = render_both("stiff/case15", "perfect-mirrors-1000", &flat);
    let mut worst = [0.0_f64; 2];
    for (backend, img) in both.images() {
        for p in &img.pixels {
            let err = (p.x - 1001.0 * E).abs() / (1001.0 * E);
            worst[backend as usize] = worst[backend as usize].max(err);
            // Measured 0 on both: 1001 additions of E = 1/16 are exact in f32 too.
            both.ensure(err <= backend.pick(1e-12, 1e-5), || format!("{}: {p} vs 1001·E", backend.name()));
        }
    }
    eprintln!(
        "case 15: perfect mirrors, depth 1000: worst relative error to 1001·E CPU {:.1e}, GPU {:.1e}",
        worst[0], worst[1]
    );
    assert_eq!(both.cpu.counts.reflection, 16 * 1000);
    if let Some(g) = &both.gpu {
        assert_eq!(g.counts, both.cpu.counts);
    }
}

/// The camera inside a glass slab (−1 < y < 1), looking up 10° off the normal: every hit both
/// reflects and refracts; the refracted ray leaves the slab and ends, the mirror ray goes on.
fn branching_slab(depth: u32) -> SceneText {
    let a = 10.0_f64.to_radians();
    SceneText::pinhole(&format!("max_depth = {depth}\nbailout = 0.0"), [0.0; 3], [a.sin(), a.cos(), 0.0], Z)
        .world([0.0; 3], [0.25; 3])
        .material(
            "glass",
            &format!("ka = 0.0\nkd = 0.0\nks = 0.0\nkr = 0.9\nkt = 0.5\nior = 1.5\nemission = {}", num(E)),
        )
        .plane([0.0, 1.0, 0.0], Y, "glass")
        .plane([0.0, -1.0, 0.0], [0.0, -1.0, 0.0], "glass")
}

#[test]
fn a_tree_deeper_than_the_gpu_stack_raises_the_overflow_bit() {
    let mut out = String::new();
    let fits = branching_slab(GPU_STACK_LIMIT).flat();
    let both = render_both("stiff/case15", "stack-fits", &fits);
    if let Some(g) = &both.gpu {
        let diff = (g.image.pixels[0] - both.cpu.image.pixels[0]).abs().max_element();
        both.ensure(diff <= 1e-5 * both.cpu.image.pixels[0].max_element(), || {
            format!("depth {GPU_STACK_LIMIT}: GPU differs by {diff:e}")
        });
        both.ensure(g.counts == both.cpu.counts, || "depth 64: the GPU traced other rays".into());
    }
    // The specialised shader's stack for depth ≥ 64 is GPU_STACK_LIMIT deep, as the full
    // shader's (whose images are the same: tests/gpu/specialisation.rs).
    let over = branching_slab(GPU_STACK_LIMIT + 1).flat();
    let options = BothOptions { expect_status: STATUS_STACK_OVERFLOW, ..BothOptions::default() };
    let both = render_both_with("stiff/case15", "stack-overflow", &over, options);
    if let Some(g) = &both.gpu {
        assert_eq!(g.key.stack_size, GPU_STACK_LIMIT);
        let diff = (g.image.pixels[0] - both.cpu.image.pixels[0]).abs().max_element();
        say!(
            out,
            "case 15: branching tree of depth {}: GPU status {:#x} (stack overflow); the dropped refracted ray changes the pixel by {diff:.1e}",
            GPU_STACK_LIMIT + 1,
            g.status,
        );
    }
    eprint!("{out}");
}

/// Ten stacked half-mirror, half-glass planes seen from among them, depth 18, no bailout: every
/// hit splits, and a sample's tree has more than 65,000 nodes.
fn branching_planes() -> SceneText {
    let a = 10.0_f64.to_radians();
    let mut s = SceneText::pinhole("max_depth = 18\nbailout = 0.0", [0.0, 4.5, 0.0], [a.sin(), 4.5 + a.cos(), 0.0], Z)
        .world([0.0; 3], [0.25; 3])
        .material(
            "glass",
            &format!("ka = 0.0\nkd = 0.0\nks = 0.0\nkr = 0.5\nkt = 0.5\nior = 1.5\nemission = {}", num(E)),
        );
    for k in 0..10 {
        s = s.plane([0.0, f64::from(k), 0.0], Y, "glass");
    }
    s
}

#[test]
fn a_tree_larger_than_the_walk_bound_raises_the_loop_bit() {
    let mut out = String::new();
    let s = branching_planes();
    // On lavapipe the driver's own loop budget (65,535 iterations in all) runs out first: the
    // walk, cut short below its bound, raises the driver's bit alone (it raised the bound's too,
    // and a tester's 4,000 lights at depth 2, 7 nodes a tree, read "some ray trees were cut").
    let lavapipe = crate::gpu::gpu().is_some_and(|t| t.context().adapter.name.contains("llvmpipe"));
    let expect_status = if lavapipe { STATUS_DRIVER_LOOP_CUTOFF } else { STATUS_LOOP_LIMIT };
    let both = render_both_with(
        "stiff/case15",
        "loop-limit",
        &s.flat(),
        BothOptions { expect_status, ..BothOptions::default() },
    );
    let nodes = both.cpu.counts.total();
    say!(
        out,
        "case 15: fully branching tree, depth 18: {nodes} rays on the CPU; the GPU walk stops at 65,000 and says so"
    );
    assert!(nodes > 65_000, "the tree has only {nodes} nodes: the loop bound is not reached");
    eprint!("{out}");
}

#[test]
fn a_walk_bound_below_the_driver_s_budget_raises_the_bound_s_bit_on_every_adapter() {
    // Lavapipe's budget cuts the 65,000-node walk first, so the bound's own bit was provoked on
    // hardware only. A bound of 1,000 nodes is reached first everywhere: the walk stops there,
    // raises STATUS_LOOP_LIMIT alone, and traces fewer rays than the CPU.
    let Some(tracer) = crate::gpu::gpu() else { return };
    let flat = branching_planes().flat();
    let options = GpuOptions { tree_nodes: 1_000, ..GpuOptions::default() };
    let g = crate::gpu::gpu_render_with(tracer, &flat, &options);
    assert_eq!(g.key.tree_nodes, 1_000, "{}", g.key.describe());
    assert_eq!(g.status, STATUS_LOOP_LIMIT, "status {:#x} on {}", g.status, tracer.context().adapter);
    let said =
        glint_gpu::status::messages(g.status, &glint_gpu::status::StatusContext::new(&flat.header, &g.key)).join("; ");
    assert!(said.contains("hit its loop bound; some ray trees were cut"), "{said}");
    let c = glint_core::render_cpu(&flat, &glint_core::CpuOptions::default(), glint_core::RenderControl::default())
        .expect("CPU render");
    // About the bound's 1,000 nodes (with their shadow rays) against the CPU's 333,799 rays.
    assert!(
        g.counts.total() * 100 < c.counts.total(),
        "GPU rays {} (bound 1,000 nodes a sample), CPU {}",
        g.counts.total(),
        c.counts.total()
    );
    // Within the default bound a small tree raises nothing.
    let shallow = SceneText::pinhole("max_depth = 3\nbailout = 0.0", [0.0, 4.5, 0.0], [0.2, 5.5, 0.0], Z)
        .world([0.0; 3], [0.25; 3])
        .material("glass", "ka = 0.0\nkd = 0.0\nks = 0.0\nkr = 0.5\nkt = 0.5\nior = 1.5")
        .plane([0.0, 4.0, 0.0], Y, "glass")
        .flat();
    assert_eq!(crate::gpu::gpu_render_with(tracer, &shallow, &options).status, 0);
}

/// 40,000 triangles in a strip under the camera: 80,000 loop iterations for one camera ray
/// and its shadow ray, past lavapipe's budget.
fn triangle_carpet(spp: u32) -> SceneText {
    const COLUMNS: u32 = 200;
    const ROWS: u32 = 100;
    let mut vertices = Vec::new();
    for j in 0..=ROWS {
        for i in 0..=COLUMNS {
            vertices.push([
                f64::from(i) / f64::from(COLUMNS) * 2.0 - 1.0,
                0.0,
                f64::from(j) / f64::from(ROWS) * 2.0 - 1.0,
            ]);
        }
    }
    let mut triangles = Vec::new();
    let at = |i: u32, j: u32| j * (COLUMNS + 1) + i;
    for j in 0..ROWS {
        for i in 0..COLUMNS {
            triangles.push([at(i, j), at(i, j + 1), at(i + 1, j)]);
            triangles.push([at(i + 1, j), at(i, j + 1), at(i + 1, j + 1)]);
        }
    }
    SceneText::new(2, 2, &format!("max_depth = 0\nspp = {spp}"), [0.0, 2.0, 0.1], [0.0; 3], Y, 20.0)
        .world([0.1; 3], [0.0; 3])
        .material("matte", "ka = 1.0\nkd = 0.8\nks = 0.0")
        .light("point", "position = [0.0, 3.0, 0.0]")
        .mesh(&vertices, &triangles, None, "matte")
}

#[test]
fn the_driver_loop_budget_is_detected_never_silent() {
    // Brute force on the GPU: every ray walks all 40,000 triangles, past lavapipe's budget.
    let flat = triangle_carpet(1).flat();
    assert_eq!(flat.header.triangle_count, 40_000);
    let Some(tracer) = crate::gpu::gpu() else { return };
    let lavapipe = tracer.context().adapter.name.contains("llvmpipe");
    let expect_status = if lavapipe { STATUS_DRIVER_LOOP_CUTOFF } else { 0 };
    let options = BothOptions { expect_status, accel: Accel::None, ..BothOptions::default() };
    let both = render_both_with("stiff/case15", "driver-loop-cutoff", &flat, options);
    let g = both.gpu.as_ref().expect("the GPU ran");
    if !lavapipe {
        let diff = both.cpu.image.pixels.iter().zip(&g.image.pixels).map(|(a, b)| (*a - *b).abs().max_element());
        let worst = diff.fold(0.0_f64, f64::max);
        both.ensure(worst <= 1e-5, || format!("without a loop budget the GPU differs by {worst:e}"));
    }
    eprintln!("case 15: 40,000 triangles on {}: GPU status {:#x}", tracer.context().adapter, g.status);
}

#[test]
fn the_bvh_keeps_the_carpet_within_the_driver_loop_budget() {
    // The same carpet through the BVH: about log N nodes per ray instead of N triangles, so
    // the canary stays quiet (status 0) and the image matches the CPU within parity.rs's
    // thresholds. The CPU image is the one the test above renders (and hashes); here it is
    // rendered directly, outside the golden-hash hook.
    let flat = triangle_carpet(1).flat();
    let Some(tracer) = crate::gpu::gpu() else { return };
    let c = glint_core::render_cpu(&flat, &glint_core::CpuOptions::default(), glint_core::RenderControl::default())
        .expect("CPU render");
    let g = crate::gpu::gpu_render_with(tracer, &flat, &GpuOptions { accel: Accel::Bvh, ..GpuOptions::default() });
    assert!(g.key.bvh, "the BVH variant ran");
    assert_eq!(g.status, 0, "through the BVH the carpet stays within the loop budget");
    let e = glint_core::compare::compare_images(&c.image, &g.image);
    eprintln!("case 15: carpet through the BVH on {}: {e:?}", tracer.context().adapter);
    assert!(e.flip_mean <= 0.005 && e.p99_abs_same_hit <= 1.0 / 255.0 && e.first_hit_mismatch <= 0.005, "{e:?}");
    assert_eq!(g.counts.total(), c.counts.total(), "rays traced");
}

#[test]
fn many_samples_stay_within_the_driver_loop_budget() {
    // The whitted scene at 64 spp, depth 16, no bailout: before samples went in separate
    // dispatches, lavapipe dropped 0.3 % of its camera rays here without a word.
    let loaded = glint_io::load_scene("whitted").expect("built-in scene");
    let mut settings = loaded.desc.render.clone();
    (settings.width, settings.height, settings.spp, settings.max_depth, settings.bailout) = (32, 18, 64, 16, 0.0);
    let flat = glint_core::FlatScene::build(&loaded.desc, &settings);
    let both = render_both("stiff/case15", "whitted-64spp", &flat);
    if let Some(g) = &both.gpu {
        assert_eq!(g.counts.camera, 32 * 18 * 64, "the GPU traced every camera ray");
        let (cpu, gpu) = (both.cpu.counts.total() as f64, g.counts.total() as f64);
        both.ensure((cpu - gpu).abs() <= 1e-3 * cpu, || format!("GPU traced {gpu} rays, CPU {cpu}"));
    }
}
