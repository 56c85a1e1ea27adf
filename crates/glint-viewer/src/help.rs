//! What each control is in the seed's equation and what changing it does (the tooltips every
//! editor shows), and the Help menu: the first five minutes, the keyboard and mouse, the docs.
//!
//!   I = E_m + I_a·k_a + Σ_j f_att,j·S_j·[ I_a,j·k_a + V_j·( I_d,j·k_d·(N·L) + I_s,j·k_s·spec ) ]
//!       + k_r·I_r + k_t·I_t

/// The tooltip of the editor labelled `label` (the label the panels give it; channels and
/// axes, "k_d R" or "Position x", take their editor's).
pub fn tooltip(label: &str) -> Option<&'static str> {
    let base = strip_part(label).unwrap_or(label);
    if base.starts_with("No cone") {
        return Some("The spot lights every direction (S_j from the exponent alone, no cutoff): OpenGL's 180°.");
    }
    Some(match base {
        "Field of view" => "The camera's vertical field of view in degrees. Smaller zooms in.",
        "Projection" => {
            "Perspective: rays fan out from the eye. Orthographic: parallel rays along the view axis, so sizes \
             do not shrink with distance (a CAD or architectural drawing's parallel projection)."
        }
        "View height" => "How tall the orthographic view is, in scene units. Smaller zooms in.",
        "Ambient I_a" => {
            "I_a: the scene's ambient intensity, the seed's stand-in for all light that arrives indirectly. \
             It adds I_a·k_a everywhere, shadowed or not: raise it and shadows turn grey."
        }
        "Background" => "The radiance of rays that leave the scene (what I_r and I_t bring back from the sky).",
        "Max depth" => {
            "How many times rays are reflected (k_r·I_r) and refracted (k_t·I_t) at most. 0: local shading only, \
             no mirrors or glass. Each level can double the rays per pixel."
        }
        "Bailout" => {
            "Adaptive depth: a reflected or refracted ray whose weight (the product of k_r or k_t along its path) \
             falls below this is not traced. 0 traces every ray to Max depth; larger is faster and darker."
        }
        "Epsilon" => {
            "ε: how far secondary rays keep from the surface they leave, so that rounding does not make a \
             surface shadow itself (acne). Too small: speckles; too large: shadows detach (peter-panning)."
        }
        "Epsilon strategy" => "How ε is applied to secondary rays (the seed's remedies for self-intersection).",
        "Fit ambient to paths" => {
            "Renders the scene with paths (at least 64 a pixel) and finds the global I_a, per channel, that \
             brings Whitted's image closest to it: what the ambient term stands in for, measured."
        }
        "Integrator" => {
            "What both tracers compute: Whitted's ray tree (the seed's model), or Monte Carlo paths, the light \
             transport the model approximates (global illumination)."
        }
        "Indirect light" => {
            "Paths follow every lobe (on), or only k_r and k_t with direct light (off): Whitted's transport, \
             so that the difference is the indirect light."
        }
        "Light shown" => {
            "The path-traced image, or one kind of its light alone: direct (what Whitted computes), indirect \
             diffuse (colour bleeding), caustics (through a mirror or glass onto a diffuse surface) or the rest. \
             The four add up to the whole image. Not saved with the scene."
        }
        "Samples per pixel" => {
            "Rays per pixel, jittered inside it and averaged: anti-aliasing of edges. Time grows in proportion."
        }
        "Width" | "Height" => "The image's size in pixels. Time grows with the pixel count.",
        "Global attenuation of k_r·I_r, k_t·I_t" => {
            "Attenuates reflected and transmitted light with the distance it travelled: 1/(c_g + l_g·d + q_g·d²)."
        }
        "c_g" | "l_g" | "q_g" => {
            "The global attenuation 1/(c_g + l_g·d + q_g·d²) of k_r·I_r and k_t·I_t over the distance d a \
             reflected or refracted ray travelled."
        }
        "Type" => "The light's kind: a point light, a directional one (the sun), or a spot (a point with a cone).",
        "Position" => "Where the point or spot light is: L points from the surface to here.",
        "Direction" => "Where the directional light shines to: L is the opposite of this, everywhere.",
        "Spot axis" => "Where the spot's cone points; S_j falls off away from this axis.",
        "I_d" => "I_d,j: the light's diffuse intensity, in I_d,j·k_d·(N·L). Brighter diffuse shading.",
        "I_s" => "I_s,j: the light's specular intensity, in I_s,j·k_s·spec. Brighter highlights.",
        "I_a,j" => {
            "I_a,j: this light's own ambient contribution, I_a,j·k_a, attenuated with the light (f_att,j·S_j) but \
             never shadowed."
        }
        "Casts shadows" => "Whether this light's V_j is traced (a shadow ray toward the light) or always 1.",
        "Attenuation" => {
            "f_att,j: how the light weakens with distance d (OpenGL's polynomial or glTF's inverse square)."
        }
        "c" | "l" | "q" => {
            "f_att,j = 1/(c + l·d + q·d²): c constant, l linear, q quadratic in the distance d to the light. \
             (1, 0, 0) is no attenuation."
        }
        "Range window" => "glTF's range: the light fades smoothly to nothing at this distance.",
        "Range" => "The distance at which the glTF range window brings the light to zero.",
        "Falloff" => "S_j inside the spot's cone: OpenGL's power of the cosine, or glTF's smooth cone.",
        "Spot exponent" => "S_j = (cos angle to the axis)^s: larger narrows the spot's bright centre.",
        "Cutoff" => "The spot's cone half-angle in degrees: no light outside it.",
        "Inner cone" => "glTF's inner cone half-angle: full intensity inside it.",
        "Outer cone" => "glTF's outer cone half-angle: no light outside it; smooth between the two cones.",
        "k_a" => "k_a: the ambient reflectance, multiplying I_a and each I_a,j. The colour in shadow.",
        "k_d" => "k_d: the diffuse reflectance, in I_d,j·k_d·(N·L). The surface's matte colour.",
        "k_s" => "k_s: the specular reflectance, in I_s,j·k_s·spec. The highlight's colour and strength.",
        "Specular model" => "spec in I_s,j·k_s·spec: Blinn's (N·H)^n, Phong's (R·V)^n, or Cook–Torrance's microfacets.",
        "Shininess n" => {
            "n, the exponent of (N·H)^n or (R·V)^n: larger makes highlights smaller and sharper. The slider \
             drags over 1–10³; type any value in [0, 10⁶]."
        }
        "Roughness m" => "m, the Beckmann RMS microfacet slope of Cook–Torrance: smaller is glossier.",
        "Fresnel" => {
            "F of Cook–Torrance: the exact dielectric Fresnel factor from the ior, or Schlick's approximation."
        }
        "k_r" => "k_r: the mirror reflectance, in k_r·I_r (I_r traced along the reflected ray).",
        "k_t" => "k_t: the transmittance, in k_t·I_t (I_t traced along the refracted ray, Snell's law with the ior).",
        "Index of refraction" => {
            "η of the material: how much refracted rays bend (1 air, 1.33 water, 1.5 glass); also the Fresnel F."
        }
        "E_m" => "E_m: the material's own emission, added as it is. Makes a surface glow; lights nothing else.",
        "Material" => "The material to edit (click an object in the image to pick its own).",
        "Checker" => "Replaces k_d by a checker pattern of two colours (k_d and the checker's k_d) on the surface.",
        "Checker k_d" => "The second k_d of the checker pattern (the material's own k_d is the first).",
        "Checker size" => "The side of the checker's squares, in scene units.",
        _ => return None,
    })
}

/// `label` without a trailing channel or axis (" R", " G", " B", " x", " y", " z").
fn strip_part(label: &str) -> Option<&str> {
    [" R", " G", " B", " x", " y", " z"].iter().find_map(|s| label.strip_suffix(s))
}

/// `response` with the tooltip of `label`, where it has one.
pub fn hint(response: egui::Response, label: &str) -> egui::Response {
    with_tooltip(response, tooltip(label))
}

/// `response` with `text` on hover, where there is one.
pub fn with_tooltip(response: egui::Response, text: Option<&str>) -> egui::Response {
    match text {
        Some(text) => response.on_hover_text(text),
        None => response,
    }
}

/// The tooltip of one option of the combo box labelled `control`.
pub fn option_tooltip(control: &str, option: &str) -> Option<&'static str> {
    Some(match (control, option) {
        ("Projection", "perspective") => "A pinhole camera at the eye; the field of view sets the zoom.",
        ("Projection", "orthographic") => {
            "Parallel rays from the plane through the eye; the view height sets the zoom. Switching keeps the \
             look-at point's framing."
        }
        ("Integrator", "whitted") => {
            "The seed's model: local Phong terms, mirror and refracted rays, the ambient term."
        }
        ("Integrator", "path") => {
            "Paths with area lights, colour bleeding and caustics; no ambient term. Samples per pixel are paths."
        }
        ("Epsilon strategy", "tmin") => "Ignore hits closer than ε along the secondary ray (the seed's first remedy).",
        ("Epsilon strategy", "nudge_ray") => "Start the secondary ray ε along its own direction.",
        ("Epsilon strategy", "nudge_normal") => "Start the secondary ray ε off the surface, along the normal.",
        ("Epsilon strategy", "robust") => {
            "Wächter & Binder's offset, scaled to the hit point's floating-point precision: no ε to tune."
        }
        ("Epsilon strategy", "skip_convex") => {
            "Do not test the primitive the ray leaves (exact for convex ones); ε is not used."
        }
        ("Type", "point") => "Light from one point in every direction; L and f_att depend on the distance.",
        ("Type", "directional") => "Parallel light from infinitely far (the sun): one L, no attenuation.",
        ("Type", "spot") => "A point light restricted to a cone around its axis (S_j).",
        ("Attenuation", "polynomial") => "OpenGL's 1/(c + l·d + q·d²).",
        ("Attenuation", "inverse_square") => "Physical 1/d², optionally windowed by glTF's range.",
        ("Falloff", "power") => "OpenGL's (cos)^s inside a hard cutoff.",
        ("Falloff", "smooth") => "glTF's smooth step between the inner and the outer cone.",
        _ => return None,
    })
}

/// Which Help window is open.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum HelpWindow {
    #[default]
    None,
    FirstMinutes,
    Bindings,
}

/// The Help menu; returns the window to open.
pub fn menu(ui: &mut egui::Ui) -> Option<HelpWindow> {
    let mut open = None;
    ui.menu_button("Help", |ui| {
        if ui.button("The first five minutes").clicked() {
            open = Some(HelpWindow::FirstMinutes);
        }
        if ui.button("Keyboard and mouse").clicked() {
            open = Some(HelpWindow::Bindings);
        }
        ui.separator();
        for (text, file) in DOCS {
            ui.hyperlink_to(text, doc_url(file));
        }
    });
    open
}

/// The documentation the Help menu links to, in the source tree.
pub const DOCS: [(&str, &str); 7] = [
    ("The viewer (docs/viewer.md)", "docs/viewer.md"),
    ("What the Whitted model leaves out: a tour (docs/tour.md)", "docs/tour.md"),
    ("Scene format (docs/scene-format.md)", "docs/scene-format.md"),
    ("Models (docs/models.md)", "docs/models.md"),
    ("Numerics and stiff cases (docs/numerics.md)", "docs/numerics.md"),
    ("Rendering from the command line (docs/rendering.md)", "docs/rendering.md"),
    ("Performance (docs/performance.md)", "docs/performance.md"),
];

fn doc_url(file: &str) -> String {
    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../..");
    let path = root.join(file);
    format!("file://{}", path.canonicalize().unwrap_or(path).display())
}

const FIRST_MINUTES: &str = "\
1. The left image is the GPU tracer (f32, WGSL), the right one the CPU reference (f64). The status bar \
compares them: FLIP and the first-hit mismatch near 0 mean the mirror agrees.
2. Drag in an image to orbit, Shift+drag to pan, the wheel to zoom. Both tracers follow.
3. Scene tab: note Max depth, then set it to 0 — mirrors and glass go black: k_r·I_r and k_t·I_t need \
traced rays. Set it back to what it was.
4. Lights tab: drag I_d and I_s, switch the light to spot and move its cone.
5. Click an object to select its material (Materials tab); change k_d, k_s and the shininess n.
6. Ctrl+click a pixel: the Probe tab splits its colour into the terms of the equation, CPU beside GPU, \
and draws its ray tree over the image.
7. View menu, Difference: shows where the two tracers differ; the Errors tab plots the error over your edits.
8. View menu, Whitted vs GI (open cornell-gi): Whitted's image beside a path-traced one, the light the model \
leaves out; Whitted − GI maps it, and the Scene tab's Fit ambient to paths finds the I_a that stands in for it best.";

const BINDINGS: [(&str, &str); 10] = [
    ("Drag", "orbit the camera around its look-at point"),
    ("Shift+drag, middle drag", "pan"),
    ("Wheel", "zoom (move toward the look-at point)"),
    ("Click", "select the object under the pointer (its material opens)"),
    ("Ctrl+click", "probe the pixel (its terms and its ray tree) and select its object"),
    ("Ctrl+S", "save an image (GPU, CPU, difference or all)"),
    ("Ctrl+Z, Ctrl+Shift+Z", "undo, redo an edit (a whole drag at once); also Ctrl+Y"),
    ("F9", "show or hide the side panel"),
    ("Escape", "close a dialog, keeping what it would change"),
    ("Drop a file", "open a scene (.toml) or a model (.gltf, .glb, .obj)"),
];

/// The open Help window, if any; closes it when the user does.
pub fn window(ctx: &egui::Context, open: &mut HelpWindow) {
    let mut keep = true;
    match *open {
        HelpWindow::None => return,
        HelpWindow::FirstMinutes => {
            egui::Window::new("The first five minutes").open(&mut keep).default_width(420.0).show(ctx, |ui| {
                ui.label(FIRST_MINUTES);
            });
        }
        HelpWindow::Bindings => {
            egui::Window::new("Keyboard and mouse").open(&mut keep).show(ctx, |ui| {
                egui::Grid::new("bindings").striped(true).num_columns(2).show(ui, |ui| {
                    for (key, what) in BINDINGS {
                        ui.strong(key);
                        ui.label(what);
                        ui.end_row();
                    }
                });
            });
        }
    }
    if !keep {
        *open = HelpWindow::None;
    }
}
