//! The images an OBJ's materials name (`map_Kd`, `map_Ke`): each statement's options placed as
//! Glint's texture, the file found beside the MTL that names it, then beside the OBJ, and each
//! file decoded once however many materials name it.

use std::path::Path;
use std::sync::Arc;

use super::mtl_file::MtlFile;
use super::mtl_map::parse_map;
use crate::texture::decode_texture;
use crate::uri::{MAX_RESOURCE_BYTES, resolve_uri};
use glint_scene::{ColorSpace, FieldIssue, TextureDesc, TextureImage, UvTransform, Wrap};

/// A texture that could not be read: the material and field naming it, the file as named, why,
/// and the MTL file and line of its statement where found.
#[derive(Debug)]
pub(super) struct TextureError {
    pub material: String,
    pub field: &'static str,
    pub uri: String,
    pub reason: String,
    pub statement: Option<Box<(String, usize)>>,
}

/// The images of one model, each decoded once however many materials name it.
#[derive(Default)]
pub(super) struct Images {
    decoded: Vec<(String, Arc<TextureImage>)>,
}

/// Where a material's texture statement is read: the OBJ file, the MTL that defined the
/// material (none where the files' counts did not add up: the OBJ's folder is searched), and
/// the material's name in the scene and in the MTL.
#[derive(Clone, Copy)]
pub(super) struct Source<'a> {
    pub obj: &'a Path,
    pub mtl: Option<&'a MtlFile>,
    pub material: &'a str,
    pub mtl_name: &'a str,
    /// Which of its file's materials of that name it is (from 0).
    pub nth: usize,
}

impl Source<'_> {
    fn mtl_folder(&self) -> &str {
        self.mtl.map_or("", |f| f.folder.as_str())
    }
}

impl Images {
    /// A `map_Kd`/`map_Ke` statement as a texture, bilinear, repeating unless `-clamp on`, placed
    /// by its `-o` and `-s` options; the options Glint's textures have no term for are named
    /// in a warning. Windows separators, common in MTL files, are read as `/`.
    pub(super) fn texture(
        &mut self,
        at: &Source<'_>,
        statement: &str,
        field: &'static str,
        warnings: &mut Vec<FieldIssue>,
    ) -> Result<TextureDesc, TextureError> {
        let map = parse_map(statement);
        let mut warn = |problem: String| {
            warnings.push(FieldIssue { field: format!("materials.{}.{field}", at.material), problem })
        };
        if map.unread {
            warn(format!(
                "options of `{statement}` cannot be read as MTL writes them: all left out, the file its last word"
            ));
        }
        if !map.ignored.is_empty() {
            warn(format!("`{statement}`: {} left out (no term in Glint's textures)", map.ignored.join(", ")));
        }
        if map.clamp {
            warn(format!(
                "`{statement}`: -clamp on is sampled clamped to the edge texels, where MTL leaves the material \
                 untextured outside the one copy"
            ));
        }
        let uri = map.file.replace('\\', "/");
        let uri = uri.strip_prefix("./").unwrap_or(&uri).to_string();
        // Relative to the MTL's folder, as Blender and three.js read it, then to the OBJ's (where
        // an MTL beside the OBJ puts both). Absent from both, the error names it where the MTL
        // places it.
        let beside_mtl = (!at.mtl_folder().is_empty() && !uri.contains(':') && !uri.starts_with('/'))
            .then(|| format!("{}/{uri}", at.mtl_folder()));
        let mut found = self.image(at, beside_mtl.as_deref().unwrap_or(&uri), field);
        if beside_mtl.is_some() && matches!(found, Err((_, Absent::Yes))) {
            found = match self.image(at, &uri, field) {
                Err((_, Absent::Yes)) => found,
                beside_obj => beside_obj,
            };
        }
        let keyword = if field == "emission_texture" { "map_Ke" } else { "map_Kd" };
        let mut t = found.map_err(|(e, _)| TextureError {
            statement: at
                .mtl
                .and_then(|f| Some(Box::new((f.uri.clone(), f.statement_line(at.mtl_name, at.nth, keyword)?)))),
            ..e
        })?;
        if map.clamp {
            (t.wrap_s, t.wrap_t) = (Wrap::ClampToEdge, Wrap::ClampToEdge);
        }
        // In OBJ's space u' = s·u + o with v up; Glint's v is 1 − v (down), so v' = s·v + 1 − s − o.
        let [su, sv] = map.scale;
        let [ou, ov] = map.offset;
        if (map.scale, map.offset) != ([1.0; 2], [0.0; 2]) {
            t.transform = Some(UvTransform { offset: [ou, 1.0 - sv - ov], rotation: 0.0, scale: [su, sv] });
        }
        Ok(t)
    }

    /// The image `uri` names (relative to the OBJ's folder), decoded once; an error says
    /// whether the file is absent.
    fn image(
        &mut self,
        at: &Source<'_>,
        uri: &str,
        field: &'static str,
    ) -> Result<TextureDesc, (TextureError, Absent)> {
        if let Some((_, image)) = self.decoded.iter().find(|(u, _)| u == uri) {
            return Ok(TextureDesc::decoded(uri.to_string(), Arc::clone(image)));
        }
        let error = |reason: String| TextureError {
            material: at.material.to_string(),
            field,
            uri: uri.to_string(),
            reason,
            statement: None,
        };
        let bytes = resolve_uri(at.obj, uri, MAX_RESOURCE_BYTES).map_err(|e| {
            let absent = if e.is_not_found() { Absent::Yes } else { Absent::No };
            (error(e.to_string()), absent)
        })?;
        let image = Arc::new(decode_texture(&bytes, ColorSpace::Srgb).map_err(|e| (error(e.to_string()), Absent::No))?);
        self.decoded.push((uri.to_string(), Arc::clone(&image)));
        Ok(TextureDesc::decoded(uri.to_string(), image))
    }
}

/// Whether a texture's file is absent (and another place may be tried).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Absent {
    Yes,
    No,
}

/// Each material's MTL file, from the loaded files' counts (in tobj's order); none for any
/// where the counts do not add up.
pub(super) fn material_files(loaded: &[MtlFile], materials: usize) -> Vec<Option<&MtlFile>> {
    let files: Vec<Option<&MtlFile>> = loaded.iter().flat_map(|f| std::iter::repeat_n(Some(f), f.materials)).collect();
    if files.len() == materials { files } else { vec![None; materials] }
}
