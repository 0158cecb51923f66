//! `soak seakeeping --references`: the panel method against the two
//! classical bodies' references, as a table and a figure; and a command
//! with neither a mesh nor `--references` refused by clap.

use std::process::{Command, Output};

fn seakeeping(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_soak"))
        .arg("seakeeping")
        .args(args)
        .output()
        .expect("runs soak")
}

#[test]
fn the_references_table_and_figure() {
    let dir = std::env::temp_dir().join(format!("soak-seakeeping-references-{}", std::process::id()));
    let png = dir.join("references.png");
    let out = seakeeping(&["--references", png.to_str().unwrap()]);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(text.contains("Hulme (1982) (576 panels)"), "{text}");
    assert!(text.contains("eigenfunctions (1152 panels)"), "{text}");
    // Every added mass within 3 % of its reference (the error column
    // after the panels' value, in percent).
    let errors: Vec<f64> = text
        .lines()
        .filter_map(|l| {
            let cols: Vec<&str> = l.split_whitespace().collect();
            (cols.len() >= 5 && cols[0].parse::<f64>().is_ok()).then(|| cols[3].parse::<f64>().unwrap())
        })
        .collect();
    assert_eq!(errors.len(), 19 + 15, "{text}");
    assert!(errors.iter().all(|e| e.abs() < 3.0), "{errors:?}");
    let bytes = std::fs::read(&png).expect("the figure");
    assert!(
        bytes.starts_with(b"\x89PNG") && bytes.len() > 10_000,
        "{} bytes",
        bytes.len()
    );
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn a_mesh_or_the_references_is_asked_for() {
    let out = seakeeping(&[]);
    assert!(!out.status.success());
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains("<MESH>"), "{err}");
    let out = seakeeping(&["builtin:sphere", "--references", "x.png"]);
    assert!(!out.status.success());
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains("cannot be used with"), "{err}");
}
