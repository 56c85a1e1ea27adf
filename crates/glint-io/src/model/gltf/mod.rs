//! glTF 2.0 import (`.gltf` with external or `data:` buffers, `.glb`): the gltf crate parses
//! and validates the JSON (`file.rs`); every buffer URI goes through `uri::resolve_uri` (never
//! the crate's importer, which reads any path a file names); accessors are read with their
//! bounds checked (`accessor.rs`); morph targets and skins pose the primitives (`deform.rs`); the node hierarchy is composed in f64 (`transform.rs`)
//! and the world-space vertices rounded once; materials, lights and cameras are mapped onto
//! the seed's model (`material.rs`, `punctual.rs`). Every error names the file and the JSON
//! path at fault.

mod accessor;
mod deform;
mod error;
mod file;
mod instancing;
mod material;
mod nodes;
mod punctual;
pub(crate) use punctual::CAMERA_SKIPPED;
mod texture;

use std::collections::BTreeMap;
use std::path::Path;

use ::gltf::mesh::Mode;

use self::accessor::Buffers;
use super::ImportOptions;
use glint_scene::{FieldIssue, MAX_COORD, MIN_DIRECTION_LENGTH, MeshDesc};
use glint_scene::{Mat4, Model};

pub use self::error::{GltfError, SUPPORTED_EXTENSIONS};
use self::file::{load_buffers, parse, read_capped};
pub use self::material::{MIRROR_ROUGHNESS, blinn_exponent};
use self::nodes::{node_matrix, node_numbers, projective_row, world_transforms};

/// The material of primitives that name none.
pub const DEFAULT_MATERIAL: &str = "gltf-default";

/// Loads the glTF or GLB file at `path`: the scene `options.scene_index` names (else the
/// file's default scene, else its first), with every mesh instance in world space.
pub fn load_gltf(path: &Path, options: &ImportOptions) -> Result<Model, GltfError> {
    let file = path.to_path_buf();
    let at = |path: String, problem: String| GltfError::At { file: file.clone(), path, problem };
    let bytes = read_capped(path).map_err(|error| GltfError::Io { file: file.clone(), error })?;
    let mut model = Model::default();
    let gltf = parse(&bytes, &file, &mut model.warnings)?;
    let numbers = node_numbers(&bytes);
    for (index, extension) in gltf.extensions_required().enumerate() {
        if !SUPPORTED_EXTENSIONS.contains(&extension) {
            return Err(GltfError::RequiredExtension { file: file.clone(), index, extension: extension.to_string() });
        }
    }
    for extension in gltf.extensions_used().filter(|e| !SUPPORTED_EXTENSIONS.contains(e)) {
        model.warnings.push(FieldIssue {
            field: "extensionsUsed".into(),
            problem: format!("`{extension}` is not supported; the file is read without it"),
        });
    }
    let buffers = load_buffers(&gltf, path)?;
    let scene = match options.scene_index {
        Some(i) => gltf.scenes().nth(i as usize).ok_or_else(|| {
            at(
                format!("scenes[{i}]"),
                format!(
                    "no such scene: the file has {} (the scene index: --scene-index, or a model object's scene_index)",
                    gltf.scenes().len()
                ),
            )
        })?,
        None => gltf
            .default_scene()
            .or_else(|| gltf.scenes().next())
            .ok_or_else(|| at("scenes".into(), "the file has no scene to render".into()))?,
    };
    // The material table: names made readable and unique, mapped once each.
    // Textured materials also note which TEXCOORD set their meshes must carry.
    let mut names: Vec<String> = Vec::new();
    let mut uv_sets: Vec<Option<u32>> = Vec::new();
    let mut images = texture::Images::default();
    let mut unread: BTreeMap<&str, usize> = BTreeMap::new();
    for m in gltf.materials() {
        for (what, present) in [
            ("normalTexture", m.normal_texture().is_some()),
            ("occlusionTexture", m.occlusion_texture().is_some()),
            ("metallicRoughnessTexture", m.pbr_metallic_roughness().metallic_roughness_texture().is_some()),
            ("alphaMode MASK (traced opaque)", m.alpha_mode() == ::gltf::material::AlphaMode::Mask),
        ] {
            if present {
                *unread.entry(what).or_default() += 1;
            }
        }
        let index = m.index().unwrap_or(names.len());
        let mut name = readable(m.name().unwrap_or(""), index, "material");
        if model.materials.contains_key(&name) {
            name = format!("{name}-{index}");
        }
        let mut desc = material::map_material(&m, &format!("materials[{index}] ({name})"), &mut model.warnings);
        material::check_emission(&m, index, &desc).map_err(|(p, e)| at(p, e))?;
        // KHR_materials_unlit names the metallic-roughness base colour, whatever else is there.
        let base = m
            .pbr_specular_glossiness()
            .filter(|_| !m.unlit())
            .map_or_else(|| m.pbr_metallic_roughness().base_color_texture(), |sg| sg.diffuse_texture());
        let mut uv_set = None;
        if let Some(info) = base {
            let (t, set) = texture::texture(&info, &buffers, path, &mut images).map_err(|(p, e)| at(p, e))?;
            // An unlit material's base colour is its emission (`material::map_material`).
            if m.unlit() {
                desc.emission_texture = Some(t);
            } else {
                desc.texture = Some(t);
            }
            uv_set = Some(set);
        }
        if let Some(info) = m.emissive_texture().filter(|_| !m.unlit()) {
            let (t, set) = texture::texture(&info, &buffers, path, &mut images).map_err(|(p, e)| at(p, e))?;
            if uv_set.is_some_and(|s| s != set) {
                model.warnings.push(FieldIssue {
                    field: format!("materials[{index}].emissiveTexture"),
                    problem: format!("reads TEXCOORD_{set}; the base colour's set is used for both"),
                });
            }
            desc.emission_texture = Some(t);
            uv_set = uv_set.or(Some(set));
        }
        model.materials.insert(name.clone(), desc);
        model.sources.insert(name.clone(), material::source(&m));
        names.push(name);
        uv_sets.push(uv_set);
    }
    if gltf.animations().len() > 0 {
        model.warnings.push(FieldIssue {
            field: "animations".into(),
            problem: format!(
                "{} animation(s) not played: the scene is traced as its nodes, weights and skins stand",
                gltf.animations().len()
            ),
        });
    }
    // Skins are posed by joints anywhere in the scene, walked before or after their mesh.
    let world_of =
        if gltf.skins().len() > 0 { world_transforms(&scene, gltf.nodes().len(), &numbers) } else { Vec::new() };
    model.warnings.extend(super::left_out("materials", "what Glint's model does not read", &unread));
    // Depth first from the scene's roots; a node reached twice is a cycle or a shared child,
    // both outside glTF's "disjoint strict trees", and refused rather than walked forever.
    let mut reached = vec![false; gltf.nodes().len()];
    // Each node with the node whose transform flattens it (its own, or an ancestor's), and the
    // first on its path whose transform took it beyond the scene's coordinates (its field and
    // why), if any.
    type Far = Option<(String, String)>;
    let mut stack: Vec<(::gltf::Node<'_>, Mat4, Option<usize>, Far)> =
        scene.nodes().map(|n| (n, Mat4::IDENTITY, None, None)).collect();
    stack.reverse();
    // The nodes whose degenerate transform flattens meshes, in the order met.
    let mut flattening: Vec<usize> = Vec::new();
    if stack.is_empty() {
        return Err(at(format!("scenes[{}].nodes", scene.index()), "the scene has no nodes".into()));
    }
    let mut skipped_modes: BTreeMap<String, Vec<String>> = BTreeMap::new();
    let mut instance_budget = instancing::MAX_INSTANCED_TRIANGLES;
    while let Some((node, parent, flattened_by, far)) = stack.pop() {
        let i = node.index();
        if std::mem::replace(&mut reached[i], true) {
            return Err(at(
                format!("nodes[{i}]"),
                "is reached twice from the scene (a cycle or a shared child; glTF node hierarchies are trees)".into(),
            ));
        }
        let local = node_matrix(&node, &numbers).map_err(|p| at(format!("nodes[{i}]"), p))?;
        if let Some(row) = projective_row(&local) {
            model.warnings.push(FieldIssue {
                field: format!("nodes[{i}].matrix"),
                problem: format!(
                    "its last row is {row:?}, not (0, 0, 0, 1): glTF allows only a matrix of translation, rotation \
                     and scale; read without that row (other readers may project by it)"
                ),
            });
        }
        let world = parent.mul(&local);
        // Named by the node's own field: a translation of 1e300 lost the triangle's size in
        // f64 and was said to be a triangle of zero area (a tester). Of a node that places
        // meshes (a camera's and a light's are held to the scene's range as such).
        let origin = [world.0[3][0], world.0[3][1], world.0[3][2]];
        let far = far.or_else(|| {
            (!origin.iter().all(|c| c.abs() <= MAX_COORD)).then(|| {
                (format!("nodes[{i}].{}", transform_field(&node, "translation")), beyond_coords(&local, origin))
            })
        });
        let flattened_by = flattened_by.or((local.determinant3() == 0.0).then_some(i));
        if let Some(mesh) = node.mesh() {
            if let Some((field, problem)) = far.clone().filter(|_| node.skin().is_none()) {
                return Err(at(field, problem));
            }
            if let Some(culprit) = flattened_by.filter(|c| node.skin().is_none() && !flattening.contains(c)) {
                flattening.push(culprit);
            }
            let instanced = instancing::instances(&node, &gltf, &buffers, &mut instance_budget)
                .map_err(|(path, problem)| at(path, problem))?;
            let placements: Vec<deform::Placement> = match (node.skin(), instanced) {
                (Some(skin), instanced) => {
                    if instanced.is_some() {
                        model.warnings.push(FieldIssue {
                            field: format!("nodes[{i}].extensions.{}", instancing::EXTENSION),
                            problem: "left out: the node is skinned, and the extension does not instance skins".into(),
                        });
                    }
                    vec![deform::Placement::Skinned(
                        deform::joint_matrices(&skin, &world_of, &buffers)
                            .map_err(|(path, problem)| at(path, problem))?,
                    )]
                }
                (None, Some(instances)) => instances.iter().map(|m| deform::Placement::Rigid(world.mul(m))).collect(),
                (None, None) => vec![deform::Placement::Rigid(world)],
            };
            // The node's morph weights, else the mesh's.
            let weights: Vec<f64> =
                node.weights().or(mesh.weights()).unwrap_or_default().iter().map(|&w| f64::from(w)).collect();
            for (k, placement) in placements.iter().enumerate() {
                for primitive in mesh.primitives() {
                    let prim_path = format!("meshes[{}].primitives[{}]", mesh.index(), primitive.index());
                    match primitive.mode() {
                        Mode::Triangles | Mode::TriangleStrip | Mode::TriangleFan => {}
                        other @ (Mode::Points | Mode::Lines | Mode::LineLoop | Mode::LineStrip) => {
                            // Once a primitive, however many instances draw it.
                            if k == 0 {
                                skipped_modes
                                    .entry(format!("meshes[{}]", mesh.index()))
                                    .or_default()
                                    .push(format!("{other:?}"));
                            }
                            continue;
                        }
                    }
                    let uv_set = primitive.material().index().and_then(|m| uv_sets[m]);
                    let material = match primitive.material().index() {
                        Some(m) => names[m].clone(),
                        None => {
                            model.materials.entry(DEFAULT_MATERIAL.into()).or_insert_with(material::default_material);
                            DEFAULT_MATERIAL.into()
                        }
                    };
                    let mut name = readable(node.name().or(mesh.name()).unwrap_or(""), i, "node");
                    if placements.len() > 1 {
                        name = format!("{name} #{k}");
                    }
                    let place = Place { placement, weights: &weights };
                    let attributes = Attributes { uv_set, colours: !primitive.material().unlit() };
                    let desc = read_primitive(&primitive, &buffers, &place, &prim_path, attributes, material, name)
                        .map_err(|(path, problem)| at(path, problem))?;
                    if let Some(set) = uv_set
                        && k == 0
                        && desc.as_ref().is_some_and(|d| d.uvs.is_none())
                    {
                        model.warnings.push(FieldIssue {
                            field: prim_path.clone(),
                            problem: format!(
                                "its material's texture reads TEXCOORD_{set}, which it does not have: planar \
                                 texture coordinates are used"
                            ),
                        });
                    }
                    // glTF 2.0 §3.7.2.1: TRIANGLES takes three indices a triangle. The rest is left
                    // out as GPUs leave it, but said (a count of 35 lost two without a word; a
                    // tester; assimp's IncorrectVertexArrays).
                    let (field, count, what, unit) = match primitive.indices() {
                        Some(a) => {
                            (format!("{prim_path}.indices"), a.count(), format!("accessors[{}]", a.index()), "indices")
                        }
                        None => (
                            format!("{prim_path}.attributes.POSITION"),
                            primitive.get(&::gltf::Semantic::Positions).map_or(0, |a| a.count()),
                            "without indices, POSITION".to_string(),
                            "vertices",
                        ),
                    };
                    if k == 0 && primitive.mode() == Mode::Triangles && !count.is_multiple_of(3) {
                        model.warnings.push(FieldIssue {
                            field,
                            problem: format!(
                                "{what} holds {count} {unit}, not a multiple of 3 (TRIANGLES takes three a \
                                 triangle): the last {} are left out",
                                count % 3
                            ),
                        });
                    }
                    let unlit = primitive.material().unlit();
                    if k == 0 && unlit && primitive.get(&::gltf::Semantic::Colors(0)).is_some() {
                        model.warnings.push(FieldIssue {
                            field: format!("{prim_path}.attributes.COLOR_0"),
                            problem: "left out: its material is unlit, whose colour is E_m, and vertex colours \
                                  multiply k_a and k_d only"
                                .into(),
                        });
                    }
                    // Integer positions and normals are KHR_mesh_quantization's: read, but a file that
                    // does not declare it is not valid glTF, which other readers may refuse.
                    for (semantic, name) in
                        [(::gltf::Semantic::Positions, "POSITION"), (::gltf::Semantic::Normals, "NORMAL")]
                    {
                        let integer =
                            primitive.get(&semantic).is_some_and(|a| a.data_type() != ::gltf::accessor::DataType::F32);
                        if k == 0 && integer && !gltf.extensions_used().any(|e| e == "KHR_mesh_quantization") {
                            model.warnings.push(FieldIssue {
                                field: format!("{prim_path}.attributes.{name}"),
                                problem: "holds integers, which glTF allows only in a file that lists \
                                          KHR_mesh_quantization in extensionsUsed; read as that extension says"
                                    .into(),
                            });
                        }
                    }
                    // As an OBJ's: one zero normal faceted the primitive without a word.
                    if k == 0
                        && primitive.get(&::gltf::Semantic::Normals).is_some()
                        && desc.as_ref().is_some_and(|d| d.normals.is_none())
                    {
                        model.warnings.push(FieldIssue {
                            field: format!("{prim_path}.attributes.NORMAL"),
                            problem: "has zero-length or non-finite normals (or ones its node's transform makes zero); shaded \
                                      with its faces' geometric normals"
                                .into(),
                        });
                    }
                    if let Some(desc) = desc {
                        model.meshes.push(desc);
                    }
                }
            }
        }
        if options.lights
            && let Some(light) = node.light()
            && let Some(l) = punctual::map_light(&light, &world, options.exposure, i, &bytes, &mut model.warnings)
                .map_err(|(path, problem)| at(path, problem))?
        {
            model.lights.push(l);
        }
        if let Some(camera) = node.camera()
            && let Some(c) = punctual::map_camera(&camera, &world, i, &mut model.warnings)
        {
            model.cameras.push(c);
        }
        stack.extend(
            node.children().map(|c| (c, world, flattened_by, far.clone())).collect::<Vec<_>>().into_iter().rev(),
        );
    }
    for &k in &flattening {
        let (field, problem) = degenerate_transform(&gltf, k, &numbers);
        // With no triangle left to trace, it is the error (it was "its one triangle has zero
        // area", the node not named; a tester's scale [0, 0, 0]).
        if !model.meshes.iter().any(super::has_area) {
            return Err(at(field, format!("{problem}, and the model has no other triangle to trace")));
        }
        model.warnings.push(FieldIssue { field, problem: format!("{problem}: they are never hit") });
    }
    for (mesh, modes) in skipped_modes {
        model.warnings.push(FieldIssue {
            field: mesh,
            problem: format!(
                "{} primitive(s) of mode {} skipped: only triangles are traced",
                modes.len(),
                modes.join(", ")
            ),
        });
    }
    if model.meshes.is_empty() {
        return Err(at(
            format!("scenes[{}]", scene.index()),
            "no triangles to trace (points and lines are not traced)".into(),
        ));
    }
    Ok(model)
}

/// The field that holds `node`'s transform: `matrix`, else the `decomposed` part named.
fn transform_field(node: &::gltf::Node<'_>, decomposed: &'static str) -> &'static str {
    match node.transform() {
        ::gltf::scene::Transform::Matrix { .. } => "matrix",
        ::gltf::scene::Transform::Decomposed { .. } => decomposed,
    }
}

/// A node's origin `origin` (in the scene) beyond the coordinates a scene may hold, `local`
/// its own transform.
fn beyond_coords(local: &Mat4, origin: [f64; 3]) -> String {
    let own = [local.0[3][0], local.0[3][1], local.0[3][2]];
    let parents = if own == origin {
        String::new()
    } else {
        format!(", which with its parents' transforms places the node at {}", listed(&origin))
    };
    format!(
        "its translation is {}{parents}; a scene's coordinates must lie in [-{MAX_COORD:e}, {MAX_COORD:e}] (as must \
         each component of a node's translation)",
        listed(&own)
    )
}

/// The field and problem of node `index`'s degenerate transform (a determinant of 0), which
/// flattens the meshes under it.
fn degenerate_transform(gltf: &::gltf::Gltf, index: usize, numbers: &[nodes::NodeNumbers]) -> (String, String) {
    let Some(node) = gltf.nodes().nth(index) else { return (format!("nodes[{index}]"), "is degenerate".into()) };
    let written = numbers.get(index);
    let under = "flattens the meshes under the node to zero area";
    match node.transform() {
        ::gltf::scene::Transform::Matrix { .. } => (
            format!("nodes[{index}].matrix"),
            format!("is a degenerate (singular) node matrix: its upper 3×3 has determinant 0, which {under}"),
        ),
        ::gltf::scene::Transform::Decomposed { scale, .. } => {
            let scale = written.and_then(|n| n.scale).unwrap_or(scale.map(f64::from));
            (
                format!("nodes[{index}].scale"),
                format!(
                    "{} is a degenerate node scale: each factor must be non-zero (its product too, in f64), and this \
                     {under}",
                    listed(&scale)
                ),
            )
        }
    }
}

/// Numbers as messages write them: `[1e300, 0, 0]`.
fn listed(v: &[f64]) -> String {
    format!("[{}]", v.iter().map(|&c| glint_scene::format_number(c)).collect::<Vec<_>>().join(", "))
}

/// Names as the scene format keeps them: readable characters, never empty.
fn readable(name: &str, index: usize, kind: &str) -> String {
    let cleaned: String =
        name.chars().map(|c| if c.is_alphanumeric() || "-_. ".contains(c) { c } else { '_' }).collect();
    let trimmed = cleaned.trim();
    if trimmed.is_empty() { format!("{kind}{index}") } else { trimmed.to_string() }
}

/// Which optional attributes of a primitive are read: the TEXCOORD set its material's
/// textures use, and COLOR_0 (not under an unlit material, whose colour is E_m).
#[derive(Clone, Copy)]
struct Attributes {
    uv_set: Option<u32>,
    colours: bool,
}

/// Where a primitive goes: its node's placement (rigid or skinned) and morph weights.
struct Place<'a> {
    placement: &'a deform::Placement,
    weights: &'a [f64],
}

/// One primitive as a world-space mesh: `Ok(None)` when it has no whole triangle. An error
/// carries the JSON path at fault.
fn read_primitive(
    primitive: &::gltf::Primitive<'_>,
    buffers: &Buffers,
    place: &Place<'_>,
    path: &str,
    attributes: Attributes,
    material: String,
    name: String,
) -> Result<Option<MeshDesc>, (String, String)> {
    let Attributes { uv_set, colours: read_colours } = attributes;
    let attr = |a: &str| format!("{path}.attributes.{a}");
    let position = primitive
        .get(&::gltf::Semantic::Positions)
        .ok_or_else(|| (attr("POSITION"), "missing: a primitive needs positions".to_string()))?;
    let mut local = accessor::read_vec3(&position, buffers).map_err(|p| (attr("POSITION"), p))?;
    for (k, p) in local.iter().enumerate() {
        // The file's own number first: after the node transforms one bad component spreads
        // to all three.
        if let Some(axis) = p.iter().position(|c| !c.is_finite()) {
            return Err((
                attr("POSITION"),
                format!(
                    "accessors[{}] element {k}: component {} = {} as stored in the file; positions must be finite",
                    position.index(),
                    ["x", "y", "z"][axis],
                    p[axis]
                ),
            ));
        }
    }
    let mut local_normals = match primitive.get(&::gltf::Semantic::Normals) {
        None => None,
        Some(acc) => {
            let n = accessor::read_vec3(&acc, buffers).map_err(|p| (attr("NORMAL"), p))?;
            if n.len() != local.len() {
                return Err((attr("NORMAL"), format!("has {} elements, POSITION {}", n.len(), local.len())));
            }
            Some(n)
        }
    };
    deform::morph(primitive, place.weights, &mut local, local_normals.as_mut(), buffers, path)?;
    let matrices = deform::vertex_matrices(primitive, place.placement, local.len(), buffers, path)?;
    let mut vertices = Vec::with_capacity(local.len());
    for (k, p) in local.iter().enumerate() {
        let m = &matrices[k];
        let w = m.point(*p);
        if !w.iter().all(|c| c.is_finite()) {
            return Err((
                attr("POSITION"),
                format!(
                    "accessors[{}] element {k} is {p:?} in the file but {w:?} after the node transforms: positions \
                     must stay finite",
                    position.index()
                ),
            ));
        }
        vertices.push(w);
    }
    // A zero or non-finite normal cannot shade: the primitive is shaded faceted, as the OBJ
    // importer does (validation would refuse it). Zero is judged on the file's normal; the
    // transformed one is only renormalised, since the transform scales its length by s² (nodes
    // scaled by 1e-6 made every normal 1e-12 long, and a smooth sphere faceted without a word).
    let length = |v: [f64; 3]| v.iter().map(|c| c * c).sum::<f64>().sqrt();
    let unit = |v: [f64; 3], zero: f64| {
        let len = length(v);
        (len.is_finite() && len > zero).then(|| v.map(|c| c / len))
    };
    let normals = local_normals.and_then(|n| {
        n.iter()
            .enumerate()
            .map(|(k, v)| unit(*v, MIN_DIRECTION_LENGTH).and_then(|v| unit(matrices[k].normal(v), f64::MIN_POSITIVE)))
            .collect::<Option<Vec<_>>>()
    });
    let uvs = match uv_set.and_then(|set| primitive.get(&::gltf::Semantic::TexCoords(set)).map(|a| (set, a))) {
        None => None,
        Some((set, acc)) => {
            let name = format!("TEXCOORD_{set}");
            let uv = accessor::read_uv(&acc, buffers).map_err(|p| (attr(&name), p))?;
            if let Some((k, axis)) =
                uv.iter().enumerate().find_map(|(k, t)| t.iter().position(|c| !c.is_finite()).map(|a| (k, a)))
            {
                return Err((
                    attr(&name),
                    format!(
                        "accessors[{}] element {k}: component {} = {}; texture coordinates must be finite",
                        acc.index(),
                        ["u", "v"][axis],
                        uv[k][axis]
                    ),
                ));
            }
            if uv.len() != vertices.len() {
                return Err((attr(&name), format!("has {} elements, POSITION {}", uv.len(), vertices.len())));
            }
            Some(uv)
        }
    };
    let colours = match primitive.get(&::gltf::Semantic::Colors(0)).filter(|_| read_colours) {
        None => None,
        Some(acc) => {
            let c = accessor::read_colours(&acc, buffers).map_err(|p| (attr("COLOR_0"), p))?;
            if let Some((k, channel)) = c
                .iter()
                .enumerate()
                .find_map(|(k, c)| c.iter().position(|v| !(v.is_finite() && *v >= 0.0)).map(|a| (k, a)))
            {
                return Err((
                    attr("COLOR_0"),
                    format!(
                        "accessors[{}] element {k}: component {} = {}; vertex colours must be finite and at least 0",
                        acc.index(),
                        ["r", "g", "b"][channel],
                        c[k][channel]
                    ),
                ));
            }
            if c.len() != vertices.len() {
                return Err((attr("COLOR_0"), format!("has {} elements, POSITION {}", c.len(), vertices.len())));
            }
            Some(c)
        }
    };
    let indices: Vec<u32> = match primitive.indices() {
        Some(acc) => accessor::read_indices(&acc, buffers).map_err(|p| (format!("{path}.indices"), p))?,
        None => (0..u32::try_from(vertices.len()).unwrap_or(u32::MAX)).collect(),
    };
    if let Some((k, &i)) = indices.iter().enumerate().find(|&(_, &i)| i as usize >= vertices.len()) {
        return Err((
            format!("{path}.indices"),
            format!("index {i} (element {k}) is beyond the {} vertices of POSITION", vertices.len()),
        ));
    }
    let mut triangles = triangulate(primitive.mode(), &indices);
    // A mirroring node (or joint) turns counter-clockwise faces clockwise: restore the winding.
    for t in triangles.iter_mut().filter(|t| matrices[t[0] as usize].determinant3() < 0.0) {
        t.swap(1, 2);
    }
    if triangles.is_empty() {
        return Ok(None);
    }
    Ok(Some(MeshDesc { vertices, triangles, normals, uvs, colours, material, name }))
}

/// How many triangles `triangulate` makes of `indices` indices in `mode`.
fn triangle_count(mode: Mode, indices: usize) -> usize {
    match mode {
        Mode::Triangles => indices / 3,
        Mode::TriangleStrip | Mode::TriangleFan => indices.saturating_sub(2),
        Mode::Points | Mode::Lines | Mode::LineLoop | Mode::LineStrip => 0,
    }
}

/// The triangles of a primitive's index list in its mode (glTF 2.0 §3.7.2.1: strips alternate
/// winding so every triangle keeps the first one's orientation; fans share the first vertex).
fn triangulate(mode: Mode, indices: &[u32]) -> Vec<[u32; 3]> {
    match mode {
        Mode::Triangles => indices.chunks_exact(3).map(|t| [t[0], t[1], t[2]]).collect(),
        Mode::TriangleStrip => (2..indices.len())
            .map(|i| {
                let (a, b, c) = (indices[i - 2], indices[i - 1], indices[i]);
                if i % 2 == 0 { [a, b, c] } else { [b, a, c] }
            })
            .collect(),
        Mode::TriangleFan => (2..indices.len()).map(|i| [indices[0], indices[i - 1], indices[i]]).collect(),
        Mode::Points | Mode::Lines | Mode::LineLoop | Mode::LineStrip => Vec::new(),
    }
}

#[cfg(test)]
mod tests;
