//! Unit tests of the glTF importer's own steps (triangulation, parsing checks, messages).

use super::*;

#[test]
fn a_gltf_1_file_is_refused_naming_its_version() {
    let file = Path::new("old.gltf");
    for (text, expected) in [
        (r#"{"asset": {"version": "1.0"}, "accessors": {"a": {}}}"#, "asset.version is `1.0`"),
        (r#"{"asset": {"version": 1}, "meshes": {"m": {}}}"#, "asset.version is `1`"),
        // Nothing of 1.0's form: parsed as an empty 2.0 file, said to have no scene (a tester).
        (r#"{"asset": {"version": "1.0"}}"#, "asset.version is `1.0`"),
    ] {
        let message = parse(text.as_bytes(), file, &mut Vec::new()).unwrap_err().to_string();
        assert!(message.contains(expected) && message.contains("glTF 2.0 only"), "{message}");
    }
    let glb = [b"glTF".as_slice(), &1u32.to_le_bytes(), &20u32.to_le_bytes(), &[0; 8]].concat();
    let message = parse(&glb, file, &mut Vec::new()).unwrap_err().to_string();
    assert!(message.contains("the GLB header's version is 1"), "{message}");
    for version in [r#""2.0""#, "2"] {
        let broken = format!(r#"{{"asset": {{"version": {version}}}, "accessors": {{"a": {{}}}}}}"#);
        let message = parse(broken.as_bytes(), file, &mut Vec::new()).unwrap_err().to_string();
        assert!(message.contains("not a valid glTF 2.0 file"), "a 2.0 file's own error: {message}");
    }
}

#[test]
fn an_empty_file_is_said_to_be_empty() {
    for (bytes, expected) in [(&b""[..], "the file is empty (0 bytes)"), (b" \n\t", "the file holds only white space")]
    {
        let message = parse(bytes, Path::new("m.glb"), &mut Vec::new()).unwrap_err().to_string();
        assert_eq!(message, format!("m.glb: not a valid glTF 2.0 file: {expected}"));
    }
}

#[test]
fn a_glb_of_another_magic_or_a_header_length_other_than_the_file_s_is_refused_naming_both() {
    let chunk = br#"{"asset":{"version":"2.0"}} "#;
    let glb = |magic: &[u8], length: u32| {
        [magic, &2u32.to_le_bytes(), &length.to_le_bytes(), &(chunk.len() as u32).to_le_bytes(), b"JSON", chunk]
            .concat()
    };
    let whole = (12 + 8 + chunk.len()) as u32;
    let file = Path::new("m.glb");
    // A tester's `glTX`: the JSON parser's "expected value at line 1 column 1".
    let message = parse(&glb(b"glTX", whole), file, &mut Vec::new()).unwrap_err().to_string();
    assert_eq!(
        message,
        "m.glb: not a valid glTF 2.0 file: not a GLB: its magic bytes are \"glTX\" (67 6C 54 58), not \"glTF\" (67 6C \
         54 46), and it is not glTF JSON either"
    );
    // Read without a word: a header of 20 bytes in a longer file.
    let message = parse(&glb(b"glTF", 20), file, &mut Vec::new()).unwrap_err().to_string();
    assert!(
        message.starts_with(&format!(
            "m.glb: not a valid glTF 2.0 file: the GLB header gives the file's length as 20 bytes, but it has {whole}:"
        )),
        "{message}"
    );
    let message = parse(&glb(b"glTF", whole + 100), file, &mut Vec::new()).unwrap_err().to_string();
    assert!(message.contains(&format!("as {} bytes, but it has {whole}: it is cut short", whole + 100)), "{message}");
    // The header's own length is read.
    assert!(parse(&glb(b"glTF", whole), file, &mut Vec::new()).is_ok());
}

#[test]
fn strips_keep_the_first_triangles_orientation_and_fans_share_the_first_vertex() {
    assert_eq!(triangulate(Mode::TriangleStrip, &[0, 1, 2, 3, 4]), vec![[0, 1, 2], [2, 1, 3], [2, 3, 4]]);
    assert_eq!(triangulate(Mode::TriangleFan, &[0, 1, 2, 3]), vec![[0, 1, 2], [0, 2, 3]]);
    assert_eq!(triangulate(Mode::Triangles, &[0, 1, 2, 3]), vec![[0, 1, 2]], "a partial triangle is dropped");
    assert!(triangulate(Mode::TriangleStrip, &[0, 1]).is_empty());
}

/// The message of a glTF 2.0 file of the top-level `json` members, which must be refused.
fn refused(json: &str) -> String {
    let text = format!(r#"{{"asset":{{"version":"2.0"}},{json}}}"#);
    let Err(err) = parse(text.as_bytes(), Path::new("m.gltf"), &mut Vec::new()) else { panic!("{json}: accepted") };
    err.to_string()
}

#[test]
fn an_image_without_a_source_or_mime_type_and_a_camera_without_its_projection_are_errors() {
    let view = r#""bufferViews":[{"buffer":0,"byteLength":4}],"buffers":[{"byteLength":4}]"#;
    let perspective_without_it =
        r#""cameras":[{"type":"perspective","orthographic":{"xmag":1,"ymag":1,"zfar":2,"znear":1}}]"#;
    for (json, path) in [
        (format!(r#""images":[{{"bufferView":0}}],{view}"#), "images[0].mimeType"),
        (r#""images":[{"name":"x"}]"#.to_string(), "images[0]"),
        (perspective_without_it.to_string(), "cameras[0]"),
    ] {
        let err = refused(&json);
        assert!(err.contains(&format!("{path}: invalid glTF")), "{err}");
    }
}

#[test]
fn an_index_out_of_bounds_says_what_the_file_has() {
    // "scene: invalid glTF: scene: Index out of bounds" named no range, and its path twice.
    for (json, said) in [
        (r#""scene":0"#, "scene: invalid glTF: Index out of bounds (the file has no scenes)"),
        (
            r#""scenes":[{"nodes":[0]}],"nodes":[{"camera":3}],"cameras":[{"type":"perspective","perspective":{"yfov":1,"znear":0.1}}]"#,
            "nodes[0].camera: invalid glTF: Index out of bounds (the file's cameras have only index 0)",
        ),
    ] {
        let err = refused(json);
        assert!(err.contains(said), "{err}");
    }
}

#[test]
fn an_invalid_value_says_what_the_specification_allows() {
    for (json, said) in [
        (
            r#""accessors":[{"componentType":5124,"count":1,"type":"SCALAR"}]"#,
            // The accessor's one error now (its missing bufferView is zeros, not an error).
            "accessors[0].componentType: invalid glTF: Invalid value (allowed: 5120 (byte), 5121 (unsigned byte)",
        ),
        (
            r#""meshes":[{"primitives":[{"attributes":{},"mode":9}]}]"#,
            "mode: Invalid value (allowed: 0 (points) to 6 (triangle fan))",
        ),
        (
            r#""materials":[{"alphaMode":"GLASS"}]"#,
            "materials[0].alphaMode: invalid glTF: Invalid value (allowed: OPAQUE, MASK or BLEND)",
        ),
    ] {
        let err = refused(json);
        assert!(err.contains(said), "{err}");
    }
}

#[test]
fn a_position_accessor_that_does_not_exist_is_an_error_naming_it_not_a_panic() {
    let json = br#"{"asset":{"version":"2.0"},"meshes":[{"primitives":[{"attributes":{"POSITION":0}}]}]}"#;
    let Err(err) = parse(json, Path::new("m.gltf"), &mut Vec::new()) else { panic!("a missing accessor was accepted") };
    let err = err.to_string();
    assert!(err.contains("meshes[0].primitives[0].attributes.POSITION"), "{err}");
    assert!(err.contains("accessor 0 does not exist (the file has 0)"), "{err}");
}

#[test]
fn a_position_accessor_without_min_and_max_is_read_with_a_warning() {
    let json = br#"{"asset":{"version":"2.0"},"buffers":[{"byteLength":36}],
        "bufferViews":[{"buffer":0,"byteLength":36}],
        "accessors":[{"bufferView":0,"componentType":5126,"count":3,"type":"VEC3","max":[1,1,0]}],
        "meshes":[{"primitives":[{"attributes":{"POSITION":0}},{"attributes":{"POSITION":0}}]}]}"#;
    let mut warnings = Vec::new();
    let gltf = parse(json, Path::new("m.gltf"), &mut warnings).expect("read");
    assert_eq!(warnings.len(), 1, "one warning for the accessor both primitives share: {warnings:?}");
    assert_eq!(warnings[0].field, "accessors[0]");
    let max = gltf.accessors().next().unwrap().max();
    assert_eq!(max, Some(::gltf::json::Value::from(vec![1, 1, 0])), "the file's max is kept");
}
