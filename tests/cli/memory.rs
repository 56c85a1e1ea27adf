//! Memory is estimated before it is taken (issue 13, point 9): a load or a render beyond the
//! limit is refused at once with the estimate, and the estimate `--json` gives is held against
//! the peak resident memory of the same run.

use glint_test_support::TempDir;
use serde_json::Value;

use super::{glint, text};

fn skip_gpu() -> bool {
    glint_test_support::skip_requested("GLINT_SKIP_GPU")
}

#[test]
fn a_render_beyond_the_memory_limit_is_refused_before_it_starts_with_the_estimate() {
    let dir = TempDir::new("memory-render");
    let start = std::time::Instant::now();
    let out = glint(
        &dir,
        ["render", "whitted", "--width", "16384", "--height", "16384", "-q", "-o", "huge.exr", "--memory-limit", "1G"],
    );
    let stderr = text(&out.stderr);
    assert!(!out.status.success(), "a 16384² render passed a 1 GiB limit");
    for f in [
        "rendering whitted at 16384x16384 would need about ",
        "CPU image 7.0 GiB",
        "more than the 1.0 GiB set by --memory-limit",
        "lower --width and --height",
    ] {
        assert!(stderr.contains(f), "no {f:?} in\n{stderr}");
    }
    // Refused before any pixel: a 16384² render takes minutes.
    assert!(start.elapsed().as_secs() < 20, "took {:?}", start.elapsed());
    assert!(dir.listing().is_empty(), "left behind {:?}", dir.listing());
    for bad in ["lots", "-1G", "12Q"] {
        let out = glint(&dir, ["render", "whitted", "-q", "-o", "x.png", "--memory-limit", bad]);
        assert!(!out.status.success() && text(&out.stderr).contains("--memory-limit"), "{bad}");
    }
}

#[test]
fn a_scene_file_beyond_the_memory_limit_is_refused_before_it_is_parsed() {
    let dir = TempDir::new("memory-load");
    // 2 MB of text: about 70 MiB to parse, refused under a 16 MiB limit.
    let vertices: Vec<String> = (0..60_000).map(|i| format!("[{i}.0, 1.0, 2.0]")).collect();
    let scene = format!(
        "[camera]\nposition = [0.0, 0.0, -5.0]\nlook_at = [0.0, 0.0, 0.0]\n\n[materials.m]\nkd = 0.5\n\n\
         [[objects]]\ntype = \"mesh\"\nmaterial = \"m\"\nvertices = [{}]\ntriangles = [[0, 1, 2]]\n",
        vertices.join(", ")
    );
    std::fs::write(dir.join("big.toml"), scene).unwrap();
    let out = glint(&dir, ["render", "big.toml", "-q", "-o", "big.png", "--memory-limit", "16M"]);
    let stderr = text(&out.stderr);
    assert!(!out.status.success());
    for f in ["loading big.toml (1.", "would need about ", "parsing the scene file", "set by --memory-limit"] {
        assert!(stderr.contains(f), "no {f:?} in\n{stderr}");
    }
    assert_eq!(dir.listing(), ["big.toml"]);
    // A stream has no size to estimate beforehand: it is read only as far as the limit leaves
    // room to parse (/dev/zero under 100M was read to 1 GiB before it was refused).
    let out = glint(&dir, ["render", "/dev/zero", "-q", "-o", "zero.png", "--memory-limit", "100M"]);
    let stderr = text(&out.stderr);
    let cap = (100u64 << 20).saturating_sub(16 << 20) / 36;
    assert!(!out.status.success() && stderr.contains(&format!("larger than {cap} bytes")), "{stderr}");
}

/// The estimate and the peak resident memory of one `glint render --json` run.
fn estimate_and_peak(dir: &TempDir, args: &[&str]) -> (f64, f64, Value) {
    let mut all = vec!["render", "-q", "--json"];
    all.extend_from_slice(args);
    let out = glint(dir, all);
    assert!(out.status.success(), "{args:?}: {}", text(&out.stderr));
    let json: Value = serde_json::from_slice(&out.stdout).expect("JSON");
    let memory = json["memory"].clone();
    let load = memory["load_estimate_bytes"].as_f64().unwrap_or(0.0);
    let render = memory["render_estimate_bytes"].as_f64().expect("render estimate");
    let peak = memory["peak_rss_bytes"].as_f64().expect("peak RSS (Linux)");
    (load.max(render), peak, memory)
}

#[test]
fn the_estimate_in_json_is_close_to_the_peak_memory_of_the_run() {
    let dir = TempDir::new("memory-json");
    let mut cases: Vec<Vec<&str>> = vec![
        vec!["whitted", "--width", "2048", "--height", "1536", "-o", "a.png"],
        vec!["whitted", "--width", "2048", "--height", "1536", "-o", "a.exr"],
        vec!["bumpy", "--resolution", "700", "--width", "32", "--height", "32", "-o", "b.png"],
    ];
    if !skip_gpu() {
        cases.push(vec!["whitted", "--width", "1536", "--height", "1536", "-o", "c.png", "--backend", "both"]);
    }
    for args in cases {
        let (estimate, peak, memory) = estimate_and_peak(&dir, &args);
        let ratio = estimate / peak;
        eprintln!("{args:?}: estimate {:.0} MB, peak {:.0} MB, ratio {ratio:.2}", estimate / 1e6, peak / 1e6);
        // Never far below what the run took (the check would pass renders that do not fit),
        // nor far above (it would refuse renders that do).
        assert!((0.8..=1.6).contains(&ratio), "{args:?}: estimate/peak {ratio:.2}: {memory:#}");
    }
}

#[test]
fn a_generated_scene_beyond_the_memory_limit_is_refused_before_it_is_made() {
    // bumpy at resolution 1500 is 9 million triangles: it was generated (18 s, 510 MB) before
    // the render's estimate refused it.
    let dir = TempDir::new("memory-generated");
    let args = ["bumpy", "--resolution", "1500", "--memory-limit", "100M"];
    for command in [&["render", "--width", "8", "--height", "6", "-o", "b.png"][..], &["bench", "rays"][..]] {
        let (verb, rest) = command.split_first().expect("a command");
        let all: Vec<&str> = [*verb].into_iter().chain(rest.iter().copied()).collect();
        let (head, tail) = all.split_at(if *verb == "bench" { 2 } else { 1 });
        let out = glint(&dir, head.iter().chain(args.iter()).chain(tail.iter()).copied());
        let stderr = text(&out.stderr);
        assert!(!out.status.success(), "{command:?}");
        for f in
            ["generating bumpy at resolution 1500 (9000002 triangles) would need about ", "BVH", "lower --resolution"]
        {
            assert!(stderr.contains(f), "{command:?}: no {f:?} in\n{stderr}");
        }
    }
    assert!(dir.listing().is_empty(), "left behind {:?}", dir.listing());
}
