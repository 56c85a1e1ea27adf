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
    /// Options read but not applied, as written (`-mm 0 2`), and malformed ones.
    pub ignored: Vec<String>,
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

/// Splits `statement` into its options and its file. An option the specification does not
/// know, or one short of its arguments, is kept in `ignored` and the parse goes on after it.
pub(super) fn parse_map(statement: &str) -> MapStatement<'_> {
    let mut out = MapStatement { file: "", offset: [0.0; 2], scale: [1.0; 2], clamp: false, ignored: Vec::new() };
    let mut rest = statement.trim_start();
    while let Some(option) = rest.split_whitespace().next().filter(|w| w.starts_with('-') && w.len() > 1) {
        rest = rest[option.len()..].trim_start();
        let Some((least, most)) = arguments(option) else {
            out.ignored.push(option.to_string());
            continue;
        };
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
        match option {
            _ if values.len() < least => out.ignored.push(format!("{written} (too few arguments)")),
            "-o" => out.offset = [numbers[0], numbers.get(1).copied().unwrap_or(0.0)],
            "-s" => out.scale = [numbers[0], numbers.get(1).copied().unwrap_or(1.0)],
            "-clamp" if values[0] == "on" || values[0] == "off" => out.clamp = values[0] == "on",
            _ => out.ignored.push(written),
        }
    }
    out.file = rest.trim_end();
    out
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
        // An unknown option is named; one short of its numbers too; the file still follows.
        let odd = parse_map("-zz -s tex.png");
        assert_eq!((odd.file, odd.scale), ("tex.png", [1.0; 2]));
        assert_eq!(odd.ignored, vec!["-zz".to_string(), "-s (too few arguments)".to_string()]);
        // A file named like a number after three of them is the file.
        assert_eq!(parse_map("-s 1 1 1 2.png").file, "2.png");
        assert_eq!(parse_map("-clamp maybe t.png").ignored, vec!["-clamp maybe".to_string()]);
    }
}
