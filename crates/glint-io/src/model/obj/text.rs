//! OBJ and MTL files as the UTF-8 text `tobj` reads. Real files come in the encoding of the
//! tool that wrote them: UTF-16 with a byte order mark, or a Windows code page with accented
//! material names (ISO-8859-1 is its subset). Assimp and Blender read those; so does Glint,
//! saying which encoding it took. Every line keeps its number, so errors still name lines, as
//! `bad_number` does for the numbers tobj would refuse or misread.

use std::borrow::Cow;

/// `bytes` as UTF-8 text, and how it was read when it was not UTF-8 (for a warning). A byte order mark decides (UTF-8, UTF-16LE or UTF-16BE, the mark removed);
/// without one, each line that is not UTF-8 is read as Windows-1252, which decodes every byte,
/// and the UTF-8 lines stay as they are (one stray byte in a comment must not turn the file's
/// UTF-8 material names into mojibake that its MTL no longer matches). Malformed UTF-16 is an
/// error.
pub(super) fn decode(bytes: &[u8]) -> Result<(Cow<'_, [u8]>, Option<String>), String> {
    let (text, how) = decode_encoding(bytes)?;
    Ok((with_line_feeds(text), how))
}

/// `text` with each carriage return that ends a line alone (classic Mac OS files) made a line
/// feed: tobj splits lines at line feeds, and a tester's MTL in bare CRs was one line, its
/// materials unread.
fn with_line_feeds(text: Cow<'_, [u8]>) -> Cow<'_, [u8]> {
    let lone = |i: usize, b: &u8| *b == b'\r' && text.get(i + 1) != Some(&b'\n');
    if !text.iter().enumerate().any(|(i, b)| lone(i, b)) {
        return text;
    }
    let out: Vec<u8> = text.iter().enumerate().map(|(i, b)| if lone(i, b) { b'\n' } else { *b }).collect();
    Cow::Owned(out)
}

fn decode_encoding(bytes: &[u8]) -> Result<(Cow<'_, [u8]>, Option<String>), String> {
    if let Some((encoding, mark)) = encoding_rs::Encoding::for_bom(bytes) {
        let body = &bytes[mark..];
        if encoding == encoding_rs::UTF_8 {
            return Ok((Cow::Borrowed(body), None));
        }
        let (text, malformed) = encoding.decode_without_bom_handling(body);
        if malformed {
            return Err(format!("malformed {} text (its byte order mark says {0})", encoding.name()));
        }
        return Ok((Cow::Owned(text.into_owned().into_bytes()), Some(format!("read as {}", encoding.name()))));
    }
    if std::str::from_utf8(bytes).is_ok() {
        return Ok((Cow::Borrowed(bytes), None));
    }
    let encoding = encoding_rs::WINDOWS_1252;
    let text = rewrite_lines(bytes, |raw| {
        std::str::from_utf8(raw).is_err().then(|| encoding.decode_without_bom_handling(raw).0.into_owned().into_bytes())
    });
    Ok((Cow::Owned(text.into_owned()), Some(format!("lines read as {}", encoding.name()))))
}

/// The name Glint gives a material that `newmtl` and `usemtl` leave nameless (Blender writes
/// both for an unnamed material); tobj refuses the bare statements, Assimp pairs them.
pub(super) const NAMELESS: &str = "\u{0}nameless";

/// A `usemtl` statement as the file wrote it: its line (1-based) and the name it gives, empty
/// when it names none.
#[derive(Clone, Debug, PartialEq, Eq)]
pub(super) struct UseMaterial {
    pub line: usize,
    pub name: String,
}

/// Every `usemtl` statement of OBJ text, for the warnings about names the MTL lacks.
pub(super) fn material_uses(text: &[u8]) -> Vec<UseMaterial> {
    let lines = text.split(|&b| b == b'\n').enumerate();
    lines.filter_map(|(n, raw)| statement_name(raw, "usemtl").map(|name| UseMaterial { line: n + 1, name })).collect()
}

/// OBJ or MTL text with each `keywords` statement (`mtllib`, `usemtl`, `newmtl`) written as
/// tobj reads it: the keyword, one space, the name. tobj takes the name after the line's first
/// space, so `  usemtl red` named `usemtl red` and `usemtl<TAB>red` was refused. A `usemtl` or
/// `newmtl` that names nothing names [`NAMELESS`]; an `mtllib` that names nothing is blanked.
pub(super) fn material_statements<'a>(text: &'a [u8], keywords: &[&str]) -> Cow<'a, [u8]> {
    rewrite_lines(text, |raw| {
        let (keyword, name) = keywords.iter().find_map(|k| statement_name(raw, k).map(|name| (*k, name)))?;
        let line = match (keyword, name.is_empty()) {
            ("mtllib", true) => String::new(),
            (_, true) => format!("{keyword} {NAMELESS}"),
            (_, false) => format!("{keyword} {name}"),
        };
        (line.as_bytes() != raw).then(|| line.into_bytes())
    })
}

/// OBJ text with its polyline statements (`l`) blanked, and how many there were: tobj reads
/// `l a b c …` as a filled polygon (a wireframe box became a solid one), and Glint traces no
/// lines. The lines stay, empty, so that errors still name the file's line numbers.
pub(super) fn without_polylines(text: &[u8]) -> (Cow<'_, [u8]>, usize) {
    let mut count = 0;
    let out = rewrite_lines(text, |raw| {
        let polyline = statement_name(raw, "l").is_some();
        count += usize::from(polyline);
        polyline.then(Vec::new)
    });
    (out, count)
}

/// OBJ text with its faces of fewer than three corners (`f 1 2`, `f 3`) blanked, and their line
/// numbers (1-based): a polygon needs three, and tobj dropped such a statement without a word
/// (and with it the count of faces the smoothing groups are read against).
pub(super) fn without_short_faces(text: &[u8]) -> (Cow<'_, [u8]>, Vec<usize>) {
    let mut lines = Vec::new();
    let mut n = 0;
    let out = rewrite_lines(text, |raw| {
        n += 1;
        let mut words = raw.split(u8::is_ascii_whitespace).filter(|w| !w.is_empty());
        let short = words.next() == Some(b"f".as_slice()) && words.count() < 3;
        if short {
            lines.push(n);
        }
        short.then(Vec::new)
    });
    (out, lines)
}

/// OBJ text whose vertex colours (`v x y z r g b`) are left out when only some vertices have
/// them, and then how many of how many `v` lines had them. tobj would pair the colours with the
/// wrong vertices, or refuse a face of an uncoloured one; Assimp and three.js likewise drop a
/// partial set. A file where every vertex or none has a colour is returned as it is.
pub(super) fn without_partial_vertex_colours(text: &[u8]) -> (Cow<'_, [u8]>, Option<(usize, usize)>) {
    let words = |raw: &[u8]| -> Option<usize> {
        let line = std::str::from_utf8(raw).ok()?;
        let mut w = line.split_whitespace().take_while(|w| !w.starts_with('#'));
        (w.next() == Some("v")).then(|| w.count())
    };
    let (mut coloured, mut all) = (0, 0);
    for raw in text.split(|&b| b == b'\n') {
        if let Some(n) = words(raw) {
            all += 1;
            coloured += usize::from(n == 6);
        }
    }
    if coloured == 0 || coloured == all {
        return (Cow::Borrowed(text), None);
    }
    let out = rewrite_lines(text, |raw| {
        (words(raw) == Some(6)).then(|| {
            let line = std::str::from_utf8(raw).unwrap_or_default();
            let position: Vec<&str> = line.split_whitespace().take(4).collect();
            position.join(" ").into_bytes()
        })
    });
    (out, Some((coloured, all)))
}

/// The first `v`, `vt` or `vn` line (1-based) with too few numbers or holding a word that is
/// not a number (tobj says only "position parse error", and drops a colour it cannot read) or
/// a number that is not a
/// finite f32 (`nan`, `inf`, or a decimal beyond f32's range, which the GPU tracer cannot hold
/// even after rebasing), and what is wrong with it.
pub(super) fn bad_number(bytes: &[u8]) -> Option<(usize, String)> {
    for (n, raw) in bytes.split(|&b| b == b'\n').enumerate() {
        let Ok(line) = std::str::from_utf8(raw) else { continue };
        // tobj reads a line up to a comment, and of `vt` and `vn` lines only the numbers it uses.
        let mut words = line.split_whitespace().take_while(|w| !w.starts_with('#'));
        // A `v` line's fourth number is w, or the first of a colour's three.
        let keyword = words.next();
        let components: &[(&str, &str)] = match keyword {
            Some("v") if words.clone().count() == 4 => &[
                ("vertex position", "x"),
                ("vertex position", "y"),
                ("vertex position", "z"),
                ("vertex position", "w"),
            ],
            Some("v") => &[
                ("vertex position", "x"),
                ("vertex position", "y"),
                ("vertex position", "z"),
                ("vertex colour", "r"),
                ("vertex colour", "g"),
                ("vertex colour", "b"),
            ],
            Some("vt") => &[("texture coordinate", "u"), ("texture coordinate", "v")],
            Some("vn") => &[("normal", "x"), ("normal", "y"), ("normal", "z")],
            _ => continue,
        };
        // Too few numbers: tobj said only "position parse error" for `v 0 0` (a tester).
        let (what, least, needs) = match keyword {
            Some("vt") => ("a texture coordinate", 2, "two numbers u v"),
            Some("vn") => ("a normal", 3, "three numbers x y z"),
            _ => ("a vertex position", 3, "three numbers x y z (then optionally w, or r g b)"),
        };
        let given = words.clone().count();
        if given < least {
            return Some((n + 1, format!("`{}`: {what} needs {needs}; {given} given", line.trim())));
        }
        // tobj said "color parse error (too many or too few components)" of 5, 7 or more.
        if keyword == Some("v") && !matches!(given, 3 | 4 | 6) {
            return Some((
                n + 1,
                format!("`{}`: a vertex is x y z, then w, or r g b: 3, 4 or 6 numbers; {given} given", line.trim()),
            ));
        }
        for (k, word) in words.enumerate().take(components.len()) {
            let (what, name) = components[k];
            let Ok(value) = word.parse::<f32>() else {
                return Some((n + 1, format!("`{}`: {what} component {name}: `{word}` is not a number", line.trim())));
            };
            if let Some(problem) = not_finite(word, value) {
                return Some((n + 1, format!("`{}`: {what} component {name}: {problem}", line.trim())));
            }
            // Validation's range, said here with the line: after import it named the mesh's
            // inner index, once a line for every face using it (`vt 1e30 1`; a tester).
            let range = glint_scene::ranges::COORD;
            if keyword == Some("vt") && !range.contains(f64::from(value)) {
                return Some((
                    n + 1,
                    format!(
                        "`{}`: {what} component {name}: {word} is outside {}, a texture coordinate's range",
                        line.trim(),
                        range.bounds()
                    ),
                ));
            }
            // Likewise a vertex colour: it was named `objects[0] mesh 0 `NAME`.colours[0]`,
            // the index of the mesh's vertex, not the file's line (a tester's -5).
            let range = glint_scene::ranges::COLOUR;
            if what == "vertex colour" && !range.contains(f64::from(value)) {
                return Some((
                    n + 1,
                    format!(
                        "`{}`: {what} component {name}: {word} is outside {}, a vertex colour's range",
                        line.trim(),
                        range.bounds()
                    ),
                ));
            }
        }
    }
    None
}

/// The first face (its 1-based line, and what is wrong) that names a normal in a file without
/// a `vn` statement: tobj reads the index as none and the file loaded, where one `vn` made an
/// index past it an error (`f 5/1/3 …`; a tester).
pub(super) fn normals_named_without_any(bytes: &[u8]) -> Option<(usize, String)> {
    let lines = || bytes.split(|&b| b == b'\n').map(|raw| std::str::from_utf8(raw).unwrap_or(""));
    if lines().any(|line| line.split_whitespace().next() == Some("vn")) {
        return None;
    }
    lines().enumerate().find_map(|(n, line)| {
        let mut words = line.split_whitespace();
        let names_normal = words.next() == Some("f")
            && words.any(|corner| corner.split('/').nth(2).is_some_and(|normal| !normal.is_empty()));
        names_normal.then(|| {
            (
                n + 1,
                format!(
                    "`{}`: face normal index out of bounds; no normals come before it (the file has no `vn` statement)",
                    line.trim()
                ),
            )
        })
    })
}

/// Why `word`, read as the f32 `value` (tobj reads f32), is no finite number; `None` when it is
/// one. What the OBJ's and the MTL's number checks say alike.
pub(super) fn not_finite(word: &str, value: f32) -> Option<String> {
    if value.is_finite() {
        None
    } else if word.parse::<f64>().is_ok_and(f64::is_finite) {
        Some(format!("{word} is beyond f32's range (±{:e})", f32::MAX))
    } else {
        Some(format!("{word} is not a finite number"))
    }
}

/// `text` with the lines `replace` gives a replacement for replaced (the line breaks kept, so
/// every line keeps its number); borrowed as it is when there are none. One pass: the copy
/// starts at the first replaced line.
fn rewrite_lines(text: &[u8], mut replace: impl FnMut(&[u8]) -> Option<Vec<u8>>) -> Cow<'_, [u8]> {
    let mut out: Option<Vec<u8>> = None;
    let mut start = 0;
    for raw in text.split(|&b| b == b'\n') {
        let replaced = replace(raw);
        match (&mut out, replaced) {
            (None, None) => {}
            (None, Some(line)) => {
                let mut copy = Vec::with_capacity(text.len() + 64);
                copy.extend_from_slice(&text[..start]);
                copy.extend_from_slice(&line);
                out = Some(copy);
            }
            (Some(copy), line) => {
                copy.push(b'\n');
                copy.extend_from_slice(line.as_deref().unwrap_or(raw));
            }
        }
        start += raw.len() + 1;
    }
    out.map_or(Cow::Borrowed(text), Cow::Owned)
}

/// The name a `keyword` line gives as tobj reads it (the rest of the line, trimmed), else
/// `None`.
fn statement_name(raw: &[u8], keyword: &str) -> Option<String> {
    let line = std::str::from_utf8(raw).ok()?.trim();
    let rest = line.strip_prefix(keyword)?;
    (rest.is_empty() || rest.starts_with(char::is_whitespace)).then(|| rest.trim().to_string())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn utf16_with_a_byte_order_mark_is_decoded_and_named() {
        let text = "v 0 0 0\nusemtl Terraindæk\n";
        for (mark, encode, name) in [
            (vec![0xFF, 0xFE], u16::to_le_bytes as fn(u16) -> [u8; 2], "UTF-16LE"),
            (vec![0xFE, 0xFF], u16::to_be_bytes, "UTF-16BE"),
        ] {
            let bytes: Vec<u8> = mark.into_iter().chain(text.encode_utf16().flat_map(encode)).collect();
            let (decoded, encoding) = decode(&bytes).unwrap();
            assert_eq!((decoded.as_ref(), encoding), (text.as_bytes(), Some(format!("read as {name}"))));
        }
        let odd = [0xFE, 0xFF, 0xD8, 0x00, 0x00, 0x41];
        assert!(decode(&odd).unwrap_err().contains("malformed UTF-16BE"), "an unpaired surrogate");
    }

    #[test]
    fn utf8_is_kept_its_mark_dropped_and_other_bytes_read_as_windows_1252() {
        let plain = "usemtl Terraindæk\n".as_bytes();
        assert!(matches!(decode(plain).unwrap(), (Cow::Borrowed(b), None) if b == plain));
        let marked: Vec<u8> = [0xEF, 0xBB, 0xBF].iter().chain(plain).copied().collect();
        assert_eq!(decode(&marked).unwrap(), (Cow::Borrowed(plain), None));
        let latin = b"usemtl Terraind\xe6k \x80\n# caf\xc3\xa9\n";
        let (decoded, encoding) = decode(latin).unwrap();
        let expected = "usemtl Terraindæk €\n# café\n";
        assert_eq!(
            (decoded.as_ref(), encoding),
            (expected.as_bytes(), Some("lines read as windows-1252".into())),
            "line by line"
        );
    }

    #[test]
    fn material_statements_are_written_as_tobj_reads_them_and_every_usemtl_is_listed() {
        let text =
            b"v 0 0 0\nusemtl \nf 1 1 1\n  usemtl  red \nusemtlx\nusemtl\tblue\nusemtl\nmtllib\nmtllib a b.mtl\n";
        let out = material_statements(text, &["mtllib", "usemtl"]);
        let expected = format!(
            "v 0 0 0\nusemtl {NAMELESS}\nf 1 1 1\nusemtl red\nusemtlx\nusemtl blue\nusemtl {NAMELESS}\n\nmtllib a b.mtl\n"
        );
        assert_eq!(std::str::from_utf8(&out).unwrap(), expected);
        let listed: Vec<(usize, String)> = material_uses(text).into_iter().map(|u| (u.line, u.name)).collect();
        let names = [(2, ""), (4, "red"), (6, "blue"), (7, "")].map(|(l, n)| (l, n.to_string()));
        assert_eq!(listed, names);
        let mtl = material_statements(b"newmtl \nKd 1 1 1\n", &["newmtl"]);
        assert_eq!(std::str::from_utf8(&mtl).unwrap(), format!("newmtl {NAMELESS}\nKd 1 1 1\n"));
        let named = b"usemtl red\nf 1 2 3\n";
        assert!(matches!(material_statements(named, &["usemtl"]), Cow::Borrowed(_)), "nothing to rewrite");
    }

    #[test]
    fn a_partial_set_of_vertex_colours_is_left_out_and_a_whole_one_kept() {
        let (out, counted) = without_partial_vertex_colours(b"v 0 0 0 1 0 0\nv 1 0 0\n  v 0 1 0 0 0 1\r\nf 1 2 3\n");
        assert_eq!(
            (std::str::from_utf8(&out).unwrap(), counted),
            ("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n", Some((2, 3)))
        );
        let whole = b"v 0 0 0 1 0 0\nv 1 0 0 0 1 0\nv 0 1 0 0 0 1\nf 1 2 3\n";
        assert!(matches!(without_partial_vertex_colours(whole), (Cow::Borrowed(_), None)));
        assert!(matches!(without_partial_vertex_colours(b"v 0 0 0 2\nv 1 0 0\n"), (Cow::Borrowed(_), None)));
    }

    #[test]
    fn polylines_are_blanked_keeping_the_line_numbers() {
        let (out, count) = without_polylines(b"v 0 0 0\nl 1 2 3 4\nlx 1\nf 1 2 3\r\n  l 2 3\n");
        assert_eq!((std::str::from_utf8(&out).unwrap(), count), ("v 0 0 0\n\nlx 1\nf 1 2 3\r\n\n", 2));
        assert!(matches!(without_polylines(b"f 1 2 3\n"), (Cow::Borrowed(_), 0)));
    }
}
