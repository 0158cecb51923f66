//! `soak bench` prints its measurements as JSON and writes its plot (the
//! bench itself is tested in soak-report).

use std::path::Path;
use std::process::{Command, Output};

/// `soak bench` with `args`, two timed steps a case at most, its plot in
/// `dir`; it must succeed.
fn bench(args: &[&str], dir: &Path) -> Output {
    let out = Command::new(env!("CARGO_BIN_EXE_soak"))
        .arg("bench")
        .args(args)
        .args(["--max-steps", "2", "--budget", "0", "--out"])
        .arg(dir)
        .output()
        .expect("run soak bench");
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    out
}

#[test]
fn bench_prints_its_measurements_and_writes_its_plot() {
    let dir = std::env::temp_dir().join(format!("soak-bench-cli-{}", std::process::id()));
    let out = bench(&["--json", "--sizes", "1,2"], &dir);
    let report: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap_or_else(|e| {
        panic!(
            "soak bench printed no JSON ({e}); stderr:\n{}",
            String::from_utf8_lossy(&out.stderr)
        )
    });
    let measurements = report["measurements"].as_array().expect("measurements");
    // Rapier alone and nine generator columns (buoyancy, + drag,
    // + radiation on each of three waters), for 1 and 2 bodies.
    assert_eq!(measurements.len(), 20);
    assert!(
        measurements
            .iter()
            .all(|m| m["median_ms"].as_f64().is_some_and(|t| t > 0.0))
    );
    // The generator's columns say where their steps went, phase by
    // phase, within the step; Rapier alone has no phases.
    for m in measurements {
        let phases = &m["phases"];
        if m["water"].is_null() {
            assert!(phases.is_null(), "{m}");
            continue;
        }
        let ms: Vec<f64> = ["predict_ms", "prepare_ms", "evaluate_ms", "hand_ms", "engine_ms"]
            .iter()
            .map(|k| phases[*k].as_f64().unwrap_or_else(|| panic!("{k} in {m}")))
            .collect();
        assert!(ms.iter().all(|&t| t >= 0.0) && ms[2] > 0.0, "{m}");
        let mean = m["mean_ms"].as_f64().expect("mean_ms");
        assert!(ms.iter().sum::<f64>() <= mean, "{m}");
    }
    assert!(dir.join("scaling.png").exists());
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn bench_phases_prints_a_row_per_generator_column() {
    let dir = std::env::temp_dir().join(format!("soak-bench-phases-{}", std::process::id()));
    let out = bench(&["--phases", "--sizes", "1", "--water", "calm"], &dir);
    let text = String::from_utf8_lossy(&out.stdout);
    let table: Vec<&str> = text
        .lines()
        .skip_while(|l| !l.starts_with("soak's step phase by phase"))
        .collect();
    assert!(
        table.len() == 5,
        "the heading, the columns' names and three rows:\n{text}"
    );
    for (row, column) in table[2..].iter().zip(["calm, buoyancy", "+ drag", "+ radiation"]) {
        assert!(row.contains(column), "{row}");
    }
    let _ = std::fs::remove_dir_all(&dir);
}
