//! A glTF file as the importer reads it: its bytes (capped before reading), parsed and
//! validated by the gltf crate after the checks that crate assumes instead of making, a file of
//! another glTF version named as such, and every buffer through the one URI resolver.

use std::path::Path;

use super::accessor::Buffers;
use super::error::GltfError;
use crate::uri::{MAX_RESOURCE_BYTES, resolve_uri};
use glint_scene::FieldIssue;

/// The file's bytes, refused beyond `MAX_RESOURCE_BYTES` before they are read.
pub(super) fn read_capped(path: &Path) -> std::io::Result<Vec<u8>> {
    let len = crate::uri::regular_file(path)?.len();
    if len > MAX_RESOURCE_BYTES {
        return Err(std::io::Error::new(
            std::io::ErrorKind::InvalidData,
            format!("{len} bytes, more than the {MAX_RESOURCE_BYTES} a model file may have"),
        ));
    }
    std::fs::read(path)
}

/// The file parsed and validated by the gltf crate, after the checks its code assumes
/// instead of making (each panicked on a file found by the gltf_model fuzz target): each
/// primitive's POSITION accessor exists (validation indexes the accessors with it); an image
/// has a URI or a buffer view, and a MIME type with a buffer view; a camera has the
/// projection its type names (`Image::source` and `Camera::projection` unwrap them).
///
/// A POSITION accessor without the `min` and `max` the specification requires is read, with a
/// warning, as three.js, Blender and Assimp read it: Glint bounds geometry from the positions
/// themselves and never reads those two.
pub(super) fn parse(bytes: &[u8], file: &Path, warnings: &mut Vec<FieldIssue>) -> Result<::gltf::Gltf, GltfError> {
    use ::gltf::json::camera::Type as CameraType;
    use ::gltf::json::mesh::Semantic;
    use ::gltf::json::validation::Checked;
    // A scene without `nodes` is valid glTF 2.0 (an empty scene), which the gltf crate's
    // parser refuses ("missing field `nodes`", calling the whole file invalid): such a file is
    // parsed again with `[]` given, on that path alone (a second parse of every file's JSON
    // for a rare case cost each load).
    // Said as such, not as JSON's "EOF while parsing a value" (of a .glb too; a tester).
    if bytes.iter().all(u8::is_ascii_whitespace) {
        let reason = if bytes.is_empty() { "the file is empty (0 bytes)" } else { "the file holds only white space" };
        return Err(GltfError::Parse { file: file.to_owned(), reason: reason.to_string() });
    }
    if let Some(error) = glb_length_short(bytes, file) {
        return Err(error);
    }
    let parsed = ::gltf::Gltf::from_slice_without_validation(bytes).or_else(|e| {
        with_scene_nodes(bytes).map_or(Err(e), |patched| ::gltf::Gltf::from_slice_without_validation(&patched))
    });
    let ::gltf::Gltf { document, blob } = parsed.map_err(|e| {
        other_version(bytes, file)
            .or_else(|| glb_cut_short(bytes, file))
            .or_else(|| not_glb(bytes, file))
            .unwrap_or_else(|| parse_error(file, e, None))
    })?;
    let mut json = document.into_json();
    // A 1.0 file with no collection of 1.0's form parses as an empty 2.0 one: refused by its
    // version, not as a file with no scene (a tester's `{"asset":{"version":"1.0"}}`). A later
    // version that reads as 2.0 is read, with a warning (`asset.version`).
    let major = json.asset.version.split('.').next().and_then(|m| m.trim().parse::<u32>().ok());
    if major.is_some_and(|m| m < 2) {
        let version = format!("`{}`", json.asset.version);
        return Err(GltfError::Version { file: file.to_owned(), where_: "asset.version", version });
    }
    // Glint reads quantised attributes (`accessor::read_vec3`, `read_uv`) and instances
    // (`instancing`) itself; the gltf crate, which would refuse a file for requiring them, is
    // not told.
    json.extensions_required.retain(|e| e != "KHR_mesh_quantization" && e != super::instancing::EXTENSION);
    let invalid = |path: String, problem: &str| GltfError::At {
        file: file.to_owned(),
        path,
        problem: format!("invalid glTF: {problem}"),
    };
    for (i, image) in json.images.iter().enumerate() {
        match (&image.buffer_view, &image.uri, &image.mime_type) {
            (Some(_), _, None) => {
                return Err(invalid(format!("images[{i}].mimeType"), "an image in a buffer view needs its MIME type"));
            }
            (None, None, _) => return Err(invalid(format!("images[{i}]"), "an image needs a uri or a bufferView")),
            _ => {}
        }
    }
    for (i, camera) in json.cameras.iter().enumerate() {
        let named = match camera.type_ {
            Checked::Valid(CameraType::Perspective) => camera.perspective.is_some(),
            Checked::Valid(CameraType::Orthographic) => camera.orthographic.is_some(),
            // Validation names an unknown type.
            Checked::Invalid => true,
        };
        if !named {
            return Err(invalid(format!("cameras[{i}]"), "the camera lacks the projection its type names"));
        }
    }
    // A later 2.x minor version is 2.0 by the specification's rule; any other major is not.
    let version = &json.asset.version;
    if !(version == "2" || version.starts_with("2.")) {
        warnings.push(FieldIssue {
            field: "asset.version".into(),
            problem: format!("`{version}`, not glTF 2.0: read as 2.0, the one version Glint reads"),
        });
    }
    for (m, mesh) in json.meshes.iter().enumerate() {
        for (p, primitive) in mesh.primitives.iter().enumerate() {
            if let Some(index) = primitive.attributes.get(&Checked::Valid(Semantic::Positions))
                && index.value() >= json.accessors.len()
            {
                return Err(GltfError::At {
                    file: file.to_owned(),
                    path: format!("meshes[{m}].primitives[{p}].attributes.POSITION"),
                    problem: format!(
                        "invalid glTF: accessor {} does not exist (the file has {})",
                        index.value(),
                        json.accessors.len()
                    ),
                });
            }
        }
    }
    let positions: std::collections::BTreeSet<usize> = json
        .meshes
        .iter()
        .flat_map(|mesh| &mesh.primitives)
        .filter_map(|primitive| primitive.attributes.get(&Checked::Valid(Semantic::Positions)))
        .map(|index| index.value())
        .collect();
    for index in positions {
        let accessor = &mut json.accessors[index];
        if accessor.min.is_none() || accessor.max.is_none() {
            warnings.push(FieldIssue {
                field: format!("accessors[{index}]"),
                problem: "a POSITION accessor without min and max (glTF requires them): bounds taken from \
                          the positions"
                    .into(),
            });
            // Only validation reads them; it needs three numbers each.
            let unread = || Some(::gltf::json::Value::from(vec![0.0; 3]));
            accessor.min = accessor.min.take().or_else(unread);
            accessor.max = accessor.max.take().or_else(unread);
        }
    }
    let counts = Counts::of(&json);
    let mut errors = Vec::new();
    ::gltf::json::validation::Validate::validate(&json, &json, ::gltf::json::Path::new, &mut |path, error| {
        errors.push((path(), error));
    });
    // An accessor without a bufferView is zeros, with or without sparse values (glTF 2.0,
    // "Accessors"); the gltf crate calls the bufferView of one without sparse missing, and a
    // valid file (a morph target's zero offsets) was refused. Glint reads it (`accessor.rs`).
    errors.retain(|(path, error)| {
        let viewless = path
            .to_string()
            .strip_prefix("accessors[")
            .and_then(|rest| rest.strip_suffix("].bufferView"))
            .and_then(|i| json.accessors.get(i.parse::<usize>().ok()?))
            .is_some_and(|a| a.buffer_view.is_none() && a.sparse.is_none());
        !(viewless && matches!(error, ::gltf::json::validation::Error::Missing))
    });
    if !errors.is_empty() {
        return Err(parse_error(file, ::gltf::Error::Validation(errors), Some(&counts)));
    }
    let document = ::gltf::Document::from_json_without_validation(json);
    Ok(::gltf::Gltf { document, blob })
}

/// The file with `"nodes": []` in each scene that has no `nodes`, if one has none (JSON, or
/// GLB with its JSON chunk rewritten and the rest kept); `None` when none lacks them or the
/// file cannot be read so (the parser then says why).
fn with_scene_nodes(bytes: &[u8]) -> Option<Vec<u8>> {
    let lacks = |json: &serde_json::Value| {
        json["scenes"].as_array().is_some_and(|s| s.iter().any(|s| s.is_object() && s.get("nodes").is_none()))
    };
    let fill = |json: &mut serde_json::Value| {
        for scene in json["scenes"].as_array_mut().into_iter().flatten() {
            if let Some(scene) = scene.as_object_mut() {
                scene.entry("nodes").or_insert_with(|| serde_json::Value::Array(Vec::new()));
            }
        }
    };
    if bytes.starts_with(b"glTF") {
        // A 12-byte header, then the JSON chunk's length and type, its bytes, and the rest.
        let length = u32::from_le_bytes(bytes.get(12..16)?.try_into().ok()?) as usize;
        let end = 20usize.checked_add(length)?;
        let mut json: serde_json::Value = serde_json::from_slice(bytes.get(20..end)?).ok()?;
        if !lacks(&json) {
            return None;
        }
        fill(&mut json);
        let mut chunk = serde_json::to_vec(&json).ok()?;
        // Chunks are 4-byte aligned, JSON padded with spaces.
        chunk.resize(chunk.len().next_multiple_of(4), b' ');
        let rest = bytes.get(end..)?;
        let total = u32::try_from(20 + chunk.len() + rest.len()).ok()?;
        let mut out = Vec::with_capacity(total as usize);
        out.extend_from_slice(&bytes[..8]);
        out.extend_from_slice(&total.to_le_bytes());
        out.extend_from_slice(&u32::try_from(chunk.len()).ok()?.to_le_bytes());
        out.extend_from_slice(&bytes[16..20]);
        out.extend_from_slice(&chunk);
        out.extend_from_slice(rest);
        return Some(out);
    }
    let mut json: serde_json::Value = serde_json::from_slice(bytes).ok()?;
    if !lacks(&json) {
        return None;
    }
    fill(&mut json);
    serde_json::to_vec(&json).ok()
}

/// A file the glTF 2.0 parser refused that says it is another version of glTF (a GLB header's
/// version, or the JSON's `asset.version`, a string in 2.0 and sometimes a number in 1.0):
/// glTF 1.0 keeps its collections in objects keyed by id, which the parser reports only as
/// "expected a sequence".
fn other_version(bytes: &[u8], file: &Path) -> Option<GltfError> {
    let error = |where_, version: String| Some(GltfError::Version { file: file.to_owned(), where_, version });
    if let Some(header) = bytes.strip_prefix(b"glTF") {
        let version = u32::from_le_bytes(header.get(..4)?.try_into().ok()?);
        return if version == 2 { None } else { error("the GLB header's version", version.to_string()) };
    }
    let json: serde_json::Value = serde_json::from_slice(bytes).ok()?;
    let version = match &json["asset"]["version"] {
        serde_json::Value::String(v) => v.clone(),
        serde_json::Value::Number(v) => v.to_string(),
        _ => return None,
    };
    if is_version_2(&version) { None } else { error("asset.version", format!("`{version}`")) }
}

/// A GLB shorter than its header's length says: the parser's "failed to fill whole buffer" did
/// not say that the file was cut short (a tester's GLB truncated to 10–4,000 bytes).
fn glb_cut_short(bytes: &[u8], file: &Path) -> Option<GltfError> {
    let header = bytes.strip_prefix(b"glTF")?;
    let declared = header.get(4..8).map(|l| u32::from_le_bytes([l[0], l[1], l[2], l[3]]));
    let reason = match declared {
        None => format!("the file ends at byte {} inside its 12-byte GLB header: it is cut short", bytes.len()),
        Some(length) if length as usize > bytes.len() => format!(
            "the GLB header gives the file's length as {length} bytes, but it has {}: it is cut short",
            bytes.len()
        ),
        Some(_) => return None,
    };
    Some(GltfError::Parse { file: file.to_owned(), reason })
}

/// A GLB whose header gives a length short of the file's: the bytes past it are no part of the
/// GLB (read without a word, a tester's header said 20 bytes of a 588-byte file). `None` where
/// the file is not a GLB or its header is whole; a length beyond the file is `glb_cut_short`'s.
fn glb_length_short(bytes: &[u8], file: &Path) -> Option<GltfError> {
    let header = bytes.strip_prefix(b"glTF")?;
    let length = u32::from_le_bytes(header.get(4..8)?.try_into().ok()?);
    ((length as usize) < bytes.len()).then(|| GltfError::Parse {
        file: file.to_owned(),
        reason: format!(
            "the GLB header gives the file's length as {length} bytes, but it has {}: a GLB's length is its whole \
             file's (header and chunks), and the bytes past it are no part of it",
            bytes.len()
        ),
    })
}

/// A file named `.glb` that neither begins with the GLB magic `glTF` nor is glTF JSON: said to
/// be no GLB, by its first bytes (its JSON parser's "expected value at line 1 column 1" read a
/// binary header as text; a tester's `glTX`).
fn not_glb(bytes: &[u8], file: &Path) -> Option<GltfError> {
    let glb = file.extension().is_some_and(|e| e.eq_ignore_ascii_case("glb"));
    let json = bytes.iter().find(|b| !b.is_ascii_whitespace()) == Some(&b'{');
    if !glb || json || bytes.starts_with(b"glTF") {
        return None;
    }
    let magic = &bytes[..bytes.len().min(4)];
    let hex: Vec<String> = magic.iter().map(|b| format!("{b:02X}")).collect();
    Some(GltfError::Parse {
        file: file.to_owned(),
        reason: format!(
            "not a GLB: its magic bytes are {:?} ({}), not \"glTF\" (67 6C 54 46), and it is not glTF JSON either",
            String::from_utf8_lossy(magic),
            hex.join(" ")
        ),
    })
}

/// Whether an `asset.version` is glTF 2's (`2.0`, a later 2.x, or `2`).
fn is_version_2(version: &str) -> bool {
    version == "2" || version.starts_with("2.")
}

/// How many items each collection of the file holds: an index out of bounds says how many
/// there are ("Index out of bounds" alone named no range).
struct Counts(Vec<(&'static str, usize)>);

impl Counts {
    fn of(json: &::gltf::json::Root) -> Self {
        let lights =
            json.extensions.as_ref().and_then(|e| e.khr_lights_punctual.as_ref()).map_or(0, |l| l.lights.len());
        Self(vec![
            ("scenes", json.scenes.len()),
            ("nodes", json.nodes.len()),
            ("meshes", json.meshes.len()),
            ("materials", json.materials.len()),
            ("cameras", json.cameras.len()),
            ("skins", json.skins.len()),
            ("accessors", json.accessors.len()),
            ("bufferViews", json.buffer_views.len()),
            ("buffers", json.buffers.len()),
            ("images", json.images.len()),
            ("samplers", json.samplers.len()),
            ("textures", json.textures.len()),
            ("KHR_lights_punctual lights", lights),
        ])
    }

    /// " (the file has N COLLECTION, indices 0 to N − 1)" for the index at `path`, by the field
    /// that holds it; nothing for a field not known here.
    fn hint(&self, path: &str) -> String {
        let field = path.rsplit('.').next().unwrap_or(path);
        let field = field.split('[').next().unwrap_or(field);
        let collection = match field {
            "scene" | "scenes" => "scenes",
            "nodes" | "children" | "joints" | "skeleton" | "node" => "nodes",
            "mesh" => "meshes",
            "material" => "materials",
            "camera" => "cameras",
            "skin" => "skins",
            "light" => "KHR_lights_punctual lights",
            "bufferView" => "bufferViews",
            "buffer" => "buffers",
            "source" => "images",
            "sampler" => "samplers",
            "index" => "textures",
            "indices" | "inverseBindMatrices" | "input" | "output" => "accessors",
            _ if field.chars().all(|c| c.is_ascii_uppercase() || c.is_ascii_digit() || c == '_') => "accessors",
            _ => return String::new(),
        };
        match self.0.iter().find(|(name, _)| *name == collection) {
            Some((name, 0)) => format!(" (the file has no {name})"),
            Some((name, 1)) => format!(" (the file's {name} have only index 0)"),
            Some((name, n)) => format!(" (the file has {n} {name}, indices 0 to {})", n - 1),
            None => String::new(),
        }
    }
}

/// The gltf crate's error with the JSON paths it names (an index out of bounds with what the
/// file has, where `counts` are known); an unsupported required extension (which its
/// validation reports among the others) gets its own message.
fn parse_error(file: &Path, e: ::gltf::Error, counts: Option<&Counts>) -> GltfError {
    match e {
        ::gltf::Error::Validation(errors) => {
            for (path, error) in &errors {
                let path = path.to_string();
                if matches!(error, ::gltf::json::validation::Error::Unsupported)
                    && let Some(rest) = path.strip_prefix("extensionsRequired[")
                    && let Some((index, value)) = rest.split_once(']')
                {
                    return GltfError::RequiredExtension {
                        file: file.to_owned(),
                        index: index.parse().unwrap_or(0),
                        extension: value.trim_start_matches([' ', '=']).trim_matches('"').to_string(),
                    };
                }
            }
            let shown: Vec<String> = errors
                .iter()
                .take(8)
                .map(|(p, e)| {
                    let path = as_written(&p.to_string());
                    let hint = match (e, counts) {
                        (::gltf::json::validation::Error::IndexOutOfBounds, Some(c)) => c.hint(&path),
                        (::gltf::json::validation::Error::Invalid, _) => allowed_values(&path),
                        _ => String::new(),
                    };
                    // One error is said after its path already: not twice ("scene: … scene: …").
                    if errors.len() == 1 { format!("{e}{hint}") } else { format!("{path}: {e}{hint}") }
                })
                .collect();
            let more = errors.len().saturating_sub(shown.len());
            let mut path = errors.first().map(|(p, _)| as_written(&p.to_string())).unwrap_or_default();
            if path.is_empty() {
                path = "(root)".into();
            }
            GltfError::At {
                file: file.to_owned(),
                path,
                problem: format!(
                    "invalid glTF: {}{}",
                    shown.join("; "),
                    if more > 0 { format!("; and {more} more") } else { String::new() }
                ),
            }
        }
        other => GltfError::Parse { file: file.to_owned(), reason: other.to_string() },
    }
}

/// What the glTF 2.0 specification allows where the gltf crate said only "Invalid value", by
/// the field's name; empty for a field not listed.
fn allowed_values(path: &str) -> String {
    let field = path.rsplit('.').next().unwrap_or(path);
    let field = field.split('[').next().unwrap_or(field);
    let allowed = match field {
        "componentType" => {
            "5120 (byte), 5121 (unsigned byte), 5122 (short), 5123 (unsigned short), 5125 (unsigned int) or 5126 (float)"
        }
        "type" if path.starts_with("accessors") => "SCALAR, VEC2, VEC3, VEC4, MAT2, MAT3 or MAT4",
        "type" if path.starts_with("cameras") => "perspective or orthographic",
        "type" if path.contains("KHR_lights_punctual") => "directional, point or spot",
        "mode" => "0 (points) to 6 (triangle fan)",
        "wrapS" | "wrapT" => "33071 (clamp to edge), 33648 (mirrored repeat) or 10497 (repeat)",
        "magFilter" => "9728 (nearest) or 9729 (linear)",
        "minFilter" => "9728, 9729 or 9984 to 9987 (the mipmap filters)",
        "alphaMode" => "OPAQUE, MASK or BLEND",
        "target" => "34962 (array buffer) or 34963 (element array buffer)",
        "min" | "max" => "as many numbers as the accessor's type has components",
        "interpolation" => "LINEAR, STEP or CUBICSPLINE",
        "path" => "translation, rotation, scale or weights",
        "byteStride" => "a multiple of 4 from 4 to 252",
        _ => return String::new(),
    };
    format!(" (allowed: {allowed})")
}

/// A validation path as the file spells it: the gltf crate names an extension by its Rust
/// field (`khrLightsPunctual`), the file by its registered name (`KHR_lights_punctual`).
fn as_written(path: &str) -> String {
    path.split('.')
        .map(|segment| {
            let (prefix, rest) = segment.split_at(segment.len().min(3));
            let vendor = matches!(prefix, "khr" | "ext");
            if !(vendor && rest.starts_with(|c: char| c.is_ascii_uppercase())) {
                return segment.to_string();
            }
            let mut name = prefix.to_ascii_uppercase();
            for c in rest.chars() {
                if c.is_ascii_uppercase() {
                    name.push('_');
                }
                name.push(c.to_ascii_lowercase());
            }
            name
        })
        .collect::<Vec<_>>()
        .join(".")
}

/// Every buffer's bytes: the GLB's BIN chunk, or its URI through the one resolver. A buffer
/// shorter than its declared `byteLength` is an error; a longer one is cut to it.
pub(super) fn load_buffers(gltf: &::gltf::Gltf, path: &Path) -> Result<Buffers, GltfError> {
    let mut out = Vec::new();
    for buffer in gltf.buffers() {
        let field = format!("buffers[{}]", buffer.index());
        let declared = buffer.length();
        let mut data = match buffer.source() {
            ::gltf::buffer::Source::Bin => gltf.blob.clone().ok_or_else(|| GltfError::At {
                file: path.to_owned(),
                path: field.clone(),
                problem: "refers to the GLB's BIN chunk, which the file does not have".into(),
            })?,
            ::gltf::buffer::Source::Uri(uri) => {
                // Not the declared length as the cap: a file may hold more (padding), and a
                // base64 URI's size is only estimated before decoding.
                resolve_uri(path, uri, MAX_RESOURCE_BYTES).map_err(|error| GltfError::Uri {
                    file: path.to_owned(),
                    path: format!("{field}.uri"),
                    error,
                })?
            }
        };
        if data.len() < declared {
            return Err(GltfError::At {
                file: path.to_owned(),
                path: format!("{field}.byteLength"),
                problem: format!("declares {declared} bytes, but the data has {}", data.len()),
            });
        }
        data.truncate(declared);
        out.push(data);
    }
    Ok(Buffers::new(gltf, out))
}
