//! Bit-identity of CPU images across refactors. Every CPU render the test suites make through
//! `render_cpu_checked` is hashed (FNV-1a over the f64 bits of every pixel, the first-hit ids
//! and the ray counts) and compared with the hash recorded for the same test and call in
//! `tests/golden/cpu-images.txt`. A change that alters a CPU image, even by one bit, fails the
//! test that rendered it; a deliberate change is recorded again with
//! `GLINT_RECORD_IMAGE_HASHES=1 cargo test --workspace` (after deleting the file).
//!
//! The key is `BINARY::TEST#N`: the test binary, the test's name (libtest names each test's
//! thread after it) and the index of the render within the test.

use std::cell::Cell;
use std::collections::HashMap;
use std::io::Write as _;
use std::path::PathBuf;
use std::sync::OnceLock;

use glint_core::CpuRender;

const ENV_RECORD: &str = "GLINT_RECORD_IMAGE_HASHES";
/// Skips the check: the hash is taken inside the render helpers, before a test's own
/// assertions on the image, so a changed image fails there first; with this set, those
/// assertions say whether the change is one they catch (a mutation round's question).
const ENV_SKIP: &str = "GLINT_SKIP_IMAGE_HASHES";

/// In the workspace root's tests/, beside the test binaries' sources (this crate is
/// crates/glint-test-support).
fn golden_path() -> PathBuf {
    PathBuf::from(concat!(env!("CARGO_MANIFEST_DIR"), "/../../tests/golden/cpu-images.txt"))
}

/// The running test binary's name (`core`, `stiff`, `gpu`): its file stem without cargo's
/// `-HASH` suffix. `CARGO_CRATE_NAME` would name this crate, not the binary.
fn binary_name() -> String {
    let exe = std::env::current_exe().expect("the test binary's path");
    let stem = exe.file_stem().expect("the test binary has a file name").to_string_lossy().into_owned();
    match stem.rsplit_once('-') {
        Some((name, hash)) if !hash.is_empty() && hash.bytes().all(|b| b.is_ascii_hexdigit()) => name.to_string(),
        _ => stem,
    }
}

/// FNV-1a, 64 bits: stable across Rust versions, unlike `DefaultHasher`.
fn fnv1a(hash: &mut u64, bytes: &[u8]) {
    for &b in bytes {
        *hash ^= u64::from(b);
        *hash = hash.wrapping_mul(0x0100_0000_01b3);
    }
}

/// The hash of a render's pixels (exact f64 bits), first hits and ray counts.
pub fn render_hash(r: &CpuRender) -> u64 {
    let mut h = 0xcbf2_9ce4_8422_2325;
    fnv1a(&mut h, &r.image.width.to_le_bytes());
    fnv1a(&mut h, &r.image.height.to_le_bytes());
    for p in &r.image.pixels {
        for c in p.to_array() {
            fnv1a(&mut h, &c.to_bits().to_le_bytes());
        }
    }
    for id in &r.image.first_hit {
        fnv1a(&mut h, &id.to_le_bytes());
    }
    let c = &r.counts;
    for n in [c.camera, c.shadow, c.reflection, c.refraction, c.bailout_saved] {
        fnv1a(&mut h, &n.to_le_bytes());
    }
    h
}

fn recorded() -> &'static HashMap<String, u64> {
    static TABLE: OnceLock<HashMap<String, u64>> = OnceLock::new();
    TABLE.get_or_init(|| {
        let text = std::fs::read_to_string(golden_path()).unwrap_or_default();
        text.lines()
            .filter(|l| !l.starts_with('#') && !l.trim().is_empty())
            .filter_map(|l| {
                let (key, hash) = l.rsplit_once(' ')?;
                Some((key.to_string(), u64::from_str_radix(hash, 16).ok()?))
            })
            .collect()
    })
}

thread_local! {
    static CALLS: Cell<u32> = const { Cell::new(0) };
}

/// Checks (or, with `GLINT_RECORD_IMAGE_HASHES=1`, records) the hash of a CPU render made by
/// the current test.
pub fn check_render_hash(r: &CpuRender) {
    if crate::skip_requested(ENV_SKIP) {
        return;
    }
    let thread = std::thread::current();
    let test = match thread.name() {
        Some(name) if name != "main" => name.to_string(),
        // With --test-threads=1 libtest runs tests on the main thread: no test name to key on.
        _ => {
            eprintln!("image hash not checked: the render does not run on a named test thread");
            return;
        }
    };
    let n = CALLS.with(|c| {
        let n = c.get();
        c.set(n + 1);
        n
    });
    let key = format!("{}::{test}#{n}", binary_name());
    let hash = render_hash(r);
    if std::env::var(ENV_RECORD).is_ok_and(|v| v == "1") {
        let mut file = std::fs::OpenOptions::new()
            .create(true)
            .append(true)
            .open(golden_path())
            .expect("open tests/golden/cpu-images.txt for recording");
        // One write per line: appends from parallel tests and binaries do not interleave.
        file.write_all(format!("{key} {hash:016x}\n").as_bytes()).expect("record an image hash");
        return;
    }
    match recorded().get(&key) {
        Some(&want) => assert_eq!(
            want, hash,
            "{key}: the CPU image is no longer bit-identical to the recorded one \
             (hash {hash:016x}, recorded {want:016x}). If the change is deliberate, record again: \
             rm tests/golden/cpu-images.txt && {ENV_RECORD}=1 cargo test --workspace. \
             To see whether the test's own assertions on the image hold, run it with {ENV_SKIP}=1"
        ),
        None => panic!(
            "{key}: no recorded image hash. Record new renders with \
             rm tests/golden/cpu-images.txt && {ENV_RECORD}=1 cargo test --workspace"
        ),
    }
}
