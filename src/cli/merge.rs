//! `glint merge TILE.exr… -o OUT.exr|OUT.png`: the tiles of `glint render --tile` joined into
//! the whole image. Every tile's header is read first (no pixels): they must be one render's
//! (the same scene hash, settings, backend, version and grid), each tile's data window must be
//! its grid block, none may come twice, and every missing one is named; then the pixels are
//! read, one tile at a time, into one f32 image (read also where a header held a problem, into
//! none, so that a tile cut short is named with it), and the output written atomically.
//! Nothing is written on any error. At most the output image and one tile are in memory.

use crate::cli::usage::usage;
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

use anyhow::{Context, bail};
use clap::Args;
use glint_core::TileGrid;
use glint_core::image::linear_f32_to_srgb8;
use glint_io::exr_file::{
    ExrHeader, ExrPixels, ExrReadError, PIXELS_SHA256, read_exr, read_exr_header, write_exr_region,
};
use glint_io::image_file::write_png_rgb8;
use glint_scene::MAX_IMAGE_SIDE;

use super::console::say;
use super::output_path::{check_outputs, is_same_file};

#[derive(Debug, Args)]
pub struct MergeArgs {
    /// The tiles: EXR files written by `glint render --tile`
    #[arg(required = true, value_name = "TILE.exr")]
    pub tiles: Vec<PathBuf>,
    /// The whole image: .exr (linear f32) or .png (sRGB, the settings in its metadata)
    #[arg(short, long)]
    pub output: PathBuf,
    /// Replace an output file even if it is read-only
    #[arg(long)]
    pub force: bool,
}

/// The attributes every tile of one render shares (its settings, scene and grid), compared in
/// this order so that a differing setting is named before the scene hash it also changes; the
/// rest (the tile's index, time, rays, the scene's name, the CPU's threads) is the tile's own.
/// The scene is judged by its content: tiles of one scene file copied under other names merge.
const SHARED: [&str; 13] = [
    "Software",
    "glint:size",
    "glint:spp",
    "glint:depth",
    "glint:epsilon",
    "glint:epsilon_mode",
    "glint:bailout",
    "glint:seed",
    "glint:integrator",
    "glint:indirect",
    "glint:backend",
    "glint:grid",
    "glint:scene_hash",
];

/// What GPU tiles share besides `SHARED`: the shader (specialised or whole), the adapter and
/// its driver. One adapter and shader give the same bits for any tile; two GPUs, two drivers or
/// two shaders need not (their f32 arithmetic, compiled apart, may round apart), and the merge
/// would be no one render's image. CPU tiles are the same bits for any machine, thread count
/// and specialisation (tested), so tiles rendered with and without `--no-specialise` merge.
const SHARED_ON_GPU: [&str; 2] = ["glint:specialised", "glint:device"];

/// The attributes `header`'s tiles must share.
fn shared_keys(header: &ExrHeader) -> Vec<&'static str> {
    let gpu = header.attribute("glint:backend") == Some("gpu");
    SHARED.iter().copied().chain(SHARED_ON_GPU.iter().copied().filter(|_| gpu)).collect()
}

/// A tile's place: its index and count from `glint:tile`.
fn tile_index(path: &Path, header: &ExrHeader) -> anyhow::Result<(u32, u32)> {
    // An earlier merge's output under the tiles' glob (`-o tiles/tile-merged.exr`).
    if let Some(n) = header.attribute("glint:merged_tiles") {
        bail!(
            "{}: the output of an earlier `glint merge` (of {n} tiles), not a tile; leave it out of the tiles \
             given; nothing was written",
            path.display()
        );
    }
    let value = header.attribute("glint:tile").with_context(|| {
        format!(
            "{}: not a tile of `glint render --tile` (it has no glint:tile attribute); nothing was written",
            path.display()
        )
    })?;
    let parsed = value.split_once('/').and_then(|(i, n)| Some((i.parse().ok()?, n.parse().ok()?)));
    parsed.with_context(|| format!("{}: glint:tile is '{value}', not I/N", path.display()))
}

/// What a path that is no regular file is, in a message's words.
fn file_kind(t: std::fs::FileType) -> &'static str {
    #[cfg(unix)]
    {
        use std::os::unix::fs::FileTypeExt;
        if t.is_fifo() {
            return "a named pipe";
        }
        if t.is_char_device() || t.is_block_device() {
            return "a device";
        }
        if t.is_socket() {
            return "a socket";
        }
    }
    if t.is_dir() { "a folder" } else { "not a regular file" }
}

/// The tile a file's name says it holds, where the name is one `glint render --tile` gives:
/// `tile-I.exr` (farm.md's `-o tiles/tile-$SLURM_ARRAY_TASK_ID.exr`) or `SCENE-tile-I.exr` (its
/// default), I in decimal. A file that cannot be read is matched to its tile by this alone.
fn index_by_name(path: &Path) -> Option<u32> {
    let name = path.file_name()?.to_str()?;
    let split = name.len().checked_sub(4)?;
    let (stem, ext) = (name.get(..split)?, name.get(split..)?);
    let (before, digits) = stem.rsplit_once('-').filter(|_| ext.eq_ignore_ascii_case(".exr"))?;
    let named = before == "tile" || before.ends_with("-tile");
    (named && !digits.is_empty() && digits.bytes().all(|b| b.is_ascii_digit())).then(|| digits.parse().ok())?
}

/// Where the index of a tile that cannot be read came from.
#[derive(Clone, Copy, PartialEq, Eq)]
enum IndexFrom {
    /// Its header, read before (the file changed or is cut short in its pixels).
    Header,
    /// Its file name (`index_by_name`).
    Name,
    /// Nowhere: which tile it was meant to hold is not known.
    Nowhere,
}

/// Why a tile file cannot be read, in a message's words: empty, not OpenEXR at all, or cut
/// short or damaged (a copy that ran out of space, a file truncated), with the EXR reader's
/// own words last. `from`: where the tile it holds was learnt, if anywhere.
fn unreadable_why(path: &Path, e: &ExrReadError, from: IndexFrom) -> String {
    let said = e.to_string();
    let detail = said.strip_prefix(&format!("{}: ", path.display())).unwrap_or(&said).to_string();
    let mut magic = [0u8; 4];
    let opened = std::fs::File::open(path).and_then(|mut f| std::io::Read::read_exact(&mut f, &mut magic));
    let len = std::fs::metadata(path).map(|m| m.len()).ok();
    match (len, opened) {
        // glint writes a tile whole or not at all (a temporary renamed): an empty one was made
        // otherwise, and holds no index to name.
        (Some(0), _) => match from {
            IndexFrom::Nowhere => "is empty (0 bytes), so which tile it was meant to hold cannot be known".into(),
            IndexFrom::Name => "is empty (0 bytes)".into(),
            IndexFrom::Header => "is empty (0 bytes) now: it changed while the merge read it".into(),
        },
        (_, Ok(())) if magic != [0x76, 0x2f, 0x31, 0x01] => format!("is not an OpenEXR file ({detail})"),
        _ => format!("cannot be read: the file is cut short or damaged ({detail})"),
    }
}

/// Why `header`'s image is none a render makes (a forged or damaged header), if it is not.
fn beyond_a_render(header: &ExrHeader) -> Option<String> {
    let (width, height) = header.display;
    let side = 1..=MAX_IMAGE_SIDE;
    (!side.contains(&width) || !side.contains(&height)).then(|| {
        format!("its image (display window) is {width}x{height}; a render's sides are in [1, {MAX_IMAGE_SIDE}]")
    })
}

/// A file that cannot be read, in a message: its path, the tile its name says it holds (`named`)
/// where it says one, and why.
fn unreadable_file(path: &Path, e: &ExrReadError, named: Option<u32>) -> String {
    match named {
        Some(i) => format!("{} (tile {i} by its name) {}", path.display(), unreadable_why(path, e, IndexFrom::Name)),
        None => format!("{}: {}", path.display(), unreadable_why(path, e, IndexFrom::Nowhere)),
    }
}

/// The tiles as held against the render of `tiles[reference]`: those of its grid by index, and
/// what is wrong with the rest.
struct Assessment<'a> {
    /// The reference tile's path, the grid's tile count, the image's size, the grid, and the
    /// attributes every tile of its render shares.
    first: &'a Path,
    count: u32,
    width: u32,
    height: u32,
    grid: TileGrid,
    keys: Vec<&'static str>,
    by_index: BTreeMap<u32, (&'a Path, &'a ExrHeader)>,
    /// Tiles of another render, with the first attribute that differs.
    stale: Vec<(&'a Path, String)>,
    /// Every other tile's problem, a sentence naming the file.
    problems: Vec<String>,
    /// Whether a tile of the render was refused for what it holds (its index is to render again).
    refused: bool,
}

fn assess<'a>(tiles: &'a [(&'a Path, ExrHeader)], reference: usize) -> anyhow::Result<Assessment<'a>> {
    let (first, header) = (tiles[reference].0, &tiles[reference].1);
    let (_, count) = tile_index(first, header)?;
    let (width, height) = header.display;
    // A forged or damaged header must not size the merged image beyond what a render makes.
    if let Some(sides) = beyond_a_render(header) {
        bail!("{}: {sides}; nothing was written", first.display());
    }
    let grid = TileGrid::new(count, width, height).with_context(|| format!("{}", first.display()))?;
    let mut found = Assessment {
        first,
        count,
        width,
        height,
        grid,
        keys: shared_keys(header),
        by_index: BTreeMap::new(),
        stale: Vec::new(),
        problems: Vec::new(),
        refused: false,
    };
    let shared = |h: &ExrHeader| found.keys.iter().map(|k| h.attribute(k).map(str::to_string)).collect::<Vec<_>>();
    let theirs = shared(header);
    // Every problem is named together with the indices to render again (a tester fixed two
    // stale tiles and a missing one in three rounds, one message each).
    for (path, header) in tiles {
        let path = *path;
        let (index, n) = match tile_index(path, header) {
            Ok(place) => place,
            Err(e) => {
                found.problems.push(e.to_string().trim_end_matches("; nothing was written").to_string());
                continue;
            }
        };
        let ours = shared(header);
        if let Some(k) = (0..found.keys.len()).find(|&k| ours[k] != theirs[k]) {
            let differs = format!(
                "{} is {} there and {} here",
                found.keys[k],
                theirs[k].as_deref().unwrap_or("absent"),
                ours[k].as_deref().unwrap_or("absent")
            );
            found.stale.push((path, differs));
            continue;
        }
        let refused = if let Some(missing) = header.attribute("glint:incomplete") {
            // `glint render --tile` writes no incomplete tile; one marked so was made otherwise.
            Some(format!(
                "{}: carries glint:incomplete (\"{missing}\"), which glint writes on a render that lost work, and \
                 the merge would hide it",
                path.display()
            ))
        } else if let Some(why) = &header.inexact {
            Some(format!(
                "{}: {why}, so its pixels need not be the values rendered, and the merge would not be the \
                 render bit for bit; merge the EXR tiles glint wrote",
                path.display()
            ))
        } else if let Some(sides) = beyond_a_render(header) {
            // Named as it would be were it the reference (a forged header first had hidden the rest).
            Some(format!("{}: {sides}", path.display()))
        } else if n != count || header.display != (width, height) {
            Some(format!(
                "{} is tile {index} of {n} of a {}x{} image, {} of {count} of {width}x{height}",
                path.display(),
                header.display.0,
                header.display.1,
                first.display()
            ))
        } else {
            match found.grid.rect(index) {
                Err(e) => Some(format!("{}: {e}", path.display())),
                Ok(rect) => {
                    let window = (header.origin, (header.width, header.height));
                    (window != ((rect.x0, rect.y0), (rect.width, rect.height))).then(|| {
                        format!(
                            "{}: its data window {}x{} at ({}, {}) is not tile {index}'s block of the {} grid ({rect})",
                            path.display(),
                            header.width,
                            header.height,
                            header.origin.0,
                            header.origin.1,
                            found.grid.describe()
                        )
                    })
                }
            }
        };
        if let Some(refused) = refused {
            found.problems.push(refused);
            found.refused = true;
            continue;
        }
        match found.by_index.get(&index) {
            // A file named for another tile may hold this one (tile-3.exr holding tile 2): the
            // tile it was named for is then among the missing, named with it.
            Some((other, _)) => found.problems.push(format!(
                "tile {index} is given twice, {} and {}: tiles must not overlap; leave one out",
                other.display(),
                path.display()
            )),
            None => {
                found.by_index.insert(index, (path, header));
            }
        }
    }
    Ok(found)
}

pub fn run(args: &MergeArgs) -> anyhow::Result<()> {
    let ext = args.output.extension().map(|e| e.to_string_lossy().to_ascii_lowercase());
    let png = match ext.as_deref() {
        Some("png") => true,
        Some("exr") => false,
        _ => usage!("{}: the merged image is written as .exr or .png", args.output.display()),
    };
    // A tile is a file `glint render --tile` wrote: a named pipe the glob caught waited for a
    // writer that never came, and a device or a folder is no tile either.
    for path in &args.tiles {
        let kind = std::fs::metadata(path).ok().map(|m| m.file_type()).filter(|t| !t.is_file());
        if let Some(t) = kind {
            bail!(
                "{}: is {}, not a tile file (the .exr a `glint render --tile` wrote); leave it out of the tiles \
                 given; nothing was written",
                path.display(),
                file_kind(t)
            );
        }
    }
    // Headers first: every check of the headers before any pixel is read or anything is written.
    // A file whose header cannot be read is one more problem, named beside every other (an
    // empty tile-2.exr had hidden a missing tile 5).
    let mut unreadable: Vec<(&Path, ExrReadError)> = Vec::new();
    let mut tiles: Vec<(&Path, ExrHeader)> = Vec::new();
    // A tile that blocks its reader (a file on a hung network mount) ends the merge at the
    // first signal: it waited for a second, and `timeout` sends one.
    super::interrupt::while_loading(|| {
        for path in &args.tiles {
            match read_exr_header(path) {
                Ok(header) => tiles.push((path, header)),
                Err(e) => unreadable.push((path, e)),
            }
        }
    });
    // A file that cannot be read, named as the tile its name says it holds (`index_by_name`) where
    // that is one of the grid's (`count`, once known): its index is then to render again.
    let unreadable_said = |count: Option<u32>| -> Vec<(String, Option<u32>)> {
        let named = |path: &Path| index_by_name(path).filter(|&i| count.is_none_or(|n| i < n));
        unreadable.iter().map(|(path, e)| (unreadable_file(path, e, named(path)), named(path))).collect()
    };
    if tiles.is_empty() {
        bail!(
            "{}; no tile could be read, so neither the render nor its grid is known; nothing was written",
            unreadable_said(None).into_iter().map(|(said, _)| said).collect::<Vec<_>>().join("; ")
        );
    }
    // Tiles are held against the render most of them are of (the first tile's on a tie), so that
    // a stale tile left from another render is the one named, wherever the glob puts it. A
    // render is its attributes (`shared_keys`, which a GPU tile has more of).
    let render_of =
        |h: &ExrHeader| shared_keys(h).into_iter().map(|k| (k, h.attribute(k).map(str::to_string))).collect::<Vec<_>>();
    // Per render, in the order of its first tile: its tiles, in the order given.
    let mut renders: Vec<(Vec<_>, Vec<usize>)> = Vec::new();
    for (i, (_, h)) in tiles.iter().enumerate() {
        let render = render_of(h);
        match renders.iter_mut().find(|(r, _)| *r == render) {
            Some((_, members)) => members.push(i),
            None => renders.push((render, vec![i])),
        }
    }
    // A render's reference is its first tile whose own header can be one (a tile of `glint
    // render --tile`, of an image and grid a render makes): a first tile with a problem of its
    // own is named with the others' against the next one, not alone (a forged header's image
    // size had hidden a missing tile). A render none of whose tiles can be one is no render to
    // keep; its tiles are named against the reference of another.
    let serving: Vec<(usize, usize)> = renders
        .iter()
        .filter_map(|(_, members)| {
            let reference = members.iter().copied().find(|&i| assess(&tiles, i).is_ok())?;
            Some((reference, members.len()))
        })
        .collect();
    let Some(agreeing) = serving.iter().map(|&(_, n)| n).max() else {
        // No header can be one: each is named, with the files that cannot be read.
        let each = (0..tiles.len()).filter_map(|i| assess(&tiles, i).err());
        let each = each.map(|e| e.to_string().trim_end_matches("; nothing was written").to_string());
        bail!(
            "{}; no tile given is one whose render and grid the others could be checked against; nothing was \
             written",
            unreadable_said(None).into_iter().map(|(said, _)| said).chain(each).collect::<Vec<_>>().join("; ")
        );
    };
    // With as many tiles of two renders (4 at spp 16, 4 at spp 8) either may be the stale one.
    let tied: Vec<usize> = serving.iter().filter(|&&(_, n)| n == agreeing).map(|&(r, _)| r).collect();
    let reference = tied[0];
    let found = assess(&tiles, reference)?;
    let (first, count, width, height) = (found.first, found.count, found.width, found.height);
    let unreadable = unreadable_said(Some(count));
    let mut said: Vec<String> = unreadable.iter().map(|(said, _)| said.clone()).collect();
    said.extend(found.problems.iter().cloned());
    if !found.stale.is_empty() {
        let others = match (agreeing, tied.len()) {
            (_, 2) => " (as many tiles are of either render: either may be the stale one)".to_string(),
            (_, 3..) => " (as many tiles are of each of these renders: any may be the stale one)".to_string(),
            (1, _) => String::new(),
            (n, _) => format!(" and {} more of the {} tiles", n - 1, args.tiles.len()),
        };
        said.push(match found.stale.as_slice() {
            [(path, differs)] => {
                format!("{} is not a tile of the same render as {}{others}: {differs}", path.display(), first.display())
            }
            many => format!(
                "{} of the {} tiles are not of the same render as {}{others}: {}",
                many.len(),
                args.tiles.len(),
                first.display(),
                many.iter().map(|(p, d)| format!("{} ({d})", p.display())).collect::<Vec<_>>().join(", ")
            ),
        });
    }
    let (by_index, grid, keys) = (&found.by_index, found.grid, &found.keys);
    // Where the headers hold no problem, the output is checked before a pixel is read.
    let mut image = if said.is_empty() {
        let sources: Vec<&Path> = args.tiles.iter().map(PathBuf::as_path).collect();
        // Before `check_outputs`, whose message calls its input a scene.
        if sources.iter().any(|s| is_same_file(s, &args.output)) {
            bail!("{}: the output would replace one of the tiles", args.output.display());
        }
        check_outputs(&[args.output.as_path()], sources[0], args.force)?;
        Some(vec![[0f32; 3]; width as usize * height as usize])
    } else {
        None
    };
    // The pixels, one tile at a time: into the image where the headers hold no problem, and
    // read all the same where they do (but for a tie, where which render is to be kept is not
    // known), so that a tile whose header reads but whose pixels do not (a copy cut short) is
    // named with the rest and rendered again with the missing tiles, not in a second round.
    let (failed, again) = if tied.len() > 1 {
        (Vec::new(), Vec::new())
    } else {
        read_pixels(by_index, &grid, width, image.as_deref_mut())?
    };
    let (pixels_failed, again_of_pixels) = (!failed.is_empty(), !again.is_empty());
    said.extend(failed);
    // The tiles to render again: the missing ones (among them those of unreadable files named
    // for them) and those whose pixels failed.
    let kept = by_index.keys().copied().filter(|i| again.binary_search(i).is_err());
    let named_again = unreadable.iter().filter_map(|&(_, i)| i).any(|i| !by_index.contains_key(&i));
    // Which tile an unreadable file of no tile's name was meant to hold is not known.
    let among = match unreadable.iter().filter(|(_, i)| i.is_none()).count() {
        0 => "",
        1 => " (the unreadable file may have been meant as one of them)",
        _ => " (the unreadable files may have been meant as some of them)",
    };
    let missing = super::job_array::missing_runs(kept, count);
    let render_again =
        |m: &super::job_array::Missing| format!("{} (with --tile I/{count}; {})", m.listing(), m.slurm_array());
    if tied.len() > 1 {
        // What each render would need, were its tiles the ones to keep.
        let choices: Vec<String> = tied
            .iter()
            .filter_map(|&r| {
                let found = assess(&tiles, r).ok()?;
                let m = super::job_array::missing_runs(found.by_index.keys().copied(), found.count);
                Some(format!("to keep the render of {}, render again {}", found.first.display(), render_again(&m)))
            })
            .collect();
        said.push(choices.join("; or, "));
    } else if missing.count == 0 {
        // Good tiles may cover every index (a tile left from an earlier render of more tiles,
        // or an empty file beside them).
        let extra = found.stale.len() + unreadable.len();
        if extra > 0 && found.problems.is_empty() && !pixels_failed {
            let them = if extra == 1 { "it" } else { "them" };
            said.push(format!("every tile of the render is there: leave {them} out of the tiles given"));
        }
    } else if !found.stale.is_empty() || found.refused || again_of_pixels || named_again {
        said.push(format!("{} of {count} tiles to render again{among}: {}", missing.count, render_again(&missing)));
    } else {
        said.push(format!(
            "{} of {count} {} missing{among}: {} (render {} with --tile I/{count}; {})",
            missing.count,
            if missing.count == 1 { "tiles is" } else { "tiles are" },
            missing.listing(),
            if missing.count == 1 { "it" } else { "them" },
            missing.slurm_array()
        ));
    }
    let Some(image) = image.filter(|_| said.is_empty()) else {
        bail!("{}; nothing was written", said.join("; "));
    };
    // The scene's name, where it came from and the flags that shaped it as the first tile gives
    // them (tiles of copies of one scene file merge): with the shared keys, what renders the
    // image again.
    let mut metadata: Vec<(String, String)> = ["glint:scene", "glint:source", "glint:load_flags"]
        .iter()
        .chain(keys)
        .filter_map(|k| Some((k.to_string(), tiles[reference].1.attribute(k)?.to_string())))
        .collect();
    metadata.push(("glint:merged_tiles".into(), count.to_string()));
    if png {
        let rgb: Vec<u8> = image.iter().flat_map(|p| p.map(linear_f32_to_srgb8)).collect();
        write_png_rgb8(&args.output, width, height, &rgb, &metadata)?;
    } else {
        let pixel = |x: usize, y: usize| image[y * width as usize + x];
        write_exr_region(&args.output, (width, height), (0, 0), (width, height), pixel, &metadata)?;
    }
    let tiles = if count == 1 { "1 tile".to_string() } else { format!("{count} tiles") };
    say!("merged {tiles} ({} grid) into {width}x{height}: wrote {}", grid.describe(), args.output.display())?;
    Ok(())
}

/// Reads the pixels of the tiles `by_index` holds, one at a time, each checked against its
/// header and digest, and copies each tile that passes into `image` (of `width` pixels a row)
/// where one is given. What fails is named, every tile of it; the indices of the tiles to
/// render again (unreadable, damaged, a pixel no render writes) are returned with it, ascending.
fn read_pixels(
    by_index: &BTreeMap<u32, (&Path, &ExrHeader)>,
    grid: &TileGrid,
    width: u32,
    mut image: Option<&mut [[f32; 3]]>,
) -> anyhow::Result<(Vec<String>, Vec<u32>)> {
    let mut failed: Vec<String> = Vec::new();
    let mut again: Vec<u32> = Vec::new();
    for (&index, &(path, checked)) in by_index {
        let tile = match super::interrupt::while_loading(|| read_exr(path)) {
            Ok(tile) => tile,
            Err(e) => {
                failed.push(format!(
                    "{} (tile {index}) {}",
                    path.display(),
                    unreadable_why(path, &e, IndexFrom::Header)
                ));
                again.push(index);
                continue;
            }
        };
        if let Err(why) = same_as_checked(path, checked, &tile) {
            failed.push(why);
            continue;
        }
        let bad = match tile.digest_holds() {
            Some(true) => None,
            Some(false) => Some(format!(
                "{}: its pixels are not the ones it was written with (their SHA-256 is not its {PIXELS_SHA256}): \
                 the file was damaged or changed since",
                path.display()
            )),
            None => Some(format!(
                "{}: has no {PIXELS_SHA256} (every tile `glint render --tile` writes has one), so a damaged pixel \
                 could not be told from a rendered one",
                path.display()
            )),
        };
        let rect = grid.rect(index)?;
        // A render writes no such pixel (it refuses an image with one): the tile was made or
        // changed otherwise, and a merge must not pass it on.
        let bad = bad.or_else(|| {
            let at = tile.rgb.iter().position(|p| !p.iter().all(|c| c.is_finite() && *c >= 0.0))?;
            let (x, y) = (rect.x0 as usize + at % rect.width as usize, rect.y0 as usize + at / rect.width as usize);
            Some(format!(
                "{}: pixel ({x}, {y}) is {:?}, which no render writes (radiance is finite and ≥ 0)",
                path.display(),
                tile.rgb[at]
            ))
        });
        if let Some(bad) = bad {
            failed.push(bad);
            again.push(index);
            continue;
        }
        if let Some(image) = image.as_deref_mut() {
            for row in 0..rect.height as usize {
                let src = &tile.rgb[row * rect.width as usize..(row + 1) * rect.width as usize];
                let start = (rect.y0 as usize + row) * width as usize + rect.x0 as usize;
                image[start..start + rect.width as usize].copy_from_slice(src);
            }
        }
        super::interrupt::check()?;
    }
    Ok((failed, again))
}

/// The pixels are read after every header was checked, so a tile replaced in between (a
/// requeued task renaming its fresh tile over the old one) would bring another render's pixels,
/// or another block's, unchecked: the header read with the pixels must be the one checked, and
/// the pixels must fill its data window.
fn same_as_checked(path: &Path, checked: &ExrHeader, tile: &ExrPixels) -> Result<(), String> {
    // A checked header has no `inexact` (refused before), and a re-read one none either unless
    // its compression changed.
    if tile.header != *checked || tile.rgb.len() != checked.width as usize * checked.height as usize {
        return Err(format!(
            "{}: the file changed while the merge read it (its header or size is not the one checked); \
             merge again once no task writes it",
            path.display()
        ));
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn an_unreadable_file_is_matched_to_its_tile_by_the_names_render_tile_gives() {
        let named = [
            ("tile-3.exr", Some(3)),
            ("tiles/tile-12.EXR", Some(12)),
            ("whitted-tile-0.exr", Some(0)),
            ("/farm/my scene-tile-4095.exr", Some(4095)),
            ("tile-007.exr", Some(7)),
            ("t3.exr", None),
            ("tile-.exr", None),
            ("tile-3.png", None),
            ("tile-3", None),
            ("mytile-3.exr", None),
            ("tile-3a.exr", None),
            ("tile--3.exr", None),
            ("tile-+3.exr", None),
            ("tile-4294967296.exr", None),
            (".glint-0123456789.tmp", None),
            ("tile-3.exr.tmp", None),
            ("日本-tile-2.exr", Some(2)),
            ("é.exr", None),
            ("exr", None),
        ];
        for (name, index) in named {
            assert_eq!(index_by_name(Path::new(name)), index, "{name}");
        }
    }

    #[test]
    fn a_tile_that_changed_after_its_check_is_refused() {
        let checked = ExrHeader {
            display: (8, 4),
            origin: (4, 0),
            width: 4,
            height: 4,
            attributes: vec![("glint:seed".into(), "0".into()), ("glint:tile".into(), "1/2".into())],
            inexact: None,
        };
        let tile = ExrPixels { header: checked.clone(), rgb: vec![[0.5; 3]; 16] };
        let path = Path::new("tile-1.exr");
        assert!(same_as_checked(path, &checked, &tile).is_ok());
        let mut seed = tile.clone();
        seed.header.attributes[0].1 = "1".into();
        let mut block = tile.clone();
        block.header.origin = (0, 0);
        let mut short = tile.clone();
        short.rgb.pop();
        for changed in [seed, block, short] {
            let e = same_as_checked(path, &checked, &changed).expect_err("a changed tile").to_string();
            assert!(e.contains("tile-1.exr") && e.contains("changed while the merge read it"), "{e}");
        }
    }
}
