//! Render-setting flags shared by the commands, applied on top of a scene's own settings.

use std::ffi::OsStr;

use anyhow::Context;
use clap::Args;
use glint_core::memory::{self, MemoryEstimate, SourceKind};
use glint_io::model::Ground;
use glint_io::model::ModelError;
use glint_io::{DEFAULT_RESOLUTION, LoadOptions, LoadedScene, RESOLUTIONS, load_scene_with};
use glint_io::{ImportOptions, ModelFormat};
use glint_scene::{
    EpsilonMode, Integrator, Range, RenderSettings, Report, epsilon_warnings_of_objects, format_number, ranges,
    settings_warnings, validate_settings,
};

use super::console::tell;
use crate::cli::usage::usage;

#[derive(Clone, Debug, Default, Args)]
pub struct SettingsArgs {
    /// Image width in pixels [1, 16384] (default: the scene's)
    #[arg(long, allow_hyphen_values = true, value_parser = parse_side)]
    pub width: Option<u32>,
    /// Image height in pixels [1, 16384]
    #[arg(long, allow_hyphen_values = true, value_parser = parse_side)]
    pub height: Option<u32>,
    /// Samples per pixel [1, 4096]; more than one are stratified and jittered (a path render's one is jittered too)
    #[arg(long, allow_hyphen_values = true, value_parser = parse_spp)]
    pub spp: Option<u32>,
    /// Maximum recursion depth [0, 1024]; 0 = local shading only
    #[arg(long, allow_hyphen_values = true, value_parser = parse_depth)]
    pub depth: Option<u32>,
    /// Self-intersection epsilon in scene units [0, 1000]
    #[arg(long, allow_hyphen_values = true, value_parser = parse_epsilon)]
    pub epsilon: Option<f64>,
    /// How epsilon is applied: tmin, nudge_ray, nudge_normal, robust or skip_convex
    #[arg(long, value_parser = parse_epsilon_mode)]
    pub epsilon_mode: Option<EpsilonMode>,
    /// Adaptive bailout: skip child rays whose path weight is below this [0, 1]; 0 disables
    #[arg(long, allow_hyphen_values = true, value_parser = parse_bailout)]
    pub bailout: Option<f64>,
    /// Seed of the sample jitter and of the paths' random numbers [0, 4294967295]
    #[arg(long, allow_hyphen_values = true, value_parser = parse_in::<0, { u32::MAX }>)]
    pub seed: Option<u32>,
    /// How light is carried: whitted (the seed's ray tree) or path (Monte Carlo paths: global
    /// illumination with area lights, colour bleeding and caustics; --spp paths a pixel, --depth
    /// bounces at most). Default: the scene's render.integrator, else whitted
    #[arg(long, value_parser = parse_integrator)]
    pub integrator: Option<Integrator>,
    /// Path tracing: on (default) follows every lobe; off follows only k_r and k_t with direct
    /// light, the transport Whitted computes, so that the difference is the indirect light
    #[arg(long, value_parser = parse_on_off)]
    pub indirect: Option<bool>,
}

/// How the scene argument is opened: the size of a generated built-in scene, and the import
/// choices of a model file. Each is an error with a scene it does not apply to.
#[derive(Clone, Copy, Debug, Default, Args)]
pub struct LoadArgs {
    /// Resolution N of a generated built-in scene (bumpy, bumpy-glass): 4·N² sphere triangles, N in [2, 1500], default 500; an error with any other scene
    #[arg(long, value_name = "N", allow_hyphen_values = true, value_parser = parse_resolution)]
    pub resolution: Option<u32>,
    /// The glTF scene to open (0-based; default: the file's default scene, else its first)
    #[arg(long, value_name = "N", allow_hyphen_values = true, value_parser = parse_index)]
    pub scene_index: Option<u32>,
    /// The model file's camera to look through (0-based; default: its first, or one framing the model)
    #[arg(long, value_name = "N", allow_hyphen_values = true, value_parser = parse_index)]
    pub camera: Option<u32>,
    /// Scale of a model file's light intensities (candela, lux) into I_d and I_s, in (0, 1e6]; default 1
    #[arg(long, value_name = "FACTOR", allow_hyphen_values = true, value_parser = parse_exposure)]
    pub exposure: Option<f64>,
    /// A grey ground under a model file: auto (unless the model has its own floor), on, off;
    /// never coplanar with the model's faces
    #[arg(long, value_name = "MODE", value_parser = parse_ground)]
    pub ground: Option<Ground>,
    /// Refuse a load or render estimated to need more memory than this (e.g. 512M, 8G;
    /// default: the memory available)
    #[arg(long, value_name = "SIZE", allow_hyphen_values = true, value_parser = memory::parse_size)]
    pub memory_limit: Option<u64>,
}

impl LoadArgs {
    /// The flags among these that change the scene as loaded, as they would be typed again
    /// (`--resolution 10 --ground off`): what an image's metadata needs, besides the scene and
    /// the settings, to be rendered again. The memory limit changes nothing drawn.
    pub fn flags(&self) -> String {
        let mut out = Vec::new();
        if let Some(n) = self.resolution {
            out.push(format!("--resolution {n}"));
        }
        if let Some(i) = self.scene_index {
            out.push(format!("--scene-index {i}"));
        }
        if let Some(i) = self.camera {
            out.push(format!("--camera {i}"));
        }
        if let Some(e) = self.exposure {
            out.push(format!("--exposure {e}"));
        }
        if let Some(g) = self.ground {
            out.push(format!("--ground {}", g.name()));
        }
        out.join(" ")
    }

    /// The load options of these flags, with the image sides given (`--width`, `--height`): a
    /// model file sizes the side not given by its camera's aspect ratio.
    pub fn options(&self, settings: Option<&SettingsArgs>) -> LoadOptions {
        let import = ImportOptions {
            scene_index: self.scene_index,
            camera: self.camera.map(|i| i as usize),
            exposure: self.exposure.unwrap_or(ImportOptions::default().exposure),
            ground: self.ground.unwrap_or_default(),
            lights: true,
            width: settings.and_then(|s| s.width),
            height: settings.and_then(|s| s.height),
        };
        LoadOptions { resolution: self.resolution, import, stream_cap: memory::stream_cap(self.memory_limit) }
    }
}

/// u32, as every whole number in a scene file (a scene's `scene_index`).
fn parse_index(s: &str) -> Result<u32, String> {
    s.trim().parse::<u32>().map_err(|_| format!("'{s}' is not an index (a whole number from 0 to {})", u32::MAX))
}

fn parse_ground(s: &str) -> Result<Ground, String> {
    s.parse()
}

/// Judged as a scene file's `exposure` is (`ranges::EXPOSURE`): a factor that f32 rounds to 0
/// would turn the model's lights off without a word.
fn parse_exposure(s: &str) -> Result<f64, String> {
    let range = ranges::EXPOSURE;
    match s.trim().parse::<f64>() {
        Ok(v) if range.contains(v) => Ok(v),
        Ok(v) => Err(format!("{} is outside {}{}", format_number(v), range.bounds(), range.why_outside(v))),
        Err(_) => Err(format!("'{s}' is not a number; allowed: {}", range.bounds())),
    }
}

fn parse_resolution(s: &str) -> Result<u32, String> {
    let (lo, hi) = (*RESOLUTIONS.start(), *RESOLUTIONS.end());
    let out_of_range = || {
        format!("--resolution takes a whole number N in [{lo}, {hi}] (4·N² triangles; default {DEFAULT_RESOLUTION})")
    };
    match s.trim().parse::<i64>() {
        Ok(v) if (i64::from(lo)..=i64::from(hi)).contains(&v) => Ok(v as u32),
        Ok(v) => Err(format!("{v} is outside [{lo}, {hi}]: {}", out_of_range())),
        Err(_) => Err(format!("'{s}' is not a whole number: {}", out_of_range())),
    }
}

/// A whole number in [LO, HI], said as the scene errors say a range (clap's own `.range()`
/// said "4097 is not in 1..=4096", Rust's syntax).
pub fn parse_in<const LO: u32, const HI: u32>(s: &str) -> Result<u32, String> {
    match s.trim().parse::<i128>() {
        Ok(v) if (i128::from(LO)..=i128::from(HI)).contains(&v) => Ok(v as u32),
        Ok(v) => Err(format!("{v} is outside the allowed range [{LO}, {HI}]")),
        Err(_) => Err(format!("'{s}' is not a whole number; allowed: [{LO}, {HI}]")),
    }
}

/// A whole number a u32 holds, refused with its setting's allowed range otherwise (a negative
/// one would get clap's "unexpected argument '-8'"). The range itself is checked with the other
/// settings, by validation, which names the scene field and the flag together.
fn parse_count(s: &str, range: Range<u32>) -> Result<u32, String> {
    let (lo, hi) = (range.min, range.max);
    match s.trim().parse::<i128>() {
        Ok(v) => u32::try_from(v).map_err(|_| format!("{v} is outside the allowed range [{lo}, {hi}]")),
        Err(_) => Err(format!("'{s}' is not a whole number; allowed: [{lo}, {hi}]")),
    }
}

/// A number, refused with its setting's allowed range when it is none ("invalid float literal"
/// named neither); the range itself is checked by validation, as for `parse_count`.
fn parse_number(s: &str, range: Range<f64>) -> Result<f64, String> {
    s.trim().parse::<f64>().map_err(|_| format!("'{s}' is not a number; allowed: {}", range.bounds()))
}

fn parse_epsilon(s: &str) -> Result<f64, String> {
    parse_number(s, ranges::EPSILON)
}

fn parse_bailout(s: &str) -> Result<f64, String> {
    parse_number(s, ranges::BAILOUT)
}

fn parse_side(s: &str) -> Result<u32, String> {
    parse_count(s, ranges::IMAGE_SIDE)
}

fn parse_spp(s: &str) -> Result<u32, String> {
    parse_count(s, ranges::SPP)
}

fn parse_depth(s: &str) -> Result<u32, String> {
    parse_count(s, ranges::DEPTH)
}

/// The most worker threads `--threads` takes, whatever the machine: more only adds memory
/// (a stack each) and scheduling, never speed.
pub const MAX_THREADS: usize = 1024;

/// `--threads`: 0 (one per core) up to 4 per core, and never more than `MAX_THREADS`.
pub fn thread_limit() -> usize {
    (4 * std::thread::available_parallelism().map_or(1, std::num::NonZero::get)).min(MAX_THREADS)
}

pub fn parse_threads(s: &str) -> Result<usize, String> {
    let max = thread_limit();
    let allowed = || format!("--threads takes 0 (one per core) to {max} (4 per core, at most {MAX_THREADS})");
    match s.trim().parse::<i128>() {
        Ok(v) if (0..=max as i128).contains(&v) => Ok(v as usize),
        Ok(v) => Err(format!("{v} is outside [0, {max}]: {}", allowed())),
        Err(_) => Err(format!("'{s}' is not a whole number: {}", allowed())),
    }
}

/// The largest `--max-rays-per-sample`: 2^40 rays is days of one core.
const MAX_RAY_CAP: u64 = 1 << 40;

pub fn parse_ray_cap(s: &str) -> Result<u64, String> {
    match s.trim().parse::<i128>() {
        Ok(v) if (1..=i128::from(MAX_RAY_CAP)).contains(&v) => Ok(v as u64),
        Ok(v) => Err(format!("{v} is outside [1, {MAX_RAY_CAP}] (rays per camera sample)")),
        Err(_) => Err(format!("'{s}' is not a whole number of rays in [1, {MAX_RAY_CAP}]")),
    }
}

pub fn parse_integrator(s: &str) -> Result<Integrator, String> {
    Integrator::from_name(s).ok_or_else(|| {
        let names: Vec<&str> = Integrator::ALL.iter().map(|m| m.name()).collect();
        format!("unknown integrator '{s}'; allowed: {}", names.join(", "))
    })
}

fn parse_on_off(s: &str) -> Result<bool, String> {
    match s {
        "on" => Ok(true),
        "off" => Ok(false),
        _ => Err(format!("'{s}' is neither on nor off")),
    }
}

fn parse_epsilon_mode(s: &str) -> Result<EpsilonMode, String> {
    EpsilonMode::from_name(s).ok_or_else(|| {
        let names: Vec<&str> = EpsilonMode::ALL.iter().map(|m| m.name()).collect();
        format!("unknown epsilon mode '{s}'; allowed: {}", names.join(", "))
    })
}

impl SettingsArgs {
    /// The scene's settings with these flags applied, validated. (A model file's load has
    /// sized the side not given by its camera's aspect ratio: `LoadArgs::options`.)
    pub fn apply(&self, base: &RenderSettings) -> anyhow::Result<RenderSettings> {
        let mut s = base.clone();
        if let Some(v) = self.width {
            s.width = v;
        }
        if let Some(v) = self.height {
            s.height = v;
        }
        if let Some(v) = self.spp {
            s.spp = v;
        }
        if let Some(v) = self.depth {
            s.max_depth = v;
        }
        if let Some(v) = self.epsilon {
            s.epsilon = v;
        }
        if let Some(v) = self.epsilon_mode {
            s.epsilon_mode = v;
        }
        if let Some(v) = self.bailout {
            s.bailout = v;
        }
        if let Some(v) = self.seed {
            s.seed = v;
        }
        if let Some(v) = self.integrator {
            s.integrator = v;
        }
        if let Some(v) = self.indirect {
            s.indirect = v;
        }
        // A flag typed for the other integrator does nothing: refused, as a model flag on a scene
        // file is (the same setting from a file is only warned of, `integrator_warnings`).
        if self.indirect == Some(false) && s.integrator == Integrator::Whitted {
            usage!(
                "--indirect off chooses what the path tracer's paths follow (only k_r and k_t), and Whitted's ray tree \
                 follows nothing else: leave --indirect out, or render with --integrator path"
            );
        }
        if self.bailout.is_some() && s.integrator == Integrator::Path {
            usage!(
                "--bailout prunes Whitted's ray tree, and the path tracer has none to prune (Russian roulette ends \
                 its paths): leave --bailout out, or render with --integrator whitted"
            );
        }
        let mut report = Report::default();
        validate_settings(&s, &mut report);
        if !report.errors.is_empty() {
            let lines: Vec<String> =
                report.errors.iter().map(|e| format!("  {} ({}): {}", e.field, flag_of(&e.field), e.problem)).collect();
            usage!("invalid render settings:\n{}", lines.join("\n"));
        }
        Ok(s)
    }
}

fn flag_of(field: &str) -> &'static str {
    match field {
        "render.width" => "--width",
        "render.height" => "--height",
        "render.spp" => "--spp",
        "render.max_depth" => "--depth",
        "render.epsilon" => "--epsilon",
        "render.bailout" => "--bailout",
        "render.integrator" => "--integrator",
        "render.indirect" => "--indirect",
        _ => "scene file",
    }
}

/// Loads a scene file, model file or built-in scene with `options` and prints its warnings,
/// first refusing a file whose load is estimated to need more memory than `memory_limit` (or
/// than is available).
pub fn load(scene: impl AsRef<OsStr>, options: &LoadOptions, memory_limit: Option<u64>) -> anyhow::Result<LoadedScene> {
    let (loaded, _) = load_with_estimate(scene, options, memory_limit)?;
    tell_warnings(&loaded, &loaded.desc.render);
    Ok(loaded)
}

/// `load` without its warnings (`tell_warnings` says them once the render's settings are
/// known), with the estimate the file's load was checked against (`None` for a built-in).
pub fn load_with_estimate(
    scene: impl AsRef<OsStr>,
    options: &LoadOptions,
    memory_limit: Option<u64>,
) -> anyhow::Result<(LoadedScene, Option<MemoryEstimate>)> {
    let scene = scene.as_ref();
    let estimate = check_load_memory(scene, options.resolution, memory_limit)?;
    let loaded = match super::interrupt::while_loading(|| load_scene_with(scene, options)) {
        Ok(loaded) => loaded,
        // Flags that do nothing for this scene: the command line's error (exit 2), not the file's.
        Err(
            e @ (glint_io::SceneError::NotGenerated { .. }
            | glint_io::SceneError::NotAModel { .. }
            | glint_io::SceneError::Model(ModelError::ObjHasNoScenes { .. } | ModelError::ObjHasNoCameras { .. })),
        ) => {
            usage!("cannot load scene '{}': {e}", scene.to_string_lossy())
        }
        Err(e) => return Err(e).with_context(|| format!("cannot load scene '{}'", scene.to_string_lossy())),
    };
    Ok((loaded, estimate))
}

/// Prints the warnings of `loaded` rendered with `settings`: those its own settings gave that
/// `settings` (its settings with the flags applied) no longer give are left out, and those the
/// flags add are said (an ε the flags lowered is not warned about, one they raised is).
pub fn tell_warnings(loaded: &LoadedScene, settings: &RenderSettings) {
    // Validation judged the scene's own settings already; judging them again walks every
    // vertex twice more (the ε warning's scene size) for nothing.
    if *settings == loaded.desc.render {
        for w in &loaded.warnings {
            tell!("warning: {}: {w}", loaded.source.display());
        }
        return;
    }
    let mut own = settings_warnings(&loaded.desc, &loaded.desc.render);
    let mut now = settings_warnings(&loaded.desc, settings);
    // The objects' overlaps are judged at the render's ε too (an `--epsilon` the file's z-fight
    // warning ignored; a tester): only where the flag changed it, as they walk every triangle.
    if settings.epsilon != loaded.desc.render.epsilon {
        own.extend(epsilon_warnings_of_objects(&loaded.desc, loaded.desc.render.epsilon));
        now.extend(epsilon_warnings_of_objects(&loaded.desc, settings.epsilon));
    }
    let kept = loaded.warnings.iter().filter(|w| !own.contains(w) || now.contains(w));
    for w in kept.chain(now.iter().filter(|w| !own.contains(w))) {
        tell!("warning: {}: {w}", loaded.source.display());
    }
}

/// Refuses a scene or model file whose load is estimated to need more memory than
/// `memory_limit` (or than is available), before it is read; the estimate of a file (`None`
/// for a built-in scene).
pub fn check_load_memory(
    scene: impl AsRef<OsStr>,
    resolution: Option<u32>,
    memory_limit: Option<u64>,
) -> anyhow::Result<Option<MemoryEstimate>> {
    let path = std::path::Path::new(scene.as_ref());
    // A generated built-in scene is held to its size before it is made: `bumpy --resolution
    // 1500` under a 100 MiB limit was generated (18 s, 510 MB) before the render refused it.
    if !path.exists()
        && let Some(b) = path.to_str().and_then(glint_io::builtin)
        && let Some((n, vertices, triangles)) = b.generated_size(resolution)
    {
        memory::check(
            format!("generating {} at resolution {n} ({triangles} triangles)", b.name),
            &memory::generated_estimate(vertices, triangles),
            memory_limit,
            "lower --resolution",
        )?;
        return Ok(None);
    }
    if let Ok(meta) = std::fs::metadata(path)
        && meta.is_file()
    {
        let kind = match ModelFormat::of(path) {
            Some(ModelFormat::Gltf) => SourceKind::Gltf,
            Some(ModelFormat::Obj) => SourceKind::Obj,
            None => SourceKind::Toml,
        };
        let estimate = memory::load_estimate(kind, meta.len());
        memory::check(
            format!("loading {} ({})", path.display(), memory::format_bytes(meta.len())),
            &estimate,
            memory_limit,
            "split the scene, or load it on a machine with more memory",
        )?;
        return Ok(Some(estimate));
    }
    Ok(None)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn an_exposure_is_judged_as_a_scene_files_is() {
        assert_eq!(parse_exposure("2.5"), Ok(2.5));
        // Above 0, but 0 in f32: the lights would go out without a word.
        assert_eq!(
            parse_exposure("1e-308").unwrap_err(),
            "1e-308 is outside (0, 1e6]: 1e-308 rounds to 0 in f32, the precision the tracers store it in"
        );
        // Written short, not as 309 digits.
        assert_eq!(parse_exposure("1e308").unwrap_err(), "1e308 is outside (0, 1e6]");
        assert_eq!(parse_exposure("-1").unwrap_err(), "-1 is outside (0, 1e6]");
    }
}
