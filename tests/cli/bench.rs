//! `glint bench rays` end to end on a small bumpy scene (CPU), its JSON, and its flag errors;
//! and the generated scenes through `glint render`.

use serde_json::Value;

use super::{expect_failure, glint, os, text};
use glint_test_support::TempDir;

/// 1280×720 rays in each set.
const RAYS: u64 = 1280 * 720;

fn field<'a>(v: &'a Value, key: &str) -> &'a Value {
    v.get(key).unwrap_or_else(|| panic!("no `{key}` in {v}"))
}

fn number(v: &Value, key: &str) -> f64 {
    field(v, key).as_f64().unwrap_or_else(|| panic!("`{key}` is not a number in {v}"))
}

#[test]
fn bench_rays_on_a_small_bumpy_reports_sane_numbers() {
    let dir = TempDir::new("bench-rays");
    let out =
        glint(&dir, ["bench", "rays", "bumpy", "--resolution", "20", "--backend", "cpu", "--json", "--runs", "2"]);
    assert!(out.status.success(), "{}", text(&out.stderr));
    let v: Value = serde_json::from_slice(&out.stdout).unwrap_or_else(|e| panic!("{e}: {}", text(&out.stdout)));
    assert_eq!(field(&v, "scene"), "bumpy");
    // 4·20² sphere triangles and the two of the ground quad; none degenerate at N = 20.
    assert_eq!(number(&v, "triangles"), 1602.0, "{v}");
    assert_eq!(number(&v, "spheres"), 0.0);
    let build = field(&v, "build");
    assert_eq!(number(build, "primitives"), 1602.0);
    assert!(number(build, "nodes") >= 2.0 * 1602.0 / 4.0 - 1.0, "a BVH with leaves of at most 4: {build}");
    assert!(number(build, "median_ms") > 0.0 && number(build, "best_ms") <= number(build, "median_ms"));
    assert!(number(build, "mtris_per_s") > 0.0);
    assert_eq!(number(build, "runs"), 2.0);
    let casts = field(&v, "casts").as_array().expect("casts is a list");
    let sets: Vec<&str> = casts.iter().map(|c| field(c, "set").as_str().unwrap()).collect();
    assert_eq!(sets, ["primary", "incoherent"], "{v}");
    for c in casts {
        assert_eq!(field(c, "backend"), "cpu");
        assert_eq!(number(c, "rays"), RAYS as f64);
        let hit = number(c, "hit_fraction");
        assert!(hit > 0.0 && hit < 1.0, "hit fraction {hit} in {c}");
        let (median, best) = (number(c, "median_ms"), number(c, "best_ms"));
        assert!(best > 0.0 && best <= median, "{c}");
        let mrays = number(c, "mrays_per_s");
        assert!((mrays - RAYS as f64 / (median * 1e3)).abs() <= 1e-6 * mrays, "Mrays/s from the median: {c}");
    }
    // The camera looks at the sphere from 3 units: at a 1.1 half-width it fills a good part
    // of the frame, and the ground quad the lower half; the rest is sky.
    let primary = number(&casts[0], "hit_fraction");
    assert!((0.3..0.8).contains(&primary), "primary hit fraction {primary}");
    assert!(field(&v, "gpu_vs_cpu").as_array().is_some_and(Vec::is_empty), "no GPU, no comparison: {v}");
    assert!(dir.listing().is_empty(), "bench rays wrote files: {:?}", dir.listing());
}

#[test]
fn bench_rays_table_names_the_statistic() {
    let dir = TempDir::new("bench-rays-table");
    let out = glint(&dir, ["bench", "rays", "bumpy", "--resolution", "8", "--threads", "1", "--runs", "1"]);
    assert!(out.status.success(), "{}", text(&out.stderr));
    let stdout = text(&out.stdout);
    for fragment in
        ["BVH build", "Mtris/s", "primary", "incoherent", "median", "best", "1 CPU threads", "258 triangles"]
    {
        assert!(stdout.contains(fragment), "no {fragment:?} in\n{stdout}");
    }
}

#[test]
fn bad_resolutions_fail_cleanly() {
    for bad in ["0", "1", "1501", "-3", "many"] {
        expect_failure(
            "bench-resolution",
            |_| os(&[&"bench", &"rays", &"bumpy", &"--resolution", &bad, &"--backend", &"cpu"]),
            &["--resolution", "[2, 1500]"],
            &[],
        );
    }
    expect_failure(
        "render-resolution",
        |d| os(&[&"render", &"bumpy", &"--resolution", &"0", &"-o", &d.join("out.png")]),
        &["--resolution", "[2, 1500]"],
        &[],
    );
    // A scene that is not generated takes no resolution: an error, not an ignored flag.
    expect_failure(
        "not-generated",
        |d| os(&[&"render", &"whitted", &"--resolution", &"20", &"-o", &d.join("out.png")]),
        &["whitted", "not a generated scene", "bumpy"],
        &[],
    );
    expect_failure(
        "bench-threads",
        |_| os(&[&"bench", &"rays", &"bumpy", &"--resolution", &"4", &"--threads", &"0"]),
        &["--threads"],
        &[],
    );
}

#[test]
fn generated_scenes_render_on_the_cpu() {
    let dir = TempDir::new("render-bumpy");
    for name in ["bumpy", "bumpy-glass"] {
        let path = dir.join(format!("{name}.png"));
        let out = glint(
            &dir,
            os(&[&"render", &name, &"--resolution", &"12", &"--width", &"48", &"--height", &"27", &"-o", &path, &"-q"]),
        );
        assert!(out.status.success(), "{name}: {}", text(&out.stderr));
        let image = image::open(&path).expect("a PNG").to_rgb8();
        // Not a constant image: sphere, ground and sky all show.
        let first = image.get_pixel(0, 0);
        assert!(image.pixels().any(|p| p != first), "{name}: constant image");
    }
}
