//! `soak accuracy --quick`: the command writes its figures and markdown and
//! prints JSON that parses, or a table that names its files. The numbers
//! themselves are checked in soak-report's `tests/accuracy.rs`.

use std::path::{Path, PathBuf};
use std::process::Command;

use serde_json::Value;

fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("soak-accuracy-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).expect("temp dir");
    dir
}

fn soak(args: &[&str]) -> String {
    let out = Command::new(env!("CARGO_BIN_EXE_soak"))
        .args(args)
        .output()
        .expect("runs soak");
    assert!(
        out.status.success(),
        "soak {args:?} failed:\n{}",
        String::from_utf8_lossy(&out.stderr)
    );
    String::from_utf8(out.stdout).expect("utf-8 output")
}

fn is_png(path: &Path) -> bool {
    std::fs::read(path).is_ok_and(|b| b.starts_with(b"\x89PNG\r\n\x1a\n"))
}

#[test]
fn quick_json_parses_and_names_its_files() {
    let dir = scratch("json");
    let md = dir.join("accuracy.md");
    let out = dir.join("img");
    let json = soak(&[
        "accuracy",
        "--quick",
        "--json",
        "--out",
        out.to_str().unwrap(),
        "--markdown",
        md.to_str().unwrap(),
    ]);
    let report: Value = serde_json::from_str(&json).expect("the JSON parses");
    assert_eq!(report["quick"], Value::Bool(true));
    assert!(report["rows"].as_array().is_some_and(|r| !r.is_empty()));
    let files: Vec<PathBuf> = report["files"]
        .as_array()
        .expect("files")
        .iter()
        .map(|p| PathBuf::from(p.as_str().expect("path")))
        .collect();
    assert_eq!(files.len(), 3, "two figures and the markdown: {files:?}");
    for p in files.iter().filter(|p| p.extension().is_some_and(|e| e == "png")) {
        assert!(p.starts_with(&out) && is_png(p), "{} is not a PNG", p.display());
    }
    let table = std::fs::read_to_string(&md).expect("markdown written");
    assert!(table.contains("](img/accuracy_sphere.png)"));
    std::fs::remove_dir_all(dir).ok();
}
