//! The probed pixel's ray tree drawn over the images: every ray a 3D segment projected with
//! the scene camera, coloured by kind (camera white, reflection cyan, refraction orange, shadow
//! yellow where the light is visible and grey where it is blocked), as thick as its path
//! weight, the branches the bailout or the depth limit cut dashed.

use egui::{Color32, Pos2, Rect, Sense, Shape, Stroke, Ui, Vec2};
use glint_core::WorldCamera;
use glint_core::cpu::ray_tree::RayTree;
use glint_core::glam::DVec3;
use glint_types::RayKind;

/// One ray in image coordinates ([0, 1]², y down).
#[derive(Clone, Debug, PartialEq)]
pub struct TreeSegment {
    pub from: (f32, f32),
    pub to: (f32, f32),
    pub colour: Color32,
    pub width: f32,
    pub dashed: bool,
}

pub const CAMERA: Color32 = Color32::WHITE;
pub const REFLECTION: Color32 = Color32::from_rgb(60, 220, 255);
pub const REFRACTION: Color32 = Color32::from_rgb(255, 150, 40);
pub const SHADOW_LIT: Color32 = Color32::from_rgb(255, 230, 60);
pub const SHADOW_BLOCKED: Color32 = Color32::from_gray(120);

/// Depth along the camera's forward axis below which a point is not drawn (segments are cut
/// there, so that a ray passing behind the camera is drawn up to it).
const NEAR: f64 = 1e-3;

/// Image position of `p` (depth already known to be ≥ NEAR), `WorldCamera::image_point`.
fn to_image(cam: &WorldCamera, p: DVec3) -> (f32, f32) {
    let (x, y) = cam.image_point(p).0.unwrap_or((0.5, 0.5));
    (x as f32, y as f32)
}

/// The part of segment a–b in front of the camera, projected.
fn project_segment(cam: &WorldCamera, a: DVec3, b: DVec3) -> Option<((f32, f32), (f32, f32))> {
    let depth = |p: DVec3| cam.image_point(p).1;
    let (da, db) = (depth(a), depth(b));
    if da < NEAR && db < NEAR {
        return None;
    }
    let clip =
        |p: DVec3, dp: f64, q: DVec3, dq: f64| if dp >= NEAR { p } else { p + (q - p) * ((NEAR - dp) / (dq - dp)) };
    Some((to_image(cam, clip(a, da, b, db)), to_image(cam, clip(b, db, a, da))))
}

/// The segments of `tree` seen through `cam`. A ray that ends nowhere (a miss) is drawn `reach`
/// long, a shadow ray at most half that, a cut ray a quarter.
pub fn segments(tree: &RayTree, cam: &WorldCamera, reach: f64) -> Vec<TreeSegment> {
    tree.nodes
        .iter()
        .filter_map(|n| {
            // Shadow rays point at their light but stop at half the reach: a distant light's
            // would otherwise cross the whole image and hide the rest of the tree.
            let length = match (n.cut, n.t, n.kind) {
                (Some(_), _, _) => reach * 0.25,
                (None, Some(t), RayKind::Shadow) => t.min(reach * 0.5),
                (None, Some(t), _) => t.min(reach * 4.0),
                (None, None, _) => reach,
            };
            let (from, to) = project_segment(cam, n.origin, n.origin + n.dir * length)?;
            let colour = match n.kind {
                RayKind::Camera => CAMERA,
                RayKind::Reflection => REFLECTION,
                RayKind::Refraction => REFRACTION,
                RayKind::Shadow if n.factor.max_element() > 0.0 => SHADOW_LIT,
                RayKind::Shadow => SHADOW_BLOCKED,
            };
            let width = 1.0 + 3.0 * n.weight.max_element().clamp(0.0, 1.0) as f32;
            Some(TreeSegment { from, to, colour, width, dashed: n.cut.is_some() })
        })
        .collect()
}

/// Draws `segments` over each image of `rects`, on a dark rim so that they show on light and
/// dark surfaces alike; each drawing is a widget labelled "Ray tree: N rays" (the tests find it).
pub fn draw(ui: &mut Ui, rects: &[Rect], segments: &[TreeSegment]) {
    if segments.is_empty() {
        return;
    }
    for (i, r) in rects.iter().enumerate() {
        let to_screen = |(x, y): (f32, f32)| r.min + Vec2::new(x * r.width(), y * r.height());
        let painter = ui.painter().with_clip_rect(*r);
        let on_screen: Vec<(Pos2, Pos2)> = segments.iter().map(|s| (to_screen(s.from), to_screen(s.to))).collect();
        let mut bounds = Rect::NOTHING;
        for rim in [true, false] {
            for s in segments {
                let (a, b) = (to_screen(s.from), to_screen(s.to));
                bounds = bounds.union(Rect::from_two_pos(a, b));
                let stroke = if rim {
                    Stroke::new(s.width + 2.0, Color32::from_black_alpha(160))
                } else {
                    Stroke::new(s.width, s.colour)
                };
                if s.dashed {
                    painter.extend(Shape::dashed_line(&[a, b], stroke, 6.0, 4.0));
                } else {
                    painter.line_segment([a, b], stroke);
                }
            }
        }
        let label = format!("Ray tree: {} rays", segments.len());
        let area = bounds.expand(2.0).intersect(*r);
        // Only beside a tree in sight: after a camera move it may lie wholly outside the image.
        if i + 1 == rects.len() && area.is_positive() {
            // The camera ray, first in the tree, projects onto the probed pixel.
            legend(ui, *r, &on_screen, on_screen.first().map(|s| s.0));
        }
        if area.is_positive() {
            let response = ui.interact(area, ui.scope_id().with(("ray tree", i)), Sense::hover());
            response.widget_info(|| egui::WidgetInfo::labeled(egui::Role::Image, true, &label));
        }
    }
}

/// What the overlay's colours and line styles mean: the kinds of ray, the cut branches
/// (dashed) and the width (the path weight).
pub const LEGEND: [(&str, Color32, bool); 6] = [
    ("camera", CAMERA, false),
    ("reflection", REFLECTION, false),
    ("refraction", REFRACTION, false),
    ("shadow, light reached", SHADOW_LIT, false),
    ("shadow, blocked", SHADOW_BLOCKED, false),
    ("cut by bailout or depth", Color32::LIGHT_GRAY, true),
];

/// The legend in a corner of the image `r`, on a dark box (`legend_corner`: never over the
/// probed `pixel`, else over as little of the tree's rays, `pieces` on screen, as it can; in
/// the bottom-right corner it hid a probed pixel there, its tree and, on cornell-gi, the
/// caustic a lesson was about). Left out where it would take more than half the image's width
/// or height (at the least window the two images side by side are each about 225 points wide:
/// the legend hid most of the CPU one).
fn legend(ui: &mut Ui, r: Rect, pieces: &[(Pos2, Pos2)], pixel: Option<Pos2>) {
    let width = 172.0;
    // Each row is as tall as a horizontal layout makes it (its interact height, 18 points by
    // default, not 16): reckoned lower, the box ran past the image onto the colour bar below it.
    let row = ui.spacing().interact_size.y;
    let height = row * (LEGEND.len() as f32 + 1.0) + 8.0;
    if 2.0 * width > r.width() || 2.0 * height > r.height() {
        return;
    }
    let at = legend_corner(r.shrink(6.0), Vec2::new(width, height), pieces, pixel);
    let mut child = ui.new_child(egui::UiBuilder::new().max_rect(at));
    egui::Frame::new().fill(Color32::from_black_alpha(170)).inner_margin(4.0).corner_radius(3.0).show(
        &mut child,
        |ui| {
            ui.spacing_mut().item_spacing.y = 0.0;
            for (name, colour, dashed) in LEGEND {
                ui.horizontal(|ui| {
                    let (line, _) = ui.allocate_exact_size(Vec2::new(22.0, 14.0), Sense::hover());
                    let (a, b) = (line.left_center(), line.right_center());
                    let stroke = Stroke::new(2.0, colour);
                    if dashed {
                        ui.painter().extend(Shape::dashed_line(&[a, b], stroke, 4.0, 3.0));
                    } else {
                        ui.painter().line_segment([a, b], stroke);
                    }
                    ui.label(egui::RichText::new(name).color(Color32::WHITE).size(11.0));
                });
            }
            ui.label(egui::RichText::new("width: the ray's path weight").color(Color32::WHITE).size(11.0));
        },
    );
}

/// Points around the probed pixel kept clear of the legend: its marker square and a margin.
const PIXEL_CLEARANCE: f32 = 10.0;

/// The box of `size` in a corner of `r`: bottom-right, bottom-left, top-right or top-left, the
/// first that covers neither the probed `pixel` nor any of the rays `pieces`, else of those
/// clear of the pixel the one over the least length of rays. Judged by the rays themselves, not
/// their bounds: a floor pixel's shadow rays up to a light span the image diagonally, their box
/// met every corner, and the least overlap put the legend over the pixel (a viewer tester).
fn legend_corner(r: Rect, size: Vec2, pieces: &[(Pos2, Pos2)], pixel: Option<Pos2>) -> Rect {
    let corners = [
        r.right_bottom() - size,
        r.left_bottom() - Vec2::new(0.0, size.y),
        r.right_top() - Vec2::new(size.x, 0.0),
        r.left_top(),
    ];
    let boxes = corners.map(|c| Rect::from_min_size(c, size));
    const SAMPLES: usize = 32;
    let cost = |b: &Rect| {
        let over_pixel =
            pixel.is_some_and(|p| b.intersects(Rect::from_center_size(p, Vec2::splat(2.0 * PIXEL_CLEARANCE))));
        let covered: f32 = pieces
            .iter()
            .map(|&(a, z)| {
                let inside = (0..=SAMPLES).filter(|&k| b.contains(a.lerp(z, k as f32 / SAMPLES as f32))).count();
                a.distance(z) * inside as f32 / (SAMPLES + 1) as f32
            })
            .sum();
        (over_pixel, covered)
    };
    let costs = boxes.map(|b| cost(&b));
    let best = (0..4).min_by(|&i, &j| costs[i].0.cmp(&costs[j].0).then(costs[i].1.total_cmp(&costs[j].1)));
    boxes[best.expect("four corners")]
}

#[cfg(test)]
mod tests {
    use super::*;
    use glint_core::{FlatScene, probe_tree};

    #[test]
    fn the_legend_takes_the_first_corner_that_leaves_the_tree_and_its_pixel_uncovered() {
        let r = Rect::from_min_size(egui::pos2(0.0, 0.0), Vec2::new(400.0, 300.0));
        let size = Vec2::new(100.0, 80.0);
        let p = egui::pos2;
        let far = [(p(10.0, 10.0), p(20.0, 20.0))];
        assert_eq!(legend_corner(r, size, &far, Some(p(10.0, 10.0))).min, p(300.0, 220.0), "bottom-right when free");
        // A tree in the bottom-right corner (a probed pixel there): bottom-left.
        let corner = [(p(350.0, 250.0), p(390.0, 290.0))];
        assert_eq!(legend_corner(r, size, &corner, Some(p(350.0, 250.0))).min, p(0.0, 220.0));
        // Along the whole bottom: the top-right.
        let bottom = [(p(0.0, 250.0), p(400.0, 290.0))];
        assert_eq!(legend_corner(r, size, &bottom, None).min, p(300.0, 0.0));
        // A floor pixel bottom-left whose shadow ray runs to a light top-right: the ray's box
        // meets every corner; the legend goes bottom-right, which no ray crosses, not over the
        // pixel (a viewer tester).
        let diagonal = [(p(40.0, 270.0), p(40.0, 270.0)), (p(40.0, 270.0), p(390.0, 5.0))];
        assert_eq!(legend_corner(r, size, &diagonal, Some(p(40.0, 270.0))).min, p(300.0, 220.0));
        // Rays through every corner: the least covered of those clear of the pixel.
        let cross =
            [(p(0.0, 300.0), p(400.0, 0.0)), (p(0.0, 0.0), p(400.0, 300.0)), (p(350.0, 290.0), p(350.0, 290.0))];
        // The diagonals cross each corner box alike: the first clear of the pixel, bottom-left.
        assert_eq!(legend_corner(r, size, &cross, Some(p(350.0, 290.0))).min, p(0.0, 220.0), "over the pixel");
    }

    /// The glass sphere's tree of whitted, as the viewer draws it, with the scene moved by `at`.
    fn drawn(at: [f64; 3]) -> Vec<TreeSegment> {
        let (mut desc, _) = glint_io::builtin("whitted").expect("built-in").load(None).expect("loads");
        glint_test_support::scene::translate(&mut desc, at);
        let settings = glint_scene::RenderSettings { width: 160, height: 120, ..desc.render.clone() };
        let tree = probe_tree(&FlatScene::build(&desc, &settings), 100, 70, 0).expect("valid tags");
        assert!(tree.nodes.len() >= 10, "the glass sphere's tree");
        segments(&tree, &FlatScene::world_camera(&desc, &settings), 10.0)
    }

    #[test]
    fn a_tree_at_a_map_coordinate_is_drawn_where_it_is_at_the_origin() {
        // UTM zone 32N: f32 stores the eye there to 1/4 of a unit, 5 units from the scene (an f32
        // eye drew the tree 2 % too large).
        let (near, far) = (drawn([0.0; 3]), drawn([452_331.127, 81.5, 5_411_876.883]));
        assert_eq!(near.len(), far.len());
        for (a, b) in near.iter().zip(&far) {
            // Relative beyond the image: a ray leaving the view ends thousands of widths away.
            let close = |x: f32, y: f32| (x - y).abs() <= 1e-4 * x.abs().max(1.0);
            for (p, q) in [(a.from, b.from), (a.to, b.to)] {
                assert!(close(p.0, q.0) && close(p.1, q.1), "{a:?} against {b:?}");
            }
        }
    }
}
