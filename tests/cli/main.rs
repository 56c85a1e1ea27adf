//! End-to-end tests of the `glint` binary: every built-in scene to PNG and EXR, the PNG
//! metadata, `--list`, and clean failures (non-zero exit, a clear message, no file left).

use std::ffi::OsString;
use std::path::Path;
use std::process::{Command, Output};

use glint_test_support::TempDir;

mod bench;
mod device;
mod memory;
mod mitsuba;
mod models;
mod reliability;
mod report;
mod slurm;
mod tiles;

pub(crate) const BIN: &str = env!("CARGO_BIN_EXE_glint");

/// The built-in scenes the issue asks for, spelled out here rather than read from the crate.
const BUILTINS: [&str; 6] = ["whitted", "cornell", "cornell-gi", "spotlights", "highlights", "lights"];

/// The generated built-in scenes (made in code at `--resolution N`).
const GENERATED: [&str; 2] = ["bumpy", "bumpy-glass"];

/// Runs `glint ARGS` with the working directory in `cwd` (so a default output name could
/// never land in the source tree).
fn glint<I, S>(cwd: &Path, args: I) -> Output
where
    I: IntoIterator<Item = S>,
    S: Into<OsString>,
{
    let args: Vec<OsString> = args.into_iter().map(Into::into).collect();
    let out = Command::new(BIN).args(&args).current_dir(cwd).output().expect("run glint");
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(!stderr.contains("panicked"), "glint {args:?} panicked:\n{stderr}");
    out
}

fn text(bytes: &[u8]) -> String {
    String::from_utf8_lossy(bytes).into_owned()
}

fn png_text_chunks(path: &Path) -> Vec<(String, String)> {
    let file = std::io::BufReader::new(std::fs::File::open(path).expect("open png"));
    let reader = png::Decoder::new(file).read_info().expect("png header");
    let info = reader.info();
    let latin1 = info.uncompressed_latin1_text.iter().map(|t| (t.keyword.clone(), t.text.clone()));
    let utf8 = info.utf8_text.iter().map(|t| (t.keyword.clone(), t.get_text().expect("iTXt text")));
    latin1.chain(utf8).collect()
}

fn meta<'a>(chunks: &'a [(String, String)], key: &str) -> &'a str {
    chunks
        .iter()
        .find(|(k, _)| k == key)
        .map(|(_, v)| v.as_str())
        .unwrap_or_else(|| panic!("PNG metadata has no {key}: {chunks:?}"))
}

/// sRGB encoding (IEC 61966-2-1) of a linear value, clamped, as 8 bits.
fn srgb8(v: f32) -> u8 {
    let v = f64::from(v).clamp(0.0, 1.0);
    let s = if v <= 0.003_130_8 { 12.92 * v } else { 1.055 * v.powf(1.0 / 2.4) - 0.055 };
    (s * 255.0).round() as u8
}

#[test]
fn renders_every_builtin_scene_to_png_and_exr_with_metadata() {
    let dir = TempDir::new("render");
    let (w, h) = (40u32, 30u32);
    for name in BUILTINS {
        let png_path = dir.join(format!("{name}.png"));
        let exr_path = dir.join(format!("{name}.exr"));
        let settings = [
            "--width",
            "40",
            "--height",
            "30",
            "--spp",
            "2",
            "--depth",
            "3",
            "--epsilon",
            "0.001",
            "--epsilon-mode",
            "nudge_normal",
            "--seed",
            "7",
            "--threads",
            "2",
            "--quiet",
        ];
        // The bailout prunes Whitted's ray trees; under the path tracer (the scene's own
        // integrator) the flag would do nothing, and is an error.
        let builtin = glint_io::BUILTIN_SCENES.iter().find(|b| b.name == name).expect("a built-in");
        let whitted = builtin.load(None).expect("loads").0.render.integrator == glint_scene::Integrator::Whitted;
        let bailout = if whitted { &["--bailout", "0.01"][..] } else { &[] };
        for path in [&png_path, &exr_path] {
            let mut args: Vec<OsString> = vec!["render".into(), name.into(), "-o".into(), path.into()];
            args.extend(settings.iter().chain(bailout).map(Into::into));
            let out = glint(&dir, &args);
            assert!(out.status.success(), "{name} -> {}: {}", path.display(), text(&out.stderr));
            // One summary line: time, rays by kind, bailout savings, throughput.
            let stdout = text(&out.stdout);
            let kinds: &[&str] = if whitted {
                &["reflection", "refraction", "bailout"]
            } else {
                &["reflected or scattered", "refracted"]
            };
            for word in [name, "camera", "shadow", "Mrays/s"].iter().chain(kinds) {
                assert!(stdout.contains(word), "{name}: summary lacks {word:?}: {stdout}");
            }
        }

        // The PNG decodes, has the right size and is not blank.
        let png = image::open(&png_path).expect("decode PNG").into_rgb8();
        assert_eq!(png.dimensions(), (w, h), "{name}.png size");
        let first = *png.get_pixel(0, 0);
        assert!(png.pixels().any(|p| *p != first), "{name}.png is a constant image");

        // The metadata round-trips the settings given on the command line.
        let chunks = png_text_chunks(&png_path);
        assert_eq!(meta(&chunks, "glint:scene"), name);
        assert_eq!(meta(&chunks, "glint:source"), format!("builtin:{name}"));
        assert_eq!(meta(&chunks, "glint:scene_hash").len(), 64, "{name}: SHA-256 in hex");
        assert!(chunks.iter().all(|(k, _)| k != "glint:load_flags"), "{name}: no load flags were given");
        assert_eq!(meta(&chunks, "glint:size"), "40x30");
        assert_eq!(meta(&chunks, "glint:spp"), "2");
        assert_eq!(meta(&chunks, "glint:depth"), "3");
        assert_eq!(meta(&chunks, "glint:epsilon").parse::<f64>().unwrap(), 0.001);
        assert_eq!(meta(&chunks, "glint:epsilon_mode"), "nudge_normal");
        if whitted {
            assert_eq!(meta(&chunks, "glint:bailout").parse::<f64>().unwrap(), 0.01);
        } else {
            // Paths have no bailout to record, and say whether they follow every lobe.
            assert!(chunks.iter().all(|(k, _)| k != "glint:bailout"), "{name}: {chunks:?}");
            assert_eq!(meta(&chunks, "glint:indirect"), "on");
        }
        assert_eq!(meta(&chunks, "glint:seed"), "7");
        assert_eq!(meta(&chunks, "glint:backend"), "cpu");
        let ms: f64 = meta(&chunks, "glint:time_ms").parse().expect("time is a number");
        assert!(ms.is_finite() && ms >= 0.0);
        let rays: u64 = meta(&chunks, "glint:rays").parse().expect("ray count is a number");
        assert!(rays >= u64::from(w * h * 2), "{name}: {rays} rays for {} camera samples", w * h * 2);
        assert!(meta(&chunks, "Software").starts_with("glint"));

        // The EXR decodes to the same size, holds finite non-negative linear radiance, and is
        // the same render: its sRGB encoding matches the PNG to within one step (f32 storage
        // can move a value across a rounding boundary).
        let exr = image::open(&exr_path).expect("decode EXR").into_rgb32f();
        assert_eq!(exr.dimensions(), (w, h), "{name}.exr size");
        for (x, y, p) in exr.enumerate_pixels() {
            assert!(p.0.iter().all(|v| v.is_finite() && *v >= 0.0), "{name}.exr ({x}, {y}) = {:?}", p.0);
            let q = png.get_pixel(x, y);
            for c in 0..3 {
                let diff = (i32::from(srgb8(p.0[c])) - i32::from(q.0[c])).abs();
                assert!(diff <= 1, "{name} ({x}, {y}) channel {c}: EXR {} vs PNG {}", p.0[c], q.0[c]);
            }
        }
    }
    let mut expected: Vec<String> = BUILTINS.iter().flat_map(|n| [format!("{n}.exr"), format!("{n}.png")]).collect();
    expected.sort();
    assert_eq!(dir.listing(), expected, "only the requested images, no temporary files");
}

#[test]
fn scene_settings_are_used_when_no_flag_overrides_them() {
    // The metadata reports the scene file's own settings (and the defaults of the format)
    // where no flag is given.
    let dir = TempDir::new("defaults");
    let scene = dir.join("own.toml");
    std::fs::write(
        &scene,
        "[render]\nwidth = 24\nheight = 16\nspp = 3\nmax_depth = 4\nepsilon_mode = \"tmin\"\n\n\
         [camera]\nposition = [0.0, 1.0, -4.0]\nlook_at = [0.0, 0.5, 0.0]\n\n\
         [materials.m]\nkd = 0.5\n\n\
         [[lights]]\ntype = \"point\"\nposition = [1.0, 3.0, -2.0]\n\n\
         [[objects]]\ntype = \"sphere\"\ncenter = [0.0, 0.5, 0.0]\nradius = 0.5\nmaterial = \"m\"\n",
    )
    .unwrap();
    let out_path = dir.join("own.png");
    let out = glint(&dir, ["render".as_ref(), scene.as_os_str(), "-o".as_ref(), out_path.as_os_str(), "-q".as_ref()]);
    assert!(out.status.success(), "{}", text(&out.stderr));
    let chunks = png_text_chunks(&out_path);
    assert_eq!(meta(&chunks, "glint:scene"), "own");
    assert_eq!(meta(&chunks, "glint:size"), "24x16");
    assert_eq!(meta(&chunks, "glint:spp"), "3");
    assert_eq!(meta(&chunks, "glint:depth"), "4");
    assert_eq!(meta(&chunks, "glint:epsilon_mode"), "tmin");
    assert_eq!(meta(&chunks, "glint:epsilon").parse::<f64>().unwrap(), 1e-6);
    assert_eq!(meta(&chunks, "glint:bailout").parse::<f64>().unwrap(), 1.0 / 255.0);
    assert_eq!(image::open(&out_path).unwrap().into_rgb8().dimensions(), (24, 16));
}

#[test]
fn warnings_judge_the_settings_the_render_uses_not_the_scene_files() {
    // ε = 0.05 is 5 % of a sphere 1 wide: warned about, unless a flag lowers it; a flag that
    // raises the default to it is warned about once.
    let dir = TempDir::new("flag-warnings");
    let scene = |epsilon: &str| {
        format!(
            "[render]\nwidth = 8\nheight = 6\n{epsilon}\n[camera]\nposition = [0.0, 0.0, -4.0]\nlook_at = [0.0, 0.0, 0.0]\n\n\
             [materials.m]\nkd = 0.5\n\n[[objects]]\ntype = \"sphere\"\ncenter = [0.0, 0.0, 0.0]\nradius = 0.5\nmaterial = \"m\"\n"
        )
    };
    std::fs::write(dir.join("large.toml"), scene("epsilon = 0.05")).unwrap();
    std::fs::write(dir.join("plain.toml"), scene("")).unwrap();
    let render = |file: &str, flags: &[&str]| {
        let out = glint(&dir, [&["render", file, "-o", "out.png", "-q"][..], flags].concat());
        assert!(out.status.success(), "{}", text(&out.stderr));
        text(&out.stderr).matches("render.epsilon").count()
    };
    assert_eq!(render("large.toml", &[]), 1, "the file's own ε");
    assert_eq!(render("large.toml", &["--epsilon", "1e-7"]), 0, "an ε the flag lowered");
    assert_eq!(render("plain.toml", &[]), 0);
    assert_eq!(render("plain.toml", &["--epsilon", "0.05"]), 1, "an ε the flag raised, once");
    // Two floors 1e-4 apart overlap within ε = 1e-3, not within 1e-7: the file's ε warned of a
    // z-fight the flag had removed (a tester).
    let floors = |epsilon: &str| {
        format!(
            "[render]\nwidth = 8\nheight = 6\nepsilon = {epsilon}\n[camera]\nposition = [0.0, 1.0, -4.0]\n\
             look_at = [0.0, 0.0, 0.0]\n[materials.m]\nkd = 0.5\n\
             [[objects]]\ntype = \"plane\"\npoint = [0.0, 0.0, 0.0]\nnormal = [0.0, 1.0, 0.0]\nmaterial = \"m\"\n\
             [[objects]]\ntype = \"plane\"\npoint = [0.0, 1e-4, 0.0]\nnormal = [0.0, 1.0, 0.0]\nmaterial = \"m\"\n"
        )
    };
    std::fs::write(dir.join("wide.toml"), floors("1e-3")).unwrap();
    std::fs::write(dir.join("narrow.toml"), floors("1e-7")).unwrap();
    let fights = |file: &str, flags: &[&str]| {
        let out = glint(&dir, [&["render", file, "-o", "out.png", "-q"][..], flags].concat());
        assert!(out.status.success(), "{}", text(&out.stderr));
        text(&out.stderr).matches("z-fighting").count()
    };
    assert_eq!(fights("wide.toml", &[]), 1, "the file's own ε");
    assert_eq!(fights("wide.toml", &["--epsilon", "1e-7"]), 0, "an ε the flag lowered");
    assert_eq!(fights("narrow.toml", &[]), 0);
    assert_eq!(fights("narrow.toml", &["--epsilon", "1e-3"]), 1, "an ε the flag raised");
}

#[test]
fn an_adapter_name_from_the_environment_is_said_to_come_from_it() {
    // Names are matched once an adapter exists: with none the error is that, not the name.
    if glint_test_support::skip_requested("GLINT_SKIP_GPU") {
        return;
    }
    let dir = TempDir::new("adapter-env");
    let run = |env: Option<&str>, flag: &[&str]| {
        let mut command = Command::new(BIN);
        command.args(["render", "whitted", "--backend", "gpu", "-o", "x.png", "-q"]).args(flag).current_dir(&dir);
        match env {
            Some(value) => command.env("WGPU_ADAPTER_NAME", value),
            None => command.env_remove("WGPU_ADAPTER_NAME"),
        };
        let out = command.output().expect("run glint");
        assert!(!out.status.success());
        text(&out.stderr)
    };
    let said = run(Some("no-such-gpu-zzz"), &[]);
    assert!(said.contains("no GPU adapter matches 'no-such-gpu-zzz' (from WGPU_ADAPTER_NAME)"), "{said}");
    let said = run(None, &["--adapter", "no-such-gpu-zzz"]);
    assert!(said.contains("'no-such-gpu-zzz' (the adapter asked for)"), "{said}");
}

#[test]
fn accel_none_and_bvh_render_the_same_pixels() {
    // `--accel none` is brute force, as before the BVH; `--accel bvh` (the default) must give
    // the same image. EXR keeps the linear f32 values; a bad choice fails cleanly.
    let dir = TempDir::new("accel");
    let mut images = Vec::new();
    for accel in ["none", "bvh"] {
        let path = dir.join(format!("cornell-{accel}.exr"));
        let args = os(&[
            &"render",
            &"cornell",
            &"--width",
            &"40",
            &"--height",
            &"30",
            &"--accel",
            &accel,
            &"-q",
            &"-o",
            &path,
        ]);
        let out = glint(&dir, args);
        assert!(out.status.success(), "--accel {accel}: {}", text(&out.stderr));
        images.push(image::open(&path).expect("EXR decodes").into_rgb32f().into_raw());
    }
    let bits = |v: &[f32]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
    assert_eq!(bits(&images[0]), bits(&images[1]), "--accel none and --accel bvh differ");
    let out = glint(&dir, ["render", "cornell", "--accel", "octree", "-q"]);
    assert!(!out.status.success());
    assert!(text(&out.stderr).contains("octree"), "{}", text(&out.stderr));
}

#[test]
fn list_shows_the_builtin_scenes() {
    let dir = TempDir::new("list");
    let out = glint(&dir, ["render", "--list"]);
    assert!(out.status.success(), "{}", text(&out.stderr));
    let stdout = text(&out.stdout);
    let lines: Vec<&str> = stdout.lines().filter(|l| !l.trim().is_empty()).collect();
    assert_eq!(lines.len(), BUILTINS.len() + GENERATED.len(), "{stdout}");
    for name in BUILTINS.into_iter().chain(GENERATED) {
        let line = lines.iter().find(|l| l.split_whitespace().next() == Some(name));
        let line = line.unwrap_or_else(|| panic!("--list does not list {name}: {stdout}"));
        // Each with its description.
        assert!(line.split_whitespace().count() > 2, "{name} has no description: {line}");
    }
    assert!(dir.listing().is_empty(), "--list wrote files: {:?}", dir.listing());
}

/// Runs a failing command in a fresh folder and checks exit status, message and that the
/// folder holds nothing but `keep` afterwards.
fn expect_failure(tag: &str, setup: impl FnOnce(&TempDir) -> Vec<OsString>, fragments: &[&str], keep: &[&str]) {
    let dir = TempDir::new(tag);
    let args = setup(&dir);
    let out = glint(&dir, &args);
    let stderr = text(&out.stderr);
    assert!(!out.status.success(), "{tag}: glint {args:?} succeeded:\n{}", text(&out.stdout));
    assert!(out.status.code().is_some_and(|c| c != 0), "{tag}: no proper exit code: {:?}", out.status);
    for f in fragments {
        assert!(stderr.contains(f), "{tag}: message does not contain {f:?}:\n{stderr}");
    }
    let mut keep: Vec<String> = keep.iter().map(ToString::to_string).collect();
    keep.sort();
    assert_eq!(dir.listing(), keep, "{tag}: files left behind");
}

fn os(items: &[&dyn AsRef<std::ffi::OsStr>]) -> Vec<OsString> {
    items.iter().map(|s| s.as_ref().to_os_string()).collect()
}

const BAD_SCENE: &str = "[camera]\nposition = [0.0, 1.0, -4.0]\nlook_at = [0.0, 0.5, 0.0]\n\n\
    [materials.m]\nkd = 0.5\n\n\
    [[objects]]\ntype = \"sphere\"\ncenter = [0.0, 0.5, 0.0]\nradius = -0.5\nmaterial = \"m\"\n";

/// A command line that cannot be run exits 2 whichever check refused it, the argument
/// parser's or Glint's own (`--width 16385` exited 1 and `--width -5` 2); a scene or render
/// that fails exits 1.
#[test]
fn a_bad_command_line_exits_2_and_a_failed_render_1() {
    let dir = TempDir::new("exit-codes");
    let models = TempDir::new("exit-codes-obj");
    std::fs::write(models.join("q.obj"), "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n").unwrap();
    let obj = models.join("q.obj").to_string_lossy().into_owned();
    for (args, code) in [
        (&["render", "whitted", "--width", "-5"][..], 2),
        (&["render", "whitted", "--width", "16385"], 2),
        (&["render", "whitted", "--epsilon", "2000"], 2),
        (&["render", "whitted", "--runs", "3"], 2),
        (&["render", "whitted", "--adapter", "x"], 2),
        (&["render", "whitted", "-o", "x.jpg"], 2),
        (&["report", "--scenes", " , ", "--cpu-only"], 2),
        // Refused by glint's own checks with exit 1 (a CLI tester): flags that do nothing for
        // the scene, a tile or shard count no sweep or grid has, a list with a hole or a name
        // twice, an empty adapter name, a merged image of another format.
        (&["render", "whitted", "--resolution", "5"], 2),
        (&["render", "whitted", "--camera", "3"], 2),
        (&["render", "whitted", "--width", "8", "--height", "8", "--tile", "0/65", "-o", "x.exr"], 2),
        (&["report", "--quick", "--cpu-only", "--scenes", "whitted,whitted"], 2),
        (&["report", "--quick", "--cpu-only", "--scenes", "whitted", "--shard", "0/12"], 2),
        (&["report", "--quick", "--cpu-only", "--scenes", "whitted,,cornell"], 2),
        (&["report", "--quick", "--adapter", "", "--scenes", "whitted"], 2),
        (&["merge", "a.exr", "-o", "out.jpg"], 2),
        // A flag an OBJ file has nothing for (exit 1 before; a newcomer).
        (&["render", &obj, "--scene-index", "0"], 2),
        (&["render", &obj, "--camera", "0"], 2),
        (&["render", "nothere.toml"], 1),
    ] {
        let out = glint(&dir, args);
        assert_eq!(out.status.code(), Some(code), "{args:?}: {}", text(&out.stderr));
    }
    assert!(dir.listing().is_empty(), "{:?}", dir.listing());
}

#[test]
fn bad_input_fails_cleanly() {
    expect_failure(
        "unknown-scene",
        |d| os(&[&"render", &"nosuchscene", &"-o", &d.join("out.png")]),
        &["nosuchscene", "whitted", "cornell", "spotlights", "highlights", "lights"],
        &[],
    );
    // The drag benchmark measures the scene it names or none: never the window's fallback.
    expect_failure(
        "benchmark-missing-model",
        |d| os(&[&"view", &d.join("missing.glb"), &"--benchmark-drag", &"1"]),
        &["--benchmark-drag", "missing.glb", "no such file"],
        &[],
    );
    // A screenshot for a script pictures the scene it names, not the fallback, and writes
    // nothing when that does not load.
    expect_failure(
        "screenshot-bad-scene",
        |d| {
            std::fs::write(d.join("bad.toml"), BAD_SCENE).expect("scene");
            os(&[&"view", &d.join("bad.toml"), &"--screenshot", &d.join("shot.png")])
        },
        &["--screenshot", "bad.toml", "objects[0].radius"],
        &["bad.toml"],
    );
    // A huge value is said as written, not in 309 digits; a screenshot not named .png is
    // refused before any window (it said "no display" first).
    expect_failure(
        "benchmark-drag-huge",
        |_| os(&[&"view", &"whitted", &"--benchmark-drag", &"1e308"]),
        &["--benchmark-drag", "(0, 600], not 1e308"],
        &[],
    );
    expect_failure(
        "screenshot-jpeg",
        |d| os(&[&"view", &"whitted", &"--screenshot", &d.join("s.jpg")]),
        &["--screenshot", "s.jpg", "name the file .png"],
        &[],
    );
    expect_failure(
        "features-benchmark-missing-model",
        |d| os(&[&"view", &d.join("missing.glb"), &"--benchmark-features"]),
        &["--benchmark-features", "missing.glb", "no such file"],
        &[],
    );
    // Negative numbers reach the flag's own message (not clap's "unexpected argument '-8'").
    expect_failure(
        "width-negative",
        |d| os(&[&"render", &"whitted", &"-o", &d.join("out.png"), &"--width", &"-8"]),
        &["--width", "-8 is outside the allowed range [1, 16384]"],
        &[],
    );
    // Beyond what a u32 holds: the flag's range, not the type's.
    expect_failure(
        "depth-overflow",
        |d| os(&[&"render", &"whitted", &"-o", &d.join("out.png"), &"--depth", &"99999999999"]),
        &["--depth", "99999999999 is outside the allowed range [0, 1024]"],
        &[],
    );
    expect_failure(
        "bailout-negative",
        |d| os(&[&"render", &"whitted", &"-o", &d.join("out.png"), &"--bailout", &"-0.5"]),
        &["--bailout", "[0, 1]"],
        &[],
    );
    expect_failure(
        "scene-is-a-folder",
        |d| os(&[&"render", &d.as_os_str(), &"-o", &d.join("out.png")]),
        &["a folder, not a scene file"],
        &[],
    );
    // Another 3D format is named as one glint does not read (a PLY was parsed as TOML and
    // refused for its first line).
    expect_failure(
        "scene-is-a-ply",
        |d| {
            std::fs::write(d.join("wuson.ply"), "ply\nformat ascii 1.0\nend_header\n").expect("ply");
            os(&[&"render", &d.join("wuson.ply"), &"-o", &d.join("out.png")])
        },
        &["wuson.ply: a .ply file, a format glint does not read", ".gltf, .glb", ".obj"],
        &["wuson.ply"],
    );
    expect_failure(
        "spp-zero",
        |d| os(&[&"render", &"whitted", &"-o", &d.join("out.png"), &"--spp", &"0"]),
        &["--spp", "[1, 4096]"],
        &[],
    );
    expect_failure(
        "bailout-range",
        |d| os(&[&"render", &"whitted", &"-o", &d.join("out.png"), &"--bailout", &"2"]),
        &["--bailout", "[0, 1]"],
        &[],
    );
    expect_failure(
        "epsilon-mode",
        |d| os(&[&"render", &"whitted", &"-o", &d.join("out.png"), &"--epsilon-mode", &"fuzzy"]),
        &["fuzzy", "robust"],
        &[],
    );
    expect_failure(
        "extension",
        |d| os(&[&"render", &"whitted", &"-o", &d.join("out.bmp"), &"--width", &"8", &"--height", &"8"]),
        &["out.bmp", "unsupported output format"],
        &[],
    );
    expect_failure(
        "no-extension",
        |d| os(&[&"render", &"whitted", &"-o", &d.join("out"), &"--width", &"8", &"--height", &"8"]),
        &["unsupported output format"],
        &[],
    );
    expect_failure(
        "missing-folder",
        |d| os(&[&"render", &"whitted", &"-o", &d.join("missing/out.png"), &"--width", &"8", &"--height", &"8"]),
        &["missing", "does not exist"],
        &[],
    );
    // A file where the folder should be was said not to exist (a tester).
    expect_failure(
        "file-as-folder",
        |d| {
            std::fs::write(d.join("notes"), "a file").unwrap();
            os(&[&"render", &"whitted", &"-o", &d.join("notes/out.png"), &"--width", &"8", &"--height", &"8"])
        },
        &["notes/out.png: the output folder", "notes is a file, not a folder"],
        &["notes"],
    );
    // A link loop was said only to be "cannot be read" (a tester).
    #[cfg(unix)]
    expect_failure(
        "link-loop",
        |d| {
            std::os::unix::fs::symlink("lp2", d.join("lp1")).unwrap();
            std::os::unix::fs::symlink("lp1", d.join("lp2")).unwrap();
            os(&[&"render", &"whitted", &"-o", &d.join("lp1/x.png"), &"--width", &"8", &"--height", &"8"])
        },
        &["lp1/x.png: the output folder", "lp1 is a symbolic link loop (too many levels of symbolic links)"],
        &["lp1", "lp2"],
    );
    expect_failure(
        "inside-a-file",
        |d| {
            std::fs::write(d.join("notes"), "a file").unwrap();
            os(&[&"render", &"whitted", &"-o", &d.join("notes/deeper/out.png"), &"--width", &"8", &"--height", &"8"])
        },
        &["notes/deeper is inside a file, not a folder"],
        &["notes"],
    );
    expect_failure(
        "invalid-scene",
        |d| {
            std::fs::write(d.join("bad.toml"), BAD_SCENE).unwrap();
            os(&[&"render", &d.join("bad.toml"), &"-o", &d.join("out.png")])
        },
        &["bad.toml", "objects[0].radius", "-0.5", "(0, 1e9]"],
        &["bad.toml"],
    );
    expect_failure(
        "typo-in-scene",
        |d| {
            std::fs::write(d.join("typo.toml"), BAD_SCENE.replace("radius = -0.5", "raduis = 0.5")).unwrap();
            os(&[&"render", &d.join("typo.toml"), &"-o", &d.join("out.exr")])
        },
        &["typo.toml", "raduis"],
        &["typo.toml"],
    );
    expect_failure(
        "missing-scene-file",
        |d| os(&[&"render", &d.join("nothere.toml"), &"-o", &d.join("out.png")]),
        &["nothere.toml"],
        &[],
    );
    // A path that exists but is not a regular file is read as one, not called missing.
    expect_failure(
        "scene-is-a-device",
        |d| os(&[&"render", &"/dev/null", &"-o", &d.join("out.png")]),
        &["/dev/null: the file is empty"],
        &[],
    );
    // Number flags take a negative value to their own range messages (clap's "unexpected
    // argument '-1'" suggested `-- -1`, which made -1 the scene).
    for (flag, value, fragment) in [
        ("--seed", "-1", "-1 is outside the allowed range [0, 4294967295]"),
        // Those clap's own test does not take for numbers ("unexpected argument '-1' found").
        ("--epsilon", "-1e-3", "-0.001 is outside the allowed range [0, 1000]"),
        ("--epsilon", "-inf", "-inf is not a finite number; allowed: [0, 1000]"),
        ("--tile", "-1/4", "not a whole number"),
        ("--camera", "-1", "--camera"),
        // Beyond u32, the range every whole number of the scene format has.
        ("--scene-index", "4294967296", "'4294967296' is not an index (a whole number from 0 to 4294967295)"),
        ("--camera", "99999999999", "'99999999999' is not an index (a whole number from 0 to 4294967295)"),
        // Not numbers at all: the range, not "invalid float literal".
        ("--epsilon", "abc", "'abc' is not a number; allowed: [0, 1000]"),
        ("--bailout", "", "'' is not a number; allowed: [0, 1]"),
        ("--width", "wide", "'wide' is not a whole number; allowed: [1, 16384]"),
    ] {
        expect_failure(
            "negative-flag",
            |d| os(&[&"render", &"whitted", &"-o", &d.join("out.png"), &flag, &value]),
            &[flag, fragment],
            &[],
        );
    }
    // Flags that would be ignored are refused.
    expect_failure("runs-without-bench", |_| os(&[&"render", &"whitted", &"--runs", &"3"]), &["--bench"], &[]);
    expect_failure(
        "output-with-bench",
        |d| os(&[&"render", &"whitted", &"--bench", &"-o", &d.join("out.png")]),
        &["--bench", "--output"],
        &[],
    );
    expect_failure(
        "adapter-on-the-cpu",
        |d| os(&[&"render", &"whitted", &"--adapter", &"llvmpipe", &"-o", &d.join("out.png")]),
        &["--adapter", "--backend gpu or both"],
        &[],
    );
    expect_failure(
        "cpu-bound-on-the-gpu",
        |d| {
            os(&[
                &"render",
                &"whitted",
                &"--backend",
                &"gpu",
                &"--max-rays-per-sample",
                &"5",
                &"-o",
                &d.join("out.png"),
            ])
        },
        &["--max-rays-per-sample", "--backend cpu or both"],
        &[],
    );
    // A loop of links is named as one (it was "no such file").
    expect_failure(
        "link-loop",
        |d| {
            std::os::unix::fs::symlink(d.join("b.toml"), d.join("a.toml")).unwrap();
            std::os::unix::fs::symlink(d.join("a.toml"), d.join("b.toml")).unwrap();
            os(&[&"render", &d.join("a.toml"), &"-o", &d.join("out.png")])
        },
        &["a.toml", "symbolic links"],
        &["a.toml", "b.toml"],
    );
    // Flags that would do nothing where they are given.
    expect_failure(
        "list-with-flags",
        |d| os(&[&"render", &"--list", &"whitted", &"-o", &d.join("x.png"), &"--width", &"0"]),
        &["--list", "cannot be used with"],
        &[],
    );
    expect_failure(
        "runs-without-bench",
        |d| os(&[&"render", &"whitted", &"--runs", &"7", &"-o", &d.join("out.png")]),
        &["--runs", "--bench"],
        &[],
    );
    expect_failure(
        "incomplete-on-the-cpu",
        |d| os(&[&"render", &"whitted", &"--allow-incomplete", &"-o", &d.join("out.png")]),
        &["--allow-incomplete", "--backend gpu or both"],
        &[],
    );
    expect_failure(
        "empty-adapter",
        |d| os(&[&"render", &"whitted", &"--backend", &"gpu", &"--adapter", &"", &"-o", &d.join("out.png")]),
        &["--adapter is empty", "glint adapters"],
        &[],
    );
    expect_failure(
        "bailout-under-paths",
        |d| os(&[&"render", &"cornell-gi", &"--bailout", &"0.5", &"-o", &d.join("out.png")]),
        &["--bailout", "Russian roulette", "--integrator whitted"],
        &[],
    );
    expect_failure(
        "scene-index-of-an-obj",
        |d| {
            let obj = d.join("q.obj");
            std::fs::write(&obj, "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n").unwrap();
            os(&[&"render", &obj, &"--scene-index", &"0", &"-o", &d.join("out.png")])
        },
        &["q.obj: an OBJ file has no scenes", "--scene-index"],
        &["q.obj"],
    );
    // A folder as the output was "unsupported output format" (a newcomer).
    for slash in ["", "/"] {
        expect_failure(
            "output-is-a-folder",
            |d| {
                std::fs::create_dir_all(d.join("adir")).unwrap();
                os(&[&"render", &"whitted", &"-o", &format!("{}{slash}", d.join("adir").display())])
            },
            &["adir", ": is a folder, not a file; choose another output name (a .png or .exr file)"],
            &["adir"],
        );
    }
    // It was "1 is not a camera of the file; it has no camera on a node" (a newcomer: OBJ has
    // neither cameras nor nodes).
    expect_failure(
        "camera-of-an-obj",
        |d| {
            let obj = d.join("q.obj");
            std::fs::write(&obj, "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n").unwrap();
            os(&[&"render", &obj, &"--camera", &"1", &"-o", &d.join("out.png")])
        },
        &["q.obj: an OBJ file has no cameras to choose from: --camera is for glTF files"],
        &["q.obj"],
    );
}

#[test]
fn a_benchmark_prints_its_figures_as_json_when_asked() {
    let dir = TempDir::new("bench-json");
    let out =
        glint(&dir, ["render", "whitted", "--width", "24", "--height", "16", "--bench", "--runs", "2", "--json", "-q"]);
    assert!(out.status.success(), "{}", text(&out.stderr));
    let json: serde_json::Value = serde_json::from_slice(&out.stdout).expect("--bench --json prints JSON");
    assert_eq!(json["scene"], "whitted");
    assert_eq!(json["runs"], 2);
    let cpu = &json["backends"][0];
    assert_eq!(cpu["backend"], "cpu");
    assert!(cpu["median_ms"].as_f64().is_some_and(|v| v > 0.0) && cpu["min_ms"].as_f64() <= cpu["median_ms"].as_f64());
    assert_eq!(cpu["rays"]["camera"], 24 * 16);
    assert!(json["gpu_cpu_ratio"].is_null(), "one backend has no ratio");
}

#[test]
fn the_path_tracer_renders_on_both_tracers_from_a_flag_or_the_scene() {
    let dir = TempDir::new("path");
    let png = dir.join("cornell.png");
    let args = ["render", "cornell", "--integrator", "path", "--width", "24", "--height", "24", "--spp", "4", "-o"];
    let out = glint(&dir, args.iter().map(OsString::from).chain([png.clone().into_os_string()]));
    assert!(out.status.success(), "{}", text(&out.stderr));
    assert!(text(&out.stdout).contains("path tracer: 4 paths a pixel"), "{}", text(&out.stdout));
    assert!(text(&out.stderr).contains("world.ambient: is not used by the path tracer"), "{}", text(&out.stderr));
    assert_eq!(meta(&png_text_chunks(&png), "glint:integrator"), "path");
    assert_eq!(meta(&png_text_chunks(&png), "glint:indirect"), "on");

    // cornell-gi asks for paths itself; both tracers render it, and --indirect off is said.
    let both = dir.join("gi.png");
    let out = glint(
        &dir,
        [
            "render",
            "cornell-gi",
            "--backend",
            "both",
            "--width",
            "24",
            "--height",
            "24",
            "--spp",
            "2",
            "--indirect",
            "off",
            "-o",
        ]
        .iter()
        .map(OsString::from)
        .chain([both.clone().into_os_string()]),
    );
    assert!(out.status.success(), "{}", text(&out.stderr));
    assert!(text(&out.stdout).contains("only k_r and k_t with direct light"), "{}", text(&out.stdout));
    // The comparison weighs each pixel's difference by its value too (HDR pixels read as others).
    assert!(text(&out.stdout).contains(", relMSE "), "{}", text(&out.stdout));
    for backend in ["cpu", "gpu"] {
        let png = dir.join(format!("gi-{backend}.png"));
        assert_eq!(meta(&png_text_chunks(&png), "glint:integrator"), "path", "{backend}");
        assert_eq!(meta(&png_text_chunks(&png), "glint:indirect"), "off", "{backend}");
    }

    // A path-only flag typed for a Whitted render is an error naming the flag (exit 2).
    let out = glint(&dir, ["render", "whitted", "--indirect", "off", "-q"]);
    assert_eq!(out.status.code(), Some(2), "{}", text(&out.stderr));
    assert!(text(&out.stderr).contains("--indirect off chooses"), "{}", text(&out.stderr));
    // The same setting kept by a file is warned of under Whitted, and a file that says Whitted
    // renders with it under --integrator path (a student switching one file between the two).
    let file = dir.join("whitted-indirect-off.toml");
    let mut whitted = glint_io::load_scene("whitted").unwrap().desc;
    whitted.render.indirect = false;
    std::fs::write(&file, glint_io::to_toml(&whitted).unwrap()).unwrap();
    let args = |more: &[&str]| -> Vec<OsString> {
        let mut a: Vec<OsString> = ["render", "--width", "16", "--height", "12", "-q", "-o"].map(OsString::from).into();
        a.insert(1, file.clone().into_os_string());
        a.push(dir.join("off.png").into_os_string());
        a.extend(more.iter().map(OsString::from));
        a
    };
    let out = glint(&dir, args(&[]));
    assert!(out.status.success(), "{}", text(&out.stderr));
    assert!(text(&out.stderr).contains("render.indirect: false is a path-tracing setting"), "{}", text(&out.stderr));
    let out = glint(&dir, args(&["--integrator", "path", "--spp", "1"]));
    assert!(out.status.success(), "{}", text(&out.stderr));
    assert!(!text(&out.stderr).contains("render.indirect"), "{}", text(&out.stderr));
    assert_eq!(meta(&png_text_chunks(&dir.join("off.png")), "glint:indirect"), "off");
}

#[test]
fn a_side_given_alone_keeps_a_model_cameras_aspect_ratio() {
    // The file's camera has aspectRatio 2: the lab scene's image is twice as wide as high, and
    // a --height alone kept the scene's width (960×120 for 240×120). The ratio is the camera's
    // exact one, not the default image's rounded one: at 0.0031 that image is 1×480, whose ratio
    // made a --height 2000 image 4 wide, not 6. A side the ratio takes beyond the limits is held
    // to them and said, with the sides asked.
    use glint_test_support::gltf::{BufferAt, Fixture};
    let dir = TempDir::new("model-aspect");
    let model = |aspect: f64| {
        let mut f = Fixture::quad();
        f.json["cameras"] = serde_json::json!([{ "type": "perspective", "perspective": { "yfov": 0.5, "aspectRatio": aspect, "znear": 0.1 } }]);
        f.json["scenes"] = serde_json::json!([{ "nodes": [0, 1] }]);
        f.json["nodes"] = serde_json::json!([{ "mesh": 0 }, { "translation": [0.5, 0.5, 4.0], "camera": 0 }]);
        f.write_gltf(&dir, &format!("aspect-{aspect}"), BufferAt::DataUri)
    };
    for (aspect, flags, size, said) in [
        (2.0, ["--height", "24"], (48, 24), None),
        (2.0, ["--width", "30"], (30, 15), None),
        (0.0031, ["--height", "2000"], (6, 2000), None),
        (
            1e12,
            ["--height", "1"],
            (16384, 1),
            Some("would make the image 1000000000000x1 pixels; the width is held to 16384"),
        ),
        (
            1e-12,
            ["--width", "2"],
            (2, 16384),
            Some("would make the image 2x2000000000000 pixels; the height is held to 16384"),
        ),
    ] {
        let mut args: Vec<OsString> = vec!["render".into(), model(aspect).into_os_string(), "--json".into()];
        args.extend(flags.iter().map(Into::into));
        args.extend(["-o".into(), dir.join("m.png").into_os_string()]);
        let run = glint(&dir, args);
        assert!(run.status.success(), "{flags:?}: {}", text(&run.stderr));
        let v: serde_json::Value = serde_json::from_str(&text(&run.stdout)).expect("JSON");
        assert_eq!((v["width"].as_u64(), v["height"].as_u64()), (Some(size.0), Some(size.1)), "{aspect} {flags:?}");
        let stderr = text(&run.stderr);
        assert_eq!(stderr.contains("would make the image"), said.is_some(), "{aspect} {flags:?}: {stderr}");
        if let Some(said) = said {
            assert!(stderr.contains(said), "{aspect} {flags:?}: {stderr}");
        }
    }
    // A side no image can have is the flag's error, as for a scene file.
    let run = glint(&dir, ["render".into(), model(2.0).into_os_string(), "--width".into(), "0".into()]);
    assert!(!run.status.success());
    assert!(text(&run.stderr).contains("render.width (--width): 0 is outside"), "{}", text(&run.stderr));
}

#[test]
fn render_json_says_which_integrator_and_its_settings() {
    let dir = TempDir::new("json-integrator");
    let null = serde_json::Value::Null;
    for (integrator, own, bailout, indirect) in [
        ("whitted", ["--bailout", "0.25"], serde_json::json!(0.25), null.clone()),
        ("path", ["--indirect", "off"], null.clone(), serde_json::json!(false)),
    ] {
        let out = dir.join(format!("{integrator}.png")).into_os_string();
        let args =
            ["render", "cornell-gi", "--width", "8", "--height", "6", "--spp", "2", "--seed", "9", "--json", "-q"];
        let chosen = ["--integrator", integrator];
        let args = args.iter().chain(&chosen).chain(&own).map(OsString::from);
        let run = glint(&dir, args.chain([OsString::from("-o"), out]));
        assert!(run.status.success(), "{integrator}: {}", text(&run.stderr));
        let v: serde_json::Value = serde_json::from_str(&text(&run.stdout)).expect("JSON");
        assert_eq!(v["integrator"], integrator);
        assert_eq!((&v["bailout"], &v["indirect"], v["seed"].as_u64()), (&bailout, &indirect, Some(9)), "{v}");
        // Rays the bailout saved: Whitted's alone.
        let saved = &v["runs"][0]["rays"]["saved_by_bailout"];
        assert_eq!(saved.is_null(), integrator == "path", "{v}");
    }
}

#[test]
fn the_comparison_reads_the_images_as_written_and_an_exr_run_writes_a_linear_difference() {
    if glint_test_support::skip_requested("GLINT_SKIP_GPU") {
        return;
    }
    let dir = TempDir::new("diff-exr");
    let args = ["render", "whitted", "--backend", "both", "--width", "80", "--height", "60", "-q", "--json"];
    let out = glint(&dir, args.iter().copied().chain(["-o", "w.exr"]));
    assert!(out.status.success(), "{}", text(&out.stderr));
    let json: serde_json::Value = serde_json::from_slice(&out.stdout).expect("JSON");
    let read = |name: &str| glint_io::exr_file::read_exr(&dir.join(name)).expect(name).rgb;
    let (cpu, gpu, diff) = (read("w-cpu.exr"), read("w-gpu.exr"), read("w-diff.exr"));
    // The difference is |gpu − cpu| of the files, 0 exactly where they are the same bits (the
    // CPU's f64 image made some of those pixels differ before).
    let mut sum = 0.0;
    for ((c, g), d) in cpu.iter().zip(&gpu).zip(&diff) {
        for k in 0..3 {
            assert_eq!(d[k], (g[k] - c[k]).abs(), "{c:?} {g:?} {d:?}");
            sum += (f64::from(g[k]) - f64::from(c[k])).abs();
        }
    }
    let mean_abs = sum / (3 * cpu.len()) as f64;
    let printed = json["gpu_vs_cpu"]["mean_abs"].as_f64().expect("mean_abs");
    assert!((printed - mean_abs).abs() <= 1e-12 * mean_abs.max(1e-30), "{printed} against {mean_abs} from the files");
    let identical = cpu.iter().zip(&gpu).filter(|(c, g)| c == g).count();
    assert!(identical > 0, "the test needs pixels the tracers agree on to the bit");
    // A PNG run's heat map is black on the same pixels.
    let out = glint(&dir, args.iter().copied().chain(["-o", "w.png"]));
    assert!(out.status.success(), "{}", text(&out.stderr));
    let heat = image::open(dir.join("w-diff.png")).expect("heat map").to_rgb8();
    let black = heat.pixels().filter(|p| p.0 == [0, 0, 0]).count();
    assert_eq!(black, identical, "black where the written images are identical");
}

#[test]
fn an_image_records_what_shaped_its_scene_so_that_it_can_be_made_again() {
    let dir = TempDir::new("provenance");
    let render = |out: &str, extra: &[&str]| {
        let mut args = vec!["render", "bumpy", "--width", "24", "--height", "16", "-q", "-o", out];
        args.extend(extra);
        let run = glint(&dir, args);
        assert!(run.status.success(), "{}", text(&run.stderr));
        png_text_chunks(&dir.join(out))
    };
    let coarse = render("a.png", &["--resolution", "10"]);
    let finer = render("b.png", &["--resolution", "12"]);
    assert_eq!(meta(&coarse, "glint:load_flags"), "--resolution 10");
    assert_ne!(meta(&coarse, "glint:scene_hash"), meta(&finer, "glint:scene_hash"), "two scenes, two hashes");
    // The same flags again make the same scene; an edited copy of a scene file does not.
    assert_eq!(meta(&render("c.png", &["--resolution", "10"]), "glint:scene_hash"), meta(&coarse, "glint:scene_hash"));
    let file =
        std::fs::read_to_string(Path::new(env!("CARGO_MANIFEST_DIR")).join("assets/scenes/lights.toml")).unwrap();
    std::fs::create_dir(dir.join("edited")).unwrap();
    std::fs::write(dir.join("lights.toml"), &file).unwrap();
    std::fs::write(
        dir.join("edited/lights.toml"),
        file.replacen("background = [0.05, 0.05, 0.07]", "background = 0.5", 1),
    )
    .unwrap();
    let scene = |file: &str| {
        let run = glint(&dir, ["render", file, "--width", "24", "--height", "16", "-q", "-o", "l.png"]);
        assert!(run.status.success(), "{}", text(&run.stderr));
        png_text_chunks(&dir.join("l.png"))
    };
    let (copy, edited, builtin) = (scene("lights.toml"), scene("edited/lights.toml"), scene("lights"));
    assert_eq!(meta(&copy, "glint:scene"), meta(&edited, "glint:scene"), "one name");
    assert_eq!(meta(&edited, "glint:source"), "edited/lights.toml");
    assert_ne!(meta(&copy, "glint:scene_hash"), meta(&edited, "glint:scene_hash"), "an edit changes the hash");
    assert_eq!(meta(&copy, "glint:scene_hash"), meta(&builtin, "glint:scene_hash"), "a copy has the built-in's");
}

/// A scene read from a pipe names its default image `scene.png`: the stem of /dev/stdin or of
/// `<(generate-scene)`'s /dev/fd/63 named it `stdin.png` or `63.png` (a newcomer).
#[test]
fn a_scene_from_a_pipe_renders_to_scene_png() {
    let dir = TempDir::new("piped-scene");
    let scene = concat!(env!("CARGO_MANIFEST_DIR"), "/assets/scenes/cornell.toml");
    // A file redirected in, and a pipe.
    for piped in [false, true] {
        let stdin = if piped { std::process::Stdio::piped() } else { std::fs::File::open(scene).unwrap().into() };
        let mut child = Command::new(BIN)
            .args(["render", "/dev/stdin", "--width", "8", "--height", "6", "-q", "--force"])
            .current_dir(&dir)
            .stdin(stdin)
            .stdout(std::process::Stdio::piped())
            .stderr(std::process::Stdio::piped())
            .spawn()
            .expect("run glint");
        if let Some(mut input) = child.stdin.take() {
            std::io::Write::write_all(&mut input, &std::fs::read(scene).unwrap()).unwrap();
        }
        let out = child.wait_with_output().expect("glint ends");
        assert!(out.status.success(), "piped {piped}: {}", text(&out.stderr));
        assert_eq!(dir.listing(), ["scene.png"], "piped {piped}");
    }
}
