//! Wavefront OBJ/MTL import (through `tobj`): meshes and the MTL materials, mapped onto the
//! seed's model as `docs/models.md` tabulates. `mtllib`, `map_Kd` and `map_Ke` go through
//! `uri::resolve_uri` like every other reference, so a file outside the model's folder is
//! refused.

use std::path::Path;

use super::mtl::{default_material, expand_colours, map_material, material_names, source, unread_statements};
use super::mtl_images::{Images, Source, TextureError, material_folders};
use super::{obj_smoothing, obj_statements, obj_text, polygon};
use crate::uri::{MAX_RESOURCE_BYTES, UriError, resolve_uri};
use glint_scene::Model;
use glint_scene::{FieldIssue, MeshDesc, Rgb};

/// Why an OBJ did not load.
#[derive(Debug, thiserror::Error)]
pub enum ObjError {
    #[error("{file}: cannot read the model: {error}")]
    Io { file: std::path::PathBuf, error: std::io::Error },
    #[error("{file}: {error}")]
    Uri { file: std::path::PathBuf, error: UriError },
    #[error("{file}:{}: invalid OBJ ({reason})", line.map_or_else(|| "?".to_string(), |l| l.to_string()))]
    Parse { file: std::path::PathBuf, line: Option<usize>, reason: String },
    #[error("{file}: no triangles (points and lines are not traced)")]
    Empty { file: std::path::PathBuf },
    #[error("{file}: materials.{material}.{field} `{uri}`: {reason}")]
    Texture { file: std::path::PathBuf, material: String, field: &'static str, uri: String, reason: String },
}

pub use super::mtl::DEFAULT_MATERIAL;

/// Loads `path`: faces triangulated (fans), one mesh per OBJ object or group and material.
pub fn load_obj(path: &Path) -> Result<Model, ObjError> {
    let raw = crate::uri::regular_file(path)
        .and_then(|_| std::fs::read(path))
        .map_err(|error| ObjError::Io { file: path.to_owned(), error })?;
    let parse_error = |line, reason| ObjError::Parse { file: path.to_owned(), line, reason };
    let mut out = Model::default();
    let (bytes, encoding) = obj_text::decode(&raw).map_err(|reason| parse_error(None, reason))?;
    out.warnings
        .extend(encoding.map(|how| FieldIssue { field: "encoding".into(), problem: format!("not UTF-8: {how}") }));
    // Comments first: a comment ending in `\` continues nothing.
    let bytes = obj_statements::without_trailing_comments(&bytes);
    let bytes = obj_statements::joined_continuations(&bytes);
    let uses = obj_text::material_uses(&bytes);
    let bytes = obj_text::material_statements(&bytes, &["mtllib", "usemtl"]);
    let (bytes, polylines) = obj_text::without_polylines(&bytes);
    if polylines > 0 {
        out.warnings.push(FieldIssue {
            field: "l".into(),
            problem: format!("{polylines} polyline statement(s) left out: lines are not traced"),
        });
    }
    let (bytes, short_faces) = obj_text::without_short_faces(&bytes);
    if let Some(first) = short_faces.first() {
        let more = match short_faces.len() {
            1 => String::new(),
            n => format!(" and {} more", n - 1),
        };
        out.warnings.push(FieldIssue {
            field: format!("line {first}{more}"),
            problem: "`f` with fewer than three corners left out: a polygon needs three".into(),
        });
    }
    let (bytes, partial_colours) = obj_text::without_partial_vertex_colours(&bytes);
    if let Some((coloured, all)) = partial_colours {
        out.warnings.push(FieldIssue {
            field: "v".into(),
            problem: format!(
                "vertex colours left out: {coloured} of the {all} vertices have one (`v x y z r g b`), the rest none"
            ),
        });
    }
    // Checked as the file wrote them: after a node transform one bad number spreads to every
    // component, and the line is lost.
    if let Some((line, reason)) = obj_text::bad_number(&bytes) {
        return Err(parse_error(Some(line), reason));
    }
    // Polygons come whole: `polygon::triangulate` cuts them (tobj's fans overlap on concave ones).
    let options = tobj::LoadOptions { triangulate: false, single_index: true, ..Default::default() };
    // Each `mtllib` on its own: a missing or unreadable one is a warning (as in Assimp and
    // Blender, the geometry stays readable); one outside the model's folder or too large is an
    // error, the first such one reported.
    let refused = std::cell::RefCell::new(None);
    let mtl_warnings = std::cell::RefCell::new(Vec::new());
    let mtl_left_out = std::cell::Cell::new(false);
    // Each loaded MTL's folder (relative to the OBJ's) and how many materials it held, in order.
    let mtl_folders = std::cell::RefCell::new(Vec::<(String, usize)>::new());
    let load_mtl = |uri: &str| -> tobj::MTLLoadResult {
        let field = format!("mtllib `{uri}`");
        let warn = |problem: String| mtl_warnings.borrow_mut().push(FieldIssue { field: field.clone(), problem });
        let text = match resolve_uri(path, uri, MAX_RESOURCE_BYTES) {
            Ok(text) => text,
            Err(ref e) if let Some(mtl) = e.missing_path() => {
                warn(format!(
                    "{} does not exist; the faces naming its materials use `{DEFAULT_MATERIAL}`",
                    mtl.display()
                ));
                mtl_left_out.set(true);
                return Err(tobj::LoadError::OpenFileFailed);
            }
            Err(error) => {
                refused.borrow_mut().get_or_insert(error);
                return Err(tobj::LoadError::OpenFileFailed);
            }
        };
        let loaded = obj_text::decode(&text).and_then(|(text, encoding)| {
            if let Some(how) = encoding {
                warn(format!("not UTF-8: {how}"));
            }
            let text = obj_statements::without_trailing_comments(&text);
            let text = obj_statements::joined_continuations(&text);
            let text = expand_colours(&obj_text::material_statements(&text, &["newmtl"]))
                .map_err(|problem| format!("{uri}:{problem}"))?;
            let loaded = tobj::load_mtl_buf(&mut text.as_slice()).map_err(|e| e.to_string())?;
            let folder = uri.replace('\\', "/").rsplit_once('/').map_or(String::new(), |(f, _)| f.to_string());
            mtl_folders.borrow_mut().push((folder, loaded.0.len()));
            Ok(loaded)
        });
        loaded.map_err(|problem| {
            warn(format!("materials not loaded ({problem}); the faces naming them use `{DEFAULT_MATERIAL}`"));
            mtl_left_out.set(true);
            tobj::LoadError::MaterialParseError
        })
    };
    let (models, materials) = tobj::load_obj_buf(&mut bytes.as_ref(), &options, |mtl| {
        let uri = mtl.to_string_lossy();
        let parts = mtl_files(path, &uri);
        if let [one] = parts.as_slice() {
            return load_mtl(one);
        }
        // `mtllib a.mtl b.mtl`: one result for tobj, the files' materials in order.
        let (mut materials, mut names) = (Vec::new(), std::collections::HashMap::new());
        for part in &parts {
            if let Ok((mut more, map)) = load_mtl(part) {
                names.extend(map.into_iter().map(|(name, i)| (name, i + materials.len())));
                materials.append(&mut more);
            }
        }
        if materials.is_empty() { Err(tobj::LoadError::OpenFileFailed) } else { Ok((materials, names)) }
    })
    .map_err(|e| parse_error(failing_line(&bytes, &options), e.to_string()))?;
    if let Some(error) = refused.into_inner() {
        return Err(ObjError::Uri { file: path.to_owned(), error });
    }
    out.warnings.extend(mtl_warnings.into_inner());
    // With an MTL left out, every name it held would be warned again.
    if !mtl_left_out.get() {
        out.warnings.extend(unknown_materials(&uses, materials.as_deref().unwrap_or_default()));
    }
    let materials = materials.unwrap_or_default();
    out.warnings.extend(unread_statements(&materials));
    let names = material_names(&materials);
    let folders = material_folders(&mtl_folders.into_inner(), materials.len());
    let mut images = Images::default();
    let unread = |TextureError { material, field, uri, reason }| ObjError::Texture {
        file: path.to_owned(),
        material,
        field,
        uri,
        reason,
    };
    for ((m, name), folder) in materials.iter().zip(&names).zip(&folders) {
        let mut material = map_material(m, name, &mut out.warnings);
        let at = Source { obj: path, mtl_folder: folder, material: name };
        if let Some(map) = m.diffuse_texture.as_deref() {
            material.texture = Some(images.texture(&at, map, "texture", &mut out.warnings).map_err(unread)?);
        }
        if let Some(map) = m.unknown_param.get("map_Ke") {
            material.emission_texture =
                Some(images.texture(&at, map, "emission_texture", &mut out.warnings).map_err(unread)?);
            // Ke multiplies map_Ke; without Ke the map alone is the emission.
            if m.emissive.is_none() {
                material.emission = Rgb::splat(1.0);
            }
        }
        out.materials.insert(name.clone(), material);
        out.sources.insert(name.clone(), source(m));
    }
    // Smoothing groups are per face statement; tobj's meshes hold the faces in file order.
    let groups = obj_smoothing::face_groups(&bytes);
    let arities: Vec<Vec<usize>> = models.iter().map(|m| face_arities(&m.mesh)).collect();
    let aligned = arities.iter().map(Vec::len).sum::<usize>() == groups.len();
    let (mut first_face, mut to_smooth) = (0, Vec::new());
    for (model, arities) in models.iter().zip(&arities) {
        let in_groups = aligned.then(|| &groups[first_face..first_face + arities.len()]);
        first_face += arities.len();
        let mesh = &model.mesh;
        let vertices: Vec<[f64; 3]> = mesh.positions.chunks_exact(3).map(|p| [p[0], p[1], p[2]]).collect();
        // tobj refuses face indices beyond the file's vertices, and validation checks again.
        let (triangles, face_of) = triangles(&vertices, mesh, arities, &model.name, &mut out.warnings);
        if triangles.is_empty() {
            continue;
        }
        let mut normals: Option<Vec<[f64; 3]>> = (mesh.normals.len() == mesh.positions.len())
            .then(|| mesh.normals.chunks_exact(3).map(|n| [n[0], n[1], n[2]]).collect());
        // A zero or non-finite normal cannot shade: the whole object is shaded faceted.
        let unusable =
            |n: &[f64; 3]| !(n.iter().all(|c| c.is_finite()) && n.iter().map(|c| c * c).sum::<f64>() > 1e-24);
        let zero_normals = normals.as_ref().is_some_and(|ns| ns.iter().any(unusable));
        if zero_normals {
            normals = None;
        }
        // Each triangle's smoothing group, where the file gives no (usable) normals but groups.
        let smoothing: Option<Vec<u32>> = in_groups
            .filter(|groups| normals.is_none() && groups.iter().any(|&g| g != 0))
            .map(|groups| face_of.iter().map(|&f| groups[f]).collect());
        if zero_normals {
            let instead = if smoothing.is_some() {
                "normals made from its smoothing groups"
            } else {
                "its faces' geometric normals"
            };
            out.warnings.push(FieldIssue {
                field: format!("object `{}`", model.name),
                problem: format!("has zero-length normals; shaded with {instead}"),
            });
        }
        // OBJ's v grows upwards from the image's bottom row; glTF's (and Glint's) downwards
        // from the top row.
        let uvs = (mesh.texcoords.len() / 2 == vertices.len() && !mesh.texcoords.is_empty())
            .then(|| mesh.texcoords.chunks_exact(2).map(|t| [t[0], 1.0 - t[1]]).collect::<Vec<_>>());
        // As the file wrote them, linear as its Kd (multiplied by it).
        let colours = (!mesh.vertex_color.is_empty() && mesh.vertex_color.len() == mesh.positions.len())
            .then(|| mesh.vertex_color.chunks_exact(3).map(|c| [c[0], c[1], c[2]]).collect::<Vec<_>>());
        let material = match mesh.material_id.and_then(|i| names.get(i)) {
            Some(name) => name.clone(),
            None => {
                out.materials.entry(DEFAULT_MATERIAL.into()).or_insert_with(default_material);
                DEFAULT_MATERIAL.into()
            }
        };
        let textured =
            out.materials.get(&material).is_some_and(|m| m.texture.is_some() || m.emission_texture.is_some());
        if textured && uvs.is_none() {
            let which = if mesh.texcoords.is_empty() { "its faces give" } else { "only some of its faces give" };
            out.warnings.push(FieldIssue {
                field: format!("object `{}`", model.name),
                problem: format!(
                    "its material `{material}` is textured but {which} texture coordinates (`vt`): planar ones are used"
                ),
            });
        }
        let mut desc = MeshDesc { vertices, triangles, normals, uvs, colours, material, name: model.name.clone() };
        if let Some(groups) = smoothing {
            to_smooth.push((out.meshes.len(), obj_smoothing::split(&mut desc, &groups)));
        }
        out.meshes.push(desc);
    }
    obj_smoothing::smooth_objects(&mut out.meshes, to_smooth);
    if out.meshes.is_empty() {
        return Err(ObjError::Empty { file: path.to_owned() });
    }
    Ok(out)
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

/// How many vertices each face statement tobj read into `mesh` has.
fn face_arities(mesh: &tobj::Mesh) -> Vec<usize> {
    // tobj lists no arities when every face is a triangle.
    if mesh.face_arities.is_empty() {
        vec![3; mesh.indices.len() / 3]
    } else {
        mesh.face_arities.iter().map(|&n| n as usize).collect()
    }
}

/// The mesh's faces (of `arities` vertices) as triangles: polygons cut by
/// `polygon::triangulate`, points and lines left out; and for each triangle, the face (of the
/// mesh's, in order) it was cut from. A polygon whose edges cross is warned once per object.
fn triangles(
    vertices: &[[f64; 3]],
    mesh: &tobj::Mesh,
    arities: &[usize],
    object: &str,
    warnings: &mut Vec<FieldIssue>,
) -> (Vec<[u32; 3]>, Vec<usize>) {
    let mut out = Vec::with_capacity(mesh.indices.len() / 3);
    let mut face_of = Vec::with_capacity(mesh.indices.len() / 3);
    let (mut start, mut crossing) = (0, Vec::new());
    for (face, &n) in arities.iter().enumerate() {
        let polygon = &mesh.indices[start..start + n];
        start += n;
        if n >= 3 && polygon::triangulate(vertices, polygon, &mut out) == polygon::Cut::SelfIntersecting {
            crossing.push(n);
        }
        face_of.resize(out.len(), face);
    }
    if let Some(n) = crossing.first() {
        let more = if crossing.len() > 1 { format!(" (and {} more faces)", crossing.len() - 1) } else { String::new() };
        warnings.push(FieldIssue {
            field: format!("object `{object}`"),
            problem: format!("a face of {n} vertices crosses itself{more}; cut into the triangles its outline allows"),
        });
    }
    (out, face_of)
}

/// One warning per `usemtl` that names no material of the MTL (its faces take the default),
/// at the first line naming it.
fn unknown_materials(uses: &[obj_text::UseMaterial], materials: &[tobj::Material]) -> Vec<FieldIssue> {
    let mut warned: Vec<&str> = Vec::new();
    let mut out = Vec::new();
    for used in uses {
        let name = if used.name.is_empty() { obj_text::NAMELESS } else { &used.name };
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

/// The line at which tobj's parse fails (tobj's errors carry none): the shortest prefix of
/// the file that fails to parse, found by bisection over line counts (about log₂ n parses of
/// prefixes, only on the error path). Materials are not read here: only the OBJ itself.
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

#[cfg(test)]
mod tests {
    use super::*;

    fn write(dir: &Path, name: &str, text: &str) -> std::path::PathBuf {
        let p = dir.join(name);
        std::fs::write(&p, text).unwrap();
        p
    }

    const QUAD: &str = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\n";

    #[test]
    fn vertex_colours_are_read_as_written_and_a_partial_set_is_left_out_with_a_warning() {
        let dir = tempfile::tempdir().unwrap();
        let whole = "v 0 0 0 1 0 0\nv 1 0 0 0 0.5 0\nv 1 1 0 0 0 2\nv 0 1 0 1 1 1\nf 1 2 3 4\n";
        let m = load_obj(&write(dir.path(), "whole.obj", whole)).unwrap();
        let expected = [[1.0, 0.0, 0.0], [0.0, 0.5, 0.0], [0.0, 0.0, 2.0], [1.0, 1.0, 1.0]];
        assert_eq!(m.meshes[0].colours.as_deref(), Some(&expected[..]));
        assert!(m.warnings.iter().all(|w| w.field != "v"), "{:?}", m.warnings);
        // Two of four: tobj would give the third vertex the fourth's colour, or refuse it.
        let partial = "v 0 0 0 1 0 0\nv 1 0 0\nv 1 1 0 0 0 1\nv 0 1 0\nf 1 2 3 4\n";
        let m = load_obj(&write(dir.path(), "partial.obj", partial)).unwrap();
        assert_eq!((m.meshes[0].colours.as_ref(), m.meshes[0].vertices.len()), (None, 4));
        let warned = m.warnings.iter().find(|w| w.field == "v").expect("a warning");
        assert!(warned.problem.contains("2 of the 4 vertices"), "{}", warned.problem);
        assert!(load_obj(&write(dir.path(), "quad.obj", QUAD)).unwrap().meshes[0].colours.is_none());
    }

    #[test]
    fn a_word_that_is_no_finite_number_is_reported_at_its_line_before_any_transform() {
        let dir = tempfile::tempdir().unwrap();
        for (text, expect) in [
            (
                "v 0 0 0\nv nan 0 0\nv 0 1 0\nf 1 2 3\n",
                ":2: invalid OBJ (`v nan 0 0`: vertex position component x: nan is not a finite number)",
            ),
            (
                "v 0 0 0\nv 1 0 0\nv 0 1e39 0\nf 1 2 3\n",
                ":3: invalid OBJ (`v 0 1e39 0`: vertex position component y: 1e39 is beyond f32's range",
            ),
            (
                "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 inf\nf 1 2 3\n",
                ":4: invalid OBJ (`vt 0 inf`: texture coordinate component v: inf",
            ),
            ("v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 -NaN\nf 1 2 3\n", ":4: invalid OBJ (`vn 0 0 -NaN`: normal component z"),
            // Assimp's number_formats.obj: tobj said only "position parse error".
            (
                "v 0 0 0\nv 1 2. 3.0\nv 1e+2 2.e+1 3.1+e2\nf 1 2 3\n",
                ":3: invalid OBJ (`v 1e+2 2.e+1 3.1+e2`: vertex position component z: `3.1+e2` is not a number)",
            ),
            // What tobj does not read is not checked: a comment, a `vt`'s w, words after a `vn`.
            (
                "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0 # a comment\nvt 0.5 0.5 junk\nvn 0 0 1 # up\nf 1 2 3\nv 0 0 nan\n",
                ":8: invalid OBJ (`v 0 0 nan`: vertex position component z: nan",
            ),
            // tobj dropped a colour it could not read, leaving the colours to the wrong vertices.
            (
                "v 0 0 0 1 0 0\nv 1 0 0 0 x 0\nv 0 1 0 0 0 1\nf 1 2 3\n",
                ":2: invalid OBJ (`v 1 0 0 0 x 0`: vertex colour component g: `x` is not a number)",
            ),
        ] {
            let obj = write(dir.path(), "bad.obj", text);
            let err = load_obj(&obj).expect_err("a bad number is refused").to_string();
            assert!(err.contains(expect), "{err}");
            assert_eq!(err.matches("component").count(), 1, "one report, for the component at fault: {err}");
        }
    }

    #[test]
    fn mtl_fields_map_onto_the_model_by_illum() {
        let dir = tempfile::tempdir().unwrap();
        write(
            dir.path(),
            "m.mtl",
            "newmtl plastic\nKa 0.1 0.1 0.1\nKd 0.5 0.25 0.125\nKs 0.4 0.4 0.4\nNs 50\nillum 2\n\
             newmtl glass\nKd 0.1 0.1 0.1\nKs 0.9 0.9 0.9\nNi 1.33\nd 0.25\nKe 0.5 0 0\nillum 4\n\
             newmtl matte\nKd 0.7 0.7 0.7\nKs 1 1 1\nillum 1\n",
        );
        let obj = write(
            dir.path(),
            "m.obj",
            &format!("mtllib m.mtl\n{QUAD}usemtl plastic\nf 1 2 3\nusemtl glass\nf 1 3 4\nusemtl matte\nf 2 3 4\n"),
        );
        let m = load_obj(&obj).expect("loads");
        let (plastic, glass, matte) = (&m.materials["plastic"], &m.materials["glass"], &m.materials["matte"]);
        assert_eq!((plastic.ka, plastic.kd, plastic.ks), (Rgb::splat(0.1), Rgb([0.5, 0.25, 0.125]), Rgb::splat(0.4)));
        assert_eq!((plastic.shininess, plastic.kr, plastic.kt), (50.0, Rgb::splat(0.0), Rgb::splat(0.0)));
        assert_eq!((glass.kr, glass.kt, glass.emission), (Rgb::splat(0.9), Rgb::splat(0.75), Rgb([0.5, 0.0, 0.0])));
        assert!(glass.ior == 1.33 && glass.ka == glass.kd, "{glass:?}");
        assert_eq!((matte.ks, matte.kr), (Rgb::splat(0.0), Rgb::splat(0.0)));
        // What the file said is kept beside the mapping, in its own terms and order.
        let source = &m.sources["glass"];
        let names: Vec<&str> = source.fields.iter().map(|f| f.0).collect();
        assert_eq!((source.format, names), ("MTL", vec!["Kd", "Ks", "Ke", "Ni", "d", "illum"]));
        assert_eq!(source.fields[4].1, [0.25]);
        let used: Vec<&str> = m.meshes.iter().map(|x| x.material.as_str()).collect();
        assert!(used.contains(&"plastic") && used.contains(&"glass") && used.contains(&"matte"), "{used:?}");
    }

    #[test]
    fn a_colour_of_one_number_is_grey_and_one_of_none_or_two_is_a_warning_naming_the_line() {
        // tobj panicked on `Kd 0.5` (found by the obj_model fuzz target).
        let dir = tempfile::tempdir().unwrap();
        write(dir.path(), "m.mtl", "newmtl grey\nKd 0.5\nKa 0.25 0.5 0.75 1\n");
        let obj = write(dir.path(), "m.obj", &format!("mtllib m.mtl\n{QUAD}usemtl grey\nf 1 2 3\n"));
        let m = load_obj(&obj).expect("loads");
        assert_eq!((m.materials["grey"].kd, m.materials["grey"].ka), (Rgb::splat(0.5), Rgb([0.25, 0.5, 0.75])));
        for bad in ["Kd", "Ks 0.5 0.25"] {
            write(dir.path(), "m.mtl", &format!("newmtl grey\n{bad}\n"));
            let m = load_obj(&obj).expect("loads without the materials");
            let warning = m.warnings.iter().map(ToString::to_string).collect::<Vec<_>>().join("; ");
            assert!(warning.contains("m.mtl:2: `") && warning.contains("takes r [g b]"), "{bad}: {warning}");
        }
    }

    #[test]
    fn an_mtllib_outside_the_folder_is_refused_naming_it() {
        let dir = tempfile::tempdir().unwrap();
        std::fs::create_dir(dir.path().join("model")).unwrap();
        write(dir.path(), "secret.mtl", "newmtl x\nKd 1 0 0\n");
        let obj = write(&dir.path().join("model"), "m.obj", &format!("mtllib ../secret.mtl\n{QUAD}"));
        let message = load_obj(&obj).unwrap_err().to_string();
        assert!(
            message.contains("../secret.mtl") && message.contains("outside the folder of the file that names it"),
            "{message}"
        );
    }

    #[test]
    fn an_opacity_or_exponent_outside_its_range_is_clamped_and_said() {
        let dir = tempfile::tempdir().unwrap();
        write(dir.path(), "m.mtl", "newmtl a\nNs -4\nd 2\nillum 4\nnewmtl b\nTr -0.5\nillum 4\n");
        let obj = write(dir.path(), "m.obj", &format!("mtllib m.mtl\n{QUAD}usemtl a\nf 1 2 3\nusemtl b\nf 1 3 4\n"));
        let m = load_obj(&obj).expect("loads");
        let said: Vec<String> = m.warnings.iter().map(ToString::to_string).collect();
        for w in [
            "materials.a.Ns: Ns -4 is outside [0, ",
            "materials.a.d: `d 2` is an opacity outside [0, 1]; the opacity is clamped to 1",
            "materials.b.Tr: `Tr -0.5` is a transparency outside [0, 1]; the opacity is clamped to 1",
        ] {
            assert!(said.iter().any(|s| s.starts_with(w)), "{w}: {said:?}");
        }
        assert_eq!((m.materials["a"].shininess, m.materials["a"].kt), (0.0, Rgb::splat(0.0)));
    }

    #[test]
    fn faces_of_fewer_than_three_corners_are_left_out_naming_their_lines() {
        let dir = tempfile::tempdir().unwrap();
        let obj = write(dir.path(), "short.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\nf 1 2\nf 3\n");
        let m = load_obj(&obj).expect("the whole face loads");
        assert_eq!(m.meshes[0].triangles.len(), 1);
        let said: Vec<String> = m.warnings.iter().map(ToString::to_string).collect();
        assert!(said.iter().any(|w| w.starts_with("line 5 and 1 more: `f` with fewer than three")), "{said:?}");
        let only = write(dir.path(), "only.obj", "v 0 0 0\nv 1 0 0\nf 1 2\n");
        assert!(load_obj(&only).unwrap_err().to_string().contains("no triangles"));
    }

    #[test]
    fn bad_indices_points_only_and_no_materials_are_clear() {
        let dir = tempfile::tempdir().unwrap();
        let bad = write(dir.path(), "bad.obj", "v 0 0 0\nv 1 0 0\nf 1 2 7\n");
        let message = load_obj(&bad).unwrap_err().to_string();
        assert!(message.contains("bad.obj:3:") && message.contains("invalid OBJ"), "the face's line: {message}");
        let points = write(dir.path(), "p.obj", "v 0 0 0\nv 1 0 0\np 1 2\n");
        assert!(load_obj(&points).unwrap_err().to_string().contains("no triangles"));
        let plain = load_obj(&write(dir.path(), "q.obj", QUAD)).expect("loads");
        assert_eq!(plain.meshes.len(), 1);
        assert_eq!(plain.meshes[0].triangles.len(), 2, "a quad is two triangles");
        assert_eq!(plain.meshes[0].material, DEFAULT_MATERIAL);
    }

    #[test]
    fn a_missing_mtl_an_unknown_or_empty_usemtl_and_windows_1252_names_load_with_warnings() {
        let dir = tempfile::tempdir().unwrap();
        let warnings = |m: &Model| m.warnings.iter().map(|w| format!("{}: {}", w.field, w.problem)).collect::<Vec<_>>();
        let missing = write(dir.path(), "a.obj", &format!("mtllib gone.mtl\n{QUAD}usemtl red\nf 1 2 3\n"));
        let model = load_obj(&missing).expect("the geometry loads without its MTL");
        assert_eq!(model.meshes.len(), 1, "one material throughout: one mesh");
        assert_eq!(model.meshes[0].material, DEFAULT_MATERIAL);
        assert_eq!(model.meshes[0].triangles.len(), 3);
        assert_eq!(warnings(&model).len(), 1, "{:?}", warnings(&model));
        assert!(warnings(&model)[0].contains("mtllib `gone.mtl`: ") && warnings(&model)[0].contains("does not exist"));

        // Terraindæk in Windows-1252 in both files (Assimp's regr01.obj), and Blender's
        // nameless material: a bare newmtl and usemtl (its empty_mat.obj).
        std::fs::write(dir.path().join("w.mtl"), b"newmtl Terraind\xe6k\nKd 1 0 0\nnewmtl \nKd 0 1 0\n").unwrap();
        let mut obj = format!("mtllib w.mtl\n{QUAD}").into_bytes();
        obj.extend_from_slice(b"usemtl Terraind\xe6k\nf 1 2 3\nusemtl \nf 1 3 4\nusemtl blue\nf 2 3 4\n");
        std::fs::write(dir.path().join("w.obj"), obj).unwrap();
        let model = load_obj(&dir.path().join("w.obj")).expect("loads");
        let materials: Vec<&str> = model.meshes.iter().map(|m| m.material.as_str()).collect();
        assert_eq!(materials, [DEFAULT_MATERIAL, "Terraindæk", "unnamed", DEFAULT_MATERIAL]);
        assert_eq!(model.materials["Terraindæk"].kd, Rgb([1.0, 0.0, 0.0]));
        assert_eq!(model.materials["unnamed"].kd, Rgb([0.0, 1.0, 0.0]));
        assert_eq!(
            warnings(&model),
            [
                "encoding: not UTF-8: lines read as windows-1252",
                "mtllib `w.mtl`: not UTF-8: lines read as windows-1252",
                "line 11: usemtl: `blue` is in no MTL file; its faces use `obj-default`",
            ]
        );
        let bare = write(dir.path(), "b.obj", &format!("{QUAD}usemtl\nf 1 2 3\n"));
        assert_eq!(
            warnings(&load_obj(&bare).expect("loads")),
            ["line 6: usemtl: names no material and no MTL file has a nameless one; its faces use `obj-default`"]
        );
    }

    #[test]
    fn tr_is_the_transparency_when_d_is_absent() {
        let dir = tempfile::tempdir().unwrap();
        write(
            dir.path(),
            "m.mtl",
            "newmtl a\nTr 0.25\nillum 4\nnewmtl b\nd 0.5\nTr 0.25\nillum 4\nnewmtl c\nTr x\nillum 4\n",
        );
        let obj = write(
            dir.path(),
            "m.obj",
            &format!("mtllib m.mtl\n{QUAD}usemtl a\nf 1 2 3\nusemtl b\nf 1 3 4\nusemtl c\nf 2 3 4\n"),
        );
        let model = load_obj(&obj).expect("loads");
        assert_eq!(model.materials["a"].kt, Rgb::splat(0.25), "Tr 0.25: k_t = 1 − d = Tr");
        assert_eq!(model.materials["b"].kt, Rgb::splat(0.5), "d wins over Tr");
        assert_eq!(model.materials["c"].kt, Rgb::splat(0.0));
        assert!(model.warnings.iter().any(|w| w.field == "materials.c.Tr" && w.problem.contains("not a number")));
        assert!(
            model.sources["a"].fields.iter().any(|(k, v)| *k == "Tr" && v == &vec![0.25]),
            "{:?}",
            model.sources["a"]
        );
    }

    #[test]
    fn mtl_statements_glint_does_not_read_are_named_once() {
        let dir = tempfile::tempdir().unwrap();
        write(
            dir.path(),
            "m.mtl",
            "newmtl a\nKd 1 1 1\nmap_Bump b.png\nTf 1 1 1\nnewmtl b\nbump b.png\nTr 0\nmap_Ks s.png\n",
        );
        let obj = write(dir.path(), "m.obj", &format!("mtllib m.mtl\n{QUAD}usemtl a\nf 1 2 3\nusemtl b\nf 1 3 4\n"));
        let warnings: Vec<String> =
            load_obj(&obj).expect("loads").warnings.iter().map(|w| format!("{}: {}", w.field, w.problem)).collect();
        assert_eq!(
            warnings,
            [
                "mtllib: statements Glint does not read, left out: Tf (1 material), map_Bump (2 materials), map_Ks (1 material)"
            ]
        );
    }

    #[test]
    fn each_mtllib_is_judged_on_its_own_and_statements_are_read_as_written() {
        let dir = tempfile::tempdir().unwrap();
        std::fs::create_dir(dir.path().join("model")).unwrap();
        let model = dir.path().join("model");
        write(dir.path(), "secret.mtl", "newmtl x\nKd 1 0 0\n");
        // A refusal is not hidden by a later missing file.
        let obj = write(&model, "r.obj", &format!("mtllib ../secret.mtl\nmtllib gone.mtl\n{QUAD}"));
        let message = load_obj(&obj).unwrap_err().to_string();
        assert!(
            message.contains("../secret.mtl") && message.contains("outside the folder of the file that names it"),
            "{message}"
        );
        // Indented and tab-separated statements, a `#word` comment, a real `unnamed` beside the
        // nameless material.
        write(&model, "m.mtl", "newmtl red\nKd 1 0 0\n#map_Bump b.png\nnewmtl\tunnamed\nKd 0 0 1\nnewmtl\nKd 0 1 0\n");
        let text = format!("  mtllib m.mtl\n{QUAD}  usemtl red\nf 1 2 3\nusemtl\tunnamed\nf 1 3 4\nusemtl\nf 2 3 4\n");
        let m = load_obj(&write(&model, "m.obj", &text)).expect("loads");
        let materials: Vec<&str> = m.meshes.iter().map(|mesh| mesh.material.as_str()).collect();
        assert_eq!(materials, [DEFAULT_MATERIAL, "red", "unnamed", "unnamed-2"]);
        assert_eq!(m.materials["unnamed-2"].kd, Rgb([0.0, 1.0, 0.0]), "the nameless one");
        assert!(m.warnings.is_empty(), "{:?}", m.warnings);
        // An MTL that does not parse is one warning, not one more for every name it held.
        write(&model, "m.mtl", "newmtl red\nKd 0.5 0.25\n");
        let m = load_obj(&model.join("m.obj")).expect("loads without its materials");
        assert_eq!(m.warnings.len(), 1, "{:?}", m.warnings);
        assert!(m.warnings[0].problem.contains("m.mtl:2:"), "{:?}", m.warnings);
    }

    fn png(path: &Path) {
        let mut out = Vec::new();
        let mut encoder = png::Encoder::new(&mut out, 2, 1);
        encoder.set_color(png::ColorType::Rgba);
        encoder.write_header().unwrap().write_image_data(&[255, 0, 0, 255, 0, 0, 255, 255]).unwrap();
        std::fs::write(path, out).unwrap();
    }

    #[test]
    fn map_kd_map_ke_and_vt_become_textures_and_uvs() {
        let dir = tempfile::tempdir().unwrap();
        png(&dir.path().join("tex.png"));
        write(
            dir.path(),
            "m.mtl",
            "newmtl t\nKa 0.5 0.5 0.5\nKd 1 1 1\nmap_Kd -s 2 2 1 .\\tex.png\nnewmtl e\nmap_Ke tex.png\n",
        );
        let obj = write(
            dir.path(),
            "m.obj",
            "mtllib m.mtl\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 1 0.25\nvt 0 1\n\
             usemtl t\nf 1/1 2/2 3/3\nusemtl e\nf 1/1 3/3 4/4\n",
        );
        let m = load_obj(&obj).expect("loads");
        let (t, e) = (&m.materials["t"], &m.materials["e"]);
        let texture = t.texture.as_ref().expect("map_Kd is a texture");
        assert_eq!(texture.path, "tex.png", "`.\\` read as the folder");
        let image = texture.image.as_ref().expect("decoded");
        assert_eq!((image.width(), image.height(), image.texels()[0]), (2, 1, [1.0, 0.0, 0.0, 1.0]));
        // `-s 2 2 1` tiles the image twice each way, about OBJ's origin (v up): in Glint's
        // space (v down) v' = 2·v + 1 − 2.
        let placed = texture.transform.expect("-s is applied");
        assert_eq!((placed.scale, placed.offset, placed.rotation), ([2.0, 2.0], [0.0, -1.0], 0.0));
        assert!(m.warnings.iter().all(|w| w.field != "materials.t.texture"), "{:?}", m.warnings);
        let glow = e.emission_texture.as_ref().expect("map_Ke is an emission texture");
        assert!(std::sync::Arc::ptr_eq(glow.image.as_ref().unwrap(), image), "one decode per image file");
        assert_eq!(e.emission, Rgb::splat(1.0), "map_Ke without Ke");
        // OBJ's v is flipped into glTF's convention.
        let uvs = m.meshes[0].uvs.as_ref().expect("vt read");
        assert_eq!(&uvs[..3], &[[0.0, 1.0], [1.0, 1.0], [1.0, 0.75]]);
    }

    #[test]
    fn continued_statements_and_trailing_comments_read_as_the_plain_file() {
        let dir = tempfile::tempdir().unwrap();
        write(dir.path(), "m.mtl", "newmtl red # the paint\nKd 0.9 0.1 0.1 # red\n");
        let plain =
            write(dir.path(), "plain.obj", &format!("mtllib m.mtl\n{QUAD}usemtl red\nf 1 3 4\nv 1 1 1\nf 1 2 5\n"));
        let annotated = write(
            dir.path(),
            "annotated.obj",
            "mtllib m.mtl # materials\nv 0 0 0\nv 1 0 0 # x\nv 1 1 0\nv 0 1 0#top\nf 1 2 \\\n   3 4 # base\n\
             usemtl red # the paint\nf 1 \\\r\n3 \\\n4 # see \\\nv 1 1 1\nf 1 2 5\n",
        );
        let (a, b) = (load_obj(&plain).expect("plain"), load_obj(&annotated).expect("annotated"));
        assert_eq!(a.meshes, b.meshes);
        assert_eq!(b.materials["red"].kd, Rgb([0.9, 0.1, 0.1]));
        assert!(b.warnings.iter().all(|w| !w.problem.contains("red")), "{:?}", b.warnings);
        // A line that does not parse after them is still named by its own number.
        let bad = write(dir.path(), "bad.obj", "v 0 0 0 # a\nf 1 \\\n 2\nv 1 x 0\n");
        assert!(load_obj(&bad).unwrap_err().to_string().contains("bad.obj:4"));
    }

    #[test]
    fn faces_in_a_smoothing_group_without_normals_get_vertex_normals() {
        let dir = tempfile::tempdir().unwrap();
        write(dir.path(), "m.mtl", "newmtl a\nnewmtl b\n");
        // A pyramid over the unit square, its sides smooth (two materials, so tobj splits it in
        // two meshes), its base flat; then a flat tetrahedron, and one half in a group.
        let obj = "mtllib m.mtl\nv 0 0 0\nv 1 0 0\nv 1 0 1\nv 0 0 1\nv 0.5 1 0.5\n\
                   o pyramid\ns 1\nusemtl a\nf 1 5 2\nf 2 5 3\nusemtl b\nf 3 5 4\nf 4 5 1\n\
                   o base\ns off\nf 1 2 3 4\n\
                   o tetra\nf 1 2 5\nf 2 3 5\n\
                   o half\ns 2\nf 1 2 5\ns 0\nf 2 3 5\n";
        let m = load_obj(&write(dir.path(), "m.obj", obj)).expect("loads");
        let by_name = |name: &'static str| m.meshes.iter().filter(move |mesh| mesh.name == name);
        let apex = [0.5, 1.0, 0.5];
        for side in by_name("pyramid") {
            let normals = side.normals.as_ref().expect("smooth sides have vertex normals");
            let at_apex = side.vertices.iter().position(|v| *v == apex).expect("the apex");
            // Shared across the two meshes (materials): the four sides' mean is straight up.
            assert!((normals[at_apex][1] - 1.0).abs() < 1e-12, "{:?}", normals[at_apex]);
        }
        assert_eq!(by_name("pyramid").count(), 2);
        for flat in ["base", "tetra"] {
            assert!(by_name(flat).all(|mesh| mesh.normals.is_none()), "{flat} is shaded with its faces' normals");
        }
        // Half in a group, half not: the edge between them stays hard (its vertices split),
        // the face outside the group keeps its own normal.
        let half = by_name("half").next().expect("half");
        let normals = half.normals.as_ref().expect("smoothing made normals");
        assert_eq!(half.vertices.len(), 6, "the two shared vertices split");
        let face = |t: [u32; 3]| t.map(|v| half.vertices[v as usize]);
        let [a, b, c] = face(half.triangles[1]);
        let (e1, e2) = ([b[0] - a[0], b[1] - a[1], b[2] - a[2]], [c[0] - a[0], c[1] - a[1], c[2] - a[2]]);
        let n = [e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0]];
        let length = n.iter().map(|c| c * c).sum::<f64>().sqrt();
        for v in half.triangles[1] {
            let got = normals[v as usize];
            assert!((0..3).all(|k| (got[k] - n[k] / length).abs() < 1e-12), "{got:?}");
        }
        assert!(m.warnings.iter().all(|w| !w.field.contains("half")), "{:?}", m.warnings);
    }

    #[test]
    fn a_textured_material_on_faces_without_texture_coordinates_is_warned() {
        let dir = tempfile::tempdir().unwrap();
        png(&dir.path().join("tex.png"));
        write(dir.path(), "m.mtl", "newmtl t\nmap_Kd tex.png\n");
        let with = "mtllib m.mtl\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 1 1\nusemtl t\n";
        for (faces, which) in [
            ("f 1/1 2/2 3/3\n", None),
            ("f 1 2 3\n", Some("its faces give")),
            ("f 1/1 2/2 3/3\nf 1 3 4\n", Some("only some")),
        ] {
            let m = load_obj(&write(dir.path(), "m.obj", &format!("{with}{faces}"))).expect("loads");
            let warned = m.warnings.iter().find(|w| w.problem.contains("textured but"));
            match which {
                None => assert!(warned.is_none(), "{faces}: {warned:?}"),
                Some(which) => assert!(
                    warned.is_some_and(|w| w.problem.contains(which) && w.problem.contains("`t`")),
                    "{faces}: {:?}",
                    m.warnings
                ),
            }
        }
    }

    #[test]
    fn an_mtllib_naming_several_files_reads_each_and_a_name_with_spaces_stays_one() {
        let dir = tempfile::tempdir().unwrap();
        write(dir.path(), "a.mtl", "newmtl red\nKd 1 0 0\n");
        write(dir.path(), "b.mtl", "newmtl blue\nKd 0 0 1\n");
        write(dir.path(), "my model.mtl", "newmtl green\nKd 0 1 0\n");
        let faces = |a: &str, b: &str| {
            format!("v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nusemtl {a}\nf 1 2 3\nusemtl {b}\nf 1 3 4\n")
        };
        let m = load_obj(&write(dir.path(), "two.obj", &format!("mtllib a.mtl b.mtl\n{}", faces("red", "blue"))))
            .expect("loads");
        assert_eq!((m.materials["red"].kd, m.materials["blue"].kd), (Rgb([1.0, 0.0, 0.0]), Rgb([0.0, 0.0, 1.0])));
        assert!(m.meshes.iter().all(|mesh| mesh.material != DEFAULT_MATERIAL), "{:?}", m.warnings);
        let m =
            load_obj(&write(dir.path(), "spaced.obj", &format!("mtllib my model.mtl\n{}", faces("green", "green"))))
                .expect("loads");
        assert_eq!(m.materials["green"].kd, Rgb([0.0, 1.0, 0.0]));
        // One of the two missing: the other's materials are read, the missing one warned.
        let m = load_obj(&write(dir.path(), "gone.obj", &format!("mtllib a.mtl gone.mtl\n{}", faces("red", "red"))))
            .expect("loads");
        assert_eq!(m.materials["red"].kd, Rgb([1.0, 0.0, 0.0]));
        assert!(
            m.warnings.iter().any(|w| w.field == "mtllib `gone.mtl`" && w.problem.contains("does not exist")),
            "{:?}",
            m.warnings
        );
    }

    #[test]
    fn a_texture_is_found_beside_its_mtl_then_beside_the_obj() {
        let dir = tempfile::tempdir().unwrap();
        let mats = dir.path().join("mats");
        std::fs::create_dir(&mats).unwrap();
        png(&mats.join("near.png"));
        png(&dir.path().join("far.png"));
        write(&mats, "m.mtl", "newmtl a\nmap_Kd near.png\nnewmtl b\nmap_Kd far.png\n");
        write(&mats, "c.mtl", "newmtl c\nmap_Kd gone.png\n");
        let faces = "usemtl a\nf 1 2 3\nusemtl b\nf 1 3 4\n";
        let m = load_obj(&write(dir.path(), "m.obj", &format!("mtllib mats/m.mtl\n{QUAD}{faces}"))).expect("loads");
        let path = |name: &str| m.materials[name].texture.as_ref().map(|t| t.path.clone());
        assert_eq!((path("a"), path("b")), (Some("mats/near.png".into()), Some("far.png".into())));
        // Absent from both: the error names the texture as the MTL places it.
        let obj = write(dir.path(), "c.obj", &format!("mtllib mats/c.mtl\n{QUAD}usemtl c\nf 1 2 3\n"));
        let message = load_obj(&obj).unwrap_err().to_string();
        assert!(message.contains("`mats/gone.png`") && message.contains("No such file"), "{message}");
    }

    #[test]
    fn a_map_kd_outside_the_folder_or_not_an_image_is_an_error_naming_it() {
        let dir = tempfile::tempdir().unwrap();
        std::fs::create_dir(dir.path().join("model")).unwrap();
        png(&dir.path().join("secret.png"));
        write(&dir.path().join("model"), "bad.png", "not an image");
        for (map, reason) in
            [("../secret.png", "outside the folder of the file that names it"), ("bad.png", "not a PNG or JPEG")]
        {
            write(&dir.path().join("model"), "m.mtl", &format!("newmtl t\nmap_Kd {map}\n"));
            let obj = write(&dir.path().join("model"), "m.obj", &format!("mtllib m.mtl\n{QUAD}usemtl t\nf 1 2 3\n"));
            let message = load_obj(&obj).unwrap_err().to_string();
            assert!(
                message.contains("m.obj")
                    && message.contains("materials.t.texture")
                    && message.contains(map)
                    && message.contains(reason),
                "{message}"
            );
        }
    }
}
