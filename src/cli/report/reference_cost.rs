//! Whether a scene's reference can finish. The reference is fixed (CPU f64, depth 16, bailout
//! 0: `Plan::reference`), and under it a material with both k_r and k_t can double a ray tree
//! at every level, up to 2^17 − 1 rays a camera sample. Whether it does depends on the geometry
//! (whitted's glass sphere: 9.3 rays a sample; three parallel glass panes: 25,100),
//! which the bound cannot see, so a scene the bound warns of is probed: its reference settings
//! rendered at one sample over a few pixels, whose mean tree, times the reference's samples,
//! estimates the reference's rays. A panes scene ran for hours behind `--quick` without a word.

use glint_core::{CpuOptions, FlatScene};
use glint_scene::{RenderSettings, SceneDesc, format_rounded, unbounded_ray_tree_cause};

use super::cpu_render::cpu_render;
use super::plan::Config;
use super::sweep::settings_for;

/// The most rays a reference may be expected to trace: 2^32, about 25 minutes at the 2.9 Mrays/s
/// of the reference on a 2-core machine (three glass panes at 24×18, depth 16), half the full
/// run of six scenes. A `--quick` reference of the panes is 1.1e10.
pub const MAX_REFERENCE_RAYS: f64 = 4_294_967_296.0;

/// The mean rays a camera sample from which a reference's trees are said to branch: whitted's
/// glass averages 9.3, three parallel glass panes 25,100. Below it the bound's worst case is
/// not what the scene does, and the report says nothing (whitted and cornell were warned of on
/// every run).
const BRANCHING_TREE_RAYS: f64 = 1000.0;

/// The probe's image: the report's, scaled down to at most 16 pixels a side.
fn probe_size(width: u32, height: u32) -> (u32, u32) {
    let scale = (16.0 / f64::from(width.max(height))).min(1.0);
    let side = |v: u32| ((f64::from(v) * scale).round() as u32).clamp(1, v);
    (side(width), side(height))
}

/// What the reference of one scene costs, where its ray tree's bound passes the render's
/// warning threshold: the warning to print, or an error where the probe puts it past
/// `MAX_REFERENCE_RAYS`. `None` for a scene whose trees stay small, or traced by paths.
pub fn judge(
    name: &str,
    desc: &SceneDesc,
    base: &RenderSettings,
    reference: &Config,
    threads: usize,
) -> anyhow::Result<Option<String>> {
    let settings = settings_for(base, reference);
    let Some(cause) = unbounded_ray_tree_cause(desc, &settings) else { return Ok(None) };
    let (pw, ph) = probe_size(base.width, base.height);
    let probe = RenderSettings { width: pw, height: ph, spp: 1, ..settings.clone() };
    let rendered = cpu_render(&FlatScene::build(desc, &probe), &CpuOptions { threads, ..CpuOptions::default() })?;
    let mean = rendered.counts.total() as f64 / rendered.counts.camera.max(1) as f64;
    let samples = f64::from(base.width) * f64::from(base.height) * f64::from(reference.spp);
    let estimate = mean * samples;
    let what = format!(
        "{name}: the reference (CPU, {} spp, depth {}, bailout 0; fixed): {cause}; a probe of {pw}×{ph} camera \
         samples traced {} rays each, so the reference's {}×{}×{} samples would trace about {estimate:.1e}",
        reference.spp,
        reference.depth,
        format_rounded(mean, 3),
        base.width,
        base.height,
        reference.spp
    );
    if estimate <= MAX_REFERENCE_RAYS && mean < BRANCHING_TREE_RAYS {
        return Ok(None);
    }
    if estimate <= MAX_REFERENCE_RAYS {
        return Ok(Some(format!("warning: {what}, within the {MAX_REFERENCE_RAYS:.1e} a reference may take")));
    }
    // The estimate scales with the pixels: the largest image whose reference fits.
    let pixels = (MAX_REFERENCE_RAYS / (mean * f64::from(reference.spp))).floor();
    let fewer = if pixels >= 1.0 {
        format!(", or render at most {pixels:.0} pixels (--width × --height)")
    } else {
        String::new()
    };
    anyhow::bail!(
        "{what}, more than the {MAX_REFERENCE_RAYS:.1e} rays a reference may take (about 25 minutes on 2 cores; \
         rays that keep meeting such a material, as between parallel glass panes, branch at every hit). The report's \
         reference depth and bailout are fixed, and with bailout 0 a smaller k_r or k_t cuts no ray: set one of them \
         to 0{fewer}, or leave the scene out of --scenes; nothing was run"
    )
}

#[cfg(test)]
mod tests {
    use super::probe_size;

    #[test]
    fn the_probe_keeps_the_aspect_within_the_image() {
        assert_eq!(probe_size(96, 72), (16, 12));
        assert_eq!(probe_size(320, 240), (16, 12));
        assert_eq!(probe_size(4096, 1), (16, 1));
        assert_eq!(probe_size(1, 4096), (1, 16));
        assert_eq!(probe_size(8, 6), (8, 6));
    }
}
