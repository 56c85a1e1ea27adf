//! Real OBJ/MTL files from Debian's `assimp-testmodels` (under /usr/share/assimp/models) through
//! `glint render`, on the CPU and the GPU. Without the package these tests fail with a clear
//! message; `GLINT_SKIP_MODELS=1` skips them on purpose.

use std::path::{Path, PathBuf};

use super::{glint, text};
use glint_test_support::TempDir;

const MODELS: &str = "/usr/share/assimp/models";

/// The model file, or `None` when `GLINT_SKIP_MODELS=1`; panics when the package is missing.
fn model(relative: &str) -> Option<PathBuf> {
    if glint_test_support::skip_requested("GLINT_SKIP_MODELS") {
        eprintln!("GLINT_SKIP_MODELS=1: skipping the model tests");
        return None;
    }
    let path = Path::new(MODELS).join(relative);
    assert!(
        path.is_file(),
        "the model tests need {} from Debian's assimp-testmodels (apt-get install assimp-testmodels), \
         or GLINT_SKIP_MODELS=1 to skip them",
        path.display()
    );
    Some(path)
}

/// With the encodings and the slips of real exporters: UTF-16 (box_UTF16BE), Windows-1252
/// material names (regr01), Blender's nameless material (empty_mat), a missing MTL
/// (cube_mtllib_after_g names `.mat`).
#[test]
fn obj_models_render_on_both_backends_and_agree() {
    let dir = TempDir::new("models");
    for name in [
        "OBJ/WusonOBJ.obj",
        "OBJ/spider.obj",
        "OBJ/cube_usemtl.obj",
        "OBJ/box_UTF16BE.obj",
        "OBJ/regr01.obj",
        "OBJ/empty_mat.obj",
        "OBJ/cube_mtllib_after_g.obj",
    ] {
        let Some(path) = model(name) else { return };
        render_model(&dir, name, &path, &[]);
    }
}

#[test]
fn an_obj_with_points_or_lines_only_or_a_malformed_number_is_a_clear_error() {
    let dir = TempDir::new("models-bad");
    let no_triangles = "no triangles (points and lines are not traced)";
    for (name, expected) in [
        ("OBJ/point_cloud.obj", no_triangles),
        ("OBJ/testpoints.obj", no_triangles),
        ("OBJ/testline.obj", no_triangles),
        // tobj's own message was "position parse error".
        (
            "OBJ/number_formats.obj",
            "number_formats.obj:11: invalid OBJ (`v 1e+2 2.e+1 3.1+e2`: vertex position component z: `3.1+e2` is not a number)",
        ),
    ] {
        let Some(path) = model(name) else { return };
        let run = glint(&dir, ["render".into(), path.into_os_string(), "-o".into(), dir.join("x.png").into()]);
        let stderr = text(&run.stderr);
        assert!(!run.status.success() && stderr.contains(expected) && stderr.contains(name), "{name}: {stderr}");
        assert!(!dir.join("x.png").exists(), "{name}: an output file was left");
    }
}

/// Faces that are concave polygons (a ring cut open, 66 vertices) and a box drawn three ways
/// (`l` polylines, `p` points, `f` faces): a fan overlapped the ring with itself, and tobj read
/// each polyline as a filled face, doubling the box. Neither overlaps itself now.
#[test]
fn concave_faces_are_cut_into_ears_and_polylines_are_not_faces() {
    let dir = TempDir::new("models-polygons");
    for name in ["OBJ/concave_polygon.obj", "OBJ/testmixed.obj"] {
        let Some(path) = model(name) else { return };
        let stderr = render_model(&dir, name, &path, &[]);
        assert!(!stderr.contains("overlaps itself"), "{name}: {stderr}");
    }
    let Some(path) = model("OBJ/testmixed.obj") else { return };
    let m = glint_io::model::load_obj(&path).expect("testmixed.obj loads");
    let triangles: usize = m.meshes.iter().map(|mesh| mesh.triangles.len()).sum();
    assert_eq!(triangles, 12, "six quads; the six polylines and seven points are left out");
    assert!(m.warnings.iter().any(|w| w.problem.contains("6 polyline statement(s) left out")), "{:?}", m.warnings);
}

/// Wuson moved far from the origin (a round offset and a projected map coordinate): stored
/// relative to its own box (`glint_scene::storage_origin`), none of its triangles lose their
/// area, its ground keeps the model's own gap, and both tracers render it as at the origin.
/// Before, at 1e6 f32 world coordinates dropped 1640 triangles and put the ground 4 units
/// lower (its gap was 64 f32 steps of 1/16). A scene that spans 1e6 itself (the model and a
/// triangle at the world origin) is stored in world space, and the loss is warned.
#[test]
fn a_model_far_from_the_origin_renders_as_at_the_origin() {
    let dir = TempDir::new("models-far");
    let Some(path) = model("OBJ/WusonOBJ.obj") else { return };
    let text = std::fs::read_to_string(&path).unwrap();
    let moved = |offset: f64, extra: &str| -> String {
        let body: String = text
            .lines()
            .map(|line| match line.strip_prefix("v ") {
                Some(xyz) => {
                    let p: Vec<f64> = xyz.split_whitespace().map(|c| c.parse().unwrap()).collect();
                    format!("v {} {} {}\n", p[0] + offset, p[1] + offset, p[2] - offset)
                }
                None => format!("{line}\n"),
            })
            .collect();
        body + extra
    };
    let render = |name: &str, obj: String| {
        let file = dir.join(name);
        std::fs::write(&file, obj).unwrap();
        let stderr = render_model(&dir, name, &file, &[]);
        let cpu = image::open(dir.join("m-cpu.png")).expect("the CPU image").into_rgb8();
        (stderr, cpu)
    };
    let lost = "triangles have no area once their vertices are stored as f32";
    let (_, at_origin) = render("origin.obj", moved(0.0, ""));
    for offset in [1e6, 452_331.127] {
        let (stderr, far) = render("far.obj", moved(offset, ""));
        assert!(!stderr.contains(lost), "{offset:e}: {stderr}");
        let worst = at_origin.as_raw().iter().zip(far.as_raw()).map(|(a, b)| a.abs_diff(*b)).max();
        assert!(worst <= Some(1), "{offset:e}: the CPU image differs from the origin's by {worst:?} of 255");
    }
    // The same model and one triangle at the world origin: the scene spans 1e6.
    let wide = moved(1e6, "v 0 0 0\nv 1 0 0\nv 0 1 0\nf -3 -2 -1\n");
    let (stderr, _) = render("wide.obj", wide);
    assert!(stderr.contains(lost) && stderr.contains("where f32 steps are 6.250e-2"), "{stderr}");
}

#[test]
fn a_tiny_model_renders_as_at_scale_one_down_to_the_least_size_and_is_refused_below() {
    // A floor of 1e-6 on the framing radius once made a 1e-8 model a dot and a 1e-10 one
    // nothing, without a word (a models tester).
    let dir = TempDir::new("models-tiny");
    let tetrahedron = |side: f64| {
        format!("v 0 0 0\nv {side:e} 0 0\nv 0 {side:e} 0\nv 0 0 {side:e}\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n")
    };
    let render = |side: f64| {
        let file = dir.join("t.obj");
        std::fs::write(&file, tetrahedron(side)).unwrap();
        render_model(&dir, "t.obj", &file, &[]);
        image::open(dir.join("m-cpu.png")).expect("the CPU image").into_rgb8()
    };
    let unit = render(1.0);
    let tiny = render(1e-8);
    let worst = unit.as_raw().iter().zip(tiny.as_raw()).map(|(a, b)| a.abs_diff(*b)).max();
    assert!(worst <= Some(1), "the 1e-8 model's image differs from the unit one's by {worst:?} of 255");
    let file = dir.join("below.obj");
    std::fs::write(&file, tetrahedron(1e-10)).unwrap();
    let done = glint(&dir, ["render".as_ref(), file.as_os_str(), "-o".as_ref(), dir.join("b.png").as_os_str()]);
    let said = text(&done.stderr);
    assert!(!done.status.success() && said.contains("the model's largest side is 1.000e-10, below 1e-9"), "{said}");
}

/// Renders `path` at 64×48 with `extra` flags on both backends (the CPU alone with
/// `GLINT_SKIP_GPU=1`), asserting success, every pixel traced and GPU–CPU parity; returns
/// what it wrote to stderr (the warnings).
fn render_model(dir: &TempDir, name: &str, path: &Path, extra: &[&str]) -> String {
    let skip_gpu = glint_test_support::skip_requested("GLINT_SKIP_GPU");
    let out = dir.join("m.png");
    let mut args: Vec<std::ffi::OsString> = vec!["render".into(), path.as_os_str().to_owned()];
    for a in ["--width", "64", "--height", "48", "--json", "--backend", if skip_gpu { "cpu" } else { "both" }] {
        args.push(a.into());
    }
    args.extend(extra.iter().map(Into::into));
    args.extend(["-o".into(), out.into_os_string()]);
    let run = glint(dir, args);
    let stdout = text(&run.stdout);
    assert!(run.status.success(), "{name}: {}\n{stdout}", text(&run.stderr));
    let v: serde_json::Value = serde_json::from_str(&stdout).expect("JSON");
    for r in v["runs"].as_array().unwrap() {
        assert!(r["rays"]["camera"].as_u64() == Some(64 * 48), "{name}: {r}");
    }
    if !skip_gpu {
        let cmp = &v["gpu_vs_cpu"];
        let (flip, mismatch) =
            (cmp["flip_mean"].as_f64().unwrap(), cmp["first_hit_mismatch_percent"].as_f64().unwrap());
        assert!(flip < 0.01 && mismatch < 1.0, "{name}: FLIP {flip}, first-hit mismatch {mismatch} %");
    }
    text(&run.stderr)
}

#[test]
fn gltf_models_render_on_both_backends_and_agree() {
    let dir = TempDir::new("gltf-models");
    for (name, extra) in [
        ("glTF2/2CylinderEngine-glTF-Binary/2CylinderEngine.glb", &[][..]),
        ("glTF2/BoxTextured-glTF/BoxTextured.gltf", &[]),
        ("glTF2/BoxTextured-glTF-Binary/BoxTextured.glb", &[]),
        ("glTF2/BoxTextured-glTF-Embedded/BoxTextured.gltf", &[]),
        ("glTF2/BoxTextured-glTF-pbrSpecularGlossiness/BoxTextured.gltf", &[]),
        ("glTF2/cameras/Cameras.gltf", &["--camera", "0"]),
        ("glTF2/textureTransform/TextureTransformTest.gltf", &[]),
        // Two POSITION accessors without the min and max glTF requires (a warning).
        ("glTF2/IncorrectVertexArrays/Cube.gltf", &[]),
    ] {
        let Some(path) = model(name) else { return };
        render_model(&dir, name, &path, extra);
    }
}

#[test]
fn broken_gltf_files_are_clear_errors_and_leave_no_file() {
    let dir = TempDir::new("gltf-broken");
    for (name, expected) in [
        ("glTF2/IndexOutOfRange/IndexOutOfRange.gltf", "indices"),
        ("glTF2/IndexOutOfRange/AllIndicesOutOfRange.gltf", "indices"),
        ("glTF2/MissingBin/BoxTextured.gltf", "buffers[0].uri"),
        ("glTF2/RecursiveNodes/RecursiveNodes.gltf", "reached twice"),
        ("glTF2/BoxWithInfinites-glTF-Binary/BoxWithInfinites.glb", "= -inf as stored in the file"),
        ("glTF/TwoBoxes/TwoBoxes.gltf", "asset.version is `1.0`: Glint reads glTF 2.0 only"),
        ("glTF/CesiumMilkTruck/CesiumMilkTruck.gltf", "asset.version is `1`: Glint reads glTF 2.0 only"),
        ("glTF/BoxTextured-glTF-Binary/BoxTextured.glb", "the GLB header's version is 1"),
        ("glTF2/draco/2CylinderEngine.gltf", "KHR_draco_mesh_compression"),
        ("glTF2/wrongTypes/badArray.gltf", "not a valid glTF"),
        ("glTF2/wrongTypes/badNumber.gltf", "not a valid glTF"),
        ("glTF2/wrongTypes/badObject.gltf", "not a valid glTF"),
        ("glTF2/wrongTypes/badString.gltf", "not a valid glTF"),
        ("glTF2/wrongTypes/badUint.gltf", "not a valid glTF"),
        ("glTF2/SchemaFailures/sceneWrongType.gltf", "not a valid glTF"),
        ("glTF2/TestNoRootNode/NoScene.gltf", "scene"),
        ("glTF2/TestNoRootNode/SceneWithoutNodes.gltf", "nodes"),
    ] {
        let Some(path) = model(name) else { return };
        let run = glint(&dir, ["render".into(), path.into_os_string(), "-o".into(), dir.join("x.png").into()]);
        let stderr = text(&run.stderr);
        let file = Path::new(name).file_name().unwrap().to_str().unwrap();
        assert!(!run.status.success(), "{name} rendered: {stderr}");
        assert!(stderr.contains(expected) && stderr.contains(file), "{name}: wanted `{expected}`: {stderr}");
        assert!(!stderr.contains("panicked"), "{name}: {stderr}");
        assert!(!dir.join("x.png").exists(), "{name}: an output file was left");
    }
}

#[test]
fn spider_mtl_textures_are_decoded_with_their_texture_coordinates() {
    // What obj_models_render_on_both_backends_and_agree then holds to the parity thresholds:
    // spider.mtl's five `map_Kd .\NAME.jpg` (Windows separators), sampled on both tracers.
    let Some(path) = model("OBJ/spider.obj") else { return };
    let m = glint_io::model::load_obj(&path).expect("spider.obj loads");
    let textured: Vec<(&String, u32, u32)> = m
        .materials
        .iter()
        .filter_map(|(name, mat)| {
            let image = mat.texture.as_ref()?.image.as_ref()?;
            Some((name, image.width(), image.height()))
        })
        .collect();
    assert_eq!(textured.len(), 5, "{textured:?}");
    assert!(textured.iter().any(|&(_, w, h)| (w, h) == (768, 768)), "drkwood2.jpg: {textured:?}");
    assert!(m.meshes.iter().all(|mesh| mesh.uvs.as_ref().is_some_and(|uv| uv.len() == mesh.vertices.len())));
}

#[test]
fn obj_vertex_colours_colour_the_faces_on_both_backends() {
    let dir = TempDir::new("models-vertex-colours");
    for name in ["OBJ/cube_with_vertexcolors.obj", "OBJ/cube_with_vertexcolors_uni.obj"] {
        let Some(path) = model(name) else { return };
        // Every vertex takes the colour its `v` line gives, whichever face (normal) it serves.
        let file = std::fs::read_to_string(&path).expect("readable");
        let written: Vec<[f64; 6]> = file
            .lines()
            .filter_map(|l| l.strip_prefix("v "))
            .map(|l| {
                let n: Vec<f64> = l.split_whitespace().map(|w| w.parse().unwrap()).collect();
                std::array::from_fn(|k| n[k])
            })
            .collect();
        let m = glint_io::model::load_obj(&path).expect("loads");
        let mesh = &m.meshes[0];
        let colours = mesh.colours.as_ref().unwrap_or_else(|| panic!("{name}: no vertex colours read"));
        assert_eq!((colours.len(), mesh.vertices.len()), (24, 24), "{name}: one per face corner");
        for (p, c) in mesh.vertices.iter().zip(colours) {
            let w = written.iter().find(|w| w[..3] == p[..]).expect("a written vertex");
            assert_eq!(c[..], w[3..], "{name}: the vertex at {p:?}");
        }
        let stderr = render_model(&dir, name, &path, &[]);
        assert!(!stderr.contains("vertex colours left out"), "{name}: {stderr}");
        // The same file without its colours renders grey: the colours reach the image.
        let coloured = image::open(dir.join("m-cpu.png")).expect("the CPU image").to_rgb8();
        let grey = dir.join("grey.obj");
        let stripped: Vec<String> = file
            .lines()
            .map(|l| match l.strip_prefix("v ") {
                Some(rest) => format!("v {}", rest.split_whitespace().take(3).collect::<Vec<_>>().join(" ")),
                None => l.to_string(),
            })
            .collect();
        std::fs::write(&grey, stripped.join("\n")).expect("written");
        render_model(&dir, name, &grey, &[]);
        let plain = image::open(dir.join("m-cpu.png")).expect("the CPU image").to_rgb8();
        let tinted = |img: &image::RgbImage| {
            img.pixels().filter(|p| p.0.iter().max().unwrap() - p.0.iter().min().unwrap() > 40).count()
        };
        assert!(
            tinted(&plain) == 0 && tinted(&coloured) > 200,
            "{name}: {} and {} tinted pixels",
            tinted(&plain),
            tinted(&coloured)
        );
    }
}

/// `map_Kd -s … -o …` places the image as those options move OBJ's texture coordinates (v up
/// from the image's bottom row): the render equals that of the same quad whose `vt` were
/// moved so by hand, with the plain `map_Kd`. A texture of distinct texels shows any flip.
#[test]
fn mtl_map_offset_and_scale_place_the_image_as_moved_coordinates_would() {
    let dir = TempDir::new("models-map-options");
    let rgba: Vec<u8> = (0..8u8).flat_map(|k| [k * 32, 255 - k * 32, (k % 3) * 120, 255]).collect();
    glint_test_support::texture::write_png(&dir.join("tex.png"), 4, 2, &rgba);
    let quad = |mtl: &str, vt: [[f64; 2]; 4]| {
        let vts: String = vt.iter().map(|[u, v]| format!("vt {u} {v}\n")).collect();
        format!("mtllib {mtl}\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n{vts}usemtl t\nf 1/1 2/2 3/3 4/4\n")
    };
    let render = |name: &str, obj: String, mtl: &str| {
        std::fs::write(dir.join(format!("{name}.mtl")), format!("newmtl t\nKd 1 1 1\nmap_Kd {mtl}\n")).unwrap();
        std::fs::write(dir.join(format!("{name}.obj")), obj).unwrap();
        let out = dir.join(format!("{name}.png"));
        let args = ["render", &format!("{name}.obj"), "--backend", "cpu", "--width", "96", "--height", "72", "-o"];
        let run = glint(&dir, args.iter().map(Into::into).chain([out.clone().into_os_string()]));
        assert!(run.status.success(), "{name}: {}", text(&run.stderr));
        assert!(!text(&run.stderr).contains("left out"), "{name}: {}", text(&run.stderr));
        image::open(&out).expect("written").to_rgb8()
    };
    let corners = [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]];
    // A fractional v scale: 1 − s_v is then no whole number that repeating would hide.
    let (s, o) = ([1.5, 0.75], [0.25, 0.125]);
    let moved = corners.map(|[u, v]| [s[0] * u + o[0], s[1] * v + o[1]]);
    for clamp in ["", "-clamp on "] {
        let options =
            render("options", quad("options.mtl", corners), &format!("{clamp}-s 1.5 0.75 1 -o 0.25 0.125 tex.png"));
        let by_hand = render("by-hand", quad("by-hand.mtl", moved), &format!("{clamp}tex.png"));
        let worst = options
            .pixels()
            .zip(by_hand.pixels())
            .flat_map(|(a, b)| (0..3).map(move |k| a.0[k].abs_diff(b.0[k])))
            .max();
        assert!(
            worst <= Some(1),
            "`{clamp}`: the options' image differs from the moved coordinates' by {worst:?} levels"
        );
        // And it is not the unplaced image.
        let unplaced = render("unplaced", quad("unplaced.mtl", corners), &format!("{clamp}tex.png"));
        let differing = options.pixels().zip(unplaced.pixels()).filter(|(a, b)| a != b).count();
        assert!(differing > 500, "`{clamp}`: only {differing} pixels changed by the options");
    }
}
