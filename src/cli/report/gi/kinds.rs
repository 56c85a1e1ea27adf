//! What Whitted's error is made of: the reference's paths split by kind of light
//! (`glint_core::path_kinds`) against Whitted's images, and the sentence the report says of it.

use anyhow::Context;
use glint_core::compare::{compare_images, rms, rms_difference};
use glint_core::path_kinds::kind_alone;
use glint_core::{CpuOptions, FlatScene, HdrImage};
use glint_io::LoadedScene;
use glint_scene::{PathKind, RenderSettings};
use indicatif::ProgressBar;
use serde::{Deserialize, Serialize};

use glint_core::Backend;

use super::{Ambient, GiResult};

/// What Whitted's error is made of: the reference's light by kind (`PathKind::ALL` order),
/// from a path render of `spp` samples at the rows' seed split four ways, against
/// Whitted's CPU image at the sweep's deepest depth and the reference's samples (its own
/// sampling error averaged out).
#[derive(Clone, Debug, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct KindSplit {
    pub spp: u32,
    /// Each kind's share of the split's light (the four kinds' means summed): they add to 1.
    pub share: [f64; 4],
    /// Each kind's root mean square over the pixels and channels: the error of an image that
    /// lacks it.
    pub rms: [f64; 4],
    /// The RMS difference of Whitted's image without its ambient from the paths' direct light
    /// (point lights against area lights' soft shadows, the glossy lobe against k_s·(H·N)^n).
    pub direct_rmse: f64,
    /// What the ambient as written adds, as a share of the split's light.
    pub ambient_share: f64,
    /// The split's light, the four kinds' means summed: black paths have no shares.
    pub paths_mean: f64,
    /// The RMS difference of what the ambient as written adds from the indirect light the paths
    /// bring (all kinds but the direct): the error of the ambient as the stand-in it is, which
    /// is the largest part where it adds more than that light.
    pub ambient_rmse: f64,
    /// Whitted's RMSE with the ambient as written at `whitted_depth` and `whitted_spp`: what
    /// its model leaves out, for scale.
    pub whitted_rmse: f64,
    pub whitted_depth: u32,
    pub whitted_spp: u32,
    /// What makes Whitted's direct light differ from the paths' in this scene.
    pub direct_causes: Vec<String>,
}

/// `a − b`, pixel by pixel.
fn minus(a: &HdrImage, b: &HdrImage) -> HdrImage {
    let mut d = a.clone();
    for (p, q) in d.pixels.iter_mut().zip(&b.pixels) {
        *p -= *q;
    }
    d
}

/// The reference's light by kind against Whitted's CPU images `written` (the ambient as
/// written) and `without` (none).
pub(super) fn split_by_kind(
    loaded: &LoadedScene,
    paths: &RenderSettings,
    [written, without]: [&HdrImage; 2],
    (whitted_depth, whitted_spp): (u32, u32),
    reference: &HdrImage,
    spp: u32,
    options: &CpuOptions,
    bar: &ProgressBar,
) -> anyhow::Result<KindSplit> {
    let name = &loaded.name;
    let cpu = |flat: &FlatScene, what: &str| -> anyhow::Result<HdrImage> {
        bar.set_message(format!("{name}: {what}"));
        let r = super::super::cpu_render::cpu_render(flat, options).with_context(|| format!("{name}: {what}"))?;
        bar.inc(1);
        Ok(r.image)
    };
    let flat = FlatScene::build(&loaded.desc, &RenderSettings { spp, ..paths.clone() });
    let mut split = KindSplit { spp, whitted_depth, whitted_spp, ..KindSplit::default() };
    let mut direct = None;
    let ambient = minus(written, without);
    // What the ambient adds less the indirect light, kind by kind.
    let mut ambient_less_indirect = ambient.clone();
    let mut means = [0.0; 4];
    for (i, kind) in PathKind::ALL.into_iter().enumerate() {
        let image = cpu(&kind_alone(&flat, kind), &format!("{} alone ({spp} spp)", kind.label()))?;
        (means[i], split.rms[i]) = (image.mean(), rms(&image.pixels));
        if kind == PathKind::Direct {
            direct = Some(image);
        } else {
            ambient_less_indirect = minus(&ambient_less_indirect, &image);
        }
    }
    // Shares of the split's own light, so that they add up: the reference's mean is another
    // estimate (on cornell-gi the 16-sample split's was 0.974 of it, and the shares added to 97 %).
    let paths_mean: f64 = means.iter().sum();
    split.share = means.map(|m| m / paths_mean.max(f64::MIN_POSITIVE));
    split.direct_rmse = rms_difference(&without.pixels, &direct.expect("the direct kind is rendered").pixels);
    split.ambient_share = ambient.mean() / paths_mean.max(f64::MIN_POSITIVE);
    split.paths_mean = paths_mean;
    split.ambient_rmse = rms(&ambient_less_indirect.pixels);
    split.whitted_rmse = compare_images(reference, written).rmse;
    split.direct_causes = direct_causes(&loaded.desc);
    Ok(split)
}

/// What makes Whitted's direct light differ from the paths' in `desc`: its emitters and its sky
/// light nothing (the paths' direct light is E S* D L, the background among the L), and its
/// highlight is not the normalised lobe the paths reflect (path-tracing.md's factors). Point
/// lights, spots and directional lights are the same in both.
fn direct_causes(desc: &glint_scene::SceneDesc) -> Vec<String> {
    let [emitter, background, highlight] = DIRECT_CAUSES;
    let mut causes = Vec::new();
    if desc.materials.values().any(|m| !m.emission.is_zero()) {
        causes.push(emitter.to_string());
    }
    if !desc.world.background.is_zero() {
        causes.push(background.to_string());
    }
    if desc.materials.values().any(|m| !m.ks.is_zero()) && desc.traced_lights().next().is_some() {
        causes.push(highlight.to_string());
    }
    causes
}

/// Every cause `direct_causes` names: a shard's are these or none (the merge writes them into
/// report.md as they are).
pub const DIRECT_CAUSES: [&str; 3] = [
    "an emitter lights nothing in Whitted's model",
    "the background lights nothing in Whitted's model, only what it is seen by",
    "its highlight k_s·spec_j is not the normalised lobe the paths reflect",
];

/// A sentence on what Whitted's remaining error is made of.
pub fn kinds_sentence(g: &GiResult) -> String {
    let k = &g.kinds;
    // A share of the paths' light; the ambient's over nearly black paths may be vast.
    let pct = |v: f64| if v < 1e4 { format!("{:.0} %", 100.0 * v) } else { format!("{:.2e} %", 100.0 * v) };
    let direct = match k.direct_causes.as_slice() {
        [] => {
            "its direct light differing from the paths' (by their noise alone: lights are the same in both)".to_string()
        }
        causes => format!("its direct light differing from the paths' ({})", causes.join("; ")),
    };
    let black = k.paths_mean <= 0.0;
    let indirect_share = k.share[1] + k.share[2] + k.share[3];
    let kinds = [
        ("the indirect diffuse light it has no term for", k.rms[1]),
        ("the caustics it has no term for", k.rms[2]),
        ("the rest of the light it has no term for (a mirror or glass between two diffuse bounces)", k.rms[3]),
    ];
    let (largest_kind, _) = kinds.iter().max_by(|a, b| a.1.total_cmp(&b.1)).expect("three kinds");
    // Without an ambient term, each kind it lacks is a part of its own. With one, the indirect
    // light is what the ambient stands in for: one part, the ambient's difference from it (an
    // ambient matching it well leaves little), named for the ambient where it adds more light
    // than that, else for the kinds it leaves out.
    let parts: Vec<(String, f64)> = if k.ambient_share > 0.0 {
        let over = black || k.ambient_share > indirect_share;
        let indirect = if over {
            "its ambient term as written, I_a·k_a, which adds more light than the indirect light it stands in \
                 for"
            .to_string()
        } else {
            format!("the indirect light its ambient term as written leaves out, mostly {largest_kind}")
        };
        vec![(direct, k.direct_rmse), (indirect, k.ambient_rmse)]
    } else {
        std::iter::once((direct, k.direct_rmse)).chain(kinds.iter().map(|(n, v)| (n.to_string(), *v))).collect()
    };
    let ambient = format!(
        "; what its ambient as written adds differs from the paths' indirect light by RMS {:.3e}",
        k.ambient_rmse
    );
    let shares = if black {
        let ambient = if k.ambient_share > 0.0 { "; the ambient as written adds light to it" } else { "" };
        format!("The paths' image is black (no light reaches the camera), so it has no shares by kind{ambient}.")
    } else {
        format!(
            "The paths' light is {} direct, {} indirect diffuse, {} caustics and {} the rest (a {}-sample split, by \
             its own total); the ambient as written adds {} of it where the indirect kinds bring {}.",
            pct(k.share[0]),
            pct(k.share[1]),
            pct(k.share[2]),
            pct(k.share[3]),
            k.spp,
            pct(k.ambient_share),
            pct(indirect_share),
        )
    };
    let at = format!("depth {}, {} samples a pixel as the reference", k.whitted_depth, k.whitted_spp);
    if k.whitted_rmse == 0.0 {
        // Every part is 0 too: none is the largest (a black scene without ambient).
        return format!(
            "Whitted's image is the reference exactly (RMSE 0 at {at}, ambient as written): it leaves nothing out \
             here. {shares}"
        );
    }
    // The same depth's most sampled CPU row, as the table has it: its own sampling error on top.
    let row = g
        .rows
        .iter()
        .filter(|r| r.backend == Backend::Cpu && r.ambient == Some(Ambient::AsWritten) && r.depth == k.whitted_depth)
        .max_by_key(|r| r.spp)
        .filter(|r| r.spp < k.whitted_spp)
        .map_or(String::new(), |r| {
            format!("; the table's {} spp row has {:.3e}, its own sampling error included", r.spp, r.rmse)
        });
    let (largest, _) = parts.iter().max_by(|a, b| a.1.total_cmp(&b.1)).expect("the direct part");
    format!(
        "Whitted's error (RMSE {:.3e} at {at}, ambient as written: its own sampling error averaged out, what its \
         model leaves out{row}) is mostly {largest}: its direct light differs from the paths' by RMS {:.3e}, and \
         it lacks indirect diffuse light (RMS {:.3e}), caustics ({:.3e}) and the rest ({:.3e}){ambient}. {shares}",
        k.whitted_rmse, k.direct_rmse, k.rms[1], k.rms[2], k.rms[3],
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_shares_by_kind_add_up_to_one() {
        // They were of the reference's mean, another estimate than the split's: on cornell-gi
        // they added to 97 %, and a rounded sum could not show it.
        let loaded = glint_io::load_scene("cornell-gi").expect("built-in");
        let paths = RenderSettings {
            width: 12,
            height: 9,
            spp: 4,
            max_depth: 4,
            integrator: glint_scene::Integrator::Path,
            ..loaded.desc.render.clone()
        };
        let options = CpuOptions { threads: 1, ..CpuOptions::default() };
        let render = |s: &RenderSettings| {
            glint_core::render_cpu(&FlatScene::build(&loaded.desc, s), &options, Default::default())
                .expect("render")
                .image
        };
        let reference = render(&RenderSettings { seed: 7, ..paths.clone() });
        let black = HdrImage::new(12, 9);
        let hidden = ProgressBar::hidden();
        let split =
            split_by_kind(&loaded, &paths, [&black, &black], (4, 4), &reference, 4, &options, &hidden).expect("split");
        let sum: f64 = split.share.iter().sum();
        assert!((sum - 1.0).abs() < 1e-12, "{:?} add to {sum}", split.share);
    }

    fn with_kinds(kinds: KindSplit) -> GiResult {
        super::super::result_for_tests(Vec::new(), kinds)
    }

    #[test]
    fn whitteds_error_is_said_at_the_references_samples_beside_the_tables_row() {
        // cornell-gi as a lecturer measured it: 0.129 at 1024 spp, 0.172 at the row's 4.
        let kinds = KindSplit {
            share: [0.8, 0.12, 0.03, 0.05],
            rms: [0.3, 0.05, 0.02, 0.01],
            direct_rmse: 0.12,
            paths_mean: 0.2,
            whitted_rmse: 0.129,
            whitted_depth: 5,
            whitted_spp: 1024,
            ..KindSplit::default()
        };
        let row = |backend, spp, depth, ambient, rmse| super::super::GiRow {
            integrator: glint_scene::Integrator::Whitted,
            backend,
            spp,
            depth,
            ambient: Some(ambient),
            ambient_rgb: None,
            median: std::time::Duration::ZERO,
            rmse,
        };
        let rows = vec![
            row(Backend::Cpu, 4, 2, Ambient::AsWritten, 0.3),
            row(Backend::Cpu, 1, 5, Ambient::AsWritten, 0.221),
            row(Backend::Cpu, 4, 5, Ambient::AsWritten, 0.172),
            row(Backend::Cpu, 4, 5, Ambient::Fitted, 0.15),
            row(Backend::Gpu, 4, 5, Ambient::AsWritten, 0.1721),
        ];
        let said = kinds_sentence(&super::super::result_for_tests(rows, kinds));
        assert!(
            said.starts_with("Whitted's error (RMSE 1.290e-1 at depth 5, 1024 samples a pixel as the reference"),
            "{said}"
        );
        assert!(said.contains("the table's 4 spp row has 1.720e-1, its own sampling error included"), "{said}");
    }

    #[test]
    fn an_ambient_that_adds_more_than_the_indirect_light_is_named_when_it_is_the_largest_part() {
        // A lit sphere under an ambient of 2 (a helper's scene): the ambient adds ten times the
        // paths' light, which has no indirect part.
        let over = KindSplit {
            spp: 16,
            share: [1.0, 0.0, 0.0, 0.0],
            rms: [0.1, 0.0, 0.0, 0.0],
            direct_rmse: 0.0157,
            ambient_share: 10.09,
            paths_mean: 0.08,
            ambient_rmse: 0.866,
            whitted_rmse: 0.868,
            whitted_depth: 5,
            whitted_spp: 64,
            direct_causes: Vec::new(),
        };
        let said = kinds_sentence(&with_kinds(over.clone()));
        assert!(said.contains("is mostly its ambient term as written"), "{said}");
        // An ambient under the indirect light leaves the kinds it stands in for to name; without
        // an ambient each kind is a part, as before.
        let under = KindSplit {
            share: [0.5, 0.4, 0.05, 0.05],
            rms: [0.1, 0.2, 0.01, 0.01],
            ambient_share: 0.2,
            ambient_rmse: 0.15,
            ..over
        };
        let said = kinds_sentence(&with_kinds(under.clone()));
        assert!(
            said.contains(
                "is mostly the indirect light its ambient term as written leaves out, mostly the indirect diffuse"
            ),
            "{said}"
        );
        // An ambient that matches the indirect light well leaves the direct light the largest,
        // though the indirect light alone is larger.
        let matched = KindSplit { direct_rmse: 0.1, ambient_share: 0.45, ambient_rmse: 0.02, ..under.clone() };
        assert!(kinds_sentence(&with_kinds(matched)).contains("is mostly its direct light"));
        let none = KindSplit { ambient_share: 0.0, ambient_rmse: 0.2, ..under.clone() };
        let said = kinds_sentence(&with_kinds(none));
        assert!(said.contains("is mostly the indirect diffuse light it has no term for"), "{said}");
        // A black reference (no light, an ambient): no shares, no division by its zero mean.
        let black = KindSplit {
            share: [0.0; 4],
            rms: [0.0; 4],
            direct_rmse: 0.0,
            ambient_share: 0.5 / f64::MIN_POSITIVE,
            paths_mean: 0.0,
            ambient_rmse: 0.2165,
            ..under
        };
        let said = kinds_sentence(&with_kinds(black.clone()));
        assert!(said.contains("is mostly its ambient term as written") && said.contains("The paths' image is black"));
        assert!(!said.contains("inf") && !said.contains(" %"), "{said}");
        // Black paths and no ambient (a tester's scene): Whitted is exact, and nothing is "mostly"
        // a part of an error of 0, nor does an ambient of 0 add light.
        let dark = KindSplit { ambient_share: 0.0, ambient_rmse: 0.0, whitted_rmse: 0.0, ..black };
        let said = kinds_sentence(&with_kinds(dark));
        assert!(said.starts_with("Whitted's image is the reference exactly (RMSE 0"), "{said}");
        assert!(!said.contains("mostly") && !said.contains("adds light"), "{said}");
    }
}
