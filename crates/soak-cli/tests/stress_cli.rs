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

/// A matrix killed with SIGKILL half-way keeps the cells it finished in its
/// journal; `--resume` runs the others only and prints the whole table,
/// the same cells with the same verdicts as a run without a stop.
#[test]
fn a_killed_matrix_resumes_from_its_journal() {
    let dir = std::env::temp_dir().join(format!("soak-stress-journal-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    let journal = dir.join("cells.jsonl");
    let only = ["--only", "sphere/1m/0.5/1/60/", "--threads", "1"];
    let lines = || std::fs::read_to_string(&journal).map_or(0, |t| t.lines().count());
    let mut child = Command::new(env!("CARGO_BIN_EXE_soak"))
        .arg("stress")
        .args(only)
        .arg("--journal")
        .arg(&journal)
        .stdout(std::process::Stdio::null())
        .stderr(std::process::Stdio::null())
        .spawn()
        .unwrap();
    let start = std::time::Instant::now();
    // The head and at least two cells.
    while lines() < 3 && child.try_wait().unwrap().is_none() {
        assert!(start.elapsed().as_secs() < 300, "no cell in five minutes");
        std::thread::sleep(std::time::Duration::from_millis(10));
    }
    child.kill().unwrap();
    let _ = child.wait();
    let kept = lines() - 1;
    let resumed = Command::new(env!("CARGO_BIN_EXE_soak"))
        .arg("stress")
        .args(only)
        .arg("--journal")
        .arg(&journal)
        .args(["--resume", "--json"])
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&resumed.stderr);
    assert!(resumed.status.success(), "{stderr}");
    let straight = Command::new(env!("CARGO_BIN_EXE_soak"))
        .arg("stress")
        .args(only)
        .arg("--json")
        .output()
        .unwrap();
    let cells = |out: &[u8]| -> Vec<(String, bool)> {
        let v: Vec<serde_json::Value> = serde_json::from_slice(out).unwrap();
        v.iter()
            .map(|c| (c["cell"].as_str().unwrap().to_string(), c["pass"] == true))
            .collect()
    };
    let (a, b) = (cells(&resumed.stdout), cells(&straight.stdout));
    assert_eq!(a, b);
    if kept < a.len() {
        assert!(
            stderr.contains(&format!(
                "resuming: {kept} of {} cells are in the journal",
                a.len()
            )),
            "{stderr}"
        );
    }
    // Every cell once in the journal now.
    assert_eq!(lines(), 1 + a.len());
    // Another matrix's journal is refused.
    let other = Command::new(env!("CARGO_BIN_EXE_soak"))
        .args(["stress", "--only", "box/1m/0.5/1/60/", "--journal"])
        .arg(&journal)
        .arg("--resume")
        .output()
        .unwrap();
    assert!(!other.status.success());
    assert!(String::from_utf8_lossy(&other.stderr).contains("of another matrix"));
    let _ = std::fs::remove_dir_all(&dir);
}
