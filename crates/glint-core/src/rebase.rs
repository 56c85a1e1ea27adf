//! View-relative coordinates for the f32 tracer. A flat scene is stored relative to its
//! geometry (`glint_scene::storage_origin`), so f32 holds its positions to the scene's own
//! size; but every f32 hit point still carries the error of its distance from that origin, so
//! a camera looking at a detail far out in a large scene would see it to the scene's size, not
//! the detail's. `rebased` moves the origin to where the camera's centre ray meets the scene
//! (`camera_frame`) — each stored position widened to f64, the origin subtracted in f64, and
//! only then rounded to f32 — so that f32 carries the distances within the view instead. The
//! CPU reference keeps tracing the scene as stored (its f64 has the digits).
//!
//! What moves: vertex positions (one buffer, so a vertex shared by triangles maps to one value
//! and watertightness holds), sphere centres, plane offsets d' = d − n·c, point and spot light
//! positions, the camera (its eye; anchored anew nearest the new origin), BVH boxes (rounded
//! outward, so traversal stays conservative) and the header's frame (the origin, added back for planar texture
//! coordinates, and the offsets' length scale). Directions, normals, radii, texture
//! coordinates and everything else are unchanged.

use glam::DVec3;

use crate::FlatScene;
use crate::bvh::{f32_down, f32_up};
use crate::cpu::intersect::Leaving;
use crate::cpu::walk::closest_hit;
use crate::cpu::{Ray, TraceContext, v3};
use crate::flat::{anchor_of, camera_eye, move_texture_origins, scene_box, telephoto};
use glint_scene::LightKind;
use glint_types::layout::{GpuPlane, GpuSphere, origin_power};

/// Where the GPU's coordinates have their origin.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub enum Frame {
    /// Where the camera looks (the default): `camera_frame`.
    #[default]
    Camera,
    /// As the flat scene is stored (`SceneHeader::frame`): the GPU's error then grows with the
    /// distance from that origin (kept to measure exactly that; a scene rebased to
    /// `WORLD_FRAME` first is traced in world space).
    Stored,
}

impl Frame {
    /// The frame (`SceneHeader::frame`) this choice rebases `scene` into, `None` where it is
    /// traced as stored. Where the camera looks: `camera_frame`, unless that is the frame it is
    /// stored in, but also then for a telephoto whose eye is stored itself
    /// (`unanchored_telephoto`), which a rebase anchors at the focus.
    pub fn rebased_into(self, scene: &FlatScene) -> Option<[f32; 4]> {
        match self {
            Frame::Camera => {
                let frame = camera_frame(scene);
                (frame != scene.header.frame || unanchored_telephoto(scene)).then_some(frame)
            }
            Frame::Stored => None,
        }
    }
}

/// A stored point moved by −c: the difference in f64, rounded once.
fn moved(p: [f32; 4], c: DVec3) -> [f32; 4] {
    let q = v3(p) - c;
    [q.x as f32, q.y as f32, q.z as f32, p[3]]
}

/// 2^k for the integer k nearest log2 x (x > 0 and finite).
fn nearest_power_of_two(x: f64) -> f64 {
    2f64.powi(x.log2().round().clamp(-1000.0, 1000.0) as i32)
}

/// How far the scene's surfaces reach from `from` (its own coordinates): the farthest corner of
/// the box around the bounded geometry, the farthest plane. 0 for a scene without surfaces.
/// Lights are not surfaces: a shadow ray's end at a light carries an error of its angle (2^-24),
/// wherever the frame is, so a far light (a sun as a point light) is no reason to coarsen it.
pub fn reach(scene: &FlatScene, from: DVec3) -> f64 {
    let mut r = 0.0_f64;
    if let Some(root) = scene.bvh_nodes.first() {
        let lo = DVec3::from(root.min.map(f64::from)) - from;
        let hi = DVec3::from(root.max.map(f64::from)) - from;
        r = r.max(lo.abs().max(hi.abs()).length());
    }
    for p in scene.planes.iter() {
        let no = p.normal_offset;
        r = r.max((v3(no).dot(from) - f64::from(no[3])).abs());
    }
    r
}

/// How large a length the offsets' scale is chosen for: how far the surfaces reach from the
/// focus; for a focus on a lone plane, which reaches nothing beyond it, the image's height there.
fn extent(scene: &FlatScene, eye: DVec3, focus: DVec3) -> f64 {
    let r = reach(scene, focus);
    if r > 0.0 { r } else { pixel_at(scene, eye, focus) * f64::from(scene.header.height) }
}

/// The height of a pixel where the centre ray meets `focus` (an orthographic camera's at any
/// distance).
fn pixel_at(scene: &FlatScene, eye: DVec3, focus: DVec3) -> f64 {
    let distance = if scene.camera.is_orthographic() { 1.0 } else { (focus - eye).length() };
    2.0 * v3(scene.camera.up).length() * distance / f64::from(scene.header.height.max(1))
}

/// How much finer than the scene's reach the grid of frame origins is (a power of two).
const GRID_DIVISIONS: f64 = 16.0;

/// At most how many pixels (their height at the focus) the grid's spacing is: c is then within
/// 222 pixels of the focus, f32's error there 1.3e-5 of a pixel and W&B's offset (256 of its
/// ulps) 3.4e-3 of one.
const GRID_PIXELS: f64 = 256.0;

/// Where the f32 tracer's digits matter most, for a camera at `eye` in a scene reaching `r`
/// from it: the first surface the ray through the image centre meets within the reach (found
/// by the CPU reference); if it meets none there, the centre of the bounded geometry; if there
/// is none, the foot of the eye on the nearest plane (the ground under a camera looking along
/// it, farther than 2R: R is then the eye's height); if there is none, the eye. Within the
/// reach: a ray grazing an infinite plane meets it arbitrarily far away (3e9 was seen orbiting
/// a model over its floor), and an origin there would cost every point of the scene its digits.
fn focus_within(scene: &FlatScene, eye: DVec3, r: f64) -> DVec3 {
    let forward = v3(scene.camera.forward);
    if let Ok(ctx) = TraceContext::new(scene)
        && forward.length() > 0.0
        && r.is_finite()
    {
        let ray = Ray { origin: eye, dir: forward.normalize() };
        // 2R: a surface at the reach itself (a floor straight below the eye) is met at t = R.
        if let Some(hit) = closest_hit(&ctx, &ray, 0.0, 2.0 * r, &Leaving::NONE) {
            return eye + hit.t * ray.dir;
        }
    }
    if let Some(b) = scene_box(&scene.bvh_nodes) {
        return b.centre;
    }
    let height = |p: &GpuPlane| v3(p.normal_offset).dot(eye) - f64::from(p.normal_offset[3]);
    match scene.planes.iter().min_by(|a, b| height(a).abs().total_cmp(&height(b).abs())) {
        Some(p) => eye - height(p) * v3(p.normal_offset),
        None => eye,
    }
}

/// The frame the GPU traces `scene` in (a world-space origin and a length scale): the focus
/// (`focus_within`) snapped to a grid of spacing g, the power of two nearest the smaller of
/// R/16 (R how far the scene's surfaces reach from the eye, `reach`) and 256 pixels at the focus
/// (`GRID_PIXELS`), and the offsets' length scale min(1, the power of two nearest the surfaces'
/// reach from the focus, `extent`).
///
/// Why the focus: an f32 hit point p carries an error of ulp(|p − c|), so the origin belongs
/// where the rays meet the scene — for a model seen from afar, the model; for the ground seen
/// from just above it, the ground under the camera. Near the eye it would be as far from the
/// model as the camera is, and coarser (measured on stiff case 17's scene: FLIP 7.1e-5 with the
/// origin at the eye against 1.6e-5 with it at the world origin, next to the model).
///
/// Why a grid this fine: c is within √3·g/2 < R/13 of the focus, so f32 keeps all but a
/// thirteenth of the range the focus itself would give; and c moves with the scene —
/// translating the scene (camera included) by any multiple of g moves the focus and c by
/// exactly as much, so the rebased scene, hence the GPU's image, is bit for bit the same for a
/// scene stored exactly at both places. A camera orbiting a model keeps its focus on the model
/// and moves c rarely, so the rebased geometry is rarely rebuilt (the GPU tracer keeps it
/// until c moves).
///
/// Why at most 256 pixels, and R without lights: R/16 alone let a far eye (a telephoto view
/// from 1e6), a far point light (a sun 1e6 away, when R counted lights) or a far plane make g
/// 2^16 and put c up to 5e4 from what is seen: a sphere seen from 1e6 at x = 30,000 had the
/// GPU's shading 4.7e-4 off the CPU's at D = 1e5 (1.1e-6 now, stiff case 22), a scene at
/// x = 5,000 under a far light 0.6 (PSNR 34.5 dB against 133.7 with the light near, case 23).
/// Bounding g by the pixel instead of the scene's size keeps R/16 — stable while orbiting, as
/// the focus moves over a model — wherever a pixel is larger than R/4096, as in every image a
/// camera around the scene makes.
///
/// Why the length scale: W&B's fixed offset near the origin (FLOAT_SCALE·n below |x| < 1/32) is
/// made for scenes of unit size; in a smaller scene it would move rays by a sizeable part of
/// it. Never above 1, so larger scenes keep W&B's constants.
pub fn camera_frame(scene: &FlatScene) -> [f32; 4] {
    let eye = camera_eye(&scene.camera);
    let r = reach(scene, eye);
    // An anchored camera looks at its anchor, which can lie beyond 2R (a telephoto over a plane
    // seen under 30° of elevation): the centre ray is followed that far.
    let focus = focus_within(scene, eye, r.max(f64::from(scene.camera.anchor[3])));
    let (pixel, extent) = (pixel_at(scene, eye, focus), extent(scene, eye, focus));
    if !(r.is_finite() && r > 0.0 && focus.is_finite() && pixel > 0.0 && extent > 0.0) {
        return scene.header.frame;
    }
    let g = nearest_power_of_two((r / GRID_DIVISIONS).min(GRID_PIXELS * pixel));
    let world = focus + scene.frame_origin();
    let c = (world / g).round() * g;
    let w = nearest_power_of_two(extent).min(1.0);
    [c.x as f32, c.y as f32, c.z as f32, w as f32]
}

/// A telephoto (`flat::telephoto`, a field of view under 0.9°) stored with its eye (w = 0): in
/// a scene as large as its distance, which anchors no eye by the distance. The CPU sums each
/// ray's direction in f64 from the stored vectors; the GPU's f32 sum, each component of order 1
/// with a step of 6e-8, moves the ray a share of a pixel that grows as the field narrows (a
/// 1e5 triangle seen from 1.1e5 through 0.0025°: 1/20 of a pixel, and shading 4 % off the CPU's
/// under a spot light's edge). Anchored near the focus, the sum's error acts over the distance
/// from there only.
fn unanchored_telephoto(scene: &FlatScene) -> bool {
    let c = &scene.camera;
    c.anchor[3] == 0.0 && telephoto(v3(c.forward), v3(c.up), c.is_orthographic())
}

/// `scene` in `frame` (see the module comment): positions moved by the difference between
/// `frame`'s origin and the scene's own, in f64, rounded once; the header's frame set. The
/// result renders the same scene on either tracer.
pub fn rebased(scene: &FlatScene, frame: [f32; 4]) -> FlatScene {
    let c = v3(frame) - scene.frame_origin();
    let mut out = scene.clone();
    if c != DVec3::ZERO {
        out.vertices = scene.vertices.iter().map(|v| moved(*v, c)).collect();
        out.spheres = scene
            .spheres
            .iter()
            .map(|s| {
                let center_radius = moved(s.center_radius, c);
                GpuSphere { center_radius, power: origin_power(center_radius), ..*s }
            })
            .collect();
        out.planes = scene
            .planes
            .iter()
            .map(|p| {
                let no = p.normal_offset;
                GpuPlane { normal_offset: [no[0], no[1], no[2], (f64::from(no[3]) - v3(no).dot(c)) as f32], ..*p }
            })
            .collect();
        out.bvh_nodes = scene.bvh_nodes.map(|n| {
            let mut n = *n;
            for k in 0..3 {
                n.min[k] = f32_down(f64::from(n.min[k]) - c[k]);
                n.max[k] = f32_up(f64::from(n.max[k]) - c[k]);
            }
            n
        });
    }
    move_the_rest(&mut out, scene, frame);
    out
}

/// `rebased`, its geometry taken from `geometry`, a scene `rebased` made of the same geometry
/// in the same frame: only the camera, the lights and the header are moved, and the geometry
/// stays the same data (`FlatScene::geometry_id`), which the GPU tracer does not upload again.
pub fn rebased_with_geometry(scene: &FlatScene, frame: [f32; 4], geometry: &FlatScene) -> FlatScene {
    let mut out = scene.clone();
    out.vertices = geometry.vertices.clone();
    out.spheres = geometry.spheres.clone();
    out.planes = geometry.planes.clone();
    out.bvh_nodes = geometry.bvh_nodes.clone();
    move_the_rest(&mut out, scene, frame);
    out
}

/// Moves `out`'s camera and point and spot lights (from `scene`'s) into `frame`, sets it, and
/// moves the textures' planar origins with it (`move_texture_origins`).
fn move_the_rest(out: &mut FlatScene, scene: &FlatScene, frame: [f32; 4]) {
    let c = v3(frame) - scene.frame_origin();
    out.header.frame = frame;
    move_texture_origins(out, scene.frame_origin(), v3(frame));
    // An anchored camera's eye, or a telephoto's (`unanchored_telephoto`), moved in f64 and
    // anchored anew, nearest the new origin (the focus, snapped); any other eye that is its own
    // anchor (w = 0) moved as the other points.
    out.camera.anchor = if scene.camera.anchor[3] > 0.0 || unanchored_telephoto(scene) {
        anchor_of(camera_eye(&scene.camera) - c, v3(scene.camera.forward), DVec3::ZERO)
    } else {
        moved(scene.camera.anchor, c)
    };
    for (l, from) in out.lights.iter_mut().zip(&scene.lights) {
        match LightKind::try_from(l.kind) {
            Ok(LightKind::Point | LightKind::Spot) => l.position = moved(from.position, c),
            // A directional light's position is unused; a tag no kind has is refused before
            // upload (`FlatScene::check_tags`).
            Ok(LightKind::Directional) | Err(_) => {}
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The focus of the scene's own camera.
    fn focus(scene: &FlatScene) -> DVec3 {
        let eye = camera_eye(&scene.camera);
        focus_within(scene, eye, reach(scene, eye))
    }
    use glint_io::parse_scene;
    use glint_types::layout::{BvhNode, WORLD_FRAME};

    /// Points the camera from `eye` along `forward` (the stored anchor placed anew).
    fn look(scene: &mut FlatScene, eye: DVec3, forward: [f32; 3]) {
        scene.camera.forward = [forward[0], forward[1], forward[2], 0.0];
        scene.camera.anchor = [eye.x as f32, eye.y as f32, eye.z as f32, 0.0];
    }

    #[test]
    fn a_telephoto_stored_with_its_eye_is_anchored_at_the_focus_even_in_its_own_frame() {
        // A 0.0025° view from 1.1e5 of a triangle as large: the distance anchors nothing.
        let text = "[render]\nwidth = 63\nheight = 34\n[camera]\nposition = [-64808.9, 15028.5, -91666.3]\n\
                    look_at = [-0.46, 0.56, -0.36]\nfov_y = 0.00253\n[materials.m]\nkd = 0.8\n[[objects]]\n\
                    type = \"mesh\"\nvertices = [[-53954.0, 0.75, -53954.0], [53954.0, 0.75, -53954.0], \
                    [0.0, 0.75, 53954.0]]\ntriangles = [[0, 1, 2]]\nmaterial = \"m\"\n";
        let (desc, _) = parse_scene(text, std::path::Path::new("t.toml")).expect("scene");
        let stored = FlatScene::build(&desc, &desc.render);
        assert_eq!(stored.camera.anchor[3], 0.0, "stored with its eye");
        let frame = Frame::Camera.rebased_into(&stored).expect("rebased although its frame is the stored one");
        assert_eq!(frame[..3], stored.header.frame[..3]);
        let traced = rebased(&stored, frame);
        // The focus is where the axis meets the triangle, near look_at (1.13e5 from the eye).
        let w = f64::from(traced.camera.anchor[3]);
        let to_look_at = (DVec3::new(-0.46, 0.56, -0.36) - DVec3::new(-64808.9, 15028.5, -91666.3)).length();
        assert!((w - to_look_at).abs() < 10.0, "anchored {w} from the eye, not at the focus ({to_look_at})");
        assert!((camera_eye(&traced.camera) - camera_eye(&stored.camera)).length() < 1e-2, "the eye moved");
        assert_eq!(Frame::Stored.rebased_into(&stored), None, "as stored means as stored");
        // A normal lens there keeps its eye.
        let mut wide = desc.clone();
        wide.camera.fov_y = 40.0;
        assert_eq!(Frame::Camera.rebased_into(&FlatScene::build(&wide, &wide.render)), None);
    }

    fn scene(offset: f64) -> FlatScene {
        let text = format!(
            r#"
[render]
width = 8
height = 6
[camera]
position = [{o}, 1.0, -5.0]
look_at = [{o}, 0.0, 0.0]
[[lights]]
type = "point"
position = [{o}, 4.0, -2.0]
[[lights]]
type = "directional"
direction = [0.0, -1.0, 0.0]
[materials.m]
kd = 0.5
[[objects]]
type = "sphere"
center = [{o}, 0.5, 0.0]
radius = 0.5
material = "m"
[[objects]]
type = "plane"
point = [0.0, 0.0, 0.0]
normal = [0.0, 1.0, 0.0]
material = "m"
[[objects]]
type = "mesh"
vertices = [[{o}, 0.0, 1.0], [{p}, 0.0, 1.0], [{o}, 1.0, 1.0], [{p}, 1.0, 1.0]]
triangles = [[0, 1, 2], [1, 3, 2]]
material = "m"
"#,
            o = offset,
            p = offset + 1.0
        );
        let (desc, _) = parse_scene(&text, std::path::Path::new("t.toml")).expect("scene");
        FlatScene::build(&desc, &desc.render)
    }

    #[test]
    fn a_rebased_scene_rebuilt_with_another_camera_keeps_its_frame() {
        // A sphere of radius 5e-3 seen from 5e-2: the camera frame's length scale is below 1.
        let text = "[camera]\nposition = [1e6, 0.01, -0.05]\nlook_at = [1e6, 0.0, 0.0]\n[materials.m]\nkd = 0.5\n\
                    [[objects]]\ntype = \"sphere\"\ncenter = [1e6, 0.005, 0.0]\nradius = 0.005\nmaterial = \"m\"\n";
        let (mut desc, _) = parse_scene(text, std::path::Path::new("t.toml")).expect("scene");
        let stored = FlatScene::build(&desc, &desc.render);
        assert_eq!(stored.header.frame[0], 1e6, "stored relative to the sphere");
        let r = rebased(&stored, camera_frame(&stored));
        assert!(r.header.frame[3] < 1.0, "the length scale of a small scene: {:?}", r.header.frame);
        desc.camera.position[1] = 0.02;
        let rebuilt = r.rebuild(&desc, &desc.render);
        assert_eq!(rebuilt.header.frame, r.header.frame);
        assert_eq!(rebuilt.camera, rebased(&FlatScene::build(&desc, &desc.render), r.header.frame).camera);
    }

    #[test]
    fn rebasing_moves_positions_and_keeps_the_rest() {
        let world = scene(1e6);
        let frame = [1e6, 1.0, -5.0, 1.0];
        let r = rebased(&world, frame);
        // The eye, its own anchor, at the frame's origin.
        assert_eq!(r.camera.anchor, [0.0, 0.0, 0.0, 0.0]);
        assert_eq!(r.camera.forward, world.camera.forward);
        assert_eq!(r.spheres[0].center_radius, [0.0, -0.5, 5.0, 0.5]);
        // y = 0 moved by the eye's y = 1: n·x = d becomes n·x = d − n·c.
        assert_eq!(r.planes[0].normal_offset, [0.0, 1.0, 0.0, -1.0]);
        assert_eq!(r.lights[0].position[..3], [0.0, 3.0, 3.0]);
        assert_eq!(r.lights[1].position, world.lights[1].position);
        // Shared vertices are one entry each: the two triangles still share their edge.
        assert_eq!(r.vertices.len(), 4);
        assert_eq!(r.vertices[3], [1.0, 0.0, 6.0, 1.0]);
        assert_eq!(r.header.frame, frame);
        // Stored relative to its geometry (`storage_origin`), the scene moves by the difference.
        assert_ne!(world.header.frame, WORLD_FRAME);
        let moved_by = v3(frame) - world.frame_origin();
        for (a, b) in r.bvh_nodes.iter().zip(world.bvh_nodes.iter()) {
            for (k, c) in moved_by.to_array().into_iter().enumerate() {
                assert!(f64::from(a.min[k]) <= f64::from(b.min[k]) - c, "min[{k}] not rounded down");
                assert!(f64::from(a.max[k]) >= f64::from(b.max[k]) - c, "max[{k}] not rounded up");
            }
        }
        // Back to the storage frame: the stored scene again.
        let back = rebased(&r, world.header.frame);
        assert_eq!(back.spheres, world.spheres);
        assert_eq!(back.vertices, world.vertices);
    }

    #[test]
    fn the_frame_is_where_the_centre_ray_meets_the_scene_on_a_grid_that_moves_with_it() {
        let near = scene(0.0);
        let r = reach(&near, camera_eye(&near.camera));
        // The farther of the box's far corner (1, 0, 1) and the plane (1 below the eye); not the
        // light, which is no surface.
        assert!((r - 38.0_f64.sqrt()).abs() < 1e-9, "{r}");
        // The centre ray (from (0, 1, −5) to the origin) meets the sphere of radius 0.5 at (0, 0.5, 0).
        let f = focus(&near);
        let d = f - DVec3::new(0.0, 0.5, 0.0);
        assert!((d.length() - 0.5).abs() < 1e-9 && f.z < 0.0, "{f}");
        // R ≈ 6.2: a grid of g = 0.5 (a pixel is 0.68 there), the focus within g/2 of the
        // origin per axis.
        let c = camera_frame(&near);
        for k in 0..3 {
            assert_eq!((f64::from(c[k]) / 0.5).fract(), 0.0, "{c:?}");
            assert!((f64::from(c[k]) - f[k]).abs() <= 0.25, "{c:?} {f}");
        }
        // The offsets' length scale from the surfaces' reach from the focus, ≈ 1.9 (the box's
        // corner (1, 1, 1)).
        let extent = extent(&near, camera_eye(&near.camera), f);
        assert!(extent > 1.8 && extent < 2.0 && c[3] == 1.0, "{extent} {c:?}");
        // Translated by a multiple of g: the frame moves as much, the rebased scene not at all.
        let far = scene(1e6);
        let cf = camera_frame(&far);
        assert_eq!(cf, [c[0] + 1e6, c[1], c[2], c[3]]);
        let (a, b) = (rebased(&near, c), rebased(&far, cf));
        assert_eq!(a.vertices, b.vertices);
        assert_eq!(a.spheres, b.spheres);
        assert_eq!(a.camera, b.camera);
        assert_eq!(a.lights, b.lights);
        assert!(a.bvh_nodes.iter().eq(b.bvh_nodes.iter()));
        // Not by a multiple: rounded differently.
        let off = scene(1e6 + 0.125);
        assert_ne!(rebased(&off, camera_frame(&off)).vertices, a.vertices);
    }

    #[test]
    fn neither_a_far_light_nor_a_far_eye_coarsens_the_frame() {
        // At x = 3,000: a grid of 2^16 would put the frame's origin at x = 0.
        let near = scene(3000.0);
        let c = camera_frame(&near);
        assert_eq!(c[0], 3000.0);
        // A point light 1e6 above (the sun as a point light).
        let mut far_light = near.clone();
        far_light.lights[0].position[1] = 1e6;
        assert_eq!(camera_frame(&far_light), c);
        // The eye 1e6 back along its axis (anchored on it), its field of view narrowed to show
        // the same (a telephoto): the same focus and pixel there (0.68), so a grid of at most 256
        // pixels (2^7) where R/16 would be 2^16.
        let mut far_eye = near.clone();
        let (eye, forward) = (camera_eye(&near.camera), v3(near.camera.forward));
        far_eye.camera.anchor = anchor_of(eye - 1e6 * forward, forward, DVec3::ZERO);
        let zoom = |v: [f32; 4]| v.map(|x| (f64::from(x) * 4.9 / (4.9 + 1e6)) as f32);
        (far_eye.camera.right, far_eye.camera.up) = (zoom(near.camera.right), zoom(near.camera.up));
        assert!(far_eye.camera.anchor[3] > 0.0);
        let cf = camera_frame(&far_eye);
        assert!((v3(cf) - v3(c)).length() <= 64.0 * 3f64.sqrt(), "{cf:?} {c:?}");
    }

    #[test]
    fn a_plane_met_beyond_the_scenes_reach_is_not_the_focus() {
        let mut s = scene(0.0);
        let eye = camera_eye(&s.camera);
        // Looking almost level: the floor y = 0, 1 below the eye, is met ~1e4 away.
        look(&mut s, eye, [0.0, -1e-4, 1.0]);
        let f = focus(&s);
        // It grazes the sphere's top (y = 1) 5 ahead instead.
        assert!((f - eye).length() < 10.0, "{f}");
        // Raised a little, it passes over everything but the floor: the geometry's centre.
        look(&mut s, DVec3::new(eye.x, 1.5, eye.z), [0.0, -1e-5, 1.0]);
        let root = s.bvh_nodes.first().copied().expect("a BVH");
        let centre = (DVec3::from(root.min.map(f64::from)) + DVec3::from(root.max.map(f64::from))) * 0.5;
        assert_eq!(focus(&s), centre);
    }

    #[test]
    fn a_centre_ray_meeting_nothing_falls_back_on_the_geometry_the_ground_then_the_eye() {
        let mut s = scene(0.0);
        // Looking up: the ray misses everything; the focus is the centre of the bounded box.
        let eye = camera_eye(&s.camera);
        look(&mut s, eye, [0.0, 1.0, 0.0]);
        let root = s.bvh_nodes.first().copied().expect("a BVH");
        let centre = (DVec3::from(root.min.map(f64::from)) + DVec3::from(root.max.map(f64::from))) * 0.5;
        assert_eq!(focus(&s), centre);
        s.bvh_nodes = crate::bvh::BvhNodes::new(&[]);
        s.spheres = Vec::new().into();
        s.vertices = Vec::new().into();
        s.triangles = Vec::new().into();
        // Planes alone: the foot of the eye (0, 1, −5) on the floor y = 0.
        assert_eq!(focus(&s), DVec3::new(0.0, 0.0, -5.0));
        s.planes = Vec::new().into();
        assert_eq!(focus(&s), camera_eye(&s.camera));
    }

    #[test]
    fn the_offsets_length_scale_follows_a_small_scene() {
        assert_eq!(nearest_power_of_two(6.0), 8.0);
        assert_eq!(nearest_power_of_two(5e-3), 1.0 / 256.0);
        let mut small = scene(0.0);
        let shrink = |a: [f32; 4]| [a[0] / 1024.0, a[1] / 1024.0, a[2] / 1024.0, a[3]];
        small.vertices = small.vertices.iter().map(|v| shrink(*v)).collect();
        small.camera.anchor = shrink(small.camera.anchor);
        small.spheres = small
            .spheres
            .iter()
            .map(|s| GpuSphere { center_radius: s.center_radius.map(|x| x / 1024.0), ..*s })
            .collect();
        small.lights[0].position = shrink(small.lights[0].position);
        small.bvh_nodes =
            small.bvh_nodes.map(|n| BvhNode { min: n.min.map(|x| x / 1024.0), max: n.max.map(|x| x / 1024.0), ..*n });
        // The surfaces reach ≈ 1.9/1024 from the focus: scale 2^-9.
        assert_eq!(camera_frame(&small)[3], 1.0 / 512.0);
    }
}
