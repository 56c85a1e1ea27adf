//! CPU twin of `shaders/trace.wgsl`: the Whitted ray tree and the pixel loop.
//!
//! The CPU recurses; the GPU walks the same tree with an explicit stack. Both add
//! k_r·I_r and k_t·I_t with the same path weights and the same bailout decisions, so only the
//! order of summation differs.

use glam::DVec3;

use super::FAR;
use super::camera::{camera_ray, eye, from_eye, sample_offset};
use super::intersect::{Hit, Leaving, Prim, all_zero};
use super::offset::{leaving_surface, spawn_ray};
use super::ray_tree::{Cut, NoTree, RayNode, TreeRecorder, record_shadow_rays};
use super::shade::{Breakdown, attenuation_factor, shade_local};
use super::surface::{max_channel, reflect_dir, refract_dir, surface_at};
use super::walk::closest_hit;
use super::{Ray, RayCounts, TraceContext, v3};
use glint_types::RayKind;
use glint_types::layout::{NO_HIT, feature};

/// Radiance along a child ray: background on a miss, else the shaded hit — times the world's
/// global attenuation f_att(t) when it is on: what the ray brings back, and the path weight its
/// own children's bailout is judged by. The background, like a directional light, is not
/// attenuated (it lies at no distance). `node` is the ray's node in `rec`'s tree.
#[allow(clippy::too_many_arguments)]
pub fn trace_ray<R: TreeRecorder>(
    ctx: &TraceContext,
    ray: &Ray,
    t_min: f64,
    leaving: &Leaving,
    depth: u32,
    weight: DVec3,
    counts: &mut RayCounts,
    rec: &mut R,
    node: usize,
) -> DVec3 {
    let mut terms = Breakdown::default();
    let probe = if R::RECORDS { Some(&mut terms) } else { None };
    let (radiance, shaded, t, f) = match closest_hit(ctx, ray, t_min, FAR, leaving) {
        Some(hit) if ctx.has(feature::GLOBAL_ATTENUATION) => {
            let f = attenuation_factor(ctx.scene.header.global_attenuation, hit.t);
            let shaded = shade_hit(ctx, ray, &hit, depth, weigh(weight, DVec3::splat(f)), counts, probe, rec, node);
            (f * shaded, shaded, Some(hit.t), f)
        }
        Some(hit) => {
            let shaded = shade_hit(ctx, ray, &hit, depth, weight, counts, probe, rec, node);
            (shaded, shaded, Some(hit.t), 1.0)
        }
        None => {
            let bg = v3(ctx.scene.header.background);
            (bg, bg, None, 1.0)
        }
    };
    if R::RECORDS {
        terms.total = shaded;
        rec.close(node, t, f, t.map(|_| terms), radiance);
    }
    radiance
}

/// A path weight times v, in f32 as the GPU's twin (`trace.wgsl`'s `weigh`) forms it, a zero
/// of v staying zero: the weight only decides the bailout, and the two tracers must decide
/// alike. f64's product of 0.2 and 5/255 (as stored) fell just below f32's 1/255, the GPU's
/// rounded onto it: the GPU traced a generation the CPU cut, every pixel 3.9e-3 apart (a
/// tester). f32's product of f32 values is correctly rounded in Rust and in WGSL alike.
pub fn weigh(weight: DVec3, v: DVec3) -> DVec3 {
    let product = (weight.as_vec3() * v.as_vec3()).as_dvec3();
    DVec3::select(v.cmpeq(DVec3::ZERO), DVec3::ZERO, product)
}

/// Local model plus k_r·I_r + k_t·I_t at a hit. `weight` is the product of k along the path
/// to this hit; a child whose path weight falls below the bailout is not traced. A recording
/// `rec` also gets the hit's shadow rays and the children the bailout, the depth limit or the
/// ray cap cut, as children of `node`.
#[allow(clippy::too_many_arguments)]
pub fn shade_hit<R: TreeRecorder>(
    ctx: &TraceContext,
    ray: &Ray,
    hit: &Hit,
    depth: u32,
    weight: DVec3,
    counts: &mut RayCounts,
    mut probe: Option<&mut Breakdown>,
    rec: &mut R,
    node: usize,
) -> DVec3 {
    let s = surface_at(ctx, ray, hit);
    // Two-sided shading: turn the normals to face the incoming ray; which side was hit
    // (entering or leaving) is read from the geometric normal.
    let front = ray.dir.dot(s.ng) < 0.0;
    let (ng, ns) = if front { (s.ng, s.ns) } else { (-s.ng, -s.ns) };
    let v = -ray.dir;
    let mut radiance = shade_local(ctx, &s, ns, ng, v, counts, probe.as_deref_mut());
    if let Some(b) = probe.as_deref_mut() {
        b.object_id = s.object_id;
        b.material = s.material;
        b.t = hit.t;
        b.point = s.p;
        b.normal = ns;
        if R::RECORDS {
            record_shadow_rays(ctx, rec, node, depth, weight, s.p, b);
        }
    }
    // A recording walks on past the depth limit only to record the children it cuts.
    let depth_cut = depth >= ctx.max_depth;
    if (depth_cut && !R::RECORDS) || !feature::recurses(ctx.features) {
        return radiance;
    }
    let mat = &ctx.scene.materials[s.material as usize];
    let kr = v3(mat.kr);
    let kt = v3(mat.kt);
    // Under total internal reflection the k_t share follows the mirror direction.
    let mut k_mirror = kr;
    let mut refracted = None;
    let mut tir = false;
    if ctx.has(feature::TRANSMISSION) && !all_zero(kt) {
        let ior = f64::from(mat.ior);
        let eta = if front { 1.0 / ior } else { ior };
        match refract_dir(ray.dir, ns, eta) {
            Some(dir) => refracted = Some(dir),
            None => {
                k_mirror += kt;
                tir = true;
            }
        }
    }
    // A child that is not traced, as the tree records it: from the hit point, flagged cut.
    // `w`: the child's path weight as the bailout judged it.
    let cut = |rec: &mut R, kind: RayKind, dir: DVec3, k: DVec3, w: DVec3, why: Cut| {
        let mut child = RayNode::new(kind, Some(node), depth + 1, &Ray { origin: s.p, dir }, k, w);
        child.cut = Some(why);
        child.tir = tir && kind == RayKind::Reflection;
        rec.open(child);
    };
    if !all_zero(k_mirror) {
        // Under total internal reflection the GPU sums k_r + k_t in f32, as its weight is.
        let w = if tir { weigh(weight, (kr.as_vec3() + kt.as_vec3()).as_dvec3()) } else { weigh(weight, k_mirror) };
        if R::RECORDS && depth_cut {
            cut(rec, RayKind::Reflection, reflect_dir(ray.dir, ns), k_mirror, w, Cut::MaxDepth);
        } else if ctx.cap_reached(counts) {
            if R::RECORDS {
                cut(rec, RayKind::Reflection, reflect_dir(ray.dir, ns), k_mirror, w, Cut::RayCap);
            }
            return radiance;
        } else if max_channel(w) < ctx.bailout {
            counts.bailout_saved += 1;
            if R::RECORDS {
                cut(rec, RayKind::Reflection, reflect_dir(ray.dir, ns), k_mirror, w, Cut::Bailout);
            }
        } else {
            counts.reflection += 1;
            let dir = reflect_dir(ray.dir, ns);
            let sp = spawn_ray(ctx, s.p, s.p_surface, ng, dir, leaving_surface(s.prim, s.index, s.ng, ng));
            let child_ray = Ray { origin: sp.origin, dir };
            let mut child_node = RayNode::new(RayKind::Reflection, Some(node), depth + 1, &child_ray, k_mirror, w);
            child_node.tir = tir;
            let child = if R::RECORDS { rec.open(child_node) } else { 0 };
            let i_r = trace_ray(ctx, &child_ray, sp.t_min, &sp.leaving, depth + 1, w, counts, rec, child);
            radiance += k_mirror * i_r;
            if let Some(b) = probe.as_deref_mut() {
                // One ray serves k_r and, under total internal reflection, k_t: list both.
                b.reflected = kr * i_r;
                if refracted.is_none() {
                    b.transmitted = kt * i_r;
                }
            }
        }
    }
    if let Some(dir) = refracted {
        let w = weigh(weight, kt);
        if R::RECORDS && depth_cut {
            cut(rec, RayKind::Refraction, dir, kt, w, Cut::MaxDepth);
            return radiance;
        }
        if ctx.cap_reached(counts) {
            if R::RECORDS {
                cut(rec, RayKind::Refraction, dir, kt, w, Cut::RayCap);
            }
            return radiance;
        }
        if max_channel(w) < ctx.bailout {
            counts.bailout_saved += 1;
            if R::RECORDS {
                cut(rec, RayKind::Refraction, dir, kt, w, Cut::Bailout);
            }
        } else {
            counts.refraction += 1;
            let sp = spawn_ray(ctx, s.p, s.p_surface, -ng, dir, leaving_surface(s.prim, s.index, s.ng, -ng));
            let ray = Ray { origin: sp.origin, dir };
            let child = if R::RECORDS {
                rec.open(RayNode::new(RayKind::Refraction, Some(node), depth + 1, &ray, kt, w))
            } else {
                0
            };
            let term = kt * trace_ray(ctx, &ray, sp.t_min, &sp.leaving, depth + 1, w, counts, rec, child);
            radiance += term;
            if let Some(b) = probe {
                b.transmitted = term;
            }
        }
    }
    radiance
}

/// The object id of a hit's primitive.
pub fn object_id(ctx: &TraceContext, hit: &Hit) -> u32 {
    let s = ctx.scene;
    match hit.prim {
        Prim::Sphere => s.spheres[hit.index as usize].object_id,
        Prim::Plane => s.planes[hit.index as usize].object_id,
        Prim::Triangle => s.meshes[s.triangles[hit.index as usize].mesh as usize].object_id,
    }
}

/// One camera sample: radiance and the id of the first object hit (`NO_HIT` for none).
/// Its rays are added to `counts`; a tree cut at `max_rays_per_sample` adds one capped sample.
/// A recording `rec` gets the sample's whole ray tree, the camera ray its node 0.
pub fn render_sample<R: TreeRecorder>(
    ctx: &TraceContext,
    x: u32,
    y: u32,
    sample: u32,
    counts: &mut RayCounts,
    probe: Option<&mut Breakdown>,
    rec: &mut R,
) -> (DVec3, u32) {
    let h = &ctx.scene.header;
    let pixel = y * h.width + x;
    // Whitted's one sample is the pixel's centre, also in a tracer with every feature on.
    let (ox, oy) = sample_offset(pixel, sample, h.spp, h.seed, ctx.has(feature::JITTER) && h.spp > 1);
    let camera = camera_ray(&ctx.scene.camera, h.width, h.height, x, y, ox, oy);
    let ray = camera.ray;
    // Recorded from the eye, where the camera ray leaves (traced from the anchor's plane).
    let node = if R::RECORDS {
        let eye_ray = Ray { origin: eye(&camera), dir: ray.dir };
        rec.open(RayNode::new(RayKind::Camera, None, 0, &eye_ray, DVec3::ONE, DVec3::ONE))
    } else {
        0
    };
    match closest_hit(ctx, &ray, camera.t_min, FAR, &Leaving::NONE) {
        Some(hit) => {
            let object = object_id(ctx, &hit);
            let mut terms = Breakdown::default();
            let mut probe = match probe {
                Some(b) => Some(b),
                None if R::RECORDS => Some(&mut terms),
                None => None,
            };
            // The tree's own counts: the cap bounds one tree, whatever the pixel traced before.
            let mut own = RayCounts { camera: 1, ..RayCounts::default() };
            let radiance = shade_hit(ctx, &ray, &hit, 0, DVec3::ONE, &mut own, probe.as_deref_mut(), rec, node);
            *counts += own;
            if let Some(b) = probe {
                b.total = radiance;
                b.t = from_eye(&camera, hit.t);
                if R::RECORDS {
                    rec.close(node, Some(b.t), 1.0, Some(b.clone()), radiance);
                }
            }
            (radiance, object)
        }
        None => {
            counts.camera += 1;
            let bg = v3(h.background);
            if let Some(b) = probe {
                *b = Breakdown { object_id: NO_HIT, total: bg, ..Breakdown::default() };
            }
            if R::RECORDS {
                rec.close(node, None, 1.0, None, bg);
            }
            (bg, NO_HIT)
        }
    }
}

/// The mean over all samples of a pixel, and the first sample's first-hit object.
pub fn render_pixel(ctx: &TraceContext, x: u32, y: u32, counts: &mut RayCounts) -> (DVec3, u32) {
    let spp = ctx.scene.header.spp;
    let (mut sum, first) = render_sample(ctx, x, y, 0, counts, None, &mut NoTree);
    for s in 1..spp {
        sum += render_sample(ctx, x, y, s, counts, None, &mut NoTree).0;
    }
    (sum / f64::from(spp), first)
}
