//! What a shard file must hold before the merge trusts it: the checks of `ShardFile::check`,
//! each naming the field at fault (a shard edited or cut short, or of another glint).

use std::time::Duration;

use glint_core::Backend;
use glint_scene::{Report, format_number, validate_settings};

use super::shard::ShardFile;

/// The longest timed run a shard may hold, a week: far beyond any render of a sweep.
const MAX_RUN_SECS: u64 = 7 * 24 * 3600;

/// More rays than a shard's renders can trace (16384² pixels × 4096 samples × 2^10 rays is
/// 1.1e15; this leaves room), and far from u64's end, so that sums of a sweep's rows stay exact.
const MAX_RAYS: u64 = 1 << 60;

impl ShardFile {
    /// What the merge relies on and a shard always writes: a shard index below the count, the
    /// sweep's scenes only, each row its own shard's, the sweep's timed runs a row, and every
    /// error and figure a finite, non-negative number, a share at most 1 (a PSNR may be
    /// infinite: identical images). The
    /// first field that is not, as `field: problem`.
    pub(super) fn check(&self) -> Result<(), String> {
        // Text the report writes as it is, into its header table and sentences: a line break
        // or a control character there broke report.md (a tester); no name or command has one.
        let m = &self.machine;
        let texts = [
            ("machine.cpu_model", &m.cpu_model),
            ("machine.os", &m.os),
            ("machine.date", &m.date),
            ("machine.command", &m.command),
            ("glint", &self.glint),
            ("cpu_device", &self.cpu_device),
        ];
        let texts = texts.into_iter().chain(self.gpu_device.iter().map(|g| ("gpu_device", g)));
        let texts =
            texts.chain(m.env.iter().map(|e| ("machine.env", e))).chain(self.scenes.iter().map(|s| ("scenes", s)));
        for (field, text) in texts {
            if text.chars().any(char::is_control) {
                return Err(format!("{field}: `{}` holds a line break or control character", text.escape_debug()));
            }
        }
        if self.shard >= self.count {
            return Err(format!("shard: is {}, not below the shard count {}", self.shard, self.count));
        }
        if self.scene_hashes.len() != self.scenes.len() {
            return Err(format!(
                "scene_hashes: has {}, not one for each of the {} scenes",
                self.scene_hashes.len(),
                self.scenes.len()
            ));
        }
        let scene_of = |at: String, name: &str| {
            if self.scenes.iter().any(|s| s == name) {
                Ok(())
            } else {
                Err(format!("{at}: `{name}` is not a scene of this sweep ({})", self.scenes.join(", ")))
            }
        };
        let own = Some(self.shard);
        let shard_of = |at: String, shard: Option<u32>| match shard {
            s if s == own => Ok(()),
            Some(s) => Err(format!("{at}.shard: is {s}, not this file's shard {}", self.shard)),
            None => Err(format!("{at}.shard: missing; this file's rows are shard {}'s", self.shard)),
        };
        let number = |at: String, v: f64| {
            if v.is_finite() && v >= 0.0 {
                Ok(())
            } else {
                Err(format!("{at}: {} is not a finite number ≥ 0", format_number(v)))
            }
        };
        // A share of pixels or of light: 1e300 merged into a 303-digit percentage (a tester).
        let fraction = |at: String, v: f64| {
            if (0.0..=1.0).contains(&v) {
                Ok(())
            } else {
                Err(format!("{at}: {} is not a fraction in [0, 1]", format_number(v)))
            }
        };
        let numbers =
            |at: String, vs: &[f64]| vs.iter().enumerate().try_for_each(|(k, &v)| number(format!("{at}[{k}]"), v));
        // A timed run no render of a sweep takes: a week's seconds (u64::MAX seconds was merged
        // into a median of 1.8e22 ms).
        let times = |at: &str, times: &[Duration]| {
            match times.iter().find(|t| t.as_secs() > MAX_RUN_SECS) {
                Some(t) => Err(format!(
                    "{at}.times: a run of {} s, longer than a week ({MAX_RUN_SECS} s), which no render of a sweep takes",
                    t.as_secs()
                )),
                // Every row is timed in the sweep's `runs` passes: a row with fewer (a run's table
                // renamed away) merged a median of two runs as if of three (a tester).
                None if times.len() != self.runs as usize => Err(format!(
                    "{at}.times: {} timed runs, not the sweep's {} (runs = {}): every row is timed in each pass",
                    times.len(),
                    self.runs,
                    self.runs
                )),
                None => Ok(()),
            }
        };
        for (i, scene) in self.results.iter().enumerate() {
            scene_of(format!("results[{i}].name"), &scene.name)?;
            let mut settings = Report::default();
            validate_settings(&scene.settings, &mut settings);
            if let Some(e) = settings.errors.first() {
                return Err(format!("results[{i}].settings: {e}"));
            }
            for (j, row) in scene.rows.iter().enumerate() {
                let at = format!("results[{i}].rows[{j}]");
                shard_of(at.clone(), row.shard)?;
                times(&at, &row.times)?;
                let e = &row.errors;
                for (name, v) in [
                    ("max_abs", e.max_abs),
                    ("mean_abs", e.mean_abs),
                    ("rmse", e.rmse),
                    ("rel_mse", e.rel_mse),
                    ("p99_abs_same_hit", e.p99_abs_same_hit),
                ] {
                    number(format!("{at}.errors.{name}"), v)?;
                }
                for (name, v) in [("flip_mean", e.flip_mean), ("first_hit_mismatch", e.first_hit_mismatch)] {
                    fraction(format!("{at}.errors.{name}"), v)?;
                }
                // +inf: identical images; −inf would need an infinite error, which finite images
                // (non-finite ones are refused) never have.
                if e.psnr.is_nan() || e.psnr == f64::NEG_INFINITY {
                    return Err(format!("{at}.errors.psnr: is {}, which no image pair has", e.psnr));
                }
                // Infinite exactly where the images are identical (`compare`: −10·log10 of the MSE).
                if e.psnr.is_infinite() != (e.rmse == 0.0) {
                    return Err(format!(
                        "{at}.errors.psnr: is {} with an rmse of {}; it is infinite exactly where the rmse is 0",
                        format_number(e.psnr),
                        format_number(e.rmse)
                    ));
                }
                // The figures `compare_images` makes of one image pair hold to each other: an
                // rmse edited from 0.2077 to 9.2077 merged beside its PSNR of 13.6 dB (a tester).
                if e.rmse > 0.0 {
                    let from_rmse = -20.0 * e.rmse.log10();
                    if (e.psnr - from_rmse).abs() > 1e-6 * from_rmse.abs().max(1.0) {
                        return Err(format!(
                            "{at}.errors.psnr: is {} with an rmse of {}, which gives {}; one of them was edited",
                            format_number(e.psnr),
                            format_number(e.rmse),
                            format_number(from_rmse)
                        ));
                    }
                }
                let within = |low: f64, high: f64| low <= high * (1.0 + 1e-9);
                if !(within(e.mean_abs, e.rmse) && within(e.rmse, e.max_abs) && within(e.p99_abs_same_hit, e.max_abs)) {
                    return Err(format!(
                        "{at}.errors: mean_abs {} ≤ rmse {} ≤ max_abs {} (and p99_abs_same_hit {} ≤ max_abs) does not \
                         hold, as it does for any image pair; one of them was edited",
                        format_number(e.mean_abs),
                        format_number(e.rmse),
                        format_number(e.max_abs),
                        format_number(e.p99_abs_same_hit)
                    ));
                }
                for (name, v) in [("twin_rmse", row.twin_rmse), ("twin_rays_pct", row.twin_rays_pct.map(f64::abs))] {
                    v.map_or(Ok(()), |v| number(format!("{at}.{name}"), v))?;
                }
                // One camera ray a sample: the CPU traces every one, and no GPU traces more. A CPU
                // row's count of 0 was merged and marked as dropped work (a tester).
                let expected = u64::from(self.width) * u64::from(self.height) * u64::from(row.config.spp);
                if row.camera_expected != expected {
                    return Err(format!(
                        "{at}.camera_expected: is {}, not {}×{}×{} spp = {expected}",
                        row.camera_expected, self.width, self.height, row.config.spp
                    ));
                }
                let cpu = row.config.backend == Backend::Cpu;
                if row.counts.camera > expected || (cpu && row.counts.camera != expected) {
                    return Err(format!(
                        "{at}.counts.camera: is {}, {} the {expected} samples of the row",
                        row.counts.camera,
                        if cpu { "not the CPU's one a sample:" } else { "more than one a sample of" }
                    ));
                }
                // Their sum is taken (rays per second): counts no render can make overflowed it.
                let c = &row.counts;
                let sum = [c.camera, c.shadow, c.reflection, c.refraction, c.bailout_saved, c.capped_samples]
                    .into_iter()
                    .try_fold(0u64, u64::checked_add);
                if sum.is_none_or(|s| s > MAX_RAYS) {
                    return Err(format!("{at}.counts: sum to more than 2^60 rays, more than any sweep traces"));
                }
            }
            for (j, row) in scene.specular.iter().enumerate() {
                let at = format!("results[{i}].specular[{j}]");
                shard_of(at.clone(), row.shard)?;
                times(&at, &row.times)?;
            }
        }
        for (i, gi) in self.gi.iter().enumerate() {
            let at = format!("gi[{i}]");
            scene_of(format!("{at}.scene"), &gi.scene)?;
            shard_of(at.clone(), gi.shard)?;
            number(format!("{at}.reference_noise"), gi.reference_noise)?;
            // Written into the report as they are: NaN merged into "fitted (NaN, 1.000, 1.000)".
            numbers(format!("{at}.fitted"), &gi.fitted)?;
            numbers(format!("{at}.written"), &gi.written)?;
            let k = &gi.kinds;
            for (name, v) in [("share", &k.share), ("rms", &k.rms)] {
                numbers(format!("{at}.kinds.{name}"), v)?;
            }
            k.share.iter().enumerate().try_for_each(|(n, &v)| fraction(format!("{at}.kinds.share[{n}]"), v))?;
            // Each kind's part of the four's sum: they add to 1, or are all 0 over black paths
            // (four shares of 0.9 merged into "270 %" of indirect light; a tester).
            let sum: f64 = k.share.iter().sum();
            let adds_up = if k.paths_mean > 0.0 { (sum - 1.0).abs() <= 1e-6 } else { sum == 0.0 };
            if !adds_up {
                return Err(format!(
                    "{at}.kinds.share: adds to {}, not {} (the paths' mean is {})",
                    format_number(sum),
                    if k.paths_mean > 0.0 { "1" } else { "0" },
                    format_number(k.paths_mean)
                ));
            }
            for (name, v) in [("kinds.spp", k.spp), ("reference_spp", gi.reference_spp)] {
                if v == 0 {
                    return Err(format!("{at}.{name}: 0; a render takes at least one sample a pixel"));
                }
            }
            for (name, v) in [
                ("direct_rmse", k.direct_rmse),
                ("paths_mean", k.paths_mean),
                ("ambient_rmse", k.ambient_rmse),
                ("whitted_rmse", k.whitted_rmse),
            ] {
                number(format!("{at}.kinds.{name}"), v)?;
            }
            // Written into report.md as they are: one with a line break began a heading there
            // (a tester).
            if let Some(c) = k.direct_causes.iter().find(|c| !super::gi::DIRECT_CAUSES.contains(&c.as_str())) {
                return Err(format!("{at}.kinds.direct_causes: `{}` is no cause this glint names", c.escape_debug()));
            }
            // Over black paths' MIN_POSITIVE a large ambient's share is rightly infinite; over
            // paths with light it is a finite part of it ("adds inf %" merged; a tester).
            let black = k.paths_mean == 0.0;
            if k.ambient_share.is_nan() || k.ambient_share < 0.0 || !(black || k.ambient_share.is_finite()) {
                return Err(format!(
                    "{at}.kinds.ambient_share: {} is not a {}number ≥ 0",
                    format_number(k.ambient_share),
                    if black { "" } else { "finite " }
                ));
            }
            for (j, row) in gi.rows.iter().enumerate() {
                number(format!("{at}.rows[{j}].rmse"), row.rmse)?;
                if row.spp == 0 {
                    return Err(format!("{at}.rows[{j}].spp: 0; a render takes at least one sample a pixel"));
                }
                if let Some(rgb) = &row.ambient_rgb {
                    numbers(format!("{at}.rows[{j}].ambient_rgb"), rgb)?;
                }
                if row.median.as_secs() > MAX_RUN_SECS {
                    return Err(format!("{at}.rows[{j}].median: {} s, longer than a week", row.median.as_secs()));
                }
            }
        }
        Ok(())
    }
}
