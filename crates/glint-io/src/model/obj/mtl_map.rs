//! An MTL texture statement (`map_Kd -s 2 2 1 -clamp on tex.png`): its options and its file,
//! after the OBJ/MTL specification's option list. `-o` and `-s` place the image (as three.js
//! and Blender read them), `-clamp on` stops it repeating; the options that have no term in
//! Glint's textures are named so that a warning can list them.

/// What a map statement asks for, in OBJ's texture space (v up from the image's bottom row).
#[derive(Clone, Debug, PartialEq)]
pub(super) struct MapStatement<'a> {
    /// The image file: the rest of the statement after its options, spaces kept.
    pub file: &'a str,
    /// `-o u v` (w is left out: the textures are 2-D).
    pub offset: [f64; 2],
    /// `-s u v`.
    pub scale: [f64; 2],
    /// `-clamp on`.
    pub clamp: bool,
    /// Options read but not applied, as written (`-mm 0 2`).
    pub ignored: Vec<String>,
    /// The options could not be read as the specification writes them, and were all left out.
    pub unread: bool,
}

/// How many arguments each option of the specification takes: on/off switches and fixed
/// counts, or one to three numbers (`-o`, `-s`, `-t`).
fn arguments(option: &str) -> Option<(usize, usize)> {
    Some(match option {
        "-blendu" | "-blendv" | "-cc" | "-clamp" | "-texres" | "-bm" | "-boost" | "-imfchan" | "-type" => (1, 1),
        "-mm" => (2, 2),
        "-o" | "-s" | "-t" => (1, 3),
        _ => return None,
    })
}

/// The largest |offset| or |scale| read (a scene file's texture transforms allow as much).
const MAX_PLACEMENT: f64 = 1e9;

/// Splits `statement` into its options and its file. A statement whose options cannot be read
/// as the specification writes them (an option it does not know, one short of its arguments,
/// a number written with a comma, a placement beyond ±1e9) is read as exporters that ignore
/// options read it: every option left out (named in `ignored`), the file its last word.
pub(super) fn parse_map(statement: &str) -> MapStatement<'_> {
    let unread = || MapStatement {
        file: "",
        offset: [0.0; 2],
        scale: [1.0; 2],
        clamp: false,
        ignored: Vec::new(),
        unread: true,
    };
    match parse_options(statement) {
        Some(read) if !read.file.is_empty() => read,
        _ => MapStatement { file: statement.split_whitespace().last().unwrap_or(""), ..unread() },
    }
}

/// The statement as the specification writes it, or `None` where it is not.
fn parse_options(statement: &str) -> Option<MapStatement<'_>> {
    let mut out =
        MapStatement { file: "", offset: [0.0; 2], scale: [1.0; 2], clamp: false, ignored: Vec::new(), unread: false };
    let mut rest = statement.trim_start();
    while let Some(option) = rest.split_whitespace().next().filter(|w| w.starts_with('-') && w.len() > 1) {
        rest = rest[option.len()..].trim_start();
        let (least, most) = arguments(option)?;
        let numeric = matches!(option, "-o" | "-s" | "-t" | "-mm" | "-texres" | "-bm" | "-boost");
        let mut values: Vec<&str> = Vec::new();
        while values.len() < most {
            let Some(word) = rest.split_whitespace().next() else { break };
            // A file may follow a short list of numbers; a switch takes any word.
            if numeric && word.parse::<f64>().is_err() {
                break;
            }
            values.push(word);
            rest = rest[word.len()..].trim_start();
        }
        let written = std::iter::once(option).chain(values.iter().copied()).collect::<Vec<_>>().join(" ");
        let numbers: Vec<f64> = values.iter().filter_map(|v| v.parse().ok()).collect();
        let placement = numbers.iter().all(|v| v.abs() <= MAX_PLACEMENT);
        match option {
            _ if values.len() < least || !placement => return None,
            "-o" => out.offset = [numbers[0], numbers.get(1).copied().unwrap_or(0.0)],
            "-s" => out.scale = [numbers[0], numbers.get(1).copied().unwrap_or(1.0)],
            "-clamp" if values[0] == "on" || values[0] == "off" => out.clamp = values[0] == "on",
            _ => out.ignored.push(written),
        }
    }
    out.file = rest.trim_end();
    Some(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn offset_scale_and_clamp_are_read_the_rest_named_and_the_file_kept_whole() {
        let m = parse_map("-s 2 3 1 -o 0.5 -clamp on -mm 0 2 -bm 1.5 my texture.png ");
        assert_eq!((m.file, m.offset, m.scale, m.clamp), ("my texture.png", [0.5, 0.0], [2.0, 3.0], true));
        assert_eq!(m.ignored, vec!["-mm 0 2".to_string(), "-bm 1.5".to_string()]);
        let plain = parse_map(".\\wal67ar_small.jpg");
        assert_eq!(
            (plain.file, plain.scale, plain.clamp, plain.ignored.len()),
            (".\\wal67ar_small.jpg", [1.0; 2], false, 0)
        );
        // A file named like a number after three of them is the file.
        assert_eq!(parse_map("-s 1 1 1 2.png").file, "2.png");
        assert_eq!(parse_map("-clamp maybe t.png").ignored, vec!["-clamp maybe".to_string()]);
        assert!(!parse_map("-s 1 1 1 2.png").unread);
        // What cannot be read as MTL options leaves them all out and takes the last word, as
        // readers that ignore options do: an unknown or capitalised option (which may take
        // arguments), a comma decimal, too few numbers, a placement beyond 1e9 or not finite,
        // a file named with a leading '-'.
        for statement in [
            "-colorspace sRGB tex.png",
            "-O 0.5 0.5 tex.png",
            "-s 0,5 0,5 1 tex.png",
            "-s tex.png",
            "-o 1e10 0 tex.png",
            "-s nan 1 tex.png",
            "-s 2 2 -zz tex.png",
        ] {
            let m = parse_map(statement);
            assert_eq!(
                (m.file, m.offset, m.scale, m.clamp, m.unread),
                ("tex.png", [0.0; 2], [1.0; 2], false, true),
                "{statement}"
            );
        }
        assert_eq!(parse_map("-wood.png").file, "-wood.png");
    }
}
