//! Wavefront OBJ/MTL import (through `tobj`): meshes and the MTL materials, mapped onto the
//! seed's model as `docs/models.md` tabulates. `mtllib`, `map_Kd` and `map_Ke` go through
//! `uri::resolve_uri` like every other reference, so a file outside the model's folder is
//! refused. The file is read in four steps: its text made into what tobj reads (`prepare`),
//! parsed with its MTL files (`mtllib`), the materials mapped (`mtl`, `mtl_images`), and the
//! faces made meshes (`meshes`).

mod meshes;
mod mtl;
mod mtl_file;
mod mtl_images;
mod mtl_map;
mod mtllib;
mod polygon;
mod prepare;
mod smoothing;
mod statements;
#[cfg(test)]
mod tests;
mod text;

use std::path::Path;

use crate::uri::UriError;
use glint_scene::Model;

/// Why an OBJ did not load.
#[derive(Debug, thiserror::Error)]
pub enum ObjError {
    #[error("{file}: cannot read the model: {error}")]
    Io { file: std::path::PathBuf, error: std::io::Error },
    #[error("{file}: {error}")]
    Uri { file: std::path::PathBuf, error: UriError },
    #[error("{file}:{}: invalid OBJ ({reason})", line.map_or_else(|| "?".to_string(), |l| l.to_string()))]
    Parse { file: std::path::PathBuf, line: Option<usize>, reason: String },
    #[error("{file}:{line}: invalid MTL ({reason})")]
    Mtl { file: std::path::PathBuf, line: usize, reason: String },
    /// `short_face`: the line of the first face of fewer than three corners, left out, and
    /// how many more there are.
    #[error("{file}: no triangles (points and lines are not traced){}", short_face.map_or_else(String::new, |(line, more)| {
        let more = if more > 0 { format!(" (and {more} more)") } else { String::new() };
        format!("; {}:{line}: a face (`f`) of fewer than three corners{more}, left out: a polygon needs three", file.display())
    }))]
    Empty { file: std::path::PathBuf, short_face: Option<(usize, usize)> },
    /// `field`: `materials.NAME.texture`; `statement`: the MTL file (as a path from the OBJ's
    /// folder) and line naming the texture.
    #[error("{file}: {field} `{uri}`{}: {reason}", statement.as_ref().map_or_else(String::new, |s| format!(" ({}:{})", s.0.display(), s.1)))]
    Texture {
        file: std::path::PathBuf,
        field: String,
        uri: String,
        reason: String,
        statement: Option<Box<(std::path::PathBuf, usize)>>,
    },
}

pub use mtl::DEFAULT_MATERIAL;

/// Loads `path`: faces triangulated (fans), one mesh per OBJ object or group and material.
pub fn load_obj(path: &Path) -> Result<Model, ObjError> {
    let raw = crate::uri::regular_file(path)
        .and_then(|_| std::fs::read(path))
        .map_err(|error| ObjError::Io { file: path.to_owned(), error })?;
    // Cut in the middle: a 1 MB number echoed back made a 2 MB message.
    let parse_error = |line, reason: String| ObjError::Parse {
        file: path.to_owned(),
        line,
        reason: glint_scene::shorten_middle(&reason),
    };
    let mut out = Model::default();
    let prepared = prepare::prepared(&raw, &mut out.warnings).map_err(|(line, reason)| parse_error(line, reason))?;
    let bytes = prepared.bytes;
    // Polygons come whole: `polygon::triangulate` cuts them (tobj's fans overlap on concave ones).
    let options = tobj::LoadOptions { triangulate: false, single_index: true, ..Default::default() };
    let libraries = mtllib::Libraries::new(path);
    let (models, materials) =
        tobj::load_obj_buf(&mut bytes.as_slice(), &options, |mtl| libraries.load(mtl)).map_err(|e| {
            let line = failing_line(&bytes, &options);
            parse_error(line, face_problem(&e, &bytes, line))
        })?;
    let read = libraries.read().map_err(|refused| match refused {
        mtllib::Refused::Uri(error) => ObjError::Uri { file: path.to_owned(), error },
        mtllib::Refused::Number { mtl, line, reason } => {
            let reason = glint_scene::shorten_middle(&reason);
            ObjError::Mtl { file: path.parent().unwrap_or(Path::new("")).join(mtl), line, reason }
        }
    })?;
    out.warnings.extend(read.warnings);
    // With an MTL left out, every name it held would be warned again.
    if !read.left_out {
        out.warnings.extend(mtllib::unknown_materials(&prepared.uses, materials.as_deref().unwrap_or_default()));
    }
    let materials = materials.unwrap_or_default();
    let names = mtl::add_materials(path, &materials, &read.files, &mut out).map_err(
        |mtl_images::TextureError { material, field, uri, reason, statement }| ObjError::Texture {
            file: path.to_owned(),
            field: format!("materials.{material}.{field}"),
            uri,
            reason,
            statement: statement.map(|s| Box::new((path.parent().unwrap_or(Path::new("")).join(&s.0), s.1))),
        },
    )?;
    meshes::add_meshes(&models, &bytes, &names, &mut out);
    if out.meshes.is_empty() {
        let short_face = prepared.short_faces.first().map(|&line| (line, prepared.short_faces.len() - 1));
        return Err(ObjError::Empty { file: path.to_owned(), short_face });
    }
    Ok(out)
}

/// The line at which tobj's parse fails (tobj's errors carry none): the shortest prefix of
/// the file that fails to parse, found by bisection over line counts (about log₂ n parses of
/// prefixes, only on the error path). Materials are not read here: only the OBJ itself.
/// tobj's error, with what a face's index may be where it names a bad one: "face vertex index
/// out of bounds" said neither the index nor the range.
fn face_problem(e: &tobj::LoadError, bytes: &[u8], line: Option<usize>) -> String {
    let statement = |line: usize| {
        bytes.split(|&b| b == b'\n').nth(line - 1).map(String::from_utf8_lossy).unwrap_or_default().trim().to_string()
    };
    let (kind, what) = match e {
        tobj::LoadError::FaceVertexOutOfBounds => ("v", "vertices"),
        tobj::LoadError::FaceTexCoordOutOfBounds => ("vt", "texture coordinates"),
        tobj::LoadError::FaceNormalOutOfBounds => ("vn", "normals"),
        tobj::LoadError::FaceParseError => {
            let rule = "a face is `f` and three or more of v, v/vt, v//vn or v/vt/vn, each a whole number";
            let Some(line) = line else { return format!("{e}: {rule}") };
            let face = statement(line);
            // Digits that no index type holds: a whole number, but one that names no statement.
            let huge = face.split(|c: char| c.is_whitespace() || c == '/').any(|w| {
                let digits = w.strip_prefix('-').unwrap_or(w);
                !digits.is_empty() && digits.bytes().all(|b| b.is_ascii_digit()) && w.parse::<i64>().is_err()
            });
            let huge = if huge { "; an index of this many digits names no statement of any file" } else { "" };
            return format!("`{face}`: {e}: {rule}{huge}");
        }
        _ => return e.to_string(),
    };
    let Some(line) = line else { return e.to_string() };
    // Indices refer to the statements before the face.
    let before = bytes.split(|&b| b == b'\n').take(line - 1);
    let count = before
        .filter(|l| {
            let mut words = l.split(|b| b.is_ascii_whitespace()).filter(|w| !w.is_empty());
            words.next() == Some(kind.as_bytes())
        })
        .count();
    format!(
        "`{}`: {e}; {count} {what} come before it, so an index runs from 1 to {count}, or from −1 back to −{count}",
        statement(line)
    )
}

fn failing_line(bytes: &[u8], options: &tobj::LoadOptions) -> Option<usize> {
    let ends: Vec<usize> =
        bytes.iter().enumerate().filter(|&(_, &b)| b == b'\n').map(|(i, _)| i + 1).chain([bytes.len()]).collect();
    let fails = |lines: usize| {
        let prefix = &bytes[..ends[lines - 1]];
        tobj::load_obj_buf(&mut &prefix[..], options, |_| Err(tobj::LoadError::OpenFileFailed)).is_err()
    };
    let (mut lo, mut hi) = (1, ends.len());
    if !fails(hi) {
        return None;
    }
    while lo < hi {
        let mid = lo + (hi - lo) / 2;
        if fails(mid) { hi = mid } else { lo = mid + 1 }
    }
    Some(lo)
}
