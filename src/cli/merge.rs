//! `glint merge TILE.exr… -o OUT.exr|OUT.png`: the tiles of `glint render --tile` joined into
//! the whole image. Every tile's header is read first (no pixels): they must be one render's
//! (the same scene hash, settings, backend, version and grid), each tile's data window must be
//! its grid block, none may come twice, and every missing one is named; only then are the
//! pixels read, one tile at a time, into one f32 image, and the output written atomically.
//! Nothing is written on any error. At most the output image and one tile are in memory.

use crate::cli::usage::usage;
use std::collections::{BTreeMap, HashMap};
use std::path::{Path, PathBuf};

use anyhow::{Context, bail};
use clap::Args;
use glint_core::TileGrid;
use glint_core::image::linear_f32_to_srgb8;
use glint_io::exr_file::{ExrHeader, ExrPixels, PIXELS_SHA256, read_exr, read_exr_header, write_exr_region};
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
    // Headers first: every check before any pixel is read or anything is written.
    let headers: Vec<ExrHeader> =
        // A tile that blocks its reader (a file on a hung network mount) ends the merge at the
        // first signal: it waited for a second, and `timeout` sends one.
        super::interrupt::while_loading(|| {
            args.tiles.iter().map(|p| read_exr_header(p).map_err(anyhow::Error::from)).collect::<anyhow::Result<_>>()
        })?;
    // Tiles are held against the render most of them are of (the first tile's on a tie), so that
    // a stale tile left from another render is the one named, wherever the glob puts it. A
    // render is its attributes (`shared_keys`, which a GPU tile has more of).
    let render_of =
        |h: &ExrHeader| shared_keys(h).into_iter().map(|k| (k, h.attribute(k).map(str::to_string))).collect::<Vec<_>>();
    // Per render: how many tiles are of it, and the first.
    let mut renders: HashMap<_, (usize, usize)> = HashMap::new();
    for (i, h) in headers.iter().enumerate() {
        renders.entry(render_of(h)).or_insert((0, i)).0 += 1;
    }
    let (agreeing, reference) =
        renders.values().copied().max_by_key(|&(n, first)| (n, std::cmp::Reverse(first))).unwrap_or((1, 0));
    let first = (&args.tiles[reference], &headers[reference]);
    let keys = shared_keys(first.1);
    let shared = |h: &ExrHeader| keys.iter().map(|k| h.attribute(k).map(str::to_string)).collect::<Vec<_>>();
    let theirs = shared(first.1);
    let (_, count) = tile_index(first.0, first.1)?;
    let (width, height) = first.1.display;
    // A forged or damaged header must not size the merged image beyond what a render makes.
    if !(1..=MAX_IMAGE_SIDE).contains(&width) || !(1..=MAX_IMAGE_SIDE).contains(&height) {
        bail!(
            "{}: its image (display window) is {width}x{height}; a render's sides are in [1, {MAX_IMAGE_SIDE}]; \
             nothing was written",
            first.0.display()
        );
    }
    let grid = TileGrid::new(count, width, height).with_context(|| format!("{}", first.0.display()))?;
    let mut by_index: BTreeMap<u32, (&Path, &ExrHeader)> = BTreeMap::new();
    // Every tile of another render, named together with the indices to render again (a tester
    // fixed two stale tiles and a missing one in three rounds, one message each).
    let mut stale: Vec<(&Path, String)> = Vec::new();
    for (path, header) in args.tiles.iter().zip(&headers) {
        let (index, n) = tile_index(path, header)?;
        let ours = shared(header);
        if let Some(k) = (0..keys.len()).find(|&k| ours[k] != theirs[k]) {
            let differs = format!(
                "{} is {} there and {} here",
                keys[k],
                theirs[k].as_deref().unwrap_or("absent"),
                ours[k].as_deref().unwrap_or("absent")
            );
            stale.push((path, differs));
            continue;
        }
        // `glint render --tile` writes no incomplete tile; one marked so was made otherwise.
        if let Some(missing) = header.attribute("glint:incomplete") {
            bail!(
                "{}: carries glint:incomplete (\"{missing}\"), which glint writes on a render that lost work, and \
                 the merge would hide it; render the tile again; nothing was written",
                path.display()
            );
        }
        if let Some(why) = &header.inexact {
            bail!(
                "{}: {why}, so its pixels need not be the values rendered, and the merge would not be the \
                 render bit for bit; merge the EXR tiles glint wrote; nothing was written",
                path.display()
            );
        }
        if n != count || header.display != (width, height) {
            bail!(
                "{} is tile {index} of {n} of a {}x{} image, {} of {count} of {width}x{height}; nothing was written",
                path.display(),
                header.display.0,
                header.display.1,
                first.0.display()
            );
        }
        let rect = grid.rect(index).with_context(|| path.display().to_string())?;
        if header.origin != (rect.x0, rect.y0) || (header.width, header.height) != (rect.width, rect.height) {
            bail!(
                "{}: its data window {}x{} at ({}, {}) is not tile {index}'s block of the {} grid ({rect}); \
                 nothing was written",
                path.display(),
                header.width,
                header.height,
                header.origin.0,
                header.origin.1,
                grid.describe()
            );
        }
        if let Some((other, _)) = by_index.insert(index, (path, header)) {
            bail!(
                "tile {index} is given twice, {} and {}: tiles must not overlap; nothing was written",
                other.display(),
                path.display()
            );
        }
    }
    let (missing, runs) = super::job_array::missing_runs(by_index.keys().copied(), count);
    if !stale.is_empty() {
        let others = match agreeing {
            1 => String::new(),
            n => format!(" and {} more of the {} tiles", n - 1, headers.len()),
        };
        let which = match stale.as_slice() {
            [(path, differs)] => format!(
                "{} is not a tile of the same render as {}{others}: {differs}",
                path.display(),
                first.0.display()
            ),
            many => format!(
                "{} of the {} tiles are not of the same render as {}{others}: {}",
                many.len(),
                headers.len(),
                first.0.display(),
                many.iter().map(|(p, d)| format!("{} ({d})", p.display())).collect::<Vec<_>>().join(", ")
            ),
        };
        // Good tiles may cover every index (a tile left from an earlier render of more tiles).
        let again = if missing == 0 {
            format!(
                "every tile of the render is there: leave {} out of the tiles given",
                if stale.len() == 1 { "it" } else { "them" }
            )
        } else {
            format!(
                "{missing} of {count} tiles to render again: {} (with --tile I/{count}; as a Slurm array, --array={})",
                runs.join(", "),
                runs.join(",")
            )
        };
        bail!("{which}; {again}; nothing was written");
    }
    if missing > 0 {
        bail!(
            "{missing} of {count} {} missing: {} (render {} with --tile I/{count}; as a Slurm array, \
             --array={}); nothing was written",
            if missing == 1 { "tiles is" } else { "tiles are" },
            runs.join(", "),
            if missing == 1 { "it" } else { "them" },
            runs.join(",")
        );
    }
    let sources: Vec<&Path> = args.tiles.iter().map(PathBuf::as_path).collect();
    // Before `check_outputs`, whose message calls its input a scene.
    if sources.iter().any(|s| is_same_file(s, &args.output)) {
        bail!("{}: the output would replace one of the tiles", args.output.display());
    }
    check_outputs(&[args.output.as_path()], sources[0], args.force)?;

    let mut image = vec![[0f32; 3]; width as usize * height as usize];
    for (&index, &(path, checked)) in &by_index {
        let tile = super::interrupt::while_loading(|| read_exr(path))?;
        same_as_checked(path, checked, &tile)?;
        match tile.digest_holds() {
            Some(true) => {}
            Some(false) => bail!(
                "{}: its pixels are not the ones it was written with (their SHA-256 is not its {PIXELS_SHA256}): \
                 the file was damaged or changed since; render the tile again; nothing was written",
                path.display()
            ),
            None => bail!(
                "{}: has no {PIXELS_SHA256} (every tile `glint render --tile` writes has one), so a damaged pixel \
                 could not be told from a rendered one; render the tile again; nothing was written",
                path.display()
            ),
        }
        let rect = grid.rect(index)?;
        // A render writes no such pixel (it refuses an image with one): the tile was made or
        // changed otherwise, and a merge must not pass it on.
        if let Some(at) = tile.rgb.iter().position(|p| !p.iter().all(|c| c.is_finite() && *c >= 0.0)) {
            let (x, y) = (rect.x0 as usize + at % rect.width as usize, rect.y0 as usize + at / rect.width as usize);
            bail!(
                "{}: pixel ({x}, {y}) is {:?}, which no render writes (radiance is finite and ≥ 0); \
                 render the tile again; nothing was written",
                path.display(),
                tile.rgb[at]
            );
        }
        for row in 0..rect.height as usize {
            let src = &tile.rgb[row * rect.width as usize..(row + 1) * rect.width as usize];
            let start = (rect.y0 as usize + row) * width as usize + rect.x0 as usize;
            image[start..start + rect.width as usize].copy_from_slice(src);
        }
        super::interrupt::check()?;
    }
    // The scene's name, where it came from and the flags that shaped it as the first tile gives
    // them (tiles of copies of one scene file merge): with the shared keys, what renders the
    // image again.
    let mut metadata: Vec<(String, String)> = ["glint:scene", "glint:source", "glint:load_flags"]
        .iter()
        .chain(&keys)
        .filter_map(|k| Some((k.to_string(), first.1.attribute(k)?.to_string())))
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

/// The pixels are read after every header was checked, so a tile replaced in between (a
/// requeued task renaming its fresh tile over the old one) would bring another render's pixels,
/// or another block's, unchecked: the header read with the pixels must be the one checked, and
/// the pixels must fill its data window.
fn same_as_checked(path: &Path, checked: &ExrHeader, tile: &ExrPixels) -> anyhow::Result<()> {
    // A checked header has no `inexact` (refused before), and a re-read one none either unless
    // its compression changed.
    if tile.header != *checked || tile.rgb.len() != checked.width as usize * checked.height as usize {
        bail!(
            "{}: the file changed while the merge read it (its header or size is not the one checked); \
             merge again once no task writes it; nothing was written",
            path.display()
        );
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

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
