//! `soak bench` prints its measurements as JSON and writes its plot (the
//! bench itself is tested in soak-report).

use std::process::Command;

#[test]
fn bench_prints_its_measurements_and_writes_its_plot() {
    let dir = std::env::temp_dir().join(format!("soak-bench-cli-{}", std::process::id()));
    let out = Command::new(env!("CARGO_BIN_EXE_soak"))
        .args([
            "bench",
            "--json",
            "--sizes",
            "1,2",
            "--max-steps",
            "2",
            "--budget",
            "0",
            "--out",
        ])
        .arg(&dir)
        .output()
        .expect("run soak bench");
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
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
    assert!(dir.join("scaling.png").exists());
    let _ = std::fs::remove_dir_all(&dir);
}
