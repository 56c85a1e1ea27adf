//! `glint render --tile` and `glint merge`: a render split into tiles and merged again is the
//! single render, bit for bit, on the CPU (Whitted's tree and the path tracer alike) and on the
//! GPU; and every way tiles can fail to belong together is an error that names the tile and
//! writes nothing.

use std::ffi::OsString;
use std::path::{Path, PathBuf};

use glint_io::exr_file::read_exr;

use super::{TempDir, glint, meta, png_text_chunks, text};

/// `glint render SCENE ARGS… -o OUT`, asserting success.
fn render(dir: &Path, scene: &str, args: &[&str], out: &Path) {
    let head = ["render", scene];
    let all = head.iter().chain(args).map(OsString::from).chain(["-q".into(), "-o".into(), out.into()]);
    let done = glint(dir, all);
    assert!(done.status.success(), "render {scene} {args:?}: {}", text(&done.stderr));
}

/// `glint merge TILES… -o OUT`.
fn merge(dir: &Path, tiles: &[PathBuf], out: &Path) -> std::process::Output {
    let args = ["merge".into()].into_iter().chain(tiles.iter().map(OsString::from)).chain(["-o".into(), out.into()]);
    glint(dir, args.collect::<Vec<OsString>>())
}

fn bits(path: &Path) -> Vec<u32> {
    let exr = read_exr(path).unwrap_or_else(|e| panic!("{e}"));
    exr.rgb.iter().flatten().map(|v| v.to_bits()).collect()
}

/// A copy of `tile` re-encoded as a storage pass might do it, its data window and attributes
/// kept (but any named in `dropped`): each sample converted by `sample`, compressed by
/// `compression`.
fn reencoded<T: exr::prelude::IntoSample>(
    tile: &Path,
    out: &Path,
    sample: impl Fn(f32) -> T + Sync,
    compression: exr::prelude::Compression,
    dropped: &[&str],
) {
    use exr::prelude::*;
    let read = read_exr(tile).unwrap_or_else(|e| panic!("{e}"));
    let h = &read.header;
    let width = h.width as usize;
    let attributes =
        LayerAttributes { layer_position: Vec2(h.origin.0 as i32, h.origin.1 as i32), ..LayerAttributes::default() };
    let channels = SpecificChannels::rgb(|p: Vec2<usize>| {
        let [r, g, b] = read.rgb[p.y() * width + p.x()];
        (sample(r), sample(g), sample(b))
    });
    let encoding = Encoding { compression, ..Encoding::SMALL_LOSSLESS };
    let mut image = Image::from_layer(Layer::new((width, h.height as usize), attributes, encoding, channels));
    image.attributes.display_window = IntegerBounds::new((0, 0), (h.display.0 as usize, h.display.1 as usize));
    for (key, value) in h.attributes.iter().filter(|(k, _)| !dropped.contains(&k.as_str())) {
        image.attributes.other.insert(Text::from(key.as_str()), AttributeValue::Text(Text::from(value.as_str())));
    }
    image.write().to_file(out).unwrap_or_else(|e| panic!("{}: {e}", out.display()));
}

fn png_pixels(path: &Path) -> Vec<u8> {
    image::open(path).unwrap_or_else(|e| panic!("{}: {e}", path.display())).into_rgb8().into_raw()
}

/// Renders `scene` whole and in `count` tiles on `backend`, merges the tiles into an EXR and a
/// PNG, and asserts both hold the single render's pixels exactly.
fn split_and_merge(dir: &Path, scene: &str, settings: &[&str], backend: &str, count: u32) {
    let label = format!("{scene}-{backend}-{count}");
    let mut args = settings.to_vec();
    args.extend(["--backend", backend]);
    let (whole_exr, whole_png) = (dir.join(format!("{label}.exr")), dir.join(format!("{label}.png")));
    render(dir, scene, &args, &whole_exr);
    render(dir, scene, &args, &whole_png);
    let tiles: Vec<PathBuf> = (0..count)
        .map(|i| {
            let tile = dir.join(format!("{label}-tile-{i}.exr"));
            let spec = format!("{i}/{count}");
            let mut tile_args = args.clone();
            tile_args.extend(["--tile", &spec]);
            render(dir, scene, &tile_args, &tile);
            tile
        })
        .collect();
    let (merged_exr, merged_png) = (dir.join(format!("{label}-merged.exr")), dir.join(format!("{label}-merged.png")));
    for out in [&merged_exr, &merged_png] {
        let done = merge(dir, &tiles, out);
        assert!(done.status.success(), "{label}: {}", text(&done.stderr));
    }
    assert_eq!(bits(&merged_exr), bits(&whole_exr), "{label}: the merged EXR differs from the single render");
    assert_eq!(png_pixels(&merged_png), png_pixels(&whole_png), "{label}: the merged PNG differs");
    // The files differ in their time and rays; their pixel digests are what a user compares
    // (the PNG had none: a merge could not be checked against a single render's PNG).
    let (whole_text, merged_text) = (png_text_chunks(&whole_png), png_text_chunks(&merged_png));
    let digest = meta(&merged_text, "glint:pixels_sha256");
    assert_eq!(digest, meta(&whole_text, "glint:pixels_sha256"), "{label}: PNG digests");
    assert_eq!(digest, glint_io::image_file::rgb8_digest(&png_pixels(&merged_png)), "{label}: the PNG digest");
    let exr_digest = |p: &Path| read_exr(p).expect("EXR").header.attribute("glint:pixels_sha256").map(str::to_string);
    assert_eq!(exr_digest(&merged_exr), exr_digest(&whole_exr), "{label}: EXR digests");
    // The same tiles merged again give the same file, byte for byte (its header attributes
    // were in a new hash order each time).
    let again = dir.join(format!("{label}-merged-again.exr"));
    assert!(merge(dir, &tiles, &again).status.success());
    let bytes = |p: &Path| std::fs::read(p).expect("merged file");
    assert!(bytes(&again) == bytes(&merged_exr), "{label}: one merge gave two different files");
    let header = read_exr(&merged_exr).expect("merged").header;
    assert_eq!(header.attribute("glint:merged_tiles"), Some(count.to_string().as_str()));
    assert_eq!(header.attribute("glint:scene"), Some(scene));
    // And what renders it again: where the scene came from, and its content.
    let tile = read_exr(&tiles[0]).expect("tile").header;
    assert_eq!(header.attribute("glint:source"), Some(format!("builtin:{scene}").as_str()));
    assert_eq!(header.attribute("glint:scene_hash"), tile.attribute("glint:scene_hash"));
}

#[test]
fn tiles_merged_are_the_single_render_bit_for_bit_on_the_cpu() {
    let dir = TempDir::new("tiles-cpu");
    let size = ["--width", "50", "--height", "38"];
    // Whitted's tree in a 2×2 grid, the path tracer (4 paths a pixel) in 5 bands.
    split_and_merge(&dir, "whitted", &[&size[..], &["--spp", "2"]].concat(), "cpu", 4);
    split_and_merge(&dir, "cornell-gi", &[&size[..], &["--spp", "4", "--depth", "6"]].concat(), "cpu", 5);
    // The CPU's images are the same bits with the whole tracer: tiles rendered with and
    // without --no-specialise merge into the single render.
    let args = [&size[..], &["--spp", "2", "--backend", "cpu"]].concat();
    let whole = dir.join("mixed.exr");
    render(&dir, "whitted", &args, &whole);
    let tiles: Vec<PathBuf> = (0..3)
        .map(|i| {
            let tile = dir.join(format!("mixed-tile-{i}.exr"));
            let spec = format!("{i}/3");
            let mut tile_args = [&args[..], &["--tile", &spec]].concat();
            if i % 2 == 1 {
                tile_args.push("--no-specialise");
            }
            render(&dir, "whitted", &tile_args, &tile);
            tile
        })
        .collect();
    let merged = dir.join("mixed-merged.exr");
    let done = merge(&dir, &tiles, &merged);
    assert!(done.status.success(), "{}", text(&done.stderr));
    assert_eq!(bits(&merged), bits(&whole), "tiles with and without specialisation merged apart from the render");
}

#[test]
fn tiles_merged_are_the_single_render_bit_for_bit_on_the_gpu() {
    if glint_test_support::skip_requested("GLINT_SKIP_GPU") {
        eprintln!("GLINT_SKIP_GPU=1: no GPU tiles");
        return;
    }
    let dir = TempDir::new("tiles-gpu");
    let size = ["--width", "40", "--height", "30"];
    split_and_merge(&dir, "whitted", &size, "gpu", 3);
    split_and_merge(&dir, "cornell-gi", &[&size[..], &["--spp", "4", "--depth", "6"]].concat(), "gpu", 4);
}

#[test]
fn tiles_that_do_not_belong_together_are_refused_by_name_and_nothing_is_written() {
    let dir = TempDir::new("tiles-refused");
    let size = ["--width", "24", "--height", "16"];
    let tile = |scene: &str, spec: &str, name: &str| {
        let path = dir.join(name);
        render(&dir, scene, &[&size[..], &["--tile", spec]].concat(), &path);
        path
    };
    let t: Vec<PathBuf> = (0..3).map(|i| tile("whitted", &format!("{i}/3"), &format!("t{i}.exr"))).collect();
    let out = dir.join("out.exr");
    let refused = |tiles: &[PathBuf], wanted: &str| {
        let done = merge(&dir, tiles, &out);
        assert!(!done.status.success(), "merged {tiles:?}");
        assert!(text(&done.stderr).contains(wanted), "{}", text(&done.stderr));
        assert!(!out.exists(), "a refused merge wrote {}", out.display());
    };
    refused(&[t[0].clone(), t[2].clone()], "1 of 3 tiles is missing: 1");
    refused(&[t[0].clone(), t[1].clone(), t[1].clone(), t[2].clone()], "tile 1 is given twice");
    let other_scene = tile("cornell", "1/3", "c1.exr");
    refused(&[t[0].clone(), other_scene, t[2].clone()], "c1.exr is not a tile of the same render as");
    let other_grid = tile("whitted", "1/4", "g1.exr");
    refused(&[t[0].clone(), other_grid, t[2].clone()], "glint:grid is 3x1 there and 2x2 here");
    let seeded = dir.join("s1.exr");
    render(&dir, "whitted", &[&size[..], &["--tile", "1/3", "--seed", "7"]].concat(), &seeded);
    refused(&[t[0].clone(), seeded, t[2].clone()], "glint:seed is 0 there and 7 here");
    // A stale tile left from another render is named wherever the glob puts it: first here, as
    // tile-0 is under `tile-*.exr` (it was the good tiles that were named).
    let stale = dir.join("s0.exr");
    render(&dir, "whitted", &[&size[..], &["--tile", "0/3", "--seed", "7"]].concat(), &stale);
    refused(&[stale.clone(), t[1].clone(), t[2].clone()], "s0.exr is not a tile of the same render as");
    refused(&[stale, t[1].clone(), t[2].clone()], "t1.exr and 1 more of the 3 tiles: glint:seed is 0 there and 7 here");
    // Every stale tile at once, with what to render again, missing ones included (of a 3x2
    // grid: three tiles of the render, two stale, tile 5 missing).
    let five: Vec<PathBuf> = (0..5)
        .map(|i| {
            let seed = if i == 1 || i == 3 { "9" } else { "0" };
            let path = dir.join(format!("f{i}.exr"));
            render(&dir, "whitted", &[&size[..], &["--tile", &format!("{i}/6"), "--seed", seed]].concat(), &path);
            path
        })
        .collect();
    refused(&five, "2 of the 5 tiles are not of the same render as ");
    refused(&five, "f0.exr and 2 more of the 5 tiles: ");
    refused(&five, "f3.exr (glint:seed is 0 there and 9 here); 3 of 6 tiles to render again: 1, 3, 5");
    refused(&five, "(with --tile I/6; as a Slurm array, --array=1-5:2); nothing was written");
    // A stale tile whose index a good tile has: nothing to render, the stale one to leave out.
    let stale_1 = dir.join("st1.exr");
    render(&dir, "whitted", &[&size[..], &["--tile", "1/3", "--seed", "9"]].concat(), &stale_1);
    refused(&[&t[..], &[stale_1]].concat(), "every tile of the render is there: leave it out of the tiles given");
    let whole = dir.join("whole.exr");
    render(&dir, "whitted", &size, &whole);
    refused(&[t[0].clone(), whole.clone(), t[2].clone()], "not a tile of `glint render --tile`");
    // A tile re-encoded with loss (half floats, PXR24's 24-bit floats) would merge into no
    // render's bits; a lossless re-encoding merges into the same bits.
    use exr::prelude::{Compression, f16};
    let (half, pxr24, piz) = (dir.join("half.exr"), dir.join("pxr24.exr"), dir.join("piz.exr"));
    reencoded(&t[1], &half, f16::from_f32, Compression::ZIP16, &[]);
    refused(&[t[0].clone(), half, t[2].clone()], "half.exr: its channel B holds F16 samples, not 32-bit floats");
    reencoded(&t[1], &pxr24, |v| v, Compression::PXR24, &[]);
    refused(&[t[0].clone(), pxr24, t[2].clone()], "its pxr24 compression is lossy for 32-bit floats");
    reencoded(&t[1], &piz, |v| v, Compression::PIZ, &[]);
    let (whole_merge, piz_merge) = (dir.join("merged.exr"), dir.join("merged-piz.exr"));
    for (tiles, output) in [(&t[..], &whole_merge), (&[t[0].clone(), piz, t[2].clone()][..], &piz_merge)] {
        let done = merge(&dir, tiles, output);
        assert!(done.status.success(), "{}", text(&done.stderr));
    }
    assert_eq!(bits(&piz_merge), bits(&whole_merge), "a PIZ copy of a tile merged into other bits");
    // Damaged pixel bytes in a chunk no checksum guards read as finite values, and were merged
    // (a tester's XOR of 20 bytes made 0.47 into 2.5e22): one low bit of every sample is told.
    let damaged = dir.join("damaged.exr");
    reencoded(&t[1], &damaged, |v| f32::from_bits(v.to_bits() ^ 1), Compression::Uncompressed, &[]);
    refused(
        &[t[0].clone(), damaged, t[2].clone()],
        "damaged.exr: its pixels are not the ones it was written with (their SHA-256 is not its glint:pixels_sha256)",
    );
    let unsigned = dir.join("unsigned.exr");
    reencoded(&t[1], &unsigned, |v| v, Compression::ZIP16, &[glint_io::exr_file::PIXELS_SHA256]);
    refused(&[t[0].clone(), unsigned, t[2].clone()], "unsigned.exr: has no glint:pixels_sha256");
    // A merge's output under the tiles' glob is named as such, not as a tile without glint:tile.
    refused(
        &[&t[..], std::slice::from_ref(&whole_merge)].concat(),
        "merged.exr: the output of an earlier `glint merge` (of 3 tiles)",
    );
    // `--tile` writes no incomplete tile; a tile marked so (made otherwise) is refused.
    let marked = dir.join("marked.exr");
    let incomplete = read_exr(&t[1]).expect("tile");
    let mut attributes = incomplete.header.attributes.clone();
    attributes.push(("glint:incomplete".into(), "the GPU's loop cut-off".into()));
    let (w, h) = (incomplete.header.width as usize, incomplete.header.height);
    glint_io::exr_file::write_exr_region(
        &marked,
        incomplete.header.display,
        incomplete.header.origin,
        (w as u32, h),
        |x, y| incomplete.rgb[y * w + x],
        &attributes,
    )
    .expect("marked tile");
    refused(
        &[t[0].clone(), marked, t[2].clone()],
        "carries glint:incomplete (\"the GPU's loop cut-off\"), which glint writes on a render that lost work",
    );
    // Pixels no render writes (NaN, infinite, negative), and a header claiming an image larger
    // than a render makes, are refused before anything is written (a NaN was merged; a claimed
    // 1e6 × 1e6 image aborted the allocation).
    let forged = |name: &str, display: (u32, u32), pixel: &(dyn Fn(usize, usize) -> [f32; 3] + Sync)| {
        let path = dir.join(name);
        glint_io::exr_file::write_exr_region(
            &path,
            display,
            incomplete.header.origin,
            (w as u32, h),
            pixel,
            &incomplete.header.attributes,
        )
        .expect("forged tile");
        path
    };
    let display = incomplete.header.display;
    for (name, value, says) in
        [("nan.exr", f32::NAN, "is [NaN"), ("inf.exr", f32::INFINITY, "is [inf"), ("neg.exr", -5.0, "is [-5.0")]
    {
        let bad = forged(name, display, &|x, y| if (x, y) == (1, 2) { [value; 3] } else { incomplete.rgb[y * w + x] });
        let origin = incomplete.header.origin;
        let at = format!("{name}: pixel ({}, {}) {says}", origin.0 + 1, origin.1 + 2);
        refused(&[t[0].clone(), bad, t[2].clone()], &at);
    }
    let huge = forged("huge.exr", (1_000_000, 1_000_000), &|x, y| incomplete.rgb[y * w + x]);
    // First, it is named with the rest (it was named alone, hiding what else was wrong).
    refused(&[huge.clone(), t[0].clone(), t[2].clone()], "huge.exr: its image (display window) is 1000000x1000000");
    refused(&[huge, t[0].clone(), t[2].clone()], "; 1 of 3 tiles to render again: 1 (with --tile I/3; ");
    let whole_first = merge(&dir, &[whole_merge.clone(), t[1].clone()], &out);
    let said = text(&whole_first.stderr);
    for wanted in ["merged.exr: the output of an earlier `glint merge`", "2 of 3 tiles are missing: 0, 2 ("] {
        assert!(said.contains(wanted), "wanted {wanted:?} in {said}");
    }
    // No file that the others could be held against: each is named.
    refused(
        &[whole_merge.clone(), whole.clone()],
        "merged.exr: the output of an earlier `glint merge` (of 3 tiles), not a tile; leave it out of the tiles given; ",
    );
    refused(
        &[whole_merge.clone(), whole.clone()],
        "whole.exr: not a tile of `glint render --tile` (it has no glint:tile attribute); no tile given is one whose \
         render and grid the others could be checked against; nothing was written",
    );
    // A named pipe or a folder the glob caught is named at once (the pipe waited for a writer).
    let pipe = dir.join("t9.exr");
    let made = std::process::Command::new("mkfifo").arg(&pipe).status().expect("mkfifo (coreutils)");
    assert!(made.success(), "mkfifo failed");
    refused(&[t[0].clone(), pipe, t[1].clone(), t[2].clone()], "t9.exr: is a named pipe, not a tile file");
    let folder = dir.join("t8.exr");
    std::fs::create_dir(&folder).expect("folder");
    refused(&[t[0].clone(), t[1].clone(), folder, t[2].clone()], "t8.exr: is a folder, not a tile file");
    // An output that is one of the tiles (the first included) is named as a tile.
    for i in [0, 2] {
        let done = merge(&dir, &t, &t[i]);
        assert!(!done.status.success(), "merged over tile {i}");
        assert!(text(&done.stderr).contains("would replace one of the tiles"), "{}", text(&done.stderr));
    }
}

#[test]
fn every_problem_of_the_tiles_is_named_at_once_unreadable_files_and_ties_included() {
    let dir = TempDir::new("tiles-problems");
    let size = ["--width", "24", "--height", "16"];
    let tile = |spec: &str, seed: &str, name: &str| {
        let path = dir.join(name);
        render(&dir, "whitted", &[&size[..], &["--tile", spec, "--seed", seed]].concat(), &path);
        path
    };
    let t: Vec<PathBuf> = (0..4).map(|i| tile(&format!("{i}/4"), "0", &format!("t{i}.exr"))).collect();
    let out = dir.join("out.exr");
    let refused = |tiles: &[PathBuf], wanted: &[String]| {
        let done = merge(&dir, tiles, &out);
        assert!(!done.status.success(), "merged {tiles:?}");
        let said = text(&done.stderr);
        for w in wanted {
            assert!(said.contains(w.as_str()), "wanted {w:?} in {said}");
        }
        assert!(said.trim_end().ends_with("; nothing was written"), "{said}");
        assert!(!out.exists(), "a refused merge wrote {}", out.display());
    };
    let at = |p: &Path| p.display().to_string();
    // An empty tile-2 named the EXR reader's "reference to missing bytes" alone, and hid a
    // missing tile 3.
    let empty = dir.join("e2.exr");
    std::fs::write(&empty, b"").expect("empty file");
    refused(
        &[t[0].clone(), t[1].clone(), empty.clone()],
        &[
            format!("{}: is empty (0 bytes), so which tile it was meant to hold cannot be known", at(&empty)),
            "2 of 4 tiles are missing (the unreadable file may have been meant as one of them): 2-3 (render them with --tile I/4; as a \
             Slurm array, --array=2-3)"
                .into(),
        ],
    );
    // A file named as `--tile` names its tiles is matched to its tile by its name: the tile is
    // to render again, in the --array with the missing ones (it was only said that the file
    // may have been meant as one of them).
    let empty_named = dir.join("tile-2.exr");
    std::fs::write(&empty_named, b"").expect("empty file");
    refused(
        &[t[0].clone(), t[1].clone(), empty_named.clone()],
        &[format!(
            "{} (tile 2 by its name) is empty (0 bytes); 2 of 4 tiles to render again: 2-3 (with --tile I/4; as a \
             Slurm array, --array=2-3); nothing was written",
            at(&empty_named)
        )],
    );
    let (head_cut, tail_cut, tail_cut2, not_exr) =
        (dir.join("h.exr"), dir.join("c2.exr"), dir.join("c3.exr"), dir.join("n.exr"));
    let bytes = std::fs::read(&t[2]).expect("tile");
    std::fs::write(&head_cut, &bytes[..40]).expect("cut tile");
    std::fs::write(&tail_cut, &bytes[..bytes.len() - 10]).expect("cut tile");
    let bytes3 = std::fs::read(&t[3]).expect("tile");
    std::fs::write(&tail_cut2, &bytes3[..bytes3.len() - 30]).expect("cut tile");
    std::fs::write(&not_exr, b"P3 1 1 255 0 0 0").expect("text file");
    refused(
        &[t[0].clone(), head_cut.clone(), t[2].clone(), not_exr.clone()],
        &[
            format!("{}: cannot be read: the file is cut short or damaged (", at(&head_cut)),
            format!("{}: is not an OpenEXR file (", at(&not_exr)),
            "2 of 4 tiles are missing (the unreadable files may have been meant as some of them): 1, 3".into(),
        ],
    );
    // The same cut header under render's default name for tile 1: tile 1 is to render again,
    // and the file of no tile's name may still have been meant as tile 3.
    let head_cut_named = dir.join("whitted-tile-1.exr");
    std::fs::copy(&head_cut, &head_cut_named).expect("copy");
    refused(
        &[t[0].clone(), head_cut_named.clone(), t[2].clone(), not_exr.clone()],
        &[
            format!("{} (tile 1 by its name) cannot be read: the file is cut short or damaged (", at(&head_cut_named)),
            format!("{}: is not an OpenEXR file (", at(&not_exr)),
            "2 of 4 tiles to render again (the unreadable file may have been meant as one of them): 1, 3 (with --tile \
             I/4; as a Slurm array, --array=1,3)"
                .into(),
        ],
    );
    // Cut short in its pixels: its header names the tile, which is to render again; every such
    // tile is named.
    refused(
        &[t[0].clone(), t[1].clone(), tail_cut.clone(), tail_cut2.clone()],
        &[
            format!("{} (tile 2) cannot be read: the file is cut short or damaged (", at(&tail_cut)),
            format!("{} (tile 3) cannot be read", at(&tail_cut2)),
            "2 of 4 tiles to render again: 2-3 (with --tile I/4; as a Slurm array, --array=2-3)".into(),
        ],
    );
    // The first tile (the one the others are held against) cut short in its pixels, and tile 3
    // missing: both are named, and both are to render again (the missing tile alone was named,
    // and the cut one only in a second round).
    let first_cut = dir.join("c0.exr");
    let bytes0 = std::fs::read(&t[0]).expect("tile");
    std::fs::write(&first_cut, &bytes0[..bytes0.len() - 10]).expect("cut tile");
    refused(
        &[first_cut.clone(), t[1].clone(), t[2].clone()],
        &[
            format!("{} (tile 0) cannot be read: the file is cut short or damaged (", at(&first_cut)),
            "2 of 4 tiles to render again: 0, 3 (with --tile I/4; as a Slurm array, --array=0,3)".into(),
        ],
    );
    // tile-3.exr holding tile 2: given twice, and tile 3 missing, both said.
    let misnamed = dir.join("t3-holds-2.exr");
    std::fs::copy(&t[2], &misnamed).expect("copy");
    refused(
        &[t[0].clone(), t[1].clone(), t[2].clone(), misnamed.clone()],
        &[
            format!(
                "tile 2 is given twice, {} and {}: tiles must not overlap; leave one out",
                at(&t[2]),
                at(&misnamed)
            ),
            "1 of 4 tiles is missing: 3 (render it with --tile I/4; as a Slurm array, --array=3)".into(),
        ],
    );
    // Two tiles of each of two renders: either may be the stale pair (tiles 2-3 were said to be).
    let (s2, s3) = (tile("2/4", "7", "s2.exr"), tile("3/4", "7", "s3.exr"));
    refused(
        &[t[0].clone(), t[1].clone(), s2.clone(), s3],
        &[
            format!("are not of the same render as {} (as many tiles are of either render: either may be", at(&t[0])),
            format!(
                "to keep the render of {}, render again 2-3 (with --tile I/4; as a Slurm array, --array=2-3); or, \
                 to keep the render of {}, render again 0-1 (with --tile I/4; as a Slurm array, --array=0-1)",
                at(&t[0]),
                at(&s2)
            ),
        ],
    );
    // Lone missing tiles a step apart are one Slurm range with a step (1,3,5,… was 7 KB for
    // 1,503 tiles, which sbatch refused).
    let seven: Vec<PathBuf> = [0, 2, 4, 6].iter().map(|i| tile(&format!("{i}/7"), "0", &format!("v{i}.exr"))).collect();
    refused(
        &seven,
        &["3 of 7 tiles are missing: 1, 3, 5 (render them with --tile I/7; as a Slurm array, --array=1-5:2)".into()],
    );
}

#[test]
fn the_tile_index_comes_from_the_flag_or_a_schedulers_variable() {
    let dir = TempDir::new("tiles-index");
    let size = ["--width", "24", "--height", "16"];
    for (variable, value) in
        [("SLURM_ARRAY_TASK_ID", "2"), ("JOB_COMPLETION_INDEX", "0"), ("AWS_BATCH_JOB_ARRAY_INDEX", "1")]
    {
        let out = dir.join(format!("{variable}.exr"));
        let args =
            ["render", "whitted", "--tile", "3", "-o"].map(OsString::from).into_iter().chain([out.clone().into()]);
        let done = std::process::Command::new(env!("CARGO_BIN_EXE_glint"))
            .args(args.chain(size.map(OsString::from)))
            .current_dir(&*dir)
            .env_remove("SLURM_ARRAY_TASK_ID")
            .env_remove("JOB_COMPLETION_INDEX")
            .env_remove("AWS_BATCH_JOB_ARRAY_INDEX")
            .env(variable, value)
            .output()
            .expect("run glint");
        assert!(done.status.success(), "{}", text(&done.stderr));
        assert!(
            text(&done.stdout).contains(&format!("tile {value}/3 (index from {variable}")),
            "{}",
            text(&done.stdout)
        );
        assert_eq!(read_exr(&out).expect("tile").header.attribute("glint:tile"), Some(format!("{value}/3").as_str()));
    }
    let done = std::process::Command::new(env!("CARGO_BIN_EXE_glint"))
        .args(["render", "whitted", "--tile", "3", "-q"])
        .current_dir(&*dir)
        .env_remove("SLURM_ARRAY_TASK_ID")
        .env_remove("JOB_COMPLETION_INDEX")
        .env_remove("AWS_BATCH_JOB_ARRAY_INDEX")
        .output()
        .expect("run glint");
    assert!(!done.status.success());
    let stderr = text(&done.stderr);
    for name in ["SLURM_ARRAY_TASK_ID", "JOB_COMPLETION_INDEX", "AWS_BATCH_JOB_ARRAY_INDEX", "--tile I/3"] {
        assert!(stderr.contains(name), "{stderr}");
    }
    // Two schedulers' indices that disagree are refused, naming both (the first had won).
    let done = std::process::Command::new(env!("CARGO_BIN_EXE_glint"))
        .args(["render", "whitted", "--tile", "3", "-q", "-o", "both.exr"])
        .current_dir(&*dir)
        .env_remove("AWS_BATCH_JOB_ARRAY_INDEX")
        .env("SLURM_ARRAY_TASK_ID", "2")
        .env("JOB_COMPLETION_INDEX", "1")
        .output()
        .expect("run glint");
    assert_eq!(done.status.code(), Some(2), "{}", text(&done.stderr));
    let stderr = text(&done.stderr);
    assert!(stderr.contains("SLURM_ARRAY_TASK_ID='2' and JOB_COMPLETION_INDEX='1' disagree"), "{stderr}");
    assert!(!dir.join("both.exr").exists());
    // An index past the grid from the scheduler (`--array=1-3` for 3 tiles) names where it
    // came from and the array that numbers them.
    let done = std::process::Command::new(env!("CARGO_BIN_EXE_glint"))
        .args(["render", "whitted", "--width", "24", "--height", "16", "--tile", "3", "-q"])
        .current_dir(&*dir)
        .env("SLURM_ARRAY_TASK_ID", "3")
        .output()
        .expect("run glint");
    assert!(!done.status.success());
    let stderr = text(&done.stderr);
    assert!(
        stderr.contains("from SLURM_ARRAY_TASK_ID (Slurm job arrays)") && stderr.contains("--array=0-2"),
        "{stderr}"
    );
    // A variable beyond u32 is said to be so, not called no number; one that is none, so.
    for (value, wanted) in [
        ("99999999999999999999", "SLURM_ARRAY_TASK_ID='99999999999999999999' (Slurm job arrays) is beyond 4294967295"),
        ("x1", "SLURM_ARRAY_TASK_ID='x1' (Slurm job arrays) is not a whole number"),
        // With the range the array must number (it had none).
        ("-1", "is not a whole number, so it names no tile: the 3 tiles are numbered 0 to 2 (Slurm: --array=0-2)"),
    ] {
        let done = std::process::Command::new(env!("CARGO_BIN_EXE_glint"))
            .args(["render", "whitted", "--width", "24", "--height", "16", "--tile", "3", "-q"])
            .current_dir(&*dir)
            .env("SLURM_ARRAY_TASK_ID", value)
            .output()
            .expect("run glint");
        let said = text(&done.stderr);
        // Without the parser's own words after them ("invalid digit found in string").
        assert!(!done.status.success() && said.contains(wanted) && !said.contains("invalid digit"), "{said}");
    }
    for (args, wanted) in [
        (&["--tile", "3/3"][..], "tiles are numbered 0 to 2"),
        (&["--tile", "1/3", "--backend", "both"][..], "--tile renders on one backend"),
        (&["--tile", "1/3", "-o", "t.png"][..], "a tile is written as OpenEXR"),
        (&["--tile", "0/500"][..], "500 tiles fit no grid of a 24x16 image"),
        (&["--tile", "0/29"][..], "the nearest counts that fit one are 28 and 30"),
        // As a word is (it said "a grid needs at least one tile", exit 1): exit 2, the range.
        (&["--tile", "0"][..], "'0' is not a whole number from 1 to 4294967295 (the tile count)"),
        (&["--tile", "abc"][..], "'abc' is not a whole number from 1 to 4294967295 (the tile count)"),
        // On the GPU: with the CPU alone --allow-incomplete is refused as doing nothing.
        (&["--tile", "1/3", "--backend", "gpu", "--allow-incomplete"][..], "--tile writes no incomplete tile"),
    ] {
        let done = glint(&dir, ["render", "whitted"].iter().chain(&size).chain(args));
        assert!(!done.status.success(), "{args:?}");
        assert!(text(&done.stderr).contains(wanted), "{args:?}: {}", text(&done.stderr));
        // The command line's own index past the grid is a usage error, as --shard 2/2 is (it
        // exited 1; a tester).
        if args == ["--tile", "3/3"] {
            assert_eq!(done.status.code(), Some(2), "{args:?}");
        }
    }
}

#[test]
fn the_scene_hash_follows_what_is_rendered_not_how_the_file_is_written() {
    // Three scene files called w.toml: the built-in text, the same with a comment (the same
    // scene: its tiles merge with the first's), and one material changed (another scene).
    let dir = TempDir::new("tiles-hash");
    let source = glint_io::builtin("whitted").and_then(|b| b.toml()).expect("built-in whitted");
    assert!(source.contains("kd = [0.9, 0.1, 0.1]"));
    let variants = [
        source.to_string(),
        format!("{source}\n# the same scene\n"),
        source.replace("kd = [0.9, 0.1, 0.1]", "kd = [0.8, 0.1, 0.1]"),
    ];
    let size = ["--width", "24", "--height", "16"];
    let tiles: Vec<PathBuf> = variants
        .iter()
        .enumerate()
        .map(|(k, body)| {
            let folder = dir.join(format!("v{k}"));
            std::fs::create_dir_all(&folder).expect("folder");
            std::fs::write(folder.join("w.toml"), body).expect("scene");
            let tile = dir.join(format!("v{k}.exr"));
            let scene = folder.join("w.toml");
            render(
                &dir,
                scene.to_str().expect("utf-8"),
                &[&size[..], &["--tile", &format!("{}/2", k.min(1))]].concat(),
                &tile,
            );
            tile
        })
        .collect();
    let out = dir.join("out.exr");
    let done = merge(&dir, &[tiles[0].clone(), tiles[1].clone()], &out);
    assert!(done.status.success(), "a comment changed the scene hash: {}", text(&done.stderr));
    let done = merge(&dir, &[tiles[0].clone(), tiles[2].clone()], &dir.join("other.exr"));
    assert!(!done.status.success());
    assert!(text(&done.stderr).contains("glint:scene_hash is"), "{}", text(&done.stderr));
    // The same scene under another name (a farm's per-task copy): its tiles merge, named as the
    // first tile names the scene.
    std::fs::write(dir.join("task-7.toml"), &variants[0]).expect("copy");
    let copy = dir.join("copy.exr");
    render(&dir, "task-7.toml", &[&size[..], &["--tile", "1/2"]].concat(), &copy);
    let merged = dir.join("copies.exr");
    let done = merge(&dir, &[tiles[0].clone(), copy], &merged);
    assert!(done.status.success(), "copies of one scene file did not merge: {}", text(&done.stderr));
    assert_eq!(read_exr(&merged).expect("merged").header.attribute("glint:scene"), Some("w"));
}
