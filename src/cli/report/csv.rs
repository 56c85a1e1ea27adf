//! `report.csv`: one row per configuration, units in the column names.
//!
//! Numbers are printed in Rust's shortest round-trip form; PSNR is `inf` for an image equal
//! to the reference. `incomplete` is true for a row whose render lost work (a GPU status flag,
//! or fewer camera rays than samples): its time and error are not its configuration's. Cells that do not apply (GPU-only figures on CPU rows, a path row's bailout) are empty.
//! `bias_rel` is the image mean's signed relative difference from the reference's
//! (`SceneResult::bias`; report.md marks the rows beyond the reference's noise).

use glint_core::Backend;

use super::sweep::{Row, SceneResult};
use crate::cli::units::ms_csv;

pub const HEADER: &[&str] = &[
    "scene",
    "backend",
    "device",
    "groups",
    "width_px",
    "height_px",
    "spp",
    "max_depth",
    "bailout",
    "specialised",
    "epsilon_mode",
    "epsilon",
    "timed_runs",
    "render_ms_median",
    "render_ms_min",
    "render_ms_max",
    "pipeline_ms",
    "shader_statements",
    "rays_total",
    "camera_rays",
    "rays_per_pixel",
    "bailout_saved_rays",
    "mrays_per_s",
    "rmse",
    "rel_mse",
    "psnr_db",
    "flip_mean",
    "max_abs",
    "first_hit_mismatch_pct",
    "image_mean",
    "bias_rel",
    "rmse_vs_cpu_twin",
    "rays_vs_cpu_twin_pct",
    "gpu_status",
    "incomplete",
    "pareto_all",
    "pareto_backend",
    "shard",
];

/// RFC 4180 quoting, only where needed (adapter names contain commas).
fn field(s: &str) -> String {
    if s.contains([',', '"', '\n', '\r']) { format!("\"{}\"", s.replace('"', "\"\"")) } else { s.to_string() }
}

/// Scientific notation keeps tiny errors short and exact ("1.234e-7"; 0 is "0e0").
fn sci(v: f64) -> String {
    format!("{v:e}")
}

fn row_fields(scene: &SceneResult, row: &Row, device: &str) -> Vec<String> {
    let c = &row.config;
    let s = &scene.settings;
    let e = &row.errors;
    let opt = |v: Option<String>| v.unwrap_or_default();
    vec![
        scene.name.clone(),
        c.backend.name().into(),
        device.into(),
        row.groups.iter().map(|g| g.name()).collect::<Vec<_>>().join(";"),
        s.width.to_string(),
        s.height.to_string(),
        c.spp.to_string(),
        c.depth.to_string(),
        // Paths have no bailout: the cell does not apply (report.md says "none (paths)").
        if scene.settings.integrator == glint_scene::Integrator::Path {
            String::new()
        } else {
            c.bailout.value().to_string()
        },
        c.specialise.to_string(),
        c.epsilon_mode.name().into(),
        s.epsilon.to_string(),
        row.times.len().to_string(),
        ms_csv(row.median()),
        ms_csv(row.times[0]),
        ms_csv(row.times[row.times.len() - 1]),
        opt(row.gpu.map(|g| ms_csv(g.pipeline))),
        opt(row.gpu.map(|g| g.statements.to_string())),
        row.counts.total().to_string(),
        row.counts.camera.to_string(),
        format!("{:.4}", row.counts.total() as f64 / scene.pixels() as f64),
        row.counts.bailout_saved.to_string(),
        format!("{:.4}", row.mrays()),
        sci(e.rmse),
        sci(e.rel_mse),
        e.psnr.to_string(),
        sci(e.flip_mean),
        sci(e.max_abs),
        (100.0 * e.first_hit_mismatch).to_string(),
        sci(row.mean),
        opt(scene.bias(row).map(|(relative, _)| sci(relative))),
        opt(row.twin_rmse.map(sci)),
        opt(row.twin_rays_pct.map(|v| format!("{v:.6}"))),
        opt(row.gpu.map(|g| g.status.to_string())),
        row.dropped_work().to_string(),
        row.pareto_all.to_string(),
        row.pareto_backend.to_string(),
        opt(row.shard.map(|s| s.to_string())),
    ]
}

/// The whole CSV: the header, then every scene's rows in sweep order. `devices` are the CPU's
/// and the GPU's names on each machine: one pair for a one-machine run, one a shard for a
/// merged one (a row's `shard` picks its pair).
pub fn render_csv(scenes: &[SceneResult], devices: &[(String, String)]) -> String {
    let mut out = HEADER.join(",");
    out.push('\n');
    for scene in scenes {
        for row in &scene.rows {
            let (cpu_device, gpu_device) = &devices[row.shard.unwrap_or(0) as usize];
            let device = if row.config.backend == Backend::Cpu { cpu_device } else { gpu_device };
            let fields: Vec<String> = row_fields(scene, row, device).iter().map(|f| field(f)).collect();
            debug_assert_eq!(fields.len(), HEADER.len());
            out.push_str(&fields.join(","));
            out.push('\n');
        }
    }
    out
}

pub const SPECULAR_HEADER: &[&str] = &[
    "scene",
    "backend",
    "specular_model",
    "width_px",
    "height_px",
    "spp",
    "max_depth",
    "timed_runs",
    "render_ms_median",
    "render_ms_min",
    "render_ms_max",
    "pipeline_ms",
    "shader_statements",
    "rays_total",
    "camera_rays",
    "shadow_rays",
    "reflection_rays",
    "refraction_rays",
    "shard",
];

/// `specular.csv`: the render time of each specular model, every material set to it.
pub fn render_specular_csv(scenes: &[SceneResult]) -> String {
    let mut out = SPECULAR_HEADER.join(",");
    out.push('\n');
    for s in scenes {
        for r in &s.specular {
            let fields = [
                field(&s.name),
                r.config.backend.name().to_string(),
                r.model.name().to_string(),
                s.settings.width.to_string(),
                s.settings.height.to_string(),
                r.config.spp.to_string(),
                r.config.depth.to_string(),
                r.times.len().to_string(),
                ms_csv(crate::cli::units::median(&r.times)),
                ms_csv(r.times[0]),
                ms_csv(r.times[r.times.len() - 1]),
                r.gpu.map_or(String::new(), |g| ms_csv(g.pipeline)),
                r.gpu.map_or(String::new(), |g| g.statements.to_string()),
                r.counts.total().to_string(),
                r.counts.camera.to_string(),
                r.counts.shadow.to_string(),
                r.counts.reflection.to_string(),
                r.counts.refraction.to_string(),
                r.shard.map_or(String::new(), |s| s.to_string()),
            ];
            out.push_str(&fields.join(","));
            out.push('\n');
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::field;

    #[test]
    fn quotes_only_what_needs_it() {
        assert_eq!(field("llvmpipe"), "llvmpipe");
        assert_eq!(field("llvmpipe (LLVM 15, 256 bits)"), "\"llvmpipe (LLVM 15, 256 bits)\"");
        assert_eq!(field("a\"b"), "\"a\"\"b\"");
    }
}
