//! Every kept proptest regression file is replayed by a property test: named in a
//! `common::config("…")` of an integration test, or kept beside the source file whose unit
//! tests use proptest's default (source-parallel) persistence. A file nobody reads would keep
//! a minimal failing case that is never run again.

use std::fs;
use std::path::{Path, PathBuf};

/// Files under `dir` (recursively) whose name satisfies `keep`.
fn files(dir: &Path, keep: &dyn Fn(&str) -> bool, out: &mut Vec<PathBuf>) {
    let Ok(entries) = fs::read_dir(dir) else {
        return;
    };
    for entry in entries.flatten() {
        let path = entry.path();
        if path.is_dir() {
            files(&path, keep, out);
        } else if path.file_name().and_then(|n| n.to_str()).is_some_and(keep) {
            out.push(path);
        }
    }
}

#[test]
fn every_regression_file_is_replayed() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let mut tests = Vec::new();
    files(&root.join("tests"), &|n| n.ends_with(".rs"), &mut tests);
    let named: String = tests
        .iter()
        .map(|p| fs::read_to_string(p).expect("a test source is readable"))
        .collect();
    let mut kept = Vec::new();
    files(
        &root.join("proptest-regressions"),
        &|n| n.ends_with(".txt"),
        &mut kept,
    );
    files(
        &root.join("tests"),
        &|n| n.ends_with(".proptest-regressions"),
        &mut kept,
    );
    assert!(
        kept.len() >= 5,
        "found only {} regression files: is the crate layout as this test expects?",
        kept.len()
    );
    for file in &kept {
        let rel = file
            .strip_prefix(root)
            .expect("under the crate")
            .to_string_lossy()
            .replace('\\', "/");
        let explicit = named.contains(&format!("\"{rel}\""));
        // proptest's default persistence: src/a/b.rs keeps proptest-regressions/a/b.txt.
        let parallel = rel
            .strip_prefix("proptest-regressions/")
            .and_then(|r| r.strip_suffix(".txt"))
            .map(|stem| root.join("src").join(format!("{stem}.rs")))
            .and_then(|src| fs::read_to_string(src).ok())
            .is_some_and(|text| text.contains("proptest!"));
        assert!(
            explicit || parallel,
            "{rel} is replayed by no property test (name it in a common::config or remove it)"
        );
    }
}
