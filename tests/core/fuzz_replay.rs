//! The fuzz corpus and every input that once broke a check, replayed on stable through the
//! checks the `cargo fuzz` targets run (crates/glint-fuzz), so CI keeps them fixed without
//! the nightly toolchain.

use std::path::Path;

use glint_fuzz::{Target, replay_folder};

#[test]
fn every_kept_fuzz_input_passes_its_check() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("crates/glint-fuzz");
    let mut failures = Vec::new();
    for target in Target::ALL {
        for kind in ["corpus", "regressions"] {
            let folder = root.join(kind).join(target.name());
            // A target that never failed has no regressions folder; every target has a corpus.
            if kind == "regressions" && !folder.exists() {
                continue;
            }
            let report =
                replay_folder(target, &folder).unwrap_or_else(|e| panic!("cannot read {}: {e}", folder.display()));
            // The corpus of each target is what fuzzing kept: never empty.
            assert!(kind == "regressions" || report.inputs > 0, "{} is empty", folder.display());
            eprintln!("{}: {} inputs replayed", folder.display(), report.inputs);
            failures.extend(report.failures);
        }
    }
    let listed: Vec<String> = failures.iter().map(|(file, message)| format!("{}: {message}", file.display())).collect();
    assert!(listed.is_empty(), "{} fuzz inputs fail their check:\n{}", listed.len(), listed.join("\n"));
}
