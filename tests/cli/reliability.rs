//! What `glint render` refuses and how it stops (issue 13): interrupts, outputs that must not
//! be replaced, images that are not results (non-finite pixels, GPU status flags), bounds on
//! `--threads`, and file-system failures reported as such.

use std::ffi::OsString;
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

use glint_test_support::TempDir;
use glint_test_support::scene::stack_overflow_slab;

use super::{BIN, glint, os, png_text_chunks, text};

fn skip_gpu() -> bool {
    glint_test_support::skip_requested("GLINT_SKIP_GPU")
}

/// Sends `signal` (TERM, INT) to a running `glint render` on `backend` and checks that it says
/// "interrupted", exits with `code`, and leaves neither the output nor a temporary.
fn interrupt_a_render(signal: &str, code: i32, backend: &str) {
    let dir = TempDir::new(&format!("interrupt-{signal}-{backend}"));
    // 2048² pixels at 64 spp: minutes of work on 2 threads (or on lavapipe), 120 MB of image.
    let child = Command::new(BIN)
        .args(["render", "whitted", "--width", "2048", "--height", "2048", "--spp", "64", "--threads", "2", "-q"])
        .args(["--backend", backend])
        .args(["-o", "big.exr"])
        .current_dir(&dir)
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("start glint");
    // Past start-up (the handler is installed before anything else), in the render; the GPU
    // first compiles its shader.
    std::thread::sleep(Duration::from_millis(if backend == "gpu" { 4000 } else { 1500 }));
    let status = Command::new("kill").args([&format!("-{signal}"), &child.id().to_string()]).status().expect("kill");
    assert!(status.success(), "kill -{signal} failed");
    let start = Instant::now();
    let out = child.wait_with_output().expect("wait for glint");
    let stderr = text(&out.stderr);
    assert_eq!(out.status.code(), Some(code), "SIG{signal}: {:?}\n{stderr}", out.status);
    assert!(stderr.contains("interrupted"), "SIG{signal}: {stderr}");
    assert!(start.elapsed() < Duration::from_secs(20), "SIG{signal}: took {:?} to stop", start.elapsed());
    assert!(dir.listing().is_empty(), "SIG{signal}: left behind {:?}", dir.listing());
}

#[test]
fn sigterm_and_sigint_stop_a_render_with_130_or_143_and_leave_no_file() {
    interrupt_a_render("TERM", 143, "cpu");
    interrupt_a_render("INT", 130, "cpu");
}

#[test]
fn a_named_pipe_is_no_model_file_and_the_first_signal_ends_a_load_waiting_on_one() {
    let dir = TempDir::new("fifo");
    let fifo = |name: &str| {
        let made = Command::new("mkfifo").arg(dir.join(name)).status().expect("mkfifo (coreutils) runs");
        assert!(made.success(), "mkfifo {name}");
    };
    // A file a model refers to, or a model file itself, that is a named pipe is refused before
    // it is opened (opening waited for a writer for ever).
    fifo("buffer.bin");
    fifo("pipe.obj");
    let gltf = r#"{"asset":{"version":"2.0"},"buffers":[{"uri":"buffer.bin","byteLength":36}]}"#;
    std::fs::write(dir.join("m.gltf"), gltf).unwrap();
    for (model, says) in [("m.gltf", "buffer.bin"), ("pipe.obj", "pipe.obj")] {
        let start = Instant::now();
        let out = glint(&dir, ["render", model, "-o", "x.png", "-q"]);
        let stderr = text(&out.stderr);
        assert!(!out.status.success() && stderr.contains("not a regular file (a named pipe"), "{model}: {stderr}");
        assert!(stderr.contains(says), "{model}: {stderr}");
        assert!(start.elapsed() < Duration::from_secs(20), "{model}: took {:?}", start.elapsed());
    }
    // A scene file may be a pipe (it is read as a stream); the first SIGTERM while the load
    // waits for its writer ends the process (it was swallowed until a second). A tile may not
    // (`glint merge` refuses it at once, tests/cli/tiles.rs).
    fifo("scene.toml");
    {
        let args = ["render", "scene.toml", "-o", "x.png", "-q"];
        let child = Command::new(BIN)
            .args(args)
            .current_dir(&dir)
            .stdout(Stdio::piped())
            .stderr(Stdio::piped())
            .spawn()
            .expect("start glint");
        std::thread::sleep(Duration::from_millis(1000));
        let status = Command::new("kill").args(["-TERM", &child.id().to_string()]).status().expect("kill");
        assert!(status.success(), "kill -TERM failed");
        let start = Instant::now();
        let (done, waiter) = std::sync::mpsc::channel();
        let id = child.id().to_string();
        std::thread::spawn(move || done.send(child.wait_with_output()));
        let Ok(out) = waiter.recv_timeout(Duration::from_secs(20)) else {
            Command::new("kill").args(["-KILL", &id]).status().expect("kill");
            panic!("{args:?}: one SIGTERM did not end a read waiting on a pipe");
        };
        assert_eq!(out.expect("wait for glint").status.code(), Some(143), "{args:?}");
        assert!(start.elapsed() < Duration::from_secs(20));
    }
}

#[test]
fn a_gpu_render_stops_between_two_submissions_on_sigint() {
    if skip_gpu() {
        return;
    }
    interrupt_a_render("INT", 130, "gpu");
}

const SCENE: &str = "[render]\nwidth = 8\nheight = 6\n\n[camera]\nposition = [0.0, 1.0, -4.0]\nlook_at = [0.0, 0.5, 0.0]\n\n\
    [materials.m]\nkd = 0.5\n\n[[lights]]\ntype = \"point\"\nposition = [1.0, 3.0, -2.0]\n\n\
    [[objects]]\ntype = \"sphere\"\ncenter = [0.0, 0.5, 0.0]\nradius = 0.5\nmaterial = \"m\"\n";

#[cfg(unix)]
#[test]
fn a_read_only_output_is_kept_unless_forced() {
    use std::os::unix::fs::PermissionsExt;
    let dir = TempDir::new("read-only");
    let out_path = dir.join("kept.png");
    std::fs::write(&out_path, "old").unwrap();
    std::fs::set_permissions(&out_path, std::fs::Permissions::from_mode(0o444)).unwrap();
    let args = |force: bool| {
        let mut a = os(&[&"render", &"whitted", &"--width", &"8", &"--height", &"6", &"-q", &"-o", &out_path]);
        if force {
            a.push("--force".into());
        }
        a
    };
    let out = glint(&dir, args(false));
    assert!(!out.status.success());
    let stderr = text(&out.stderr);
    assert!(stderr.contains("kept.png") && stderr.contains("read-only") && stderr.contains("--force"), "{stderr}");
    assert_eq!(std::fs::read_to_string(&out_path).unwrap(), "old");
    assert_eq!(dir.listing(), ["kept.png"]);
    let out = glint(&dir, args(true));
    assert!(out.status.success(), "{}", text(&out.stderr));
    assert_eq!(image::open(&out_path).expect("a PNG now").into_rgb8().dimensions(), (8, 6));
}

#[cfg(unix)]
#[test]
fn the_input_scene_is_never_an_output_by_any_name() {
    let dir = TempDir::new("same-file");
    // A scene file named like an image: TOML whatever its extension.
    std::fs::write(dir.join("scene.png"), SCENE).unwrap();
    std::fs::write(dir.join("scene.toml"), SCENE).unwrap();
    std::os::unix::fs::symlink(dir.join("scene.png"), dir.join("link.png")).unwrap();
    std::fs::hard_link(dir.join("scene.png"), dir.join("hard.png")).unwrap();
    for (scene, output) in [
        ("scene.png", "scene.png"),
        ("scene.png", "./scene.png"),
        ("link.png", "scene.png"),
        ("scene.png", "link.png"),
        ("scene.png", "hard.png"),
        // Said as the input scene, not as an unsupported output format.
        ("scene.toml", "scene.toml"),
    ] {
        for extra in [&[][..], &["--force"][..]] {
            let mut args = os(&[&"render", &scene, &"-q", &"-o", &output]);
            args.extend(extra.iter().map(OsString::from));
            let out = glint(&dir, args);
            let stderr = text(&out.stderr);
            assert!(!out.status.success(), "{scene} -o {output} {extra:?} succeeded");
            assert!(stderr.contains("is the input scene"), "{scene} -o {output}: {stderr}");
            assert_eq!(std::fs::read_to_string(dir.join("scene.png")).unwrap(), SCENE, "{scene} -o {output}");
        }
    }
    assert_eq!(std::fs::read_to_string(dir.join("scene.toml")).unwrap(), SCENE);
    assert_eq!(dir.listing(), ["hard.png", "link.png", "scene.png", "scene.toml"]);
}

#[test]
fn an_output_that_is_a_folder_is_refused_before_any_output_is_written() {
    let dir = TempDir::new("folder-output");
    std::fs::create_dir(dir.join("bo-gpu.png")).unwrap();
    let out = glint(&dir, ["render", "whitted", "--width", "8", "--height", "6", "--backend", "both", "-o", "bo.png"]);
    let stderr = text(&out.stderr);
    assert!(!out.status.success() && stderr.contains("bo-gpu.png: is a folder, not a file"), "{stderr}");
    assert_eq!(dir.listing(), ["bo-gpu.png"], "bo-cpu.png was written before the refusal");
}

#[test]
fn a_failed_write_of_both_backends_images_leaves_none_of_them() {
    // On a nearly full disk `--backend both` failed on NAME-gpu after NAME-cpu was in place,
    // and said nothing of it. A file-size limit (prlimit, SIGXFSZ ignored so that the write
    // fails with EFBIG) just above the CPU's image makes a later image's write fail.
    if skip_gpu() {
        return;
    }
    assert!(
        Command::new("prlimit").arg("--version").output().is_ok(),
        "prlimit not found: install util-linux (apt-get install util-linux)"
    );
    let args = ["render", "whitted", "--width", "40", "--height", "30", "--backend", "both", "-q", "-o", "g.png"];
    let ok = TempDir::new("both-sizes");
    let out = glint(&ok, args);
    assert!(out.status.success(), "{}", text(&out.stderr));
    let size = |name: &str| std::fs::metadata(ok.join(name)).expect(name).len();
    // The CPU's image is written first: a limit at its size fails a later, larger one. Where it
    // is the largest, the limit fails it, the first, and the assertions below still hold.
    let (cpu, later) = (size("g-cpu.png"), size("g-gpu.png").max(size("g-diff.png")));
    let limit = if later > cpu { cpu } else { size("g-gpu.png").min(size("g-diff.png")) - 1 };
    eprintln!("file size limit {limit} (CPU image {cpu}, largest later one {later})");
    let dir = TempDir::new("both-fails");
    let out = Command::new("sh")
        .args(["-c", "trap '' XFSZ; exec prlimit --fsize=\"$0\" -- \"$@\"", &limit.to_string(), BIN])
        .args(args)
        .current_dir(&dir)
        .output()
        .expect("run glint");
    let stderr = text(&out.stderr);
    assert!(!out.status.success(), "{stderr}");
    assert!(stderr.contains("File too large"), "{stderr}");
    assert!(stderr.contains("nothing was written (none of g-cpu.png, g-gpu.png, g-diff.png)"), "{stderr}");
    assert_eq!(dir.listing(), Vec::<String>::new(), "{stderr}");
}

#[test]
fn a_texture_or_model_the_scene_reads_is_never_an_output() {
    // `-o tex.png` on a scene whose material reads tex.png overwrote the texture without a word.
    let dir = TempDir::new("texture-output");
    let scene = glint_test_support::texture::textured_scene(&dir, 8, 6);
    std::fs::write(dir.join("scene.toml"), &scene.text).unwrap();
    let texture = std::fs::read(dir.join("tex.png")).unwrap();
    for extra in [&[][..], &["--backend", "cpu", "--force"][..]] {
        let mut args = os(&[&"render", &"scene.toml", &"-q", &"-o", &"./tex.png"]);
        args.extend(extra.iter().map(OsString::from));
        let out = glint(&dir, args);
        let stderr = text(&out.stderr);
        assert!(!out.status.success(), "-o tex.png {extra:?} succeeded");
        assert!(stderr.contains("is a texture the scene reads") && stderr.contains("tex.png"), "{stderr}");
        assert_eq!(std::fs::read(dir.join("tex.png")).unwrap(), texture, "the texture is left as it was");
    }
    // Named as its resolver reads it: `t%20x.png` is the file `t x.png` (it was looked for as
    // `t%20x.png` and overwritten).
    assert!(scene.text.contains("path = \"tex.png\""), "{}", scene.text);
    std::fs::write(dir.join("t x.png"), &texture).unwrap();
    std::fs::write(dir.join("encoded.toml"), scene.text.replace("path = \"tex.png\"", "path = \"t%20x.png\"")).unwrap();
    let out = glint(&dir, ["render", "encoded.toml", "-q", "--force", "-o", "t x.png"]);
    assert!(text(&out.stderr).contains("is a texture the scene reads"), "{}", text(&out.stderr));
    assert_eq!(std::fs::read(dir.join("t x.png")).unwrap(), texture, "the encoded texture is left as it was");
    // A model's texture, beside the model in a subfolder.
    std::fs::create_dir(dir.join("sub")).unwrap();
    std::fs::write(dir.join("sub/tex2.png"), &texture).unwrap();
    std::fs::write(dir.join("sub/m.mtl"), "newmtl m\nKd 1 1 1\nmap_Kd tex2.png\n").unwrap();
    std::fs::write(
        dir.join("sub/m.obj"),
        "mtllib m.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 0 1\nusemtl m\nf 1/1 2/2 3/3\n",
    )
    .unwrap();
    let camera = "[camera]\nposition = [0.3, 0.3, 3.0]\nlook_at = [0.3, 0.3, 0.0]\n";
    let model = format!("{camera}[[objects]]\ntype = \"model\"\npath = \"sub/m.obj\"\n");
    std::fs::write(dir.join("model.toml"), model).unwrap();
    let out = glint(&dir, ["render", "model.toml", "-q", "--width", "8", "--height", "6", "-o", "sub/tex2.png"]);
    assert!(text(&out.stderr).contains("is a texture the scene reads"), "{}", text(&out.stderr));
    assert_eq!(std::fs::read(dir.join("sub/tex2.png")).unwrap(), texture, "the model's texture is left as it was");
    // A scene file's override of the model's material reads its texture beside the scene (a
    // reviewer's find: it was overwritten, while the model's own, unread, was refused).
    std::fs::write(dir.join("over.png"), &texture).unwrap();
    let over = format!(
        "{camera}[materials.\"m/m\"]\ntexture = {{ path = \"over.png\" }}\n[[objects]]\ntype = \"model\"\npath = \"sub/m.obj\"\n"
    );
    std::fs::write(dir.join("over.toml"), over).unwrap();
    let out = glint(&dir, ["render", "over.toml", "-q", "--width", "8", "--height", "6", "-o", "over.png"]);
    assert!(text(&out.stderr).contains("is a texture the scene reads"), "{}", text(&out.stderr));
    assert_eq!(std::fs::read(dir.join("over.png")).unwrap(), texture, "the override's texture is left as it was");
}

/// Two facing mirror planes, the camera between them, radiance growing by k_r = 1e9 per bounce
/// over an emission of 1e9: finite in f64 at depth 4, beyond f32 (1e45).
fn overflowing_scene(depth: u32) -> String {
    format!(
        "[render]\nwidth = 4\nheight = 4\nmax_depth = {depth}\nbailout = 0.0\n\n\
         [camera]\nposition = [0.0, 0.0, 1.0]\nlook_at = [0.0, 0.0, 2.0]\n\n\
         [materials.mirror]\nkr = 1e9\nemission = 1e9\n\n\
         [[objects]]\ntype = \"plane\"\npoint = [0.0, 0.0, 0.0]\nnormal = [0.0, 0.0, 1.0]\nmaterial = \"mirror\"\n\n\
         [[objects]]\ntype = \"plane\"\npoint = [0.0, 0.0, 4.0]\nnormal = [0.0, 0.0, -1.0]\nmaterial = \"mirror\"\n"
    )
}

#[test]
fn radiance_beyond_f32_is_an_error_naming_its_cause_and_writes_nothing() {
    let dir = TempDir::new("overflow");
    let mut backends = vec!["cpu"];
    if !skip_gpu() {
        backends.extend(["gpu", "both"]);
    }
    for depth in [4, 40] {
        std::fs::write(dir.join("gain.toml"), overflowing_scene(depth)).unwrap();
        for backend in &backends {
            for output in ["out.exr", "out.png"] {
                let out = glint(&dir, ["render", "gain.toml", "--backend", backend, "-q", "-o", output]);
                let stderr = text(&out.stderr);
                let tag = format!("depth {depth}, {backend}, {output}");
                assert!(!out.status.success(), "{tag}: succeeded");
                for f in [
                    "render is not a valid image",
                    "not a finite f32 number",
                    "no image was written",
                    "materials.mirror returns k_r + k_t = 1000000000 times",
                    &format!("up to {depth} bounces"),
                    "materials.mirror.emission = 1000000000",
                    "keep k_r + k_t ≤ 1",
                ] {
                    assert!(stderr.contains(f), "{tag}: no {f:?} in\n{stderr}");
                }
                assert!(!stderr.contains("this is a bug"), "{tag}: {stderr}");
                assert_eq!(dir.listing(), ["gain.toml"], "{tag}: left behind");
            }
        }
    }
}

/// Facing mirrors of k_r = 2 around a lit floor and sphere, looked at along their normal: a path
/// bounces between them, its weight doubling, before it meets the floor. Beyond depth ≈ 127 the
/// weight passes f32's range while the light it finally meets is below 1.
fn doubling_mirrors(depth: u32) -> String {
    format!(
        "[render]\nwidth = 48\nheight = 36\nmax_depth = {depth}\nbailout = 0.0\n\
         [camera]\nposition = [0.0, 1.0, -0.5]\nlook_at = [0.0, 1.0, 3.0]\nfov_y = 1\n\
         [materials.m]\nka = 0.0\nkd = 0.0\nkr = 2.0\n[materials.d]\nkd = 0.7\n\
         [[lights]]\ntype = \"point\"\nposition = [0.0, 1.8, 0.0]\n\
         [[objects]]\ntype = \"plane\"\npoint = [0.0, 0.0, 1.0]\nnormal = [0.0, 0.0, -1.0]\nmaterial = \"m\"\n\
         [[objects]]\ntype = \"plane\"\npoint = [0.0, 0.0, -1.0]\nnormal = [0.0, 0.0, 1.0]\nmaterial = \"m\"\n\
         [[objects]]\ntype = \"plane\"\npoint = [0.0, 0.0, 0.0]\nnormal = [0.0, 1.0, 0.0]\nmaterial = \"d\"\n\
         [[objects]]\ntype = \"sphere\"\ncenter = [0.3, 0.5, 0.2]\nradius = 0.3\nmaterial = \"d\"\n"
    )
}

#[test]
fn a_gpu_path_weight_past_f32_is_refused_as_the_cpu_s_radiance_is() {
    // The GPU held the weight at f32's largest value and wrote a finite, wrong image at depth
    // 140, which the CPU refused (a tester). At depth 120 both are finite and agree.
    if skip_gpu() {
        eprintln!("GLINT_SKIP_GPU=1: the GPU's side of the overflow is not rendered");
        return;
    }
    let dir = TempDir::new("doubling");
    for (depth, refused) in [(120, false), (140, true)] {
        std::fs::write(dir.join("mirrors.toml"), doubling_mirrors(depth)).unwrap();
        for backend in ["cpu", "gpu"] {
            let out = glint(&dir, ["render", "mirrors.toml", "--backend", backend, "-q", "-o", "out.exr"]);
            let stderr = text(&out.stderr);
            let tag = format!("depth {depth}, {backend}");
            assert_eq!(!out.status.success(), refused, "{tag}:\n{stderr}");
            if refused {
                assert!(
                    stderr.contains("not a finite f32 number") && stderr.contains("keep k_r + k_t ≤ 1"),
                    "{tag}: {stderr}"
                );
                assert!(!dir.join("out.exr").exists(), "{tag}: an image was written");
            } else {
                std::fs::remove_file(dir.join("out.exr")).expect(&tag);
            }
        }
    }
}

#[test]
fn a_gpu_status_flag_fails_the_render_unless_incomplete_images_are_allowed() {
    if skip_gpu() {
        eprintln!("GLINT_SKIP_GPU=1: no GPU render to raise a status flag");
        return;
    }
    let dir = TempDir::new("status");
    std::fs::write(dir.join("slab.toml"), stack_overflow_slab()).unwrap();
    let out = glint(&dir, ["render", "slab.toml", "--backend", "gpu", "-q", "-o", "slab.png"]);
    let stderr = text(&out.stderr);
    assert!(!out.status.success(), "a stack overflow passed:\n{stderr}");
    for f in ["the gpu render is incomplete (status 0x2)", "GPU stack", "--allow-incomplete", "no image was written"] {
        assert!(stderr.contains(f), "no {f:?} in\n{stderr}");
    }
    assert_eq!(dir.listing(), ["slab.toml"]);

    let out = glint(&dir, ["render", "slab.toml", "--backend", "gpu", "-q", "-o", "slab.png", "--allow-incomplete"]);
    let stderr = text(&out.stderr);
    assert!(out.status.success(), "{stderr}");
    assert!(stderr.contains("warning: the gpu image is incomplete"), "{stderr}");
    let chunks = png_text_chunks(&dir.join("slab.png"));
    let value = |key: &str| chunks.iter().find(|(k, _)| k == key).map(|(_, v)| v.clone());
    assert_eq!(value("glint:gpu_status").as_deref(), Some("0x2"), "{chunks:?}");
    assert!(value("glint:incomplete").is_some_and(|v| v.contains("GPU stack")), "{chunks:?}");
}

#[test]
fn threads_are_bounded_and_the_error_names_the_flag_and_range() {
    let dir = TempDir::new("threads");
    for value in ["100000", "-1", "many"] {
        let out = glint(
            &dir,
            ["render", "whitted", "--width", "8", "--height", "8", "-q", "-o", "x.png", "--threads", value],
        );
        let stderr = text(&out.stderr);
        assert!(!out.status.success(), "--threads {value} succeeded");
        assert!(stderr.contains("--threads") && stderr.contains("takes 0 (one per core) to "), "{value}: {stderr}");
    }
    let out =
        glint(&dir, ["render", "whitted", "--width", "8", "--height", "8", "-q", "-o", "x.png", "--threads", "100000"]);
    assert!(text(&out.stderr).contains("100000 is outside [0, "), "{}", text(&out.stderr));
    assert!(dir.listing().is_empty());
}

#[cfg(unix)]
#[test]
fn a_file_system_failure_is_reported_as_one_not_as_a_format_error() {
    // A file size limit of 8 kB (ulimit -f, SIGXFSZ ignored): the EXR write fails with EFBIG,
    // as a full disk fails with ENOSPC.
    let dir = TempDir::new("full");
    let script = "ulimit -f 16; trap '' XFSZ; exec \"$0\" \"$@\"";
    for output in ["out.exr", "out.png"] {
        let out = Command::new("sh")
            .args(["-c", script, BIN, "render", "whitted", "--width", "512", "--height", "512", "-q", "-o", output])
            .current_dir(&dir)
            .output()
            .expect("run sh");
        let stderr = text(&out.stderr);
        assert!(!out.status.success(), "{output}: succeeded");
        assert!(stderr.contains(output) && stderr.contains("File too large"), "{output}: {stderr}");
        assert!(!stderr.contains("format error") && !stderr.contains("decoding"), "{output}: {stderr}");
        assert!(dir.listing().is_empty(), "{output}: left {:?}", dir.listing());
    }
}

#[test]
fn a_legal_250_byte_output_name_is_written() {
    let dir = TempDir::new("long-name");
    let name = format!("{}.png", "n".repeat(246));
    let out = glint(&dir, ["render", "whitted", "--width", "8", "--height", "6", "-q", "-o", &name]);
    assert!(out.status.success(), "{}", text(&out.stderr));
    assert_eq!(dir.listing(), [name]);
}

/// A scene file's name in any script, or not UTF-8 at all, renders to a PNG of its own name:
/// 日本.toml failed to write (PNG's tEXt holds Latin-1 only; its path is `glint:source`), and a
/// name not in UTF-8 was refused by the argument parser without naming the argument.
#[cfg(unix)]
#[test]
fn a_scene_named_in_any_script_or_not_utf8_renders_under_its_own_name() {
    use std::os::unix::ffi::OsStrExt;
    let dir = TempDir::new("scene-names");
    let body = "[camera]\nposition = [0.0, 0.0, -3.0]\nlook_at = [0.0, 0.0, 0.0]\n[materials.m]\nkd = 0.5\n\
        [[lights]]\ntype = \"point\"\nposition = [0.0, 2.0, -2.0]\n\
        [[objects]]\ntype = \"sphere\"\ncenter = [0.0, 0.0, 0.0]\nradius = 1.0\nmaterial = \"m\"\n";
    let latin = std::ffi::OsStr::from_bytes(b"w\xff");
    for stem in [std::ffi::OsStr::new("日本"), latin] {
        let mut scene = stem.to_os_string();
        scene.push(".toml");
        std::fs::write(dir.join(&scene), body).expect("scene");
        let out = glint(
            &dir,
            [
                std::ffi::OsStr::new("render"),
                &scene,
                "--width".as_ref(),
                "8".as_ref(),
                "--height".as_ref(),
                "6".as_ref(),
                "-q".as_ref(),
            ],
        );
        assert!(out.status.success(), "{stem:?}: {}", text(&out.stderr));
        let mut png = stem.to_os_string();
        png.push(".png");
        assert!(dir.join(&png).is_file(), "{stem:?}: {:?}", dir.listing());
    }
    // `report --scenes` takes it in its comma-separated list (clap's list of strings refused
    // it): the list's next scene, missing, is the error, so the name was read and loaded.
    let mut list = OsString::from(" ");
    list.push(latin);
    list.push(".toml , gone.toml");
    let out = glint(&dir, [std::ffi::OsStr::new("report"), "--quick".as_ref(), "--scenes".as_ref(), &list]);
    let stderr = text(&out.stderr);
    assert!(!out.status.success() && stderr.contains("gone.toml") && !stderr.contains("invalid UTF-8"), "{stderr}");
}

/// A name longer than file systems allow is refused before the render, naming its length (it
/// failed after the whole render, a farm task's work thrown away), and so, with `--backend
/// both`, before any of the three images is written.
#[test]
fn an_output_name_too_long_for_the_file_system_is_refused_before_the_render() {
    let dir = TempDir::new("too-long-name");
    let name = format!("{}.png", "n".repeat(252));
    for backend in ["cpu", "both"] {
        let out = glint(
            &dir,
            ["render", "whitted", "--width", "8", "--height", "6", "-q", "--backend", backend, "-o", &name],
        );
        let stderr = text(&out.stderr);
        assert!(!out.status.success(), "{backend}: succeeded");
        let length = if backend == "cpu" { 256 } else { 260 };
        let said = format!("the file name is {length} bytes long; file systems allow at most 255");
        assert!(stderr.contains(&said), "{backend}: {stderr}");
        assert!(!stderr.contains("render ms") && dir.listing().is_empty(), "{backend}: {stderr} {:?}", dir.listing());
    }
}

/// Glass between two facing mirrors with no bailout: every glass hit doubles the tree, to
/// 2^1025 rays a camera sample at `max_depth = 1024`.
const BRANCHING: &str = "[render]\nwidth = 4\nheight = 4\nmax_depth = 1024\nbailout = 0.0\n\n\
    [camera]\nposition = [0.0, 0.0, 1.0]\nlook_at = [0.0, 0.0, 2.0]\n\n\
    [materials.mirror]\nkr = 0.9\n\n[materials.glass]\nkr = 0.5\nkt = 0.5\nior = 1.5\n\n\
    [[lights]]\ntype = \"point\"\nposition = [0.0, 1.0, 2.0]\n\n\
    [[objects]]\ntype = \"plane\"\npoint = [0.0, 0.0, 0.0]\nnormal = [0.0, 0.0, 1.0]\nmaterial = \"mirror\"\n\n\
    [[objects]]\ntype = \"plane\"\npoint = [0.0, 0.0, 4.0]\nnormal = [0.0, 0.0, -1.0]\nmaterial = \"mirror\"\n\n\
    [[objects]]\ntype = \"sphere\"\ncenter = [0.0, 0.0, 2.5]\nradius = 1.0\nmaterial = \"glass\"\n";

#[test]
fn a_ray_tree_without_end_stops_at_the_cap_naming_the_pixel_and_the_remedy() {
    let dir = TempDir::new("ray-cap");
    std::fs::write(dir.join("tree.toml"), BRANCHING).unwrap();
    // The default cap (2^22 rays a sample) and a small one both stop it, in well under the
    // hours the whole tree would take.
    for cap in [None, Some("5000")] {
        let mut args = vec!["render", "tree.toml", "-q", "-o", "tree.exr"];
        args.extend(cap.iter().flat_map(|c| ["--max-rays-per-sample", *c]));
        let out = glint(&dir, args);
        let stderr = text(&out.stderr);
        assert!(!out.status.success(), "{cap:?}: a capped render succeeded");
        let cap_text = format!("reached the cap of {} rays", cap.unwrap_or("4194304"));
        for f in ["up to 2^1025 − 1", "pixel (", &cap_text, "set render.bailout", "--max-rays-per-sample"] {
            assert!(stderr.contains(f), "{cap:?}: no {f:?} in\n{stderr}");
        }
        assert_eq!(dir.listing(), ["tree.toml"], "{cap:?}: left behind");
    }
    // With a bailout the same tree ends by itself, under the same cap.
    let bounded = BRANCHING.replace("bailout = 0.0", "bailout = 0.004");
    std::fs::write(dir.join("tree.toml"), bounded).unwrap();
    let out = glint(&dir, ["render", "tree.toml", "-q", "-o", "tree.exr", "--max-rays-per-sample", "5000"]);
    assert!(out.status.success(), "{}", text(&out.stderr));
    // A cap below what a bounded scene needs is the cause, and said to be (whitted was told to
    // set the bailout it has).
    let out = glint(&dir, ["render", "whitted", "-q", "-o", "w.exr", "--max-rays-per-sample", "1"]);
    let stderr = text(&out.stderr);
    assert!(!out.status.success() && stderr.contains("raise the cap"), "{stderr}");
    // To the scene's own bound, which suffices (whitted: 41 tree rays at depth 5 with its
    // bailout, each hit with a shadow ray to its one light).
    assert!(
        stderr.contains("within 82 rays (41 reflected and refracted, each hit with a shadow ray to each of 1 light)"),
        "{stderr}"
    );
    let out = glint(
        &dir,
        ["render", "whitted", "-q", "-o", "w.exr", "--max-rays-per-sample", "82", "--width", "64", "--height", "48"],
    );
    assert!(out.status.success(), "{}", text(&out.stderr));
    assert!(!stderr.contains("set render.bailout"), "{stderr}");
    for bad in ["0", "-3", "1099511627777", "x"] {
        let out = glint(&dir, ["render", "tree.toml", "-q", "-o", "bad.exr", "--max-rays-per-sample", bad]);
        let stderr = text(&out.stderr);
        assert!(!out.status.success() && stderr.contains("[1, 1099511627776]"), "{bad}: {stderr}");
    }
}

/// `DISPLAY` naming an X server that is not there: the error says so, not the retry's
/// "EventLoop can't be recreated".
#[test]
fn a_display_without_a_server_is_named_as_the_cause() {
    let dir = TempDir::new("no-x-server");
    // A display number no test machine runs: its socket is absent.
    let display = ":197";
    assert!(!std::path::Path::new("/tmp/.X11-unix/X197").exists(), "a server runs on {display}");
    let out = Command::new(BIN)
        .args(["view", "whitted"])
        .current_dir(&*dir)
        .env("DISPLAY", display)
        .env_remove("WAYLAND_DISPLAY")
        .output()
        .expect("run glint");
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(!out.status.success(), "{stderr}");
    let last = stderr.lines().rfind(|l| l.starts_with("error")).unwrap_or_else(|| panic!("no error line: {stderr}"));
    assert!(!last.contains("can't be recreated"), "the retry's error hides the cause: {last}");
    assert!(last.contains("X server") && last.contains("DISPLAY=:197"), "{last}");
    assert!(!last.contains(".rs:"), "a source location is no cause: {last}");
}

#[test]
fn a_reader_that_goes_away_ends_the_output_not_the_command() {
    // `glint render --list | head -1`, `glint render … | true`: a closed pipe on stdout (or on
    // stderr, shared with it by `2>&1`). `println!` panicked there (exit 101), after the images
    // were written.
    let dir = TempDir::new("closed-pipe");
    for args in
        [&["render", "--list"][..], &["render", "whitted", "--width", "32", "--height", "24", "-q", "-o", "w.png"][..]]
    {
        let (reader, writer) = std::io::pipe().expect("a pipe");
        drop(reader);
        let err_writer = writer.try_clone().expect("a second handle");
        let status = Command::new(BIN)
            .args(args)
            .current_dir(&dir)
            .stdout(writer)
            .stderr(err_writer)
            .status()
            .expect("run glint");
        assert!(status.success(), "glint {args:?} with a closed stdout and stderr: {status}");
    }
    assert_eq!(dir.listing(), ["w.png"]);
}

/// A file size limit (`ulimit -f`) makes the write fail: glint says so, naming the output, exits
/// 1 and leaves nothing — the limit's signal, SIGXFSZ, would end it silently, its temporary
/// left behind.
#[cfg(unix)]
#[test]
fn a_file_size_limit_is_reported_and_leaves_no_file() {
    let dir = TempDir::new("file-size-limit");
    for output in ["big.png", "big.exr"] {
        // 20 blocks of 1 KiB (bash counts 1024 bytes); a 512×384 image takes more in either format.
        let script = format!("ulimit -f 20; exec '{BIN}' render whitted --width 512 --height 384 -q -o {output}");
        let out = Command::new("bash").args(["-c", &script]).current_dir(&dir).output().expect("bash");
        let stderr = text(&out.stderr);
        assert_eq!(out.status.code(), Some(1), "{output}: {:?}\n{stderr}", out.status);
        assert!(stderr.contains(output) && stderr.contains("File too large"), "{output}: {stderr}");
        assert!(dir.listing().is_empty(), "{output}: left behind {:?}", dir.listing());
    }
}

#[cfg(unix)]
#[test]
fn an_output_that_is_a_link_is_replaced_and_its_target_kept() {
    // rendering.md: the link goes, the file it pointed to is left as it was.
    let dir = TempDir::new("link-output");
    std::fs::write(dir.join("target.txt"), "kept").unwrap();
    std::os::unix::fs::symlink(dir.join("target.txt"), dir.join("link.png")).unwrap();
    let out = glint(&dir, ["render", "whitted", "--width", "8", "--height", "6", "-q", "-o", "link.png"]);
    assert!(out.status.success(), "{}", text(&out.stderr));
    assert!(!std::fs::symlink_metadata(dir.join("link.png")).unwrap().file_type().is_symlink(), "still a link");
    assert_eq!(image::open(dir.join("link.png")).expect("a PNG").into_rgb8().dimensions(), (8, 6));
    assert_eq!(std::fs::read_to_string(dir.join("target.txt")).unwrap(), "kept");
}
