//! The CPU render loop: tiles in parallel (rayon), deterministic for any thread count.

use std::sync::atomic::{AtomicBool, AtomicU64, Ordering};
use std::time::{Duration, Instant};

use glam::DVec3;
use rayon::prelude::*;

pub use crate::cpu::Accel;
use crate::cpu::emitter::Emitters;
use crate::cpu::path::path_pixel;
use crate::cpu::ray_tree::{NoTree, RayTree};
use crate::cpu::shade::Breakdown;
use crate::cpu::trace::{render_pixel, render_sample};
use crate::cpu::{DEFAULT_MAX_RAYS_PER_SAMPLE, RayCounts, TraceContext};
use crate::flat::FlatScene;
use crate::image::HdrImage;
use crate::tiles::PixelRect;
use glint_scene::Integrator;
use glint_types::layout::{UnknownTag, feature};

/// Edge of a square tile in pixels.
pub const TILE: u32 = 16;

#[derive(Clone, Copy, Debug)]
pub struct CpuOptions {
    /// Worker threads; 0 = one per core.
    pub threads: usize,
    /// Skip the work of features the scene does not use (the default). Off, every feature
    /// runs; the image is bit-identical either way.
    pub specialise: bool,
    /// How rays find primitives (the BVH by default); the image is bit-identical either way.
    pub accel: Accel,
    /// The bound on one camera sample's ray tree: a pixel whose tree reaches it stops the
    /// render with `CpuRenderError::RayCap` (the reference is never silently truncated).
    pub max_rays_per_sample: u64,
    /// The pixels to render (the whole image by default), into an image of the rectangle's
    /// size: the same bits as those pixels of the whole image, since a pixel depends on its
    /// coordinates only (a tile of a render spread over machines, `glint render --tile`).
    pub region: Option<PixelRect>,
}

impl Default for CpuOptions {
    fn default() -> Self {
        Self {
            threads: 0,
            specialise: true,
            accel: Accel::default(),
            max_rays_per_sample: DEFAULT_MAX_RAYS_PER_SAMPLE,
            region: None,
        }
    }
}

/// One finished tile, handed to the progress callback.
#[derive(Clone, Debug)]
pub struct Tile {
    pub x0: u32,
    pub y0: u32,
    pub width: u32,
    pub height: u32,
    pub radiance: Vec<DVec3>,
    pub first_hit: Vec<u32>,
    pub counts: RayCounts,
}

impl Tile {
    /// Copies the tile's pixels and first hits into their place in `image`, which holds the
    /// pixels of `region`.
    pub fn copy_into(&self, image: &mut HdrImage, region: PixelRect) {
        for row in 0..self.height {
            let src = (row * self.width) as usize..((row + 1) * self.width) as usize;
            let dst_start = ((self.y0 - region.y0 + row) * image.width + self.x0 - region.x0) as usize;
            let dst = dst_start..dst_start + self.width as usize;
            image.pixels[dst.clone()].copy_from_slice(&self.radiance[src.clone()]);
            image.first_hit[dst].copy_from_slice(&self.first_hit[src]);
        }
    }
}

/// Cancellation and progress hooks (the viewer and the CLI progress bar).
#[derive(Clone, Copy, Default)]
pub struct RenderControl<'a> {
    pub cancel: Option<&'a AtomicBool>,
    pub on_tile: Option<&'a (dyn Fn(&Tile) + Sync)>,
    /// Rays traced so far, added after every pixel: progress inside a long tile.
    pub rays: Option<&'a AtomicU64>,
}

impl std::fmt::Debug for RenderControl<'_> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("RenderControl").field("cancel", &self.cancel).finish_non_exhaustive()
    }
}

#[derive(Clone, Debug)]
pub struct CpuRender {
    pub image: HdrImage,
    pub counts: RayCounts,
    /// Wall time of the render itself (thread-pool set-up excluded).
    pub elapsed: Duration,
    pub threads: usize,
}

#[derive(Debug, thiserror::Error)]
pub enum CpuRenderError {
    #[error("render cancelled")]
    Cancelled,
    #[error("could not start {threads} render threads: {message}")]
    ThreadPool { threads: usize, message: String },
    #[error("invalid flat scene: {0}")]
    InvalidScene(#[from] UnknownTag),
    #[error("the region {region} is not inside the {width}x{height} image, or has no pixel")]
    Region { region: PixelRect, width: u32, height: u32 },
    #[error(
        "pixel ({x}, {y}): a camera sample's ray tree reached the cap of {cap} rays, so the render stopped; the \
         scene's reflection and refraction branch without end: set render.bailout (e.g. 1/255, with k_r + k_t < 1 \
         in every material) or lower render.max_depth, or raise the cap (--max-rays-per-sample)"
    )]
    RayCap { x: u32, y: u32, cap: u64 },
}

/// Why a tile was not finished.
enum TileStop {
    Cancelled,
    RayCap { x: u32, y: u32 },
}

pub fn tile_count(width: u32, height: u32) -> usize {
    (width.div_ceil(TILE) * height.div_ceil(TILE)) as usize
}

/// What a tile's pixels are computed by.
enum Shading {
    Whitted,
    Path(Emitters),
}

fn render_tile(
    ctx: &TraceContext,
    shading: &Shading,
    region: PixelRect,
    x0: u32,
    y0: u32,
    stop: &Stop,
) -> Result<Tile, TileStop> {
    let h = &ctx.scene.header;
    let width = TILE.min(region.x0 + region.width - x0);
    let height = TILE.min(region.y0 + region.height - y0);
    let mut counts = RayCounts::default();
    let n = (width * height) as usize;
    let mut radiance = Vec::with_capacity(n);
    let mut first_hit = Vec::with_capacity(n);
    for y in y0..y0 + height {
        for x in x0..x0 + width {
            // Per pixel, not only per tile: a tile of a 4096-path reference took seconds, more
            // than a scheduler waits between SIGTERM and SIGKILL (a tester's KillWait of 5 s).
            if stop.requested() {
                return Err(TileStop::Cancelled);
            }
            let before = counts.total();
            let (c, id) = match shading {
                Shading::Whitted => render_pixel(ctx, x, y, &mut counts),
                Shading::Path(emitters) => path_pixel(ctx, emitters, x, y, h.spp, &mut counts),
            };
            if counts.capped_samples > 0 {
                stop.capped.store(true, Ordering::Relaxed);
                return Err(TileStop::RayCap { x, y });
            }
            // A stop may have cut this pixel's tree (`TraceContext::cap_reached`): it is no
            // pixel of the render, and its tile none to hand on.
            if stop.requested() {
                return Err(TileStop::Cancelled);
            }
            if let Some(rays) = stop.rays {
                rays.fetch_add(counts.total() - before, Ordering::Relaxed);
            }
            radiance.push(c);
            first_hit.push(id);
        }
    }
    Ok(Tile { x0, y0, width, height, radiance, first_hit, counts })
}

/// What stops the render at the next pixel: the caller's cancel flag, or a capped pixel.
struct Stop<'a> {
    cancel: Option<&'a AtomicBool>,
    capped: AtomicBool,
    rays: Option<&'a AtomicU64>,
}

impl Stop<'_> {
    fn requested(&self) -> bool {
        self.capped.load(Ordering::Relaxed) || self.cancel.is_some_and(|c| c.load(Ordering::Relaxed))
    }
}

/// Renders the image, or `options.region` of it, on the CPU.
pub fn render_cpu(
    scene: &FlatScene,
    options: &CpuOptions,
    control: RenderControl,
) -> Result<CpuRender, CpuRenderError> {
    let (w, h) = (scene.header.width, scene.header.height);
    let region = options.region.unwrap_or(PixelRect::full(w, h));
    if !region.within(w, h) {
        return Err(CpuRenderError::Region { region, width: w, height: h });
    }
    let threads = if options.threads == 0 { rayon::current_num_threads().max(1) } else { options.threads };
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .thread_name(|i| format!("glint-cpu-{i}"))
        .build()
        .map_err(|e| CpuRenderError::ThreadPool { threads, message: e.to_string() })?;
    let features = if options.specialise { scene.header.features } else { feature::ALL };
    let ctx = TraceContext::with_features(scene, features)?
        .with_accel(options.accel)
        .with_ray_cap(options.max_rays_per_sample)
        .with_cancel(control.cancel);
    // What the scene asks for: its header says which integrator, and its features are that one's.
    let shading = match ctx.integrator {
        Integrator::Whitted => Shading::Whitted,
        Integrator::Path => Shading::Path(Emitters::of(&ctx)),
    };
    let stop = Stop { cancel: control.cancel, capped: AtomicBool::new(false), rays: control.rays };
    let (w, h) = (region.width, region.height);
    let origins: Vec<(u32, u32)> = (0..h.div_ceil(TILE))
        .flat_map(|ty| (0..w.div_ceil(TILE)).map(move |tx| (region.x0 + tx * TILE, region.y0 + ty * TILE)))
        .collect();
    let start = Instant::now();
    // Each finished tile goes into the image at once and its buffers are freed: keeping all
    // of them until the end grew the workers' heaps page by page (thousands of mprotect calls).
    let image = std::sync::Mutex::new(HdrImage::new(w, h));
    let tiles: Vec<Result<RayCounts, TileStop>> = pool.install(|| {
        origins
            .par_iter()
            .map(|&(x0, y0)| {
                let tile = render_tile(&ctx, &shading, region, x0, y0, &stop)?;
                if let Some(cb) = control.on_tile {
                    cb(&tile);
                }
                tile.copy_into(&mut image.lock().unwrap_or_else(|e| e.into_inner()), region);
                Ok(tile.counts)
            })
            .collect()
    });
    let elapsed = start.elapsed();
    // A capped pixel is the error to report even where other tiles then saw the stop.
    if let Some((x, y)) = tiles.iter().find_map(|t| match t {
        Err(TileStop::RayCap { x, y }) => Some((*x, *y)),
        Ok(_) | Err(TileStop::Cancelled) => None,
    }) {
        return Err(CpuRenderError::RayCap { x, y, cap: options.max_rays_per_sample });
    }
    let image = image.into_inner().unwrap_or_else(|e| e.into_inner());
    let mut counts = RayCounts::default();
    for tile_counts in tiles {
        counts += tile_counts.map_err(|_| CpuRenderError::Cancelled)?;
    }
    Ok(CpuRender { image, counts, elapsed, threads })
}

/// The breakdown of one camera sample of pixel (x, y) into the terms of the model, its hit
/// point in world space.
///
/// # Errors
/// If the scene holds a tag no kind has (never for a scene from `FlatScene::build`; its fields
/// are public, so a scene built by hand may).
pub fn probe_pixel(scene: &FlatScene, x: u32, y: u32, sample: u32) -> Result<Breakdown, UnknownTag> {
    let ctx = TraceContext::new(scene)?;
    let mut b = Breakdown::default();
    let mut counts = RayCounts::default();
    render_sample(&ctx, x, y, sample, &mut counts, Some(&mut b), &mut NoTree);
    if b.object_id != glint_types::layout::NO_HIT {
        b.point += scene.frame_origin();
    }
    Ok(b)
}

/// The whole ray tree of one camera sample of pixel (x, y), as the render traced it: node 0
/// is the camera ray, its `radiance` the sample's radiance, bit for bit; its points in world
/// space.
///
/// # Errors
/// As `probe_pixel`.
pub fn probe_tree(scene: &FlatScene, x: u32, y: u32, sample: u32) -> Result<RayTree, UnknownTag> {
    let ctx = TraceContext::new(scene)?;
    let mut tree = RayTree::default();
    let mut counts = RayCounts::default();
    render_sample(&ctx, x, y, sample, &mut counts, None, &mut tree);
    tree.translate(scene.frame_origin());
    Ok(tree)
}

/// What the camera ray through the centre of pixel (x, y) hits first: picking in the viewer.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Picked {
    /// The object's id (its index in the scene's objects).
    pub object: u32,
    /// The material of the primitive hit (`FlatScene::material_names` index): one of a model's
    /// several.
    pub material: u32,
}

/// The first hit of the camera ray through the centre of pixel (x, y), `None` for none.
///
/// # Errors
/// As `probe_pixel`.
pub fn pick(scene: &FlatScene, x: u32, y: u32) -> Result<Option<Picked>, UnknownTag> {
    let ctx = TraceContext::new(scene)?;
    let h = &scene.header;
    let camera = crate::cpu::camera::camera_ray(&scene.camera, h.width, h.height, x, y, 0.5, 0.5);
    let hit = crate::cpu::walk::closest_hit(
        &ctx,
        &camera.ray,
        camera.t_min,
        crate::cpu::FAR,
        &crate::cpu::intersect::Leaving::NONE,
    );
    Ok(hit.map(|hit| {
        let s = crate::cpu::surface::surface_at(&ctx, &camera.ray, &hit);
        Picked { object: s.object_id, material: s.material }
    }))
}

/// Each pixel's first hit through its centre, row by row: the object's id, `NO_HIT` for none.
/// A one-sample Whitted render records these; a jittered render's first hits (a path's first
/// sample) fall anywhere in the pixel, and an outline drawn from them is ragged.
///
/// # Errors
/// As `probe_pixel`.
pub fn centre_hits(scene: &FlatScene) -> Result<Vec<u32>, UnknownTag> {
    let ctx = TraceContext::new(scene)?;
    let h = &scene.header;
    let hit = |x: u32, y: u32| {
        let camera = crate::cpu::camera::camera_ray(&scene.camera, h.width, h.height, x, y, 0.5, 0.5);
        let leaving = crate::cpu::intersect::Leaving::NONE;
        match crate::cpu::walk::closest_hit(&ctx, &camera.ray, camera.t_min, crate::cpu::FAR, &leaving) {
            Some(hit) => crate::cpu::surface::surface_at(&ctx, &camera.ray, &hit).object_id,
            None => glint_types::layout::NO_HIT,
        }
    };
    Ok((0..h.height).into_par_iter().flat_map_iter(|y| (0..h.width).map(move |x| hit(x, y))).collect())
}

#[cfg(test)]
mod tests {
    use super::*;
    use glint_io::builtin;

    #[test]
    fn centre_hits_are_what_picking_each_pixel_finds() {
        let b = builtin("whitted").expect("built-in scene");
        let (desc, _) = b.load(None).expect("parses");
        let settings = glint_scene::RenderSettings { width: 24, height: 18, ..desc.render.clone() };
        let scene = FlatScene::build(&desc, &settings);
        let hits = centre_hits(&scene).expect("valid tags");
        assert_eq!(hits.len(), 24 * 18);
        for (i, &id) in hits.iter().enumerate() {
            let (x, y) = ((i % 24) as u32, (i / 24) as u32);
            assert_eq!(
                pick(&scene, x, y).expect("valid tags").map_or(glint_types::layout::NO_HIT, |p| p.object),
                id,
                "({x}, {y})"
            );
        }
        assert!(hits.contains(&glint_types::layout::NO_HIT) && hits.iter().any(|&h| h != glint_types::layout::NO_HIT));
    }

    #[test]
    fn a_hand_built_scene_with_an_unknown_tag_is_an_error_to_probe_and_pick_not_a_panic() {
        let b = builtin("whitted").expect("built-in scene");
        let (desc, _) = b.load(None).expect("parses");
        let settings = glint_scene::RenderSettings { width: 8, height: 6, ..desc.render.clone() };
        let mut scene = FlatScene::build(&desc, &settings);
        let mut spheres = scene.spheres.to_vec();
        spheres[0].material = 999;
        scene.spheres = spheres.into();
        let expected = UnknownTag { what: "sphere material index", value: 999 };
        assert_eq!(probe_pixel(&scene, 4, 3, 0).err(), Some(expected));
        assert_eq!(probe_tree(&scene, 4, 3, 0).err(), Some(expected));
        assert_eq!(pick(&scene, 4, 3).err(), Some(expected));
        assert_eq!(centre_hits(&scene).err(), Some(expected));
    }

    #[test]
    fn auto_traces_small_scenes_by_brute_force_and_large_ones_through_the_bvh() {
        use crate::bvh::AUTO_MIN_PRIMITIVES;
        use crate::cpu::Traversal;
        let b = builtin("whitted").expect("built-in scene");
        let (desc, _) = b.load(None).expect("parses");
        let mut flat = FlatScene::build(&desc, &desc.render);
        assert!(flat.spheres.len() + flat.triangles.len() < AUTO_MIN_PRIMITIVES);
        assert_eq!(Accel::Auto.traversal(&flat), Traversal::BruteForce);
        assert_eq!(Accel::Bvh.traversal(&flat), Traversal::Bvh);
        assert_eq!(Accel::None.traversal(&flat), Traversal::BruteForce);
        let sphere = flat.spheres[0];
        flat.spheres = vec![sphere; AUTO_MIN_PRIMITIVES - flat.triangles.len()].into();
        assert_eq!(Accel::Auto.traversal(&flat), Traversal::Bvh);
        assert_eq!(Accel::None.traversal(&flat), Traversal::BruteForce);
    }

    #[test]
    fn a_flat_scene_with_an_unknown_tag_is_refused_not_traced() {
        let b = builtin("spotlights").expect("built-in scene");
        let (desc, _) = b.load(None).expect("parses");
        let mut settings = desc.render.clone();
        (settings.width, settings.height) = (8, 8);
        let mut flat = FlatScene::build(&desc, &settings);
        flat.lights[0].kind = 9;
        let err = render_cpu(&flat, &CpuOptions::default(), RenderControl::default()).unwrap_err();
        assert_eq!(err.to_string(), "invalid flat scene: 9 is not a valid light kind");
        let mut flat = FlatScene::build(&desc, &settings);
        flat.header.epsilon_mode = 17;
        let err = render_cpu(&flat, &CpuOptions::default(), RenderControl::default()).unwrap_err();
        assert_eq!(err.to_string(), "invalid flat scene: 17 is not a valid epsilon mode");
    }
}
