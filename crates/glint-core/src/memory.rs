//! What a load or a render will take in memory, estimated before anything large is allocated,
//! and the check that refuses an estimate beyond the memory there is (issue 13, point 9).
//!
//! The per-item figures are the sizes of the buffers the code allocates (`size_of` of the
//! stored types) plus what the parsers and the BVH builder need on top, measured with peak RSS
//! (`/usr/bin/time -f %M`) and rounded up; `tests/cli/memory.rs` holds each estimate against
//! the peak RSS of a real run.

use std::fmt;
use std::path::Path;

use crate::bvh::WideNode;
use crate::flat::{GPU_LEAF_BYTES_PER_PRIM, LeafCorners};
use glint_scene::{ObjectDesc, RenderSettings, SceneDesc};
use glint_types::layout::{BvhNode, QuantizedPair};
use glint_types::layout::{GpuMesh, GpuPlane, GpuSphere, GpuTriangle};

/// Peak memory of a TOML scene while it is parsed and checked, per byte of the file: the text,
/// toml's tables and the typed description (a 10.9 MB file of 100,000 triangles peaked at
/// 330 MB, 30 bytes a byte).
const TOML_BYTES_PER_FILE_BYTE: u64 = 36;
/// The same for a glTF or GLB file: the buffers, the f64 vertices and the scene around them
/// (2CylinderEngine.glb, 1.8 MB: 28 MB above the process's own).
const GLTF_BYTES_PER_FILE_BYTE: u64 = 20;
/// The same for OBJ text (`v x y z` lines: tobj's f32 arrays, then f64 vertices).
const OBJ_BYTES_PER_FILE_BYTE: u64 = 12;
/// The process itself: code, the thread pool, the allocator's arenas.
const PROCESS_BYTES: u64 = 16 << 20;
/// A GPU device with its pipelines (lavapipe keeps them in host memory: 92 MB measured).
const GPU_DEVICE_BYTES: u64 = 128 << 20;
/// The BVH builder's scratch per bounded primitive (bounds, centroid, bin indices), beside
/// the nodes (at most two per primitive) and the leaf references.
const BVH_BUILD_BYTES_PER_PRIM: u64 = 64;

/// One part of an estimate.
#[derive(Clone, Debug, PartialEq, Eq, serde::Serialize)]
pub struct MemoryPart {
    pub what: &'static str,
    pub bytes: u64,
}

/// An estimate of the memory a step will take, by part.
#[derive(Clone, Debug, Default, PartialEq, Eq, serde::Serialize)]
pub struct MemoryEstimate {
    pub parts: Vec<MemoryPart>,
}

impl MemoryEstimate {
    pub fn total(&self) -> u64 {
        self.parts.iter().map(|p| p.bytes).sum()
    }

    fn add(&mut self, what: &'static str, bytes: u64) {
        if bytes > 0 {
            self.parts.push(MemoryPart { what, bytes });
        }
    }
}

impl fmt::Display for MemoryEstimate {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}", format_bytes(self.total()))?;
        let parts: Vec<String> = self.parts.iter().map(|p| format!("{} {}", p.what, format_bytes(p.bytes))).collect();
        write!(f, " ({})", parts.join(", "))
    }
}

/// Bytes as people read them: 512 B, 3.4 MiB, 12.0 GiB.
pub fn format_bytes(bytes: u64) -> String {
    const UNITS: [&str; 5] = ["B", "KiB", "MiB", "GiB", "TiB"];
    let mut value = bytes as f64;
    let mut unit = 0;
    while value >= 1024.0 && unit + 1 < UNITS.len() {
        value /= 1024.0;
        unit += 1;
    }
    if unit == 0 { format!("{bytes} B") } else { format!("{value:.1} {}", UNITS[unit]) }
}

/// The kinds of file a load estimate knows (which kind a path is, glint-io's formats say).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SourceKind {
    Toml,
    Gltf,
    Obj,
}

/// What loading a file of `file_bytes` bytes will take, before it is read.
pub fn load_estimate(kind: SourceKind, file_bytes: u64) -> MemoryEstimate {
    let (what, factor) = match kind {
        SourceKind::Toml => ("parsing the scene file", TOML_BYTES_PER_FILE_BYTE),
        SourceKind::Gltf => ("importing the glTF file", GLTF_BYTES_PER_FILE_BYTE),
        SourceKind::Obj => ("importing the OBJ file", OBJ_BYTES_PER_FILE_BYTE),
    };
    let mut e = MemoryEstimate::default();
    e.add("process", PROCESS_BYTES);
    e.add(what, file_bytes.saturating_mul(factor));
    e
}

/// The counts of what a scene stores, as the flat layout will hold it.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
struct Counts {
    spheres: u64,
    planes: u64,
    triangles: u64,
    vertices: u64,
    normals: u64,
    uvs: u64,
    colours: u64,
    meshes: u64,
    texels: u64,
}

fn counts(desc: &SceneDesc) -> Counts {
    let mut c = Counts::default();
    let mesh = |m: &glint_scene::MeshDesc, c: &mut Counts| {
        c.meshes += 1;
        c.triangles += m.triangles.len() as u64;
        c.vertices += m.vertices.len() as u64;
        c.normals += m.normals.as_ref().map_or(0, |n| n.len() as u64);
        c.uvs += m.uvs.as_ref().map_or(0, |n| n.len() as u64);
        c.colours += m.colours.as_ref().map_or(0, |n| n.len() as u64);
    };
    for object in &desc.objects {
        match object {
            ObjectDesc::Sphere(_) => c.spheres += 1,
            ObjectDesc::Plane(_) => c.planes += 1,
            ObjectDesc::Mesh(m) => mesh(m, &mut c),
            ObjectDesc::Model(model) => {
                for m in model.loaded.iter().flat_map(|l| &l.meshes) {
                    mesh(m, &mut c);
                }
            }
        }
    }
    for m in desc.materials.values() {
        for t in [&m.texture, &m.emission_texture].into_iter().flatten() {
            c.texels += t.image.as_ref().map_or(0, |i| i.texels().len() as u64);
        }
    }
    c
}

/// `n` items of `item` bytes, saturating.
fn size(n: u64, item: usize) -> u64 {
    n.saturating_mul(item as u64)
}

/// The flat layout's geometry buffers for `c`.
fn geometry_bytes(c: &Counts) -> u64 {
    size(c.spheres, size_of::<GpuSphere>())
        + size(c.planes, size_of::<GpuPlane>())
        + size(c.triangles, size_of::<GpuTriangle>())
        + size(c.meshes, size_of::<GpuMesh>())
        // Positions, normals and colours are vec4<f32>, texture coordinates vec2<f32>; normals,
        // texture coordinates and colours are stored for every vertex once any mesh has them.
        + size(c.vertices, 16)
        + if c.normals > 0 { size(c.vertices, 16) } else { 0 }
        + if c.uvs > 0 { size(c.vertices, 8) } else { 0 }
        + if c.colours > 0 { size(c.vertices, 16) } else { 0 }
}

/// The process, the description of `c` and what a render builds of it (flat geometry, BVH):
/// the part of `render_estimate` that grows with the scene, not the image.
fn scene_estimate(c: &Counts) -> MemoryEstimate {
    let bounded = c.spheres + c.triangles;
    // Nodes, references, the CPU walk's leaf-order corners, and the build's working set.
    let bvh = size(bounded, 2 * size_of::<BvhNode>() + 4)
        + bounded.saturating_mul(LeafCorners::BYTES_PER_PRIM)
        + size(bounded, BVH_BUILD_BYTES_PER_PRIM as usize);
    // The description is already in memory; it is part of the estimate because it is part
    // of the peak, and the estimate is held against the process's peak in the tests.
    let description = size(c.vertices, 24)
        + size(c.normals, 24)
        + size(c.uvs, 16)
        + size(c.colours, 24)
        + size(c.triangles, 12)
        + size(c.spheres + c.planes, size_of::<ObjectDesc>());
    let mut e = MemoryEstimate::default();
    e.add("process", PROCESS_BYTES);
    e.add("scene description", description);
    e.add("flat geometry", geometry_bytes(c));
    e.add("BVH", bvh);
    e
}

/// What a generated scene of `vertices` and `triangles` in its meshes takes once made and
/// built for a render, before it is made (`render_estimate`'s scene part: a bumpy at
/// resolution 1500 had been generated, 18 s and 510 MB, before a 100 MiB limit refused it).
pub fn generated_estimate(vertices: u64, triangles: u64) -> MemoryEstimate {
    scene_estimate(&Counts { meshes: 1, vertices, triangles, ..Counts::default() })
}

/// Which images a render keeps and writes.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct RenderPlan {
    pub cpu: bool,
    pub gpu: bool,
    /// The output is an EXR (linear f32) rather than a PNG.
    pub exr: bool,
}

/// What rendering `desc` at `settings` will take beyond the loaded description: the flat
/// scene and its BVH, the images of each backend, the GPU device and its buffers, the output
/// encoding and, with both backends, the comparison.
pub fn render_estimate(desc: &SceneDesc, settings: &RenderSettings, plan: RenderPlan) -> MemoryEstimate {
    let c = counts(desc);
    let geometry = geometry_bytes(&c);
    let bounded = c.spheres + c.triangles;
    let texels = size(c.texels, 16);
    let pixels = u64::from(settings.width) * u64::from(settings.height);
    let mut e = scene_estimate(&c);
    e.add("textures", texels);
    // An HdrImage: f64 RGB and a u32 first hit per pixel.
    let image = size(pixels, 28);
    // sRGB bytes and the PNG stream, or f32 RGB and the EXR encoder's copy.
    let encoded = size(pixels, if plan.exr { 24 } else { 6 });
    if plan.cpu {
        e.add("CPU image", image);
        // The walk's wide nodes (`BvhNodes::wide`), made at the first CPU trace: 0.103 a
        // triangle on `bumpy`; an eighth per primitive allows for leaves of fewer primitives.
        e.add("CPU walk's wide nodes", size(bounded, size_of::<WideNode>() / 8));
    }
    if plan.gpu {
        e.add("GPU device", GPU_DEVICE_BYTES);
        // The device's copy of the scene (with the tree's quantized form, kept on the host too,
        // `BvhNodes::gpu`: fewer records than primitives, and its leaf-order corners,
        // `fill_gpu_leaves`), the output, sample and readback buffers (vec4<f32> a pixel
        // each), and the decoded image.
        let tree = size(bounded, size_of::<QuantizedPair>() * 2) + bounded.saturating_mul(GPU_LEAF_BYTES_PER_PRIM);
        e.add("GPU scene buffers", geometry + texels + tree);
        e.add("GPU images", size(pixels, 48) + image);
    }
    let outputs = u64::from(plan.cpu) + u64::from(plan.gpu);
    e.add("output encoding", encoded.saturating_mul(outputs));
    if plan.cpu && plan.gpu {
        // The difference image (sRGB) and FLIP's f32 copies of both images and its error map.
        e.add("comparison", size(pixels, 3 + 12 + 12 + 4));
    }
    e
}

/// Memory this process can still take: Linux's MemAvailable, lowered to what is left of a
/// cgroup (v2) limit; `None` where neither can be read.
pub fn available() -> Option<u64> {
    let meminfo = std::fs::read_to_string("/proc/meminfo").ok();
    let system = meminfo.as_deref().and_then(|text| {
        text.lines()
            .find_map(|l| l.strip_prefix("MemAvailable:"))
            .and_then(|v| v.trim().trim_end_matches("kB").trim().parse::<u64>().ok())
            .map(|kb| kb * 1024)
    });
    let read = |name: &str| std::fs::read_to_string(Path::new("/sys/fs/cgroup").join(name)).ok();
    let cgroup = match (read("memory.max"), read("memory.current")) {
        (Some(max), Some(current)) => {
            max.trim().parse::<u64>().ok().zip(current.trim().parse::<u64>().ok()).map(|(m, c)| m.saturating_sub(c))
        }
        _ => None,
    };
    match (system, cgroup) {
        (Some(s), Some(c)) => Some(s.min(c)),
        (s, c) => s.or(c),
    }
}

/// This process's peak resident memory so far (Linux's VmHWM), for reports.
pub fn peak_rss() -> Option<u64> {
    let status = std::fs::read_to_string("/proc/self/status").ok()?;
    let kb = status.lines().find_map(|l| l.strip_prefix("VmHWM:"))?.trim().trim_end_matches("kB").trim().parse::<u64>();
    kb.ok().map(|kb| kb * 1024)
}

/// An estimate beyond the memory a step may take.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
#[error(
    "{what} would need about {estimate}, more than the {} {limit_source}; {remedy}",
    format_bytes(*limit)
)]
pub struct MemoryError {
    pub what: String,
    pub estimate: MemoryEstimate,
    pub limit: u64,
    /// Where the limit comes from ("available", "set by --memory-limit").
    pub limit_source: &'static str,
    pub remedy: String,
}

/// The most bytes a scene file of unknown size (a pipe, a device) may have for its parse to fit
/// `limit` (a limit the user set, else the memory available; `None` when neither is known):
/// read that far, not to the 1 GiB any file may have (`/dev/zero` under `--memory-limit 100M`
/// took 1 GiB before it was refused).
pub fn stream_cap(limit: Option<u64>) -> Option<u64> {
    let limit = limit.or_else(available)?;
    Some(limit.saturating_sub(PROCESS_BYTES) / TOML_BYTES_PER_FILE_BYTE)
}

/// Where a limit the user set comes from, as the error says it.
const SET_BY_FLAG: &str = "set by --memory-limit";

/// Refuses `estimate` when it exceeds `limit` (a limit the user set), else the memory
/// available; passes when neither is known.
pub fn check(
    what: impl Into<String>,
    estimate: &MemoryEstimate,
    limit: Option<u64>,
    remedy: impl Into<String>,
) -> Result<(), MemoryError> {
    let (limit, limit_source) = match limit {
        Some(l) => (l, SET_BY_FLAG),
        None => match available() {
            Some(a) => (a, "available"),
            None => return Ok(()),
        },
    };
    if estimate.total() <= limit {
        return Ok(());
    }
    // Below what the process takes whatever it does, no smaller scene or image fits: the
    // remedies of a scene ("lower --width and --height" under --memory-limit 10M) cannot help.
    let remedy = if limit_source == SET_BY_FLAG && limit < PROCESS_BYTES {
        format!("that is below the {} glint takes before any scene or image; raise it", format_bytes(PROCESS_BYTES))
    } else {
        remedy.into()
    };
    Err(MemoryError { what: what.into(), estimate: estimate.clone(), limit, limit_source, remedy })
}

/// Parses a size such as `512M`, `2G`, `1.5GiB` or a number of bytes.
pub fn parse_size(s: &str) -> Result<u64, String> {
    // A leading '+', as every other number flag takes it (`--spp +3`; `--memory-limit +3G` was
    // "not a size").
    let t = s.trim();
    let t = t.strip_prefix('+').unwrap_or(t);
    let split = t.find(|c: char| !(c.is_ascii_digit() || c == '.')).unwrap_or(t.len());
    let (number, unit) = t.split_at(split);
    let value: f64 = number.parse().map_err(|_| format!("'{s}' is not a size (e.g. 512M, 2G, 1.5GiB)"))?;
    let scale: f64 = match unit.trim().to_ascii_lowercase().as_str() {
        "" | "b" => 1.0,
        "k" | "kb" | "kib" => 1024.0,
        "m" | "mb" | "mib" => 1024.0 * 1024.0,
        "g" | "gb" | "gib" => 1024.0 * 1024.0 * 1024.0,
        "t" | "tb" | "tib" => 1024.0 * 1024.0 * 1024.0 * 1024.0,
        other => return Err(format!("unknown unit '{other}' in '{s}'; allowed: B, K, M, G, T")),
    };
    let bytes = value * scale;
    if !bytes.is_finite() || !(1.0..=1.0e15).contains(&bytes) {
        return Err(format!("'{s}' is outside [1 B, 1e15 B]"));
    }
    Ok(bytes as u64)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_limit_below_the_process_itself_asks_for_more_not_a_smaller_scene() {
        let mut estimate = MemoryEstimate::default();
        estimate.add("process", PROCESS_BYTES);
        estimate.add("CPU image", 1 << 15);
        let e = check("rendering s at 40x30", &estimate, Some(10 << 20), "lower --width and --height").unwrap_err();
        assert!(
            e.to_string().ends_with(
                "set by --memory-limit; that is below the 16.0 MiB glint takes before any scene or image; raise it"
            ),
            "{e}"
        );
        let e = check("rendering s at 40x30", &estimate, Some(PROCESS_BYTES + 1), "lower --width and --height")
            .unwrap_err();
        assert!(e.to_string().ends_with("; lower --width and --height"), "{e}");
    }

    #[test]
    fn sizes_parse_with_binary_units_and_bad_ones_are_named() {
        assert_eq!(parse_size("512M"), Ok(512 << 20));
        assert_eq!(parse_size("1.5GiB"), Ok(3 << 29));
        assert_eq!(parse_size("4096"), Ok(4096));
        assert!(parse_size("12X").unwrap_err().contains("unknown unit 'x'"));
        assert!(parse_size("-1G").unwrap_err().contains("not a size"));
        assert!(parse_size("0").unwrap_err().contains("outside"));
        assert_eq!(format_bytes(512), "512 B");
        assert_eq!(format_bytes(3 << 29), "1.5 GiB");
    }

    #[test]
    fn a_render_estimate_grows_with_pixels_and_backends() {
        let b = glint_io::builtin("whitted").expect("built-in");
        let (desc, _) = b.load(None).expect("loads");
        let mut settings = desc.render.clone();
        (settings.width, settings.height) = (1000, 1000);
        let cpu = render_estimate(&desc, &settings, RenderPlan { cpu: true, gpu: false, exr: false });
        let both = render_estimate(&desc, &settings, RenderPlan { cpu: true, gpu: true, exr: false });
        assert!(cpu.total() >= 28_000_000 + PROCESS_BYTES, "{cpu}");
        assert!(both.total() > cpu.total() + GPU_DEVICE_BYTES, "{both}");
        let err = check("rendering", &both, Some(64 << 20), "lower --width").unwrap_err();
        let message = err.to_string();
        assert!(message.contains("more than the 64.0 MiB set by --memory-limit; lower --width"), "{message}");
        assert!(message.contains("CPU image 26.7 MiB"), "{message}");
    }

    #[test]
    fn a_size_takes_a_leading_plus_as_the_number_flags_do() {
        assert_eq!(parse_size("+3G"), parse_size("3G"));
        assert_eq!(parse_size("+512"), Ok(512));
        assert!(parse_size("++3G").is_err() && parse_size("-3G").is_err());
    }
}
