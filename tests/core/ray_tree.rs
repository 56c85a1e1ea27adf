//! The CPU ray tree (`probe_tree`) describes exactly what the render computed: recomputed from
//! its recorded terms and factors alone it gives each pixel's radiance bit for bit, and its
//! shape follows the model (k products along the path, bailout and depth cuts).

use glint_core::cpu::TraceContext;
use glint_core::cpu::ray_tree::{Cut, RayTree};
use glint_core::cpu::trace::{render_pixel, weigh};
use glint_core::glam::DVec3;
use glint_core::{FlatScene, probe_tree};
use glint_io::load_scene;
use glint_types::RayKind;

use super::support::SceneText;

fn whitted(width: u32, height: u32, depth: u32, bailout: f64) -> FlatScene {
    let loaded = load_scene("whitted").expect("built-in scene");
    let mut s = loaded.desc.render.clone();
    (s.width, s.height, s.spp, s.max_depth, s.bailout) = (width, height, 1, depth, bailout);
    FlatScene::build(&loaded.desc, &s)
}

fn bits(v: DVec3) -> [u64; 3] {
    v.to_array().map(f64::to_bits)
}

/// Every `step`-th pixel: the tree's recomputed radiance and its root's recorded radiance are
/// the rendered pixel's, bit for bit.
fn check_totals(flat: &FlatScene, step: usize) -> usize {
    let ctx = TraceContext::new(flat).expect("valid tags");
    let background = glint_core::cpu::v3(flat.header.background);
    let mut nodes = 0;
    for y in (0..flat.header.height).step_by(step) {
        for x in (0..flat.header.width).step_by(step) {
            let mut counts = Default::default();
            let (pixel, _) = render_pixel(&ctx, x, y, &mut counts);
            let tree = probe_tree(flat, x, y, 0).expect("valid tags");
            assert_eq!(bits(tree.nodes[0].radiance.expect("root radiance")), bits(pixel), "({x}, {y}) root");
            assert_eq!(bits(tree.radiance_of(0, background)), bits(pixel), "({x}, {y}) recomputed from the tree");
            nodes += tree.nodes.len();
        }
    }
    nodes
}

#[test]
fn the_tree_recomputes_every_pixel_of_whitted_bit_for_bit() {
    for (depth, bailout) in [(5, 0.01), (5, 0.0), (1, 0.01), (0, 0.01)] {
        let nodes = check_totals(&whitted(160, 120, depth, bailout), 3);
        assert!(nodes > 160 * 120 / 9, "depth {depth}: only {nodes} nodes");
    }
}

#[test]
fn the_tree_recomputes_pixels_under_global_attenuation_bit_for_bit() {
    let flat = SceneText::new(
        24,
        16,
        "max_depth = 3\nbailout = 0.0",
        [0.0, 1.0, -4.0],
        [0.0, 0.5, 0.0],
        [0.0, 1.0, 0.0],
        50.0,
    )
    .world_attenuated([0.1; 3], [0.2, 0.3, 0.4], [1.0, 0.1, 0.01])
    .material("glass", "ka = 0.0\nkd = 0.1\nks = 0.5\nshininess = 40.0\nkr = 0.2\nkt = 0.7\nior = 1.5")
    .material("floor", "ka = 0.2\nkd = 0.7\nks = 0.0\nkr = 0.3")
    .sphere([0.0, 0.6, 0.0], 0.6, "glass")
    .plane([0.0; 3], [0.0, 1.0, 0.0], "floor")
    .light("point", "position = [2.0, 4.0, -2.0]\ndiffuse = 1.0\nspecular = 1.0")
    .flat();
    assert!(flat.header.features & glint_types::layout::feature::GLOBAL_ATTENUATION != 0);
    check_totals(&flat, 1);
    let tree = probe_tree(&flat, 12, 8, 0).expect("valid tags");
    assert!(tree.nodes.iter().any(|n| n.kind != RayKind::Camera && n.hit() && n.attenuation < 1.0), "{tree:#?}");
}

/// The glass sphere of whitted at depths 5 and 2: a camera ray, refraction and reflection rays whose
/// weights are the products of k along their paths, shadow rays, and the cut children.
#[test]
fn a_glass_sphere_pixel_records_weights_shadows_and_cuts() {
    let deep = check_glass_tree(5);
    assert!(deep.nodes.iter().any(|n| n.cut == Some(Cut::Bailout)), "the bailout cuts a branch");
    let shallow = check_glass_tree(2);
    assert!(shallow.nodes.iter().any(|n| n.cut == Some(Cut::MaxDepth)), "the depth limit cuts a branch");
}

fn check_glass_tree(max_depth: u32) -> RayTree {
    let flat = whitted(160, 120, max_depth, 0.01);
    let tree: RayTree = probe_tree(&flat, 100, 70, 0).expect("valid tags");
    let camera = &tree.nodes[0];
    assert_eq!((camera.kind, camera.parent, camera.weight), (RayKind::Camera, None, DVec3::ONE));
    assert!(tree.count(RayKind::Refraction) >= 2 && tree.count(RayKind::Reflection) >= 2, "{}", tree.nodes.len());
    assert!(tree.count(RayKind::Shadow) >= 1);
    for (i, n) in tree.nodes.iter().enumerate().skip(1) {
        let parent = &tree.nodes[n.parent.expect("a parent")];
        assert!(n.parent.unwrap() < i, "depth-first: the parent comes first");
        assert_eq!(n.depth, parent.depth + 1);
        if n.kind == RayKind::Shadow {
            assert_eq!(n.weight, parent.weight * parent.attenuation);
            assert!(n.light.is_some() && n.cut.is_none());
        } else {
            let k = flat.materials[parent.terms.as_ref().expect("parent hit").material as usize];
            let (kr, kt) = (glint_core::cpu::v3(k.kr), glint_core::cpu::v3(k.kt));
            // The path weight is the parent's times the ray's own k, in f32 as the GPU forms it
            // (k_r + k_t summed in f32 under total internal reflection).
            let k32 = if n.tir { (kr.as_vec3() + kt.as_vec3()).as_dvec3() } else { n.factor };
            let parent_weight = weigh(parent.weight, DVec3::splat(parent.attenuation));
            assert_eq!(n.weight, weigh(parent_weight, k32), "node {i}");
            let want = match n.kind {
                RayKind::Reflection if n.tir => kr + kt,
                RayKind::Reflection => kr,
                RayKind::Refraction => kt,
                RayKind::Camera | RayKind::Shadow => unreachable!("checked above"),
            };
            assert_eq!(n.factor, want, "node {i}");
            match n.cut {
                Some(Cut::Bailout) => assert!(n.weight.max_element() < 0.01),
                Some(Cut::MaxDepth) => assert_eq!(parent.depth, max_depth),
                Some(Cut::RayCap) => panic!("no ray cap at this size"),
                None => assert!(n.weight.max_element() >= 0.01 && parent.depth < max_depth),
            }
        }
    }
    tree
}

/// A raised stop flag cuts a sample's tree short, not only the render between pixels: nested
/// glass shells of k_r = k_t = 1/2 at depth 1024 and bailout 0 double the tree at every level
/// (a tester's, under a cap raised to 2^40, ran for minutes after a SIGTERM). The cap is 2^27
/// here, so that a tree the flag does not cut ends in the cap, failing, seconds later (2^25
/// took 3.9 s on one core).
#[test]
fn a_stop_flag_cuts_a_tree_that_would_not_end() {
    use std::sync::atomic::{AtomicBool, Ordering};
    let text = "[render]\nwidth = 2\nheight = 2\nmax_depth = 1024\nbailout = 0\n\
                [camera]\nposition = [0, 0, 0]\nlook_at = [0, 0, 1]\n\
                [materials.g]\nkd = 0\nkr = 0.5\nkt = 0.5\nior = 1\n\
                [[objects]]\ntype = \"sphere\"\ncenter = [0, 0, 0]\nradius = 1\nmaterial = \"g\"\n\
                [[objects]]\ntype = \"sphere\"\ncenter = [0, 0, 0]\nradius = 2\nmaterial = \"g\"\n";
    let (desc, _) = glint_io::parse_scene(text, std::path::Path::new("bomb.toml")).expect("valid scene");
    let flat = FlatScene::build(&desc, &desc.render);
    let options = glint_core::CpuOptions { max_rays_per_sample: 1 << 27, threads: 1, ..Default::default() };
    let cancel = AtomicBool::new(false);
    let start = std::time::Instant::now();
    let result = std::thread::scope(|s| {
        s.spawn(|| {
            std::thread::sleep(std::time::Duration::from_millis(200));
            cancel.store(true, Ordering::Relaxed);
        });
        let control = glint_core::RenderControl { cancel: Some(&cancel), ..Default::default() };
        glint_core::render_cpu(&flat, &options, control)
    });
    assert!(matches!(result, Err(glint_core::render::CpuRenderError::Cancelled)), "{result:?}");
    // Stopped within the next child's trace; a minute is a margin for a loaded machine, where
    // without the flag in the tree it ran for hours.
    assert!(start.elapsed() < std::time::Duration::from_secs(60), "{:?}", start.elapsed());
}
