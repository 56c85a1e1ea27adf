//! `glint view`: the interactive viewer (also what `glint` with no subcommand opens).

use std::path::PathBuf;

use anyhow::bail;
use clap::Args;
use glint_io::load_scene_with;
use glint_viewer::{GiView, ViewMode, ViewerError, ViewerOptions};

use super::console::say;
use super::settings::{LoadArgs, SettingsArgs, check_load_memory};

#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum StartView {
    Gpu,
    Cpu,
    SideBySide,
    Wipe,
    Difference,
    /// Whitted's image beside the path-traced one (the scene is switched to paths)
    WhittedVsGi,
    /// Whitted's image wiped against the path-traced one
    WhittedWipeGi,
    /// Whitted − paths on a diverging colour map
    WhittedMinusGi,
}

impl StartView {
    /// The viewer's mode, and how Whitted vs GI shows its two images.
    fn modes(self) -> (ViewMode, GiView) {
        match self {
            Self::Gpu => (ViewMode::Gpu, GiView::SideBySide),
            Self::Cpu => (ViewMode::Cpu, GiView::SideBySide),
            Self::SideBySide => (ViewMode::SideBySide, GiView::SideBySide),
            Self::Wipe => (ViewMode::Wipe, GiView::SideBySide),
            Self::Difference => (ViewMode::Difference, GiView::SideBySide),
            Self::WhittedVsGi => (ViewMode::WhittedVsGi, GiView::SideBySide),
            Self::WhittedWipeGi => (ViewMode::WhittedVsGi, GiView::Wipe),
            Self::WhittedMinusGi => (ViewMode::WhittedVsGi, GiView::Difference),
        }
    }
}

#[derive(Debug, Args)]
pub struct ViewArgs {
    /// A scene file (.toml), a model file (.gltf, .glb, .obj) opened in a lab scene, or the name of a built-in scene
    #[arg(default_value = "whitted", value_parser = clap::value_parser!(std::ffi::OsString))]
    pub scene: std::ffi::OsString,
    #[command(flatten)]
    pub settings: SettingsArgs,
    #[command(flatten)]
    pub scene_size: LoadArgs,
    /// The view to start in
    #[arg(long, value_enum, default_value_t = StartView::SideBySide)]
    pub view: StartView,
    /// Render, save a screenshot of the window (PNG with the settings embedded) and exit
    #[arg(long, value_name = "PNG")]
    pub screenshot: Option<PathBuf>,
    /// Orbit the camera for SECONDS as a drag would, then print the frame rates and exit
    #[arg(long, value_name = "SECONDS", allow_hyphen_values = true)]
    pub benchmark_drag: Option<f64>,
    /// Use each feature that needs a shader variant of its own (more samples, depth 0, a spot
    /// light, Phong, Cook–Torrance) for the first time, print the longest frame interval while
    /// each rendered, and exit
    #[arg(long)]
    pub benchmark_features: bool,
    /// Render the scene with paths and let the GPU add samples for SECONDS, then print the
    /// samples reached, their rate and the frame intervals meanwhile, and exit
    #[arg(long, value_name = "SECONDS", allow_hyphen_values = true)]
    pub benchmark_paths: Option<f64>,
}

impl Default for ViewArgs {
    /// What `glint` without a subcommand opens: the built-in whitted scene as it is.
    fn default() -> Self {
        Self {
            scene: "whitted".into(),
            settings: SettingsArgs::default(),
            scene_size: LoadArgs::default(),
            view: StartView::SideBySide,
            screenshot: None,
            benchmark_drag: None,
            benchmark_features: false,
            benchmark_paths: None,
        }
    }
}

/// The flag of a scripted run (a benchmark or a screenshot), which must not measure or picture
/// the window's fallback scene in place of the one it names.
fn scripted_flag(args: &ViewArgs) -> Option<&'static str> {
    [
        (args.benchmark_features, "--benchmark-features"),
        (args.benchmark_paths.is_some(), "--benchmark-paths"),
        (args.benchmark_drag.is_some(), "--benchmark-drag"),
        (args.screenshot.is_some(), "--screenshot"),
    ]
    .into_iter()
    .find_map(|(given, flag)| given.then_some(flag))
}

pub fn run(args: &ViewArgs) -> anyhow::Result<()> {
    for (flag, value) in [("--benchmark-drag", args.benchmark_drag), ("--benchmark-paths", args.benchmark_paths)] {
        if let Some(s) = value
            && !(s.is_finite() && s > 0.0 && s <= 600.0)
        {
            bail!("{flag} takes a number of seconds in (0, 600], not {}", glint_scene::format_number(s));
        }
    }
    // Before any window: without a display the first word was "no display" for a name that
    // could never be written.
    if let Some(path) = &args.screenshot
        && !path.extension().is_some_and(|e| e.eq_ignore_ascii_case("png"))
    {
        bail!("--screenshot {}: a screenshot is written as PNG; name the file .png", path.display());
    }
    check_load_memory(&args.scene, args.scene_size.resolution, args.scene_size.memory_limit)?;
    let load = args.scene_size.options(Some(&args.settings));
    // A scene that does not load is reported in the viewer window; flags apply to one that does.
    // A resolution the scene cannot take is a flag error, before any window opens, and so is
    // a scene a benchmark or a screenshot cannot load: it would measure, or picture, the
    // window's fallback instead, and a script would take that for the scene.
    let mut read = None;
    let settings = match super::interrupt::while_loading(|| load_scene_with(&args.scene, &load)) {
        Ok(loaded) => {
            let settings = args.settings.apply(&loaded.desc.render)?;
            read = Some(loaded);
            Some(settings)
        }
        Err(e @ glint_io::SceneError::NotGenerated { .. }) => bail!("--resolution: {e}"),
        Err(e @ glint_io::SceneError::NotAModel { .. }) => bail!("{e}"),
        Err(e) => match scripted_flag(args) {
            Some(flag) => bail!("{flag}: cannot load scene '{}': {e}", args.scene.to_string_lossy()),
            None => None,
        },
    };
    let (view, gi_view) = args.view.modes();
    let options = ViewerOptions {
        settings,
        view: Some(view),
        gi_view,
        paths_benchmark: args.benchmark_paths,
        scene: args.scene.clone(),
        load,
        loaded: read,
        screenshot: args.screenshot.clone(),
        drag_benchmark: args.benchmark_drag,
        features_benchmark: args.benchmark_features,
        ..ViewerOptions::default()
    };
    match glint_viewer::run(options) {
        Ok(Some(report)) => {
            say!("{report}")?;
            Ok(())
        }
        // Closed by a signal (and not taken over in the window): "interrupted", 130 or 143.
        Ok(None) => super::interrupt::check(),
        // One line, no chain: the message already says what to do instead.
        Err(e @ (ViewerError::NoDisplay | ViewerError::Window(_))) => bail!("{e}"),
        Err(e) => Err(e.into()),
    }
}
