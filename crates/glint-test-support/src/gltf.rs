//! Small glTF fixtures for what Debian's test models lack (each light type and falloff,
//! transmission and ior, emissive strength, hostile URIs, hierarchies, primitive modes),
//! written by the test itself: the JSON with serde_json, the binary buffer by hand.

use std::path::{Path, PathBuf};

use base64::Engine as _;
use base64::engine::general_purpose::STANDARD;
use serde_json::{Value, json};

/// A glTF document under construction: its JSON and its one binary buffer.
#[derive(Clone, Debug)]
pub struct Fixture {
    pub json: Value,
    pub bin: Vec<u8>,
}

/// Where a written fixture's buffer lives.
#[derive(Clone, Debug)]
pub enum BufferAt {
    /// A `data:` URI (base64) inside the JSON.
    DataUri,
    /// A file of this name beside the `.gltf`, named by a relative URI.
    File(String),
    /// This URI, verbatim, and no file written (hostile URIs).
    Uri(String),
}

impl Fixture {
    /// One scene with one node holding a one-primitive mesh: the unit quad in the z = 0 plane
    /// facing +z (two counter-clockwise triangles, indexed, with normals), material 0 (white,
    /// rough dielectric).
    pub fn quad() -> Self {
        let mut f = Self { json: Value::Null, bin: Vec::new() };
        let positions = f.push_f32(&[0., 0., 0., 1., 0., 0., 1., 1., 0., 0., 1., 0.]);
        let normals = f.push_f32(&[0., 0., 1., 0., 0., 1., 0., 0., 1., 0., 0., 1.]);
        let indices = f.push_u16(&[0, 1, 2, 0, 2, 3]);
        let views = f.json["bufferViews"].clone();
        f.json = json!({
            "asset": { "version": "2.0", "generator": "glint-test-support" },
            "scene": 0,
            "scenes": [{ "nodes": [0] }],
            "nodes": [{ "mesh": 0, "name": "quad" }],
            "meshes": [{ "primitives": [{
                "attributes": { "POSITION": 0, "NORMAL": 1 }, "indices": 2, "material": 0, "mode": 4
            }] }],
            "materials": [{ "name": "white", "pbrMetallicRoughness": {
                "baseColorFactor": [1.0, 1.0, 1.0, 1.0], "metallicFactor": 0.0, "roughnessFactor": 1.0
            } }],
            "accessors": [
                { "bufferView": positions, "componentType": 5126, "count": 4, "type": "VEC3",
                  "min": [0.0, 0.0, 0.0], "max": [1.0, 1.0, 0.0] },
                { "bufferView": normals, "componentType": 5126, "count": 4, "type": "VEC3" },
                { "bufferView": indices, "componentType": 5123, "count": 6, "type": "SCALAR" }
            ],
            "bufferViews": views,
            "buffers": [{ "byteLength": 0 }]
        });
        f
    }

    /// Appends f32 values as a new buffer view; its index.
    pub fn push_f32(&mut self, values: &[f32]) -> usize {
        let bytes: Vec<u8> = values.iter().flat_map(|v| v.to_le_bytes()).collect();
        self.push_view(&bytes)
    }

    /// Appends u16 values (padded to 4 bytes) as a new buffer view; its index.
    pub fn push_u16(&mut self, values: &[u16]) -> usize {
        let bytes: Vec<u8> = values.iter().flat_map(|v| v.to_le_bytes()).collect();
        self.push_view(&bytes)
    }

    fn push_view(&mut self, bytes: &[u8]) -> usize {
        while !self.bin.len().is_multiple_of(4) {
            self.bin.push(0);
        }
        let view = json!({ "buffer": 0, "byteOffset": self.bin.len(), "byteLength": bytes.len() });
        self.bin.extend_from_slice(bytes);
        let views = self.views_mut();
        views.push(view);
        views.len() - 1
    }

    fn views_mut(&mut self) -> &mut Vec<Value> {
        if !self.json.is_object() {
            // Before the JSON exists (inside `quad`), views collect in a scratch document.
            self.json = json!({ "bufferViews": [] });
        }
        self.json["bufferViews"].as_array_mut().expect("bufferViews is an array")
    }

    /// Writes `NAME.gltf` into `dir` with the buffer where `at` says; its path.
    pub fn write_gltf(&self, dir: &Path, name: &str, at: BufferAt) -> PathBuf {
        let mut json = self.json.clone();
        json["buffers"][0]["byteLength"] = json!(self.bin.len());
        let uri = match at {
            BufferAt::DataUri => format!("data:application/octet-stream;base64,{}", STANDARD.encode(&self.bin)),
            BufferAt::File(file) => {
                std::fs::write(dir.join(&file), &self.bin).expect("write the fixture's buffer");
                file
            }
            BufferAt::Uri(uri) => uri,
        };
        json["buffers"][0]["uri"] = json!(uri);
        let path = dir.join(format!("{name}.gltf"));
        std::fs::write(&path, serde_json::to_vec_pretty(&json).expect("JSON")).expect("write the fixture");
        path
    }

    /// Writes `NAME.glb` into `dir` (JSON chunk, BIN chunk); its path.
    pub fn write_glb(&self, dir: &Path, name: &str) -> PathBuf {
        let mut json = self.json.clone();
        json["buffers"][0]["byteLength"] = json!(self.bin.len());
        let mut text = serde_json::to_vec(&json).expect("JSON");
        while !text.len().is_multiple_of(4) {
            text.push(b' ');
        }
        let mut bin = self.bin.clone();
        while !bin.len().is_multiple_of(4) {
            bin.push(0);
        }
        let total = 12 + 8 + text.len() + 8 + bin.len();
        let mut out = Vec::with_capacity(total);
        out.extend_from_slice(b"glTF");
        out.extend_from_slice(&2u32.to_le_bytes());
        out.extend_from_slice(&(total as u32).to_le_bytes());
        out.extend_from_slice(&(text.len() as u32).to_le_bytes());
        out.extend_from_slice(b"JSON");
        out.extend_from_slice(&text);
        out.extend_from_slice(&(bin.len() as u32).to_le_bytes());
        out.extend_from_slice(b"BIN\0");
        out.extend_from_slice(&bin);
        let path = dir.join(format!("{name}.glb"));
        std::fs::write(&path, out).expect("write the fixture");
        path
    }
}
