//! `glint report --shard I/N` and `glint report --merge DIR…`: a sweep split over machines.
//!
//! The work is cut into families: one scene's configurations that differ only in backend and
//! specialisation (so that a GPU row and its CPU twin, a full shader and its specialised one,
//! are timed and compared on one machine). Families are dealt to the N shards by expected cost
//! (pixels × samples × (depth + 1) × (runs + 1), the largest first to the least loaded shard),
//! the same way on every machine. A shard renders the CPU reference of each scene it has a
//! family of (deterministic, so every shard's errors are the ones a one-machine run measures),
//! and writes its rows to `shard-I-of-N.toml`. The merge reads every shard's file, checks that
//! they are one sweep's and that none is missing, puts the rows back in the sweep's order and
//! writes the CSV, Markdown and plots a one-machine run writes; each row keeps its shard's
//! timing and says which shard (and so which machine) it comes from.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

use anyhow::{Context, bail};
use glint_core::Backend;
use glint_scene::Integrator;
use serde::{Deserialize, Serialize};

use super::machine::Machine;
use super::plan::{Config, Planned, SceneNeeds};
use super::sweep::SceneResult;

/// `--shard I/N`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct ShardSpec {
    pub index: u32,
    pub count: u32,
}

pub fn parse_shard(s: &str) -> Result<ShardSpec, String> {
    let (index, count) = super::super::job_array::parse_part(s, "shard", false)?;
    // A count of 0 is refused by parse_part, with its range.
    let index = index.unwrap_or_default();
    if index >= count {
        return Err(format!("shard {index} of {count}: shards of {count} are numbered 0 to {}", count - 1));
    }
    Ok(ShardSpec { index, count })
}

/// A family: the configurations of one scene that differ only in backend and specialisation.
fn family(config: &Config) -> (u32, u32, super::plan::Bailout, glint_scene::EpsilonMode) {
    (config.spp, config.depth, config.bailout, config.epsilon_mode)
}

/// Each planned configuration's family, as the index of its first configuration in plan order.
fn family_heads(planned: &[Planned]) -> Vec<usize> {
    planned
        .iter()
        .enumerate()
        .map(|(i, p)| planned.iter().position(|q| family(&q.config) == family(&p.config)).unwrap_or(i))
        .collect()
}

/// How many families (scene, family) a sweep of `planned` configurations over scenes of
/// `needs` has, each with a configuration its scene needs (`Planned::measured_for`): each is
/// timed whole by one shard, so more shards than this would have nothing to run.
pub fn families(planned: &[Planned], needs: &[SceneNeeds]) -> usize {
    let heads = family_heads(planned);
    let measured =
        |n: &SceneNeeds, head: usize| (0..planned.len()).any(|j| heads[j] == head && planned[j].measured_for(*n));
    needs.iter().map(|n| heads.iter().enumerate().filter(|&(i, &head)| i == head && measured(n, head)).count()).sum()
}

/// Which shard times each (scene, planned configuration): `shards[scene][config]`, over the
/// configurations each scene needs (`needs`; one it leaves out costs nothing, and a family of
/// none is dealt to no shard: its entries say shard 0, which measures none of it). Shards past
/// the count of families get none (`families`), and are not walked: a count of 2^32 costs what
/// the families do.
pub fn assign(planned: &[Planned], needs: &[SceneNeeds], pixels: u64, runs: u32, count: u32) -> Vec<Vec<u32>> {
    let heads = family_heads(planned);
    let mut families: BTreeMap<(usize, usize), f64> = BTreeMap::new();
    for (scene, n) in needs.iter().enumerate() {
        for (p, &first) in planned.iter().zip(&heads) {
            if !p.measured_for(*n) {
                continue;
            }
            // Keyed by the family's first configuration, in plan order.
            let c = &p.config;
            let cost = pixels as f64 * f64::from(c.spp) * f64::from(c.depth + 1) * f64::from(runs + 1);
            *families.entry((scene, first)).or_default() += cost;
        }
    }
    let mut order: Vec<((usize, usize), f64)> = families.into_iter().collect();
    // The largest first; equal costs in plan order, so every machine deals the same.
    order.sort_by(|a, b| b.1.total_cmp(&a.1).then(a.0.cmp(&b.0)));
    // Each family goes to the least loaded shard, the lowest of equals: while empty shards are
    // left, that is the next one, so only the first `used` ever receive one.
    let used = (count as usize).min(order.len()).max(1);
    let mut load = vec![0.0f64; used];
    let mut owner: BTreeMap<(usize, usize), u32> = BTreeMap::new();
    for (key, cost) in order {
        let shard = (0..used).min_by(|&a, &b| load[a].total_cmp(&load[b]).then(a.cmp(&b))).unwrap_or(0);
        load[shard] += cost;
        owner.insert(key, shard as u32);
    }
    (0..needs.len())
        .map(|scene| heads.iter().map(|&first| owner.get(&(scene, first)).copied().unwrap_or(0)).collect())
        .collect()
}

/// The layout of `shard-I-of-N.toml`. Bump it with any change to what a shard writes (the
/// `ShardFile` and every type in it; tests/golden/shard-keys.txt lists the keys of a CPU-only
/// shard, so a change to the GPU rows' fields alone is not caught there): the merge refuses a
/// shard of another format instead of reading fields it lacks as empty.
pub const SHARD_FORMAT: u32 = 5;

/// What a shard writes: the sweep it is part of, its machine, and its rows.
#[derive(Debug, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ShardFile {
    /// `SHARD_FORMAT` of the glint that wrote it.
    pub format: u32,
    pub glint: String,
    pub shard: u32,
    pub count: u32,
    pub width: u32,
    pub height: u32,
    pub runs: u32,
    pub quick: bool,
    pub reference_spp: u32,
    pub integrator: Option<Integrator>,
    /// Every scene of the sweep, in its order.
    pub scenes: Vec<String>,
    /// Each scene's content hash as the tracers read it (`FlatScene::content_hash`), in the
    /// same order: a scene file or texture edited between two shards' runs is another sweep.
    pub scene_hashes: Vec<String>,
    pub backends: Vec<Backend>,
    pub cpu_device: String,
    pub gpu_device: Option<String>,
    pub machine: Machine,
    pub results: Vec<SceneResult>,
    /// Whitted against the path-traced reference, for the scenes whose first configuration
    /// this shard has.
    pub gi: Vec<super::gi::GiResult>,
    /// Where the merge read it from (not written): what its messages name.
    #[serde(skip)]
    pub path: PathBuf,
}

impl ShardFile {
    /// What must be equal in every shard of one sweep, as text for the message. The GPU too:
    /// its rows' f32 error and the GPU-against-CPU figures are one adapter's, as a merged
    /// render's tiles are (`glint merge` refuses tiles of two adapters).
    fn sweep(&self) -> [(&'static str, String); 10] {
        let backends: Vec<&str> = self.backends.iter().map(|b| b.name()).collect();
        [
            ("glint version", self.glint.clone()),
            ("shard count", self.count.to_string()),
            ("size", format!("{}x{}", self.width, self.height)),
            ("timed runs", self.runs.to_string()),
            ("--quick", self.quick.to_string()),
            ("reference spp", self.reference_spp.to_string()),
            ("integrator", self.integrator.map_or("each scene's own".into(), |i| i.name().into())),
            ("scene list", self.scenes.join(",")),
            ("backends", backends.join(",")),
            ("GPU", self.gpu_device.clone().unwrap_or_else(|| "none".into())),
        ]
    }
}

impl ShardFile {
    /// Every row's timed runs in order, as a run writes them (a median is read from the middle).
    fn sort_times(&mut self) {
        for scene in &mut self.results {
            scene.rows.iter_mut().for_each(|r| r.times.sort());
            scene.specular.iter_mut().for_each(|r| r.times.sort());
        }
    }
}

pub fn file_name(spec: ShardSpec) -> String {
    format!("shard-{}-of-{}.toml", spec.index, spec.count)
}

pub fn write(dir: &Path, spec: ShardSpec, file: &ShardFile) -> anyhow::Result<PathBuf> {
    let path = dir.join(file_name(spec));
    let text = toml::to_string(file).context("the shard's results as TOML")?;
    glint_io::atomic::write_file_atomically(&path, text.as_bytes())
        .map_err(|e| anyhow::anyhow!("cannot write {}: {}", e.path.display(), e.error))?;
    Ok(path)
}

/// Every shard file in `dirs`, checked to be one whole sweep, in shard order.
pub fn read_all(dirs: &[PathBuf]) -> anyhow::Result<Vec<ShardFile>> {
    let mut found: Vec<(PathBuf, ShardFile)> = Vec::new();
    // A shard that was cancelled, failed or never ran made no folder (it creates --out when it
    // writes): one folder a shard is the recipe, so an absent one is a missing shard to name
    // with the rest, not the end of the merge.
    let mut absent: Vec<&Path> = Vec::new();
    // Folders that exist but hold no shard file: a typo'd or wrong folder, which the merge
    // passed over in silence wherever the other folders held every shard.
    let mut empty: Vec<&Path> = Vec::new();
    for dir in dirs {
        let entries = match std::fs::read_dir(dir) {
            Ok(entries) => entries,
            Err(e) if e.kind() == std::io::ErrorKind::NotFound => {
                absent.push(dir);
                continue;
            }
            Err(e) => return Err(e).with_context(|| format!("cannot read the folder {}", dir.display())),
        };
        let mut names: Vec<PathBuf> = entries
            .filter_map(Result::ok)
            .map(|e| e.path())
            .filter(|p| p.file_name().is_some_and(|n| n.to_string_lossy().starts_with("shard-")))
            .filter(|p| p.extension().is_some_and(|e| e == "toml"))
            .collect();
        names.sort();
        if names.is_empty() {
            empty.push(dir);
        }
        for path in names {
            // A shard is a file `glint report --shard` wrote: a named pipe named like one would
            // hold the merge, waiting for a writer, past a SIGTERM (a tester).
            let text = glint_io::uri::regular_file(&path)
                .and_then(|_| std::fs::read_to_string(&path))
                .with_context(|| format!("cannot read {}", path.display()))?;
            check_format(&path, &text)?;
            // Unknown keys are refused too (`deny_unknown_fields`): a run's table renamed away
            // was read as a row of fewer runs, the stray table ignored (a tester).
            let mut file: ShardFile = toml::from_str(&text).with_context(|| {
                format!(
                    "{}: not a shard as `glint report --shard` writes it: the file was edited or damaged; run that \
                     shard again; nothing was written",
                    path.display()
                )
            })?;
            file.path.clone_from(&path);
            file.sort_times();
            if let Err(problem) = file.check() {
                bail!(
                    "{}: {problem}: the file was edited or damaged; run that shard again; nothing was written",
                    path.display()
                );
            }
            found.push((path, file));
        }
    }
    // "a, b do not exist", "a does not exist".
    let not_existing = |folders: &[&Path]| {
        let list: Vec<String> = folders.iter().map(|d| d.display().to_string()).collect();
        format!("{} {} not exist", list.join(", "), if folders.len() == 1 { "does" } else { "do" })
    };
    if found.is_empty() {
        let none = if absent.len() == dirs.len() {
            not_existing(&absent)
        } else {
            let list: Vec<String> = dirs.iter().map(|d| d.display().to_string()).collect();
            format!("no shard-I-of-N.toml in {}", list.join(", "))
        };
        bail!("{none}: run `glint report --shard I/N --out DIR` first");
    }
    let no_shard_in = |folders: &[&Path]| {
        let list: Vec<String> = folders.iter().map(|d| d.display().to_string()).collect();
        format!("no shard-I-of-N.toml in {}", list.join(", "))
    };
    // Every folder given that supplied no shard, as the merge of that folder alone says it.
    let folders_without = absent.len() + empty.len();
    let mut unsupplied = Vec::new();
    if !absent.is_empty() {
        unsupplied.push(not_existing(&absent));
    }
    if !empty.is_empty() {
        unsupplied.push(no_shard_in(&empty));
    }
    // Beside missing shards, an absent folder is likely theirs.
    let mut absent = if absent.is_empty() {
        String::new()
    } else {
        format!("; {} (a shard that failed or never ran writes no folder)", not_existing(&absent))
    };
    if !empty.is_empty() {
        absent.push_str(&format!("; {}", no_shard_in(&empty)));
    }
    // Shards are held against the sweep most of them are of (the first's on a tie), so that a
    // stale shard is the one named, whichever file the folders list first (as `glint merge`
    // names a stale tile).
    let mut sweeps: Vec<((_, &[String]), usize, usize)> = Vec::new();
    for (i, (_, file)) in found.iter().enumerate() {
        let key = (file.sweep(), file.scene_hashes.as_slice());
        match sweeps.iter_mut().find(|(k, _, _)| *k == key) {
            Some((_, n, _)) => *n += 1,
            None => sweeps.push((key, 1, i)),
        }
    }
    // With no sweep of most shards (two shards, one stale) either may be the stale one.
    let (_, agreeing, reference) =
        *sweeps.iter().max_by_key(|&&(_, n, i)| (n, std::cmp::Reverse(i))).expect("at least one shard");
    let tied = sweeps.iter().filter(|(_, n, _)| *n == agreeing).count() > 1;
    let (first_path, first) = &found[reference];
    let others = match (agreeing, tied) {
        (_, true) => " (as many shards are of either sweep: either may be the stale one)".to_string(),
        (1, false) => String::new(),
        (n, false) => format!(" and {} more of the {} shards", n - 1, found.len()),
    };
    let expected = first.sweep();
    let mut by_index: BTreeMap<u32, &Path> = BTreeMap::new();
    for (path, file) in &found {
        if let Some(((what, theirs), (_, ours))) = expected.iter().zip(file.sweep()).find(|((_, a), (_, b))| a != b) {
            bail!(
                "{} is not a shard of the same sweep as {}{others}: its {what}: {ours}, not {theirs}; nothing was \
                 written",
                path.display(),
                first_path.display()
            );
        }
        if let Some(reason) = changed_scene(first, file) {
            bail!(
                "{} is not a shard of the same sweep as {}{others}: {reason}; nothing was written",
                path.display(),
                first_path.display()
            );
        }
        if let Some(other) = by_index.insert(file.shard, path) {
            bail!(
                "shard {} is given twice, {} and {}; nothing was written",
                file.shard,
                other.display(),
                path.display()
            );
        }
    }
    let missing = crate::cli::job_array::missing_runs(by_index.keys().copied(), first.count);
    if missing.count > 0 {
        bail!(
            "{} of {} {} missing: {} (run {} with --shard I/{}; {}){absent}; nothing was written",
            missing.count,
            first.count,
            if missing.count == 1 { "shards is" } else { "shards are" },
            missing.listing(),
            if missing.count == 1 { "it" } else { "them" },
            first.count,
            missing.slurm_array()
        );
    }
    // Every shard was found, but a folder given supplied none: a typo or a wrong folder the
    // user meant to merge, which is refused as it is when given alone (it was passed over).
    if !unsupplied.is_empty() {
        bail!(
            "{}: run `glint report --shard I/N --out DIR` first, or leave {} out of --merge (all {} shards were found \
             in the other folders); nothing was written",
            unsupplied.join("; "),
            if folders_without == 1 { "it" } else { "them" },
            first.count
        );
    }
    let mut files: Vec<ShardFile> = found.into_iter().map(|(_, f)| f).collect();
    files.sort_by_key(|f| f.shard);
    Ok(files)
}

/// An error unless `text` (the file at `path`) is a shard of this glint's `SHARD_FORMAT`. Read
/// before the whole file, whose fields another format may lack or name otherwise.
fn check_format(path: &Path, text: &str) -> anyhow::Result<()> {
    #[derive(Deserialize)]
    struct Head {
        format: Option<toml::Value>,
        glint: Option<String>,
    }
    if text.trim().is_empty() {
        bail!(
            "{}: is empty, not a shard glint wrote (it writes a shard whole or not at all): the file was made or \
             cut short otherwise; run that shard again; nothing was written",
            path.display()
        );
    }
    let Ok(head) = toml::from_str::<Head>(text) else {
        // Not TOML or not a table: the full read names what is wrong.
        return Ok(());
    };
    let format = match &head.format {
        Some(toml::Value::Integer(n)) if *n == i64::from(SHARD_FORMAT) => return Ok(()),
        Some(v) => format!("shard format {v}"),
        None => "no shard format (a glint from before shard formats)".to_string(),
    };
    let glint = head.glint.map_or_else(String::new, |v| format!(", glint {v}"));
    bail!(
        "{}: written by another glint ({format}{glint}); this glint merges shard format {SHARD_FORMAT} only: run \
         that shard again with this glint; nothing was written",
        path.display()
    )
}

/// Why two shards with the same scene names are not of the same scenes, if they are not: a
/// scene whose content hash differs.
fn changed_scene(first: &ShardFile, other: &ShardFile) -> Option<String> {
    // `check` gave every shard one hash a scene.
    let i = (0..other.scenes.len()).find(|&i| first.scene_hashes[i] != other.scene_hashes[i])?;
    Some(format!(
        "scene {} differs between them (its content hash, `glint:scene_hash` in a render's metadata): the scene or its \
         textures changed between the shards' runs, so render every shard of the same files again",
        other.scenes[i]
    ))
}

/// The shards' Whitted-against-paths results, in the sweep's order of scenes; an error unless
/// every scene has one (a shard's file edited or cut short).
pub fn join_gi(files: &mut [ShardFile]) -> anyhow::Result<Vec<super::gi::GiResult>> {
    let names = files[0].scenes.clone();
    // `--quick` and the backends are the same in every shard (`check`): one plan for all.
    let (quick, backends) = (files[0].quick, &files[0].backends);
    let (reference, planned) = (super::gi::reference_axes(quick), super::gi::planned_rows(backends, quick));
    let split = super::gi::split_whitted_axes(quick);
    for f in files.iter() {
        f.gi.iter().try_for_each(|gi| gi_planned(gi, reference, split, &planned)).with_context(|| {
            format!("{}: was edited or is another sweep's; run its shard again; nothing was written", f.path.display())
        })?;
    }
    let mut all: Vec<super::gi::GiResult> = files.iter_mut().flat_map(|f| std::mem::take(&mut f.gi)).collect();
    all.sort_by_key(|g| names.iter().position(|n| *n == g.scene).unwrap_or(usize::MAX));
    for name in &names {
        let found = all.iter().filter(|g| g.scene == *name).count();
        if found != 1 {
            bail!(
                "scene {name} has {found} Whitted-against-paths sections in the shards, not one: a shard's file was \
                 edited or cut short; run that shard again; nothing was written"
            );
        }
    }
    Ok(all)
}

/// Whether a scene's Whitted-against-paths section holds the rows (`planned`) and the reference
/// (samples, depth) the sweep makes: its rows are the report's table.
fn gi_planned(
    gi: &super::gi::GiResult,
    (spp, depth): (u32, u32),
    split: (u32, u32),
    planned: &[super::gi::GiRowKey],
) -> anyhow::Result<()> {
    let scene = &gi.scene;
    if (gi.reference_spp, gi.reference_depth) != (spp, depth) {
        bail!(
            "scene {scene}'s path-traced reference is {} spp at depth {}, not the sweep's {spp} spp at depth {depth}",
            gi.reference_spp,
            gi.reference_depth
        );
    }
    let whitted = (gi.kinds.whitted_depth, gi.kinds.whitted_spp);
    if whitted != split {
        bail!(
            "scene {scene}'s split by kind holds the paths against Whitted at depth {}, {} spp, not the sweep's depth \
             {}, {} spp",
            whitted.0,
            whitted.1,
            split.0,
            split.1
        );
    }
    let keys: Vec<_> = gi.rows.iter().map(super::gi::GiRow::key).collect();
    if let Some(k) = (0..planned.len().max(keys.len())).find(|&k| keys.get(k) != planned.get(k)) {
        let what = |key: Option<&super::gi::GiRowKey>| key.map_or_else(|| "none".to_string(), |k| k.describe());
        bail!(
            "scene {scene}'s Whitted-against-paths row {k} is {}, not the sweep's {} ({} rows planned, {} found)",
            what(keys.get(k)),
            what(planned.get(k)),
            planned.len(),
            keys.len()
        );
    }
    for (k, row) in gi.rows.iter().enumerate() {
        use super::gi::Ambient;
        let consistent = match (row.ambient, row.ambient_rgb) {
            (Some(Ambient::AsWritten), Some(rgb)) => rgb == gi.written,
            (Some(Ambient::Without), Some(rgb)) => rgb == [0.0; 3],
            (Some(Ambient::Fitted), Some(_)) | (None, None) => true,
            (Some(_), None) | (None, Some(_)) => false,
        };
        if !consistent {
            bail!(
                "scene {scene}'s Whitted-against-paths row {k} ({}) has ambient_rgb {:?}, which its ambient ({}) does \
                 not give",
                row.key().describe(),
                row.ambient_rgb,
                match row.ambient {
                    Some(Ambient::AsWritten) => format!("as written: {:?}", gi.written),
                    Some(Ambient::Without) => "none: [0.0, 0.0, 0.0]".to_string(),
                    Some(Ambient::Fitted) => "fitted: some I_a".to_string(),
                    None => "a path row's: none".to_string(),
                }
            );
        }
    }
    Ok(())
}

/// The shards' rows joined per scene, in the sweep's order of scenes and of configurations;
/// an error where a scene lacks a configuration or has one twice (a shard's file edited or cut
/// short: the shards' split gives each configuration to exactly one).
pub fn join(files: &mut [ShardFile], planned: &[Planned]) -> anyhow::Result<Vec<SceneResult>> {
    let position = |c: &Config| planned.iter().position(|p| p.config == *c).unwrap_or(usize::MAX);
    let names = files[0].scenes.clone();
    // Which shard measures each configuration of each scene: the split every shard made.
    let first = &files[0];
    // Every shard writes a result, its needs included, for every scene (`check`).
    let needs: Vec<SceneNeeds> = names
        .iter()
        .map(|n| first.results.iter().find(|r| r.name == *n).map(|r| r.needs))
        .collect::<Option<_>>()
        .with_context(|| format!("{}: a scene of the sweep has no result", first.path.display()))?;
    let owners = assign(planned, &needs, u64::from(first.width) * u64::from(first.height), first.runs, first.count);
    let paths: Vec<PathBuf> = files.iter().map(|f| f.path.clone()).collect();
    let mut out: Vec<SceneResult> = Vec::new();
    let mut first_of: Vec<&Path> = Vec::new();
    for (f, path) in files.iter_mut().zip(&paths) {
        for part in std::mem::take(&mut f.results) {
            match out.iter().position(|j| j.name == part.name) {
                Some(k) => {
                    // Every shard renders a scene from the one file at the one size: settings
                    // that differ were edited (spp = 0 was merged without a word).
                    let j = &mut out[k];
                    if j.settings != part.settings || j.reference != part.reference {
                        bail!(
                            "{}: scene {}'s settings or reference are not those {} has; the file was edited: run \
                             its shard again; nothing was written",
                            path.display(),
                            part.name,
                            first_of[k].display()
                        );
                    }
                    // A shard without rows in the scene rendered no reference.
                    if j.reference_stats.is_none() {
                        j.reference_stats = part.reference_stats;
                    }
                    j.rows.extend(part.rows);
                    j.specular.extend(part.specular);
                }
                None => {
                    out.push(part);
                    first_of.push(path);
                }
            }
        }
    }
    out.sort_by_key(|j| names.iter().position(|n| *n == j.name).unwrap_or(usize::MAX));
    for j in &mut out {
        j.rows.sort_by_key(|r| position(&r.config));
        let measured: Vec<usize> = j.rows.iter().map(|r| position(&r.config)).collect();
        let scene = names.iter().position(|n| *n == j.name);
        // A path scene leaves out the rows that only vary the bailout (`Planned::measured_for`).
        let expected: Vec<usize> = (0..planned.len()).filter(|&i| planned[i].measured_for(j.needs)).collect();
        let short = expected.iter().copied().find(|i| measured.iter().filter(|m| *m == i).count() != 1);
        if let Some(i) = short {
            let what =
                format!("{} {}", planned[i].config.backend.name(), planned[i].config.describe(j.needs.integrator));
            let owner = scene.and_then(|s| owners.get(s)).and_then(|o| o.get(i)).copied();
            match (measured.iter().filter(|m| **m == i).count(), owner) {
                (0, Some(shard)) => bail!(
                    "scene {} lacks the configuration ({what}), which shard {shard} measures: shard {shard}'s file \
                     ({}) was edited or cut short; run shard {shard} again; nothing was written",
                    j.name,
                    paths.get(shard as usize).map_or_else(|| "missing".into(), |p| p.display().to_string())
                ),
                // Twice: either file may be the edited one.
                (times, _) => bail!(
                    "scene {} has the configuration ({what}) {times} times, not once: a shard's file was edited or \
                     copied; run the shards that have it again; nothing was written",
                    j.name
                ),
            }
        }
        // A scene without a specular lobe has no specular rows (`SceneNeeds::specular`).
        if measured != expected || j.specular.is_empty() == j.needs.specular {
            bail!(
                "scene {} has {} rows in the shards, not the sweep's {} configurations once each with its \
                 specular models ({} rows): a shard's file was edited or cut short; run that shard again; nothing was \
                 written",
                j.name,
                j.rows.len(),
                expected.len(),
                j.specular.len()
            );
        }
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::cli::report::plan::Plan;

    #[test]
    fn shards_past_the_families_get_nothing_and_cost_nothing() {
        let planned = Plan::full(64).configs(&[Backend::Cpu, Backend::Gpu]);
        let needs =
            [SceneNeeds { integrator: Integrator::Whitted, recurses: true, bailout_cuts: true, specular: true }; 5];
        let families = families(&planned, &needs);
        assert!(families > 5 && families < 5 * planned.len(), "{families}");
        let fitted = assign(&planned, &needs, 320 * 240, 3, families as u32);
        // As many shards as families: one each, every shard used.
        let used: std::collections::BTreeSet<u32> = fitted.iter().flatten().copied().collect();
        assert_eq!(used.len(), families);
        // Any more deal the same (no 2^32-long load vector), and leave the rest empty.
        assert_eq!(assign(&planned, &needs, 320 * 240, 3, u32::MAX), fitted);
        // A scene without child rays has fewer families: the deep grid rows it leaves out.
        let flat = [SceneNeeds { recurses: false, bailout_cuts: false, ..needs[0] }];
        let fewer = self::families(&planned, &flat);
        assert!(fewer < families / 5, "{fewer} of {}", families / 5);
        let used: std::collections::BTreeSet<u32> =
            assign(&planned, &flat, 320 * 240, 3, fewer as u32).into_iter().flatten().collect();
        assert_eq!(used.len(), fewer, "a shard was dealt only configurations the scene leaves out");
    }

    #[test]
    fn every_family_goes_to_one_shard_and_the_loads_balance() {
        let planned = Plan::full(64).configs(&[Backend::Cpu, Backend::Gpu]);
        let needs =
            [SceneNeeds { integrator: Integrator::Whitted, recurses: true, bailout_cuts: true, specular: true }; 5];
        for count in [1, 2, 3, 7] {
            let shards = assign(&planned, &needs, 320 * 240, 3, count);
            let mut load = vec![0.0; count as usize];
            for scene in &shards {
                for (i, p) in planned.iter().enumerate() {
                    for (j, q) in planned.iter().enumerate() {
                        if family(&p.config) == family(&q.config) {
                            assert_eq!(scene[i], scene[j], "a family split over shards");
                        }
                    }
                    let c = &p.config;
                    load[scene[i] as usize] += f64::from(c.spp) * f64::from(c.depth + 1);
                }
            }
            let (most, least) =
                (load.iter().copied().fold(0.0, f64::max), load.iter().copied().fold(f64::MAX, f64::min));
            assert!(least > 0.0 && most <= 2.0 * least, "{count} shards: loads {load:?}");
            assert_eq!(shards, assign(&planned, &needs, 320 * 240, 3, count), "not the same on every machine");
        }
    }

    #[test]
    fn shard_specs_parse_or_say_what_is_wrong() {
        assert_eq!(parse_shard("1/4"), Ok(ShardSpec { index: 1, count: 4 }));
        assert!(
            parse_shard("4/4").unwrap_err().contains("shards of 4 are numbered 0 to 3"),
            "{:?}",
            parse_shard("4/4")
        );
        assert!(
            parse_shard("0/0")
                .unwrap_err()
                .contains("'0' is not a whole number from 1 to 4294967295 (the shard count)")
        );
        assert!(parse_shard("4").unwrap_err().contains("'4' is not I/N (shard I of N, I from 0)"));
        assert!(
            parse_shard("x/4")
                .unwrap_err()
                .contains("'x' is not a whole number from 0 to 4294967295 (the shard's index)")
        );
    }
}
