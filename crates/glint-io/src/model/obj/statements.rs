//! OBJ and MTL statements as writers spread and annotate them, joined and cut back to what
//! `tobj` reads: a line ending in `\` continues on the next (the OBJ specification's line
//! continuation, which tobj refused as a "face parse error"), and `#` starts a comment after a
//! statement as it does at a line's start (`f 1 2 3 # base`, refused; `usemtl red # paint`,
//! read as the material `red # paint`). Every line keeps its number, so errors still name
//! lines.

use std::borrow::Cow;

/// `text` with every statement continued by a trailing `\` joined into its first line, the
/// lines it took left empty. A comment line's `\` continues nothing (trailing comments are cut
/// first, `without_trailing_comments`).
pub(super) fn joined_continuations(text: &[u8]) -> Cow<'_, [u8]> {
    let continued = |line: &[u8]| {
        let line = line.trim_ascii();
        line.ends_with(b"\\") && !line.starts_with(b"#")
    };
    let lines: Vec<&[u8]> = text.split(|&b| b == b'\n').collect();
    if !lines.iter().any(|l| continued(l)) {
        return Cow::Borrowed(text);
    }
    let mut out: Vec<Vec<u8>> = Vec::with_capacity(lines.len());
    let mut i = 0;
    while i < lines.len() {
        let mut statement = Vec::new();
        let first = i;
        while continued(lines[i]) && i + 1 < lines.len() {
            let part = lines[i].trim_ascii_end();
            statement.extend_from_slice(&part[..part.len() - 1]);
            statement.push(b' ');
            i += 1;
        }
        statement.extend_from_slice(lines[i]);
        out.push(statement);
        out.extend((first..i).map(|_| Vec::new()));
        i += 1;
    }
    Cow::Owned(out.join(&b'\n'))
}

/// Statements whose rest is a name or a file name, where `#` may be part of it: their comment
/// starts at a `#` after white space.
fn names_something(keyword: &[u8]) -> bool {
    matches!(
        keyword,
        b"mtllib" | b"usemtl" | b"newmtl" | b"o" | b"g" | b"bump" | b"disp" | b"decal" | b"refl" | b"norm"
    ) || keyword.starts_with(b"map_")
}

/// `text` with the comment after each statement cut off (with the white space before it).
pub(super) fn without_trailing_comments(text: &[u8]) -> Cow<'_, [u8]> {
    let mut out: Option<Vec<Vec<u8>>> = None;
    for (n, line) in text.split(|&b| b == b'\n').enumerate() {
        let cut = comment_start(line);
        if let (None, Some(_)) = (&out, cut) {
            out = Some(text.split(|&b| b == b'\n').take(n).map(<[u8]>::to_vec).collect());
        }
        if let Some(lines) = &mut out {
            lines.push(cut.map_or(line, |c| line[..c].trim_ascii_end()).to_vec());
        }
    }
    out.map_or(Cow::Borrowed(text), |lines| Cow::Owned(lines.join(&b'\n')))
}

/// Where a statement's trailing comment starts, if it has one (a whole-line comment is left to
/// tobj).
fn comment_start(line: &[u8]) -> Option<usize> {
    let hash = line.iter().position(|&b| b == b'#')?;
    let start = line.iter().position(|b| !b.is_ascii_whitespace())?;
    if start == hash {
        return None;
    }
    let keyword_end = line[start..].iter().position(u8::is_ascii_whitespace).map_or(line.len(), |e| start + e);
    if !names_something(&line[start..keyword_end]) {
        return Some(hash);
    }
    (keyword_end.max(1)..line.len()).find(|&i| line[i] == b'#' && line[i - 1].is_ascii_whitespace())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn text(bytes: &[u8]) -> &str {
        std::str::from_utf8(bytes).unwrap()
    }

    #[test]
    fn a_continued_statement_is_joined_into_its_first_line_and_every_line_keeps_its_number() {
        let obj = b"v 0 0 0\nf 1 2 \\\n  3 4\\\r\n 5\n# note \\\nv 1 1 1\n";
        assert_eq!(text(&joined_continuations(obj)), "v 0 0 0\nf 1 2    3 4  5\n\n\n# note \\\nv 1 1 1\n");
        let plain = b"v 0 0 0\nf 1 2 3\n";
        assert!(matches!(joined_continuations(plain), Cow::Borrowed(_)));
        // A `\` on the last line has nothing to join.
        assert_eq!(text(&joined_continuations(b"f 1 2 3 \\")), "f 1 2 3 \\");
    }

    #[test]
    fn trailing_comments_are_cut_but_not_a_hash_inside_a_name() {
        let obj = b"# whole\nf 1/1/1 2/2/1 3/3/1 # base\nf 1 2 3#c\r\nusemtl tex # the paint\nusemtl Material#1\n\
                    mtllib a#b.mtl # lib\nv 1 2 3\n";
        let expected =
            "# whole\nf 1/1/1 2/2/1 3/3/1\nf 1 2 3\nusemtl tex\nusemtl Material#1\nmtllib a#b.mtl\nv 1 2 3\n";
        assert_eq!(text(&without_trailing_comments(obj)), expected);
        let mtl = b"newmtl red # the red one\nKd 0.9 0.1 0.1 # red\nmap_Kd tex #2.png\n";
        assert_eq!(text(&without_trailing_comments(mtl)), "newmtl red\nKd 0.9 0.1 0.1\nmap_Kd tex\n");
        assert!(matches!(without_trailing_comments(b"v 1 2 3\n# c\n"), Cow::Borrowed(_)));
    }
}
