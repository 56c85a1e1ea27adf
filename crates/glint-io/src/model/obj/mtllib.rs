//! An OBJ's `mtllib` statements: each MTL file read for tobj, what went wrong with it kept for
//! the importer, and the `usemtl` names no file defines.

use std::cell::{Cell, RefCell};
use std::path::Path;

use super::mtl::{DEFAULT_MATERIAL, bad_number, expand_colours, long_colours};
use super::mtl_file::MtlFile;
use super::{statements, text};
use crate::uri::{MAX_RESOURCE_BYTES, UriError, resolve_uri};
use glint_scene::FieldIssue;

/// The MTL files of one OBJ as tobj asks for them, one `mtllib` statement at a time. A missing
/// or unreadable one is a warning (as in Assimp and Blender, the geometry stays readable); one
/// outside the model's folder or too large, or with a number that cannot be read, is an error,
/// the first such one reported. Cells: tobj takes its loader as `Fn`.
pub(super) struct Libraries<'a> {
    obj: &'a Path,
    refused: RefCell<Option<Refused>>,
    warnings: RefCell<Vec<FieldIssue>>,
    left_out: Cell<bool>,
    /// Each loaded MTL, in order.
    files: RefCell<Vec<MtlFile>>,
}

/// Why an OBJ's MTL file is an error.
#[derive(Debug)]
pub(super) enum Refused {
    /// Outside the model's folder, too large, or not a file.
    Uri(UriError),
    /// A number of a statement Glint reads (`mtl::bad_number`): the MTL file as the OBJ names
    /// it, the line, why.
    Number { mtl: String, line: usize, reason: String },
}

/// What reading an OBJ's MTL files gave besides its materials.
pub(super) struct Read {
    pub warnings: Vec<FieldIssue>,
    /// Whether an MTL file was missing or unreadable.
    pub left_out: bool,
    pub files: Vec<MtlFile>,
}

impl<'a> Libraries<'a> {
    pub fn new(obj: &'a Path) -> Self {
        Self {
            obj,
            refused: RefCell::new(None),
            warnings: RefCell::new(Vec::new()),
            left_out: Cell::new(false),
            files: RefCell::new(Vec::new()),
        }
    }

    /// The materials of one `mtllib` statement (`mtl`, its rest), for tobj.
    pub fn load(&self, mtl: &Path) -> tobj::MTLLoadResult {
        let uri = mtl.to_string_lossy();
        let parts = mtl_files(self.obj, &uri);
        if let [one] = parts.as_slice() {
            return self.load_file(one);
        }
        // `mtllib a.mtl b.mtl`: one result for tobj, the files' materials in order.
        let (mut materials, mut names) = (Vec::new(), std::collections::HashMap::new());
        for part in &parts {
            if let Ok((mut more, map)) = self.load_file(part) {
                names.extend(map.into_iter().map(|(name, i)| (name, i + materials.len())));
                materials.append(&mut more);
            }
        }
        if materials.is_empty() { Err(tobj::LoadError::OpenFileFailed) } else { Ok((materials, names)) }
    }

    /// What the files read gave, or the first file refused.
    pub fn read(self) -> Result<Read, Refused> {
        if let Some(error) = self.refused.into_inner() {
            return Err(error);
        }
        Ok(Read { warnings: self.warnings.into_inner(), left_out: self.left_out.get(), files: self.files.into_inner() })
    }

    fn load_file(&self, uri: &str) -> tobj::MTLLoadResult {
        let field = format!("mtllib `{uri}`");
        let warn = |problem: String| self.warnings.borrow_mut().push(FieldIssue { field: field.clone(), problem });
        let text = match resolve_uri(self.obj, uri, MAX_RESOURCE_BYTES) {
            Ok(text) => text,
            Err(ref e) if let Some(mtl) = e.missing_path() => {
                warn(format!(
                    "{} does not exist; the faces naming its materials use `{DEFAULT_MATERIAL}`",
                    mtl.display()
                ));
                self.left_out.set(true);
                return Err(tobj::LoadError::OpenFileFailed);
            }
            Err(error) => {
                self.refused.borrow_mut().get_or_insert(Refused::Uri(error));
                return Err(tobj::LoadError::OpenFileFailed);
            }
        };
        let loaded = text::decode(&text).and_then(|(text, encoding)| {
            if let Some(how) = encoding {
                warn(format!("not UTF-8: {how}"));
            }
            let text_before_joining = String::from_utf8_lossy(&text).into_owned();
            let text = statements::without_trailing_comments(&text);
            let text = statements::joined_continuations(&text);
            if let Some((line, reason)) = bad_number(&text) {
                let number = Refused::Number { mtl: uri.to_string(), line, reason };
                self.refused.borrow_mut().get_or_insert(number);
                return Err("a number that cannot be read".to_string());
            }
            if let [(line, first), rest @ ..] = long_colours(&text).as_slice() {
                let more = match rest.len() {
                    0 => String::new(),
                    1 => " (and 1 more line)".to_string(),
                    n => format!(" (and {n} more lines)"),
                };
                warn(format!(
                    "line {line}: `{first}`: a colour is r g b; the numbers after the third are ignored{more}"
                ));
            }
            let text = expand_colours(&text::material_statements(&text, &["newmtl"]))
                .map_err(|problem| format!("{uri}:{problem}"))?;
            let loaded = tobj::load_mtl_buf(&mut text.as_slice()).map_err(|e| e.to_string())?;
            // tobj maps a name to its last definition: an earlier one was dropped without a
            // word (two `newmtl red`, the faces took the second's colour; a tester).
            let mut counts: std::collections::BTreeMap<&str, usize> = std::collections::BTreeMap::new();
            for m in &loaded.0 {
                *counts.entry(m.name.as_str()).or_default() += 1;
            }
            for (name, n) in counts.into_iter().filter(|(_, n)| *n > 1) {
                warn(format!("`newmtl {name}` is written {n} times; the faces naming it use the last"));
            }
            let folder = uri.replace('\\', "/").rsplit_once('/').map_or(String::new(), |(f, _)| f.to_string());
            self.files.borrow_mut().push(MtlFile {
                uri: uri.to_string(),
                folder,
                materials: loaded.0.len(),
                text: text_before_joining,
            });
            Ok(loaded)
        });
        loaded.map_err(|problem| {
            warn(format!("materials not loaded ({problem}); the faces naming them use `{DEFAULT_MATERIAL}`"));
            self.left_out.set(true);
            tobj::LoadError::MaterialParseError
        })
    }
}

/// The MTL files an `mtllib` statement names: its whole rest where that is a file beside the
/// OBJ (a name with spaces, as Blender writes `mtllib my model.mtl`); else, as the OBJ
/// specification allows, each of its words that ends in `.mtl` where they all do
/// (`mtllib a.mtl b.mtl`); else the whole rest (missing, warned).
fn mtl_files(obj: &Path, rest: &str) -> Vec<String> {
    let folder = obj.parent().unwrap_or(Path::new("."));
    let words: Vec<&str> = rest.split_whitespace().collect();
    let all_mtl = words.len() > 1 && words.iter().all(|w| w.to_ascii_lowercase().ends_with(".mtl"));
    if !all_mtl || folder.join(rest).is_file() {
        return vec![rest.to_string()];
    }
    words.into_iter().map(str::to_string).collect()
}

/// One warning per `usemtl` that names no material of the MTL (its faces take the default),
/// at the first line naming it.
pub(super) fn unknown_materials(uses: &[text::UseMaterial], materials: &[tobj::Material]) -> Vec<FieldIssue> {
    let mut warned: Vec<&str> = Vec::new();
    let mut out = Vec::new();
    for used in uses {
        let name = if used.name.is_empty() { text::NAMELESS } else { &used.name };
        if warned.contains(&name) || materials.iter().any(|m| m.name == name) {
            continue;
        }
        warned.push(name);
        let problem = if used.name.is_empty() {
            format!("names no material and no MTL file has a nameless one; its faces use `{DEFAULT_MATERIAL}`")
        } else {
            format!("`{}` is in no MTL file; its faces use `{DEFAULT_MATERIAL}`", used.name)
        };
        out.push(FieldIssue { field: format!("line {}: usemtl", used.line), problem });
    }
    out
}
