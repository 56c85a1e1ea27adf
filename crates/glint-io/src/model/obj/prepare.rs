//! An OBJ's text made into what tobj reads: decoded, comments and continuations resolved,
//! material names kept whole, and what tobj would mishandle (polylines, faces of fewer than three
//! corners, partial vertex colours) left out with a warning each.

use super::{statements, text};
use glint_scene::FieldIssue;

/// The text tobj parses, and the file's `usemtl` statements as it wrote them.
pub(super) struct Prepared {
    /// Owned: each step borrows the one before.
    pub bytes: Vec<u8>,
    pub uses: Vec<text::UseMaterial>,
    /// The lines (1-based) of faces of fewer than three corners, left out.
    pub short_faces: Vec<usize>,
}

/// `raw` prepared for tobj, its warnings pushed onto `warnings`; or the line (where known) and
/// why the file is not an OBJ.
pub(super) fn prepared(raw: &[u8], warnings: &mut Vec<FieldIssue>) -> Result<Prepared, (Option<usize>, String)> {
    let (bytes, encoding) = text::decode(raw).map_err(|reason| (None, reason))?;
    warnings.extend(encoding.map(|how| FieldIssue { field: "encoding".into(), problem: format!("not UTF-8: {how}") }));
    // Comments first: a comment ending in `\` continues nothing.
    let bytes = statements::without_trailing_comments(&bytes);
    let bytes = statements::joined_continuations(&bytes);
    let uses = text::material_uses(&bytes);
    let bytes = text::material_statements(&bytes, &["mtllib", "usemtl"]);
    let (bytes, polylines) = text::without_polylines(&bytes);
    if polylines > 0 {
        warnings.push(FieldIssue {
            field: "l".into(),
            problem: format!("{polylines} polyline statement(s) left out: lines are not traced"),
        });
    }
    let (bytes, short_faces) = text::without_short_faces(&bytes);
    if let Some(first) = short_faces.first() {
        let more = match short_faces.len() {
            1 => String::new(),
            n => format!(" and {} more", n - 1),
        };
        warnings.push(FieldIssue {
            field: format!("line {first}{more}"),
            problem: "`f` with fewer than three corners left out: a polygon needs three".into(),
        });
    }
    // Before the partial colours go: `v 1 0 0 0.5 0.5 x` among uncoloured vertices lost its
    // bad word with its colour, and loaded (a tester).
    if let Some((line, reason)) = text::bad_number(&bytes).or_else(|| text::normals_named_without_any(&bytes)) {
        return Err((Some(line), reason));
    }
    let (bytes, partial_colours) = text::without_partial_vertex_colours(&bytes);
    if let Some((coloured, all)) = partial_colours {
        warnings.push(FieldIssue {
            field: "v".into(),
            problem: format!(
                "vertex colours left out: {coloured} of the {all} vertices have one (`v x y z r g b`), the rest none"
            ),
        });
    }
    Ok(Prepared { bytes: bytes.into_owned(), uses, short_faces })
}
