//! `soak stress` prints the cells it ran as JSON and exits with success
//! when every one passed (the matrix itself is tested in soak-report).

use std::process::Command;

#[test]
fn stress_prints_its_cells_and_exits_with_their_verdict() {
    let out = Command::new(env!("CARGO_BIN_EXE_soak"))
        .args(["stress", "--json", "--only", "sphere/1m/0.5/1/60/plane/buoyancy"])
        .output()
        .expect("run soak stress");
    let cells: Vec<serde_json::Value> = serde_json::from_slice(&out.stdout).unwrap_or_else(|e| {
        panic!(
            "soak stress printed no JSON ({e}); stderr:\n{}",
            String::from_utf8_lossy(&out.stderr)
        )
    });
    assert_eq!(cells.len(), 1);
    assert_eq!(cells[0]["cell"], "sphere/1m/0.5/1/60/plane/buoyancy");
    assert_eq!(cells[0]["pass"], true, "{}", cells[0]["failures"]);
    assert!(out.status.success());

    let none = Command::new(env!("CARGO_BIN_EXE_soak"))
        .args(["stress", "--only", "no such cell"])
        .output()
        .expect("run soak stress");
    assert!(!none.status.success());
    assert!(
        String::from_utf8_lossy(&none.stderr).contains("no cell of the matrix matches"),
        "{}",
        String::from_utf8_lossy(&none.stderr)
    );
}
