//! Glint's path tracers against an independent renderer: one closed Cornell box (an area light,
//! Lambertian walls, two Lambertian spheres) written by `mitsuba_cornell.py` both as a Glint
//! scene and for Mitsuba 3 (PyPI `mitsuba`, variant `scalar_rgb`, integrator `path`, box pixel
//! filter), rendered by Mitsuba and by Glint's CPU and GPU, each Glint image compared with
//! Mitsuba's: the image mean per channel within 2 %, and the RMSE of the 4×4-binned images
//! within 5 % of the mean. `GLINT_SKIP_MITSUBA=1` skips it on purpose; without Mitsuba it fails
//! saying what to install. The GPU image needs an adapter (lavapipe in CI); `GLINT_SKIP_GPU=1`
//! leaves it out on purpose.

use std::process::Command;

use glint_test_support::TempDir;

use super::{glint, text};

const SCRIPT: &str = include_str!("mitsuba_cornell.py");
const SIZE: u32 = 64;
const SPP: u32 = 256;

/// The image's linear RGB, row by row.
fn read_exr(path: &std::path::Path) -> Vec<[f32; 3]> {
    let img = image::open(path).unwrap_or_else(|e| panic!("decode {}: {e}", path.display())).into_rgb32f();
    assert_eq!((img.width(), img.height()), (SIZE, SIZE), "{}", path.display());
    img.pixels().map(|p| p.0).collect()
}

fn means(img: &[[f32; 3]]) -> [f64; 3] {
    let n = img.len() as f64;
    [0, 1, 2].map(|c| img.iter().map(|p| f64::from(p[c])).sum::<f64>() / n)
}

/// The image in 4×4 blocks, each the mean of its pixels.
fn binned(img: &[[f32; 3]]) -> Vec<[f64; 3]> {
    let (n, b) = (SIZE as usize, SIZE as usize / 4);
    let mut out = vec![[0.0; 3]; b * b];
    for (i, p) in img.iter().enumerate() {
        let cell = &mut out[(i / n / 4) * b + (i % n) / 4];
        for c in 0..3 {
            cell[c] += f64::from(p[c]) / 16.0;
        }
    }
    out
}

#[test]
fn the_path_tracer_agrees_with_mitsuba_3_on_a_cornell_box() {
    if glint_test_support::skip_requested("GLINT_SKIP_MITSUBA") {
        eprintln!("GLINT_SKIP_MITSUBA=1: the comparison with Mitsuba 3 is skipped");
        return;
    }
    let dir = TempDir::new("mitsuba");
    let script = dir.join("mitsuba_cornell.py");
    std::fs::write(&script, SCRIPT).expect("write the script");
    let run = Command::new("python3")
        .arg(&script)
        .arg(&*dir)
        .args([SIZE.to_string(), SPP.to_string()])
        .output()
        .unwrap_or_else(|e| {
            panic!("python3 did not run ({e}): install Python 3 and `pip install mitsuba`, or set GLINT_SKIP_MITSUBA=1")
        });
    assert!(
        run.status.success(),
        "Mitsuba 3 did not render ({}): install it with `pip install mitsuba` (PyPI), or set GLINT_SKIP_MITSUBA=1\n{}",
        run.status,
        text(&run.stderr)
    );
    let skip_gpu = glint_test_support::skip_requested("GLINT_SKIP_GPU");
    let backends: &[&str] = if skip_gpu { &["cpu"] } else { &["cpu", "gpu"] };
    let mitsuba = read_exr(&dir.join("mitsuba.exr"));
    let m = means(&mitsuba);
    let bm = binned(&mitsuba);
    for backend in backends {
        let glint_exr = dir.join(format!("glint-{backend}.exr"));
        let out = glint(
            &dir,
            [
                "render".into(),
                dir.join("scene.toml").into_os_string(),
                "--integrator".into(),
                "path".into(),
                "--backend".into(),
                (*backend).into(),
                "-q".into(),
                "-o".into(),
                glint_exr.clone().into_os_string(),
            ],
        );
        assert!(
            out.status.success(),
            "{backend}: {} (the GPU image needs an adapter: install mesa-vulkan-drivers, or set GLINT_SKIP_GPU=1)",
            text(&out.stderr)
        );
        let ours = read_exr(&glint_exr);
        let g = means(&ours);
        let bg = binned(&ours);
        let squares: f64 = bm.iter().zip(&bg).flat_map(|(a, b)| (0..3).map(move |c| (a[c] - b[c]).powi(2))).sum();
        let rmse = (squares / (3 * bm.len()) as f64).sqrt();
        let mean = (m[0] + m[1] + m[2]) / 3.0;
        eprintln!(
            "Cornell box, Glint {backend} against Mitsuba 3: means {g:?} against {m:?}; 4x4-binned RMSE {:.2} % of the mean",
            100.0 * rmse / mean
        );
        for c in 0..3 {
            assert!(
                (g[c] - m[c]).abs() <= 0.02 * m[c],
                "{backend}, channel {c}: Glint's mean {} against Mitsuba's {}",
                g[c],
                m[c]
            );
        }
        assert!(rmse <= 0.05 * mean, "{backend}: 4x4-binned RMSE {rmse} against the mean {mean}");
    }
}
