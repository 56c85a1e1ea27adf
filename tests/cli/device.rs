//! The device suite's scripts (issue 31) where no hardware GPU is: the bundle's size check, the
//! suite refusing a software adapter instead of passing lavapipe off as the hardware, and the
//! adapter listing it reads, quiet on a headless machine.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

use glint_test_support::TempDir;

use crate::BIN;

fn script(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("scripts").join(name)
}

/// Runs a Python script of scripts/; fails with what to install where there is no python3.
fn python(script_name: &str, args: &[&str]) -> Output {
    Command::new("python3")
        .arg(script(script_name))
        .args(args)
        .output()
        .unwrap_or_else(|e| panic!("the device scripts need python3 ({e}): apt-get install python3"))
}

fn text(o: &Output) -> String {
    format!("{}{}", String::from_utf8_lossy(&o.stdout), String::from_utf8_lossy(&o.stderr))
}

#[test]
fn the_bundle_size_check_refuses_what_a_device_run_cannot_carry() {
    let dir = TempDir::new("device-bundle-size");
    let bundle = dir.join("bundle");
    std::fs::create_dir_all(bundle.join("bin")).expect("bundle folder");
    std::fs::write(bundle.join("bin").join("big"), vec![7u8; 3 << 20]).expect("a 3 MiB file");
    let bundle_arg = bundle.to_str().expect("utf-8 path");

    // The working tree travels too: 1 MiB is less than both together.
    let over = python("device-bundle", &["--check", bundle_arg, "--limit-mib", "1"]);
    assert!(!over.status.success(), "a bundle over the limit passed:\n{}", text(&over));
    assert!(text(&over).contains("bundle 3.0 MiB + working tree"), "{}", text(&over));
    assert!(text(&over).contains("over the 1 MiB a device run carries"), "{}", text(&over));

    let within = python("device-bundle", &["--check", bundle_arg, "--limit-mib", "1000"]);
    assert!(within.status.success(), "{}", text(&within));
    assert!(text(&within).contains("within the 1000 MiB"), "{}", text(&within));

    let missing = dir.join("no-such-bundle");
    let absent = python("device-bundle", &["--check", missing.to_str().expect("utf-8 path")]);
    assert!(!absent.status.success() && text(&absent).contains("is not a folder"), "{}", text(&absent));
}

#[test]
fn the_device_suite_refuses_a_software_adapter_without_the_rehearsal_flag() {
    if glint_test_support::skip_requested("GLINT_SKIP_GPU") {
        eprintln!("GLINT_SKIP_GPU=1: skipping the device suite's adapter check");
        return;
    }
    let dir = TempDir::new("device-suite-adapter");
    let (bundle, out) = (dir.join("bundle"), dir.join("out"));
    std::fs::create_dir_all(&bundle).expect("bundle folder");
    let args = ["--glint", BIN, "--bundle", bundle.to_str().expect("utf-8"), "--out", out.to_str().expect("utf-8")];
    let o = python("device-suite", &args);
    // This machine's adapter is lavapipe (mesa-vulkan-drivers), a software one.
    assert!(!o.status.success(), "the suite passed on a software adapter:\n{}", text(&o));
    assert!(text(&o).contains("no hardware GPU adapter: found llvmpipe"), "{}", text(&o));
    let summary: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("device-suite.json")).expect("the JSON summary"))
            .expect("JSON");
    assert_eq!(summary["passed"], false);
    let adapter = summary["checks"].as_array().expect("checks").iter().find(|c| c["name"] == "hardware adapter");
    assert_eq!(adapter.expect("the adapter check")["status"], "fail");
    let md = std::fs::read_to_string(out.join("device-suite.md")).expect("the Markdown summary");
    assert!(md.contains("| hardware adapter | fail |"), "{md}");
    // Why, for the next attempt: this machine has no NVIDIA GPU at all.
    assert!(md.contains("No NVIDIA GPU is visible") && md.contains("- Driver: no nvidia-smi listing"), "{md}");
    assert!(summary["driver"]["vulkan_manifests"].as_array().is_some_and(|m| !m.is_empty()), "{summary}");
    let log = std::fs::read_to_string(out.join("device-suite.log")).expect("the log");
    assert!(log.contains("the Vulkan loader's report"), "{log}");
}

/// `glint adapters --json` is what the suite reads; a headless machine (no desktop session, so
/// no `XDG_RUNTIME_DIR`: a GPU server, a batch job) lists it without the "error: XDG_RUNTIME_DIR
/// is invalid" lines Mesa's device-select layer made libwayland print on every run.
#[test]
fn adapters_are_listed_as_json_without_display_errors_on_a_headless_machine() {
    if glint_test_support::skip_requested("GLINT_SKIP_GPU") {
        eprintln!("GLINT_SKIP_GPU=1: skipping the adapter listing");
        return;
    }
    let dir = TempDir::new("adapters-headless");
    for args in [&["adapters", "--json"][..], &["render", "--backend", "gpu", "--width", "8", "--height", "6", "-q"]] {
        let o = Command::new(BIN)
            .args(args)
            .current_dir(&dir)
            .env_remove("XDG_RUNTIME_DIR")
            .env_remove("WAYLAND_DISPLAY")
            .env_remove("NODEVICE_SELECT")
            .output()
            .expect("run glint");
        assert!(o.status.success(), "glint {args:?}: {}", text(&o));
        let stderr = String::from_utf8_lossy(&o.stderr);
        assert!(!stderr.contains("XDG_RUNTIME_DIR") && !stderr.contains("error"), "glint {args:?}: {stderr}");
        if args[0] == "adapters" {
            let adapters: serde_json::Value = serde_json::from_slice(&o.stdout).expect("JSON");
            let first = &adapters.as_array().expect("a list")[0];
            for key in ["name", "backend", "device_type", "driver", "software"] {
                assert!(!first[key].is_null(), "{key} missing: {first}");
            }
        }
    }
}
