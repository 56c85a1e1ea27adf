//! The central view: GPU, CPU, side by side, split wipe or difference; and the pointer input
//! on it (orbit, pan, zoom, pick, probe), mapped to pixels of the full-resolution image.

use egui::{Color32, Pos2, Rect, Sense, Stroke, Ui, Vec2, pos2};
use glint_core::glam::DVec3;

use glint_core::compare::{
    HEATMAP_LOG10_MAX, HEATMAP_LOG10_MIN, PixelDiffs, SignedDifference, diverging_colour, heatmap_colour,
};

use crate::gizmos::Gizmo;
use crate::outline::Segment;
use crate::ray_tree_view::{self, TreeSegment};

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ViewMode {
    Gpu,
    Cpu,
    SideBySide,
    Wipe,
    Difference,
    /// Whitted's image against the path-traced one (`GiView` says how).
    WhittedVsGi,
}

impl ViewMode {
    pub const ALL: [Self; 6] =
        [Self::Gpu, Self::Cpu, Self::SideBySide, Self::Wipe, Self::Difference, Self::WhittedVsGi];

    pub fn label(self) -> &'static str {
        match self {
            Self::Gpu => "GPU",
            Self::Cpu => "CPU reference",
            Self::SideBySide => "Side by side",
            Self::Wipe => "Split wipe",
            Self::Difference => "Difference",
            Self::WhittedVsGi => "Whitted vs GI",
        }
    }
}

/// How the Whitted vs GI view holds the two images against each other.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum GiView {
    #[default]
    SideBySide,
    Wipe,
    /// Whitted − paths on a diverging colour map.
    Difference,
}

impl GiView {
    pub const ALL: [Self; 3] = [Self::SideBySide, Self::Wipe, Self::Difference];

    pub fn label(self) -> &'static str {
        match self {
            Self::SideBySide => "Whitted beside GI",
            Self::Wipe => "Whitted wipe GI",
            Self::Difference => "Whitted − GI",
        }
    }
}

/// An image on screen: its texture, its size in pixels, and whether it is of an earlier
/// revision than the document's (a drag or an edit since: dimmed and marked "updating…").
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Shown {
    pub id: egui::TextureId,
    pub size: (u32, u32),
    pub stale: bool,
    /// Of an earlier revision because the document's has invalid values: nothing renders
    /// until they are mended (said so, not "updating…").
    pub held: bool,
}

/// The textures to show (any may be missing: no GPU, CPU still rendering, no comparison).
#[derive(Clone, Copy, Debug, Default)]
pub struct Textures<'a> {
    pub gpu: Option<Shown>,
    pub cpu: Option<Shown>,
    pub diff: Option<egui::TextureId>,
    /// Why the GPU image is missing work (a status flag its shader raised), shown over it.
    pub gpu_incomplete: Option<&'a str>,
    /// The per-pixel differences behind `diff`, read under the cursor.
    pub diffs: Option<&'a PixelDiffs>,
    /// Whitted's image, the path-traced one (the GPU's mean, else the CPU's), and Whitted − GI.
    pub whitted: Option<Shown>,
    pub gi: Option<Shown>,
    pub gi_diff: Option<egui::TextureId>,
    pub gi_signed: Option<&'a SignedDifference>,
    /// Samples a pixel of the path-traced image the difference was made with.
    pub gi_samples: Option<u32>,
    /// The one kind of light the paths show (Scene → Light shown), `None` for all of it: the
    /// GI side and Whitted − GI say so (with caustics alone it was still called "GI (paths)",
    /// and the lamp read "too bright"; a lecturer).
    pub gi_kind: Option<glint_scene::PathKind>,
}

impl Textures<'_> {
    /// What the GI side is called: the paths' whole light, or the one kind shown.
    pub fn gi_name(&self) -> String {
        self.gi_kind.map_or_else(|| "GI (paths)".to_string(), |k| format!("GI: {} alone", k.label().to_lowercase()))
    }
}

/// What the pointer did on the view this frame.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum ViewAction {
    /// A drag by this much over an image this many points wide.
    Orbit(Vec2, f32),
    Pan(Vec2, f32),
    Zoom(f32),
    /// A plain click on pixel (x, y).
    Pick(u32, u32),
    /// A Ctrl/Cmd-click on pixel (x, y): probes it, and selects the object there as a plain
    /// click does.
    Probe(u32, u32),
    /// The toolbar's integrator switch.
    Integrator(glint_scene::Integrator),
    /// The toolbar's Pause (true) or Continue of the GPU's path batches.
    Pause(bool),
}

/// The largest rect of aspect `w:h` centred in `area`.
fn fit(area: Rect, w: u32, h: u32) -> Rect {
    let aspect = w as f32 / h.max(1) as f32;
    let size = if area.width() / area.height().max(1.0) > aspect {
        Vec2::new(area.height() * aspect, area.height())
    } else {
        Vec2::new(area.width(), area.width() / aspect)
    };
    Rect::from_center_size(area.center(), size)
}

const UV: Rect = Rect::from_min_max(Pos2::ZERO, pos2(1.0, 1.0));

/// Where an image of `texture` pixels goes in `rect`, laid out for the current frame: an image
/// of another aspect (the previous scene's while a model loads, the previous size's) keeps its
/// own, letterboxed, never stretched to the new frame.
pub fn placement(rect: Rect, frame: (u32, u32), texture: (u32, u32)) -> Rect {
    let aspect = |(w, h): (u32, u32)| w as f32 / h.max(1) as f32;
    if (aspect(frame) / aspect(texture) - 1.0).abs() < 0.01 { rect } else { fit(rect, texture.0, texture.1) }
}

impl Textures<'_> {
    /// These textures, those of an earlier revision marked held (the document is invalid).
    pub fn held(mut self) -> Self {
        for shown in [&mut self.gpu, &mut self.cpu, &mut self.whitted, &mut self.gi].into_iter().flatten() {
            shown.held = shown.stale;
        }
        self
    }
}

/// The tint of an image of an earlier revision.
const STALE_TINT: Color32 = Color32::from_gray(120);

/// Draws `tex` in `rect` (of a `frame` image): dimmed, marked "NAME: updating…", where it is of
/// an earlier revision.
fn image(ui: &mut Ui, rect: Rect, tex: Option<Shown>, uv: Rect, frame: (u32, u32), name: &str, missing: &str) {
    match tex {
        Some(t) => {
            // The wipe shows part of each image: the halves must meet, so only whole images
            // are letterboxed.
            let at = if uv == UV { placement(rect, frame, t.size) } else { rect };
            if at != rect {
                ui.painter().rect_filled(rect, 0.0, Color32::from_gray(24));
            }
            ui.painter().image(t.id, at, uv, if t.stale { STALE_TINT } else { Color32::WHITE });
            if t.stale {
                let state = if t.held { "held while a value is invalid" } else { "updating…" };
                let text = egui::RichText::new(format!("{name}: {state}")).color(Color32::WHITE).size(13.0);
                anchored_label(ui, at.left_bottom() + Vec2::new(6.0, -4.0), egui::Align2::LEFT_BOTTOM, text, Some(at));
            }
        }
        None => {
            ui.painter().rect_filled(rect, 0.0, Color32::from_gray(24));
            ui.painter().text(
                rect.center(),
                egui::Align2::CENTER_CENTER,
                missing,
                egui::FontId::proportional(14.0),
                Color32::GRAY,
            );
        }
    }
}

/// A red banner across the top of a GPU image whose shader raised a status flag: the image is
/// missing work and must not pass for a result. A label, so that the UI tests can find it.
fn incomplete_banner(ui: &mut Ui, rect: Rect, why: Option<&str>) {
    let Some(why) = why else { return };
    let text = egui::RichText::new(format!("GPU image incomplete: {why}")).color(Color32::WHITE).strong();
    let mut child = ui.new_child(egui::UiBuilder::new().max_rect(rect.shrink(4.0)));
    egui::Frame::new().fill(Color32::from_rgb(170, 20, 20)).inner_margin(4.0).show(&mut child, |ui| {
        ui.add(egui::Label::new(text).wrap());
    });
}

/// A white label over an image with its `anchor` corner at `pos`, shown only where it fits
/// inside `image` (the wipe's labels at wipe 0 or 1 would stand outside it).
fn image_label(ui: &mut Ui, image: Rect, pos: Pos2, anchor: egui::Align2, text: &str) {
    let text = egui::RichText::new(text).color(Color32::WHITE).size(13.0);
    anchored_label(ui, pos, anchor, text, Some(image));
}

/// A label widget with its `anchor` corner at `pos`, left out where it would stand outside
/// `inside`. A widget, not painted text, so that the UI tests find it and its place.
fn anchored_label(ui: &mut Ui, pos: Pos2, anchor: egui::Align2, text: egui::RichText, inside: Option<Rect>) {
    let galley = egui::WidgetText::from(text.clone()).into_galley(
        ui,
        Some(egui::TextWrapMode::Extend),
        f32::INFINITY,
        egui::TextStyle::Body,
    );
    let rect = anchor.anchor_size(pos, galley.size());
    if inside.is_some_and(|r| !r.contains_rect(rect)) {
        return;
    }
    let mut child = ui.new_child(egui::UiBuilder::new().max_rect(rect));
    child.add(egui::Label::new(text).selectable(false).extend());
}

/// Marks the probed pixel (x, y) of a `size` image in each of `rects`: a white square with a
/// black rim around it (at least 9 points wide), labelled for screen readers and the tests.
fn probe_marker(ui: &mut Ui, rects: &[Rect], size: (u32, u32), (x, y): (u32, u32)) {
    for (i, r) in rects.iter().enumerate() {
        let (w, h) = (size.0.max(1) as f32, size.1.max(1) as f32);
        let pixel = Rect::from_min_max(
            r.min + Vec2::new(x as f32 / w * r.width(), y as f32 / h * r.height()),
            r.min + Vec2::new((x + 1) as f32 / w * r.width(), (y + 1) as f32 / h * r.height()),
        );
        let mark = Rect::from_center_size(pixel.center(), pixel.size().max(Vec2::splat(9.0)));
        let painter = ui.painter().with_clip_rect(*r);
        painter.rect_stroke(mark.expand(1.0), 0.0, Stroke::new(1.0, Color32::BLACK), egui::StrokeKind::Middle);
        painter.rect_stroke(mark, 0.0, Stroke::new(1.5, Color32::WHITE), egui::StrokeKind::Middle);
        let label = format!("Probed pixel ({x}, {y})");
        let response = ui.interact(mark, ui.scope_id().with(("probe marker", i)), Sense::hover());
        response.widget_info(|| egui::WidgetInfo::labeled(egui::Role::Image, true, &label));
    }
}

/// Draws the selected object's outline (edges between pixels, see `outline`) on each image of
/// `rects`: an orange line on a dark rim, visible on light and dark surfaces alike. Each outline
/// is a widget labelled "Selected: NAME" over its bounds, for screen readers and the tests.
fn selection_outline(ui: &mut Ui, rects: &[Rect], size: (u32, u32), name: &str, segments: &[Segment]) {
    if segments.is_empty() {
        return;
    }
    let (w, h) = (size.0.max(1) as f32, size.1.max(1) as f32);
    for (i, r) in rects.iter().enumerate() {
        let to_screen = |(x, y): (u32, u32)| r.min + Vec2::new(x as f32 / w * r.width(), y as f32 / h * r.height());
        let painter = ui.painter().with_clip_rect(*r);
        let mut bounds = Rect::NOTHING;
        for (stroke, colour) in [(3.0, Color32::from_black_alpha(200)), (1.5, Color32::from_rgb(255, 170, 30))] {
            for [a, b] in segments {
                let (a, b) = (to_screen(*a), to_screen(*b));
                bounds = bounds.union(Rect::from_two_pos(a, b));
                painter.line_segment([a, b], Stroke::new(stroke, colour));
            }
        }
        let label = format!("Selected: {name}");
        let response = ui.interact(bounds.intersect(*r), ui.scope_id().with(("selection outline", i)), Sense::hover());
        response.widget_info(|| egui::WidgetInfo::labeled(egui::Role::Image, true, &label));
    }
}

/// Points below the difference image for its colour bar, tick labels and the readout.
const COLOUR_BAR_STRIP: f32 = 48.0;

/// The heat map's scale under the difference image `r`: black for identical pixels, then the
/// colour of each |GPU − CPU| from 10^HEATMAP_LOG10_MIN to 10^HEATMAP_LOG10_MAX (log10), a
/// tick and a label per decade.
fn colour_bar(ui: &mut Ui, r: Rect) {
    let zero = Rect::from_min_size(pos2(r.left(), r.bottom() + 6.0), Vec2::new(14.0, 12.0));
    let bar = Rect::from_min_max(pos2(zero.right() + 6.0, zero.top()), pos2(r.right(), zero.bottom()));
    let painter = ui.painter().clone();
    painter.rect_filled(zero, 0.0, Color32::BLACK);
    painter.rect_stroke(zero, 0.0, Stroke::new(1.0, Color32::GRAY), egui::StrokeKind::Outside);
    const STEPS: usize = 96;
    for i in 0..STEPS {
        let x0 = bar.left() + bar.width() * i as f32 / STEPS as f32;
        let x1 = bar.left() + bar.width() * (i + 1) as f32 / STEPS as f32;
        let [red, green, blue] = heatmap_colour((i as f64 + 0.5) / STEPS as f64);
        painter.rect_filled(
            Rect::from_min_max(pos2(x0, bar.top()), pos2(x1 + 0.5, bar.bottom())),
            0.0,
            Color32::from_rgb(red, green, blue),
        );
    }
    let label_pos = |x: f32| pos2(x, bar.bottom() + 2.0);
    image_label_at(ui, label_pos(zero.center().x), egui::Align2::CENTER_TOP, "0");
    let decades = (HEATMAP_LOG10_MAX - HEATMAP_LOG10_MIN) as i32;
    for k in 0..=decades {
        let x = bar.left() + bar.width() * k as f32 / decades as f32;
        painter.vline(x, bar.bottom()..=bar.bottom() + 2.0, Stroke::new(1.0, Color32::GRAY));
        let exponent = HEATMAP_LOG10_MIN as i32 + k;
        let anchor = match k {
            0 => egui::Align2::LEFT_TOP,
            k if k == decades => egui::Align2::RIGHT_TOP,
            _ => egui::Align2::CENTER_TOP,
        };
        image_label_at(ui, label_pos(x), anchor, &format!("1e{exponent}"));
    }
}

/// "|GPU − CPU| at (x, y)" under the colour bar for the pixel under the cursor.
fn difference_readout(ui: &mut Ui, r: Rect, at: Option<((u32, u32), (f64, bool))>) {
    let text = match at {
        Some(((x, y), (d, differs))) => format!(
            "({x}, {y}): |GPU − CPU| = {d:.3e}{}",
            if differs { ", first hit differs" } else { ", same first hit" }
        ),
        None => "|GPU − CPU| (max channel, linear), log scale; point at a pixel for its value".into(),
    };
    image_label_at(ui, pos2(r.left(), r.bottom() + 34.0), egui::Align2::LEFT_TOP, &text);
}

/// The diverging scale under the Whitted − GI image `r`: −scale (blue, Whitted too dark) through
/// 0 (white) to +scale (red, too bright).
fn signed_colour_bar(ui: &mut Ui, r: Rect, scale: f64) {
    let bar = Rect::from_min_max(pos2(r.left(), r.bottom() + 6.0), pos2(r.right(), r.bottom() + 18.0));
    let painter = ui.painter().clone();
    const STEPS: usize = 96;
    for i in 0..STEPS {
        let x0 = bar.left() + bar.width() * i as f32 / STEPS as f32;
        let x1 = bar.left() + bar.width() * (i + 1) as f32 / STEPS as f32;
        let [red, green, blue] = diverging_colour(2.0 * (i as f64 + 0.5) / STEPS as f64 - 1.0);
        painter.rect_filled(
            Rect::from_min_max(pos2(x0, bar.top()), pos2(x1 + 0.5, bar.bottom())),
            0.0,
            Color32::from_rgb(red, green, blue),
        );
    }
    let label_pos = |x: f32| pos2(x, bar.bottom() + 2.0);
    image_label_at(ui, label_pos(bar.left()), egui::Align2::LEFT_TOP, &format!("−{scale} Whitted too dark"));
    image_label_at(ui, label_pos(bar.center().x), egui::Align2::CENTER_TOP, "0");
    image_label_at(ui, label_pos(bar.right()), egui::Align2::RIGHT_TOP, &format!("too bright +{scale}"));
}

/// A signed value of the readout, as a class reads it aloud: −0.2916, not −2.916e-1.
fn signed(v: f64) -> String {
    let plain = glint_scene::format_rounded(v, 4);
    if v > 0.0 { format!("+{plain}") } else { plain.replace('-', "−") }
}

/// "Whitted − GI at (x, y)" under the diverging bar for the pixel under the cursor, the
/// verdict beside the mean: at the end of the line it was cut off in a narrow window (a
/// viewer tester at 760×480).
fn signed_readout(ui: &mut Ui, r: Rect, at: Option<((u32, u32), DVec3)>, samples: Option<u32>, gi: &str) {
    let text = match at {
        Some(((x, y), d)) => format!(
            "({x}, {y}): Whitted − {gi} = {}{} (R {}, G {}, B {})",
            signed(d.element_sum() / 3.0),
            match d.element_sum() {
                s if s < 0.0 => ": too dark",
                s if s > 0.0 => ": too bright",
                _ => ": the same",
            },
            signed(d.x),
            signed(d.y),
            signed(d.z),
        ),
        None => match samples {
            Some(n) => format!("Whitted − {gi}, mean of R, G, B; paths of {n} samples. Point at a pixel."),
            // The difference shown is of an earlier edit (or none yet): its count is not this one's.
            None => format!("Whitted − {gi}, mean of R, G, B; the difference of this edit is being made…"),
        },
    };
    image_label_at(ui, pos2(r.left(), r.bottom() + 34.0), egui::Align2::LEFT_TOP, &text);
}

/// A small grey label of the colour bar with its `anchor` at `pos`.
fn image_label_at(ui: &mut Ui, pos: Pos2, anchor: egui::Align2, text: &str) {
    anchored_label(ui, pos, anchor, egui::RichText::new(text).color(Color32::LIGHT_GRAY).size(11.0), None);
}

fn draw_gizmos(ui: &Ui, rect: Rect, gizmos: &[Gizmo]) {
    let to_screen = |(x, y): (f32, f32)| rect.min + Vec2::new(x * rect.width(), y * rect.height());
    let painter = ui.painter().with_clip_rect(rect);
    for g in gizmos {
        let width = if g.selected { 2.0 } else { 1.2 };
        for line in &g.lines {
            let pts: Vec<Pos2> = line.iter().copied().map(to_screen).collect();
            painter.add(egui::Shape::line(pts, Stroke::new(width, g.colour)));
        }
        if let Some(m) = g.marker {
            let c = to_screen(m);
            painter.circle(c, 5.0, g.colour, Stroke::new(width, Color32::BLACK));
            if g.selected {
                painter.circle_stroke(c, 9.0, Stroke::new(1.5, Color32::WHITE));
            }
        }
    }
}

/// Draws the view in the available space; returns what the pointer did and where the images are.
pub fn show(
    ui: &mut Ui,
    mode: ViewMode,
    gi_view: GiView,
    wipe: &mut f32,
    tex: Textures,
    (w, h): (u32, u32),
    gizmos: &[Gizmo],
    show_gizmos: bool,
    probed: Option<(u32, u32)>,
    selected: Option<(&str, &[Segment])>,
    tree: &[TreeSegment],
) -> (Vec<ViewAction>, Vec<Rect>) {
    let area = ui.available_rect_before_wrap();
    let response = ui.allocate_rect(area, Sense::click_and_drag());
    // The two images a view holds against each other: GPU and CPU, or Whitted and the paths.
    let gi = mode == ViewMode::WhittedVsGi;
    let gi_name = tex.gi_name();
    let (left_tex, right_tex, left_name, right_name, left_missing, right_missing) = if gi {
        (tex.whitted, tex.gi, "Whitted", gi_name.as_str(), "Whitted rendering…", "paths rendering…")
    } else {
        (tex.gpu, tex.cpu, "GPU", "CPU", "no GPU image", "CPU reference rendering…")
    };
    let incomplete = if gi { None } else { tex.gpu_incomplete };
    let mode = match (mode, gi_view) {
        (ViewMode::WhittedVsGi, GiView::SideBySide) => ViewMode::SideBySide,
        (ViewMode::WhittedVsGi, GiView::Wipe) => ViewMode::Wipe,
        (m, _) => m,
    };
    let rects: Vec<Rect> = match mode {
        ViewMode::SideBySide => {
            let half = Rect::from_min_size(area.min, Vec2::new(area.width() / 2.0, area.height()));
            let left = fit(half.shrink(4.0), w, h);
            let right = fit(half.translate(Vec2::new(area.width() / 2.0, 0.0)).shrink(4.0), w, h);
            image(ui, left, left_tex, UV, (w, h), left_name, left_missing);
            image(ui, right, right_tex, UV, (w, h), right_name, right_missing);
            incomplete_banner(ui, left, incomplete);
            image_label(ui, left, left.left_top() + Vec2::new(6.0, 4.0), egui::Align2::LEFT_TOP, left_name);
            image_label(ui, right, right.left_top() + Vec2::new(6.0, 4.0), egui::Align2::LEFT_TOP, right_name);
            if show_gizmos {
                draw_gizmos(ui, left, gizmos);
            }
            vec![left, right]
        }
        _ => {
            // The difference view keeps a strip below the image for its colour bar.
            let image_area = if matches!(mode, ViewMode::Difference | ViewMode::WhittedVsGi) {
                Rect::from_min_max(area.min, pos2(area.right(), area.bottom() - COLOUR_BAR_STRIP))
            } else {
                area
            };
            let r = fit(image_area.shrink(4.0), w, h);
            match mode {
                ViewMode::Gpu => {
                    image(ui, r, tex.gpu, UV, (w, h), "GPU", left_missing);
                    incomplete_banner(ui, r, tex.gpu_incomplete);
                    if show_gizmos {
                        draw_gizmos(ui, r, gizmos);
                    }
                }
                ViewMode::Cpu => image(ui, r, tex.cpu, UV, (w, h), "CPU", right_missing),
                ViewMode::Difference => {
                    let diff = tex.diff.map(|id| Shown { id, size: (w, h), stale: false, held: false });
                    image(ui, r, diff, UV, (w, h), "Difference", "comparing GPU and CPU…");
                    colour_bar(ui, r);
                }
                ViewMode::WhittedVsGi => {
                    let diff = tex.gi_diff.map(|id| Shown { id, size: (w, h), stale: false, held: false });
                    // Only what is rendering: after an ambient edit the paths go on (a lecturer
                    // read that they were rendered again).
                    let current = |t: Option<Shown>| t.is_some_and(|t| !t.stale);
                    let waiting = match (current(tex.whitted), current(tex.gi)) {
                        (true, true) => "taking the difference…",
                        (false, true) => "rendering Whitted…",
                        (true, false) => "rendering the paths…",
                        (false, false) => "rendering Whitted and the paths…",
                    };
                    image(ui, r, diff, UV, (w, h), "Whitted − GI", waiting);
                    if let Some(d) = tex.gi_signed {
                        signed_colour_bar(ui, r, d.scale);
                    }
                }
                ViewMode::Wipe | ViewMode::SideBySide => {
                    // The first image left of the wipe line, the second right of it.
                    let split = r.left() + *wipe * r.width();
                    let left = Rect::from_min_max(r.min, pos2(split, r.bottom()));
                    let right = Rect::from_min_max(pos2(split, r.top()), r.max);
                    let (left_uv, right_uv) = (
                        Rect::from_min_max(Pos2::ZERO, pos2(*wipe, 1.0)),
                        Rect::from_min_max(pos2(*wipe, 0.0), pos2(1.0, 1.0)),
                    );
                    image(ui, left, left_tex, left_uv, (w, h), left_name, left_missing);
                    image(ui, right, right_tex, right_uv, (w, h), right_name, right_missing);
                    ui.painter().vline(split, r.y_range(), Stroke::new(1.5, Color32::WHITE));
                    let top = r.top() + 4.0;
                    image_label(ui, r, pos2(split - 6.0, top), egui::Align2::RIGHT_TOP, left_name);
                    image_label(ui, r, pos2(split + 6.0, top), egui::Align2::LEFT_TOP, right_name);
                    incomplete_banner(ui, r, incomplete);
                    if show_gizmos {
                        draw_gizmos(ui, r, gizmos);
                    }
                }
            }
            vec![r]
        }
    };
    if let Some((name, segments)) = selected {
        selection_outline(ui, &rects, (w, h), name, segments);
    }
    ray_tree_view::draw(ui, &rects, tree);
    if let Some(p) = probed {
        probe_marker(ui, &rects, (w, h), p);
    }
    let mut actions = Vec::new();
    let to_pixel = |p: Pos2| {
        rects.iter().find(|r| r.contains(p)).map(|r| {
            let x = ((p.x - r.left()) / r.width() * w as f32).floor().clamp(0.0, w as f32 - 1.0) as u32;
            let y = ((p.y - r.top()) / r.height() * h as f32).floor().clamp(0.0, h as f32 - 1.0) as u32;
            (x, y)
        })
    };
    if mode == ViewMode::Difference
        && let (Some(diffs), Some(r)) = (tex.diffs, rects.first())
    {
        let hovered = response.hover_pos().and_then(to_pixel);
        difference_readout(ui, *r, hovered.and_then(|(x, y)| diffs.at(x, y).map(|d| ((x, y), d))));
    }
    if mode == ViewMode::WhittedVsGi
        && let Some(r) = rects.first()
    {
        let hovered = response.hover_pos().and_then(to_pixel);
        let at = hovered.and_then(|(x, y)| tex.gi_signed.and_then(|d| d.at(x, y)).map(|d| ((x, y), d)));
        signed_readout(ui, *r, at, tex.gi_samples, &gi_name);
    }
    let modifiers = ui.input(|i| i.modifiers);
    if response.clicked()
        && let Some((x, y)) = response.interact_pointer_pos().and_then(to_pixel)
    {
        actions.push(if modifiers.command { ViewAction::Probe(x, y) } else { ViewAction::Pick(x, y) });
    }
    let view_size = rects.first().map_or(area.size(), |r| r.size());
    let delta = response.drag_delta();
    if delta != Vec2::ZERO {
        let pan = modifiers.shift || response.dragged_by(egui::PointerButton::Middle);
        actions.push(if pan { ViewAction::Pan(delta, view_size.y) } else { ViewAction::Orbit(delta, view_size.x) });
    }
    if response.hovered() {
        let scroll = ui.input(|i| i.smooth_scroll_delta.y);
        if scroll != 0.0 {
            actions.push(ViewAction::Zoom(scroll));
        }
    }
    (actions, rects)
}
