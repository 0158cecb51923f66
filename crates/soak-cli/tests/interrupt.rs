//! Ctrl-C stops a long headless run cleanly: it writes what it recorded,
//! says where it stopped and exits with 130; a run that never ends on its
//! own (`--duration forever`) included.

use std::io::{BufRead, BufReader};
use std::path::PathBuf;
use std::process::{Child, Command, Stdio};
use std::time::Duration;

fn scene(name: &str) -> PathBuf {
    [env!("CARGO_MANIFEST_DIR"), "..", "..", "data", "scenes", name]
        .iter()
        .collect()
}

/// `soak ARGS`, its progress printed every tenth of a second.
fn soak(args: &[&std::ffi::OsStr]) -> Child {
    Command::new(env!("CARGO_BIN_EXE_soak"))
        .args(args)
        .env("SOAK_PROGRESS_SECONDS", "0.1")
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("runs soak")
}

/// Sends SIGINT to `child` once it has printed `progress` lines of progress
/// (each holding "left", or "until stopped" for a run without an end), and waits for it (at most two minutes), reading
/// its output meanwhile (a full pipe would block it). Returns its exit
/// status, standard output and standard error.
fn interrupt(mut child: Child, progress: usize) -> (Option<i32>, Vec<u8>, String) {
    let stderr = child.stderr.take().expect("piped");
    let (lines_tx, lines) = std::sync::mpsc::channel();
    let reader = std::thread::spawn(move || {
        let mut all = String::new();
        for line in BufReader::new(stderr).lines().map_while(Result::ok) {
            let _ = lines_tx.send(line.clone());
            all.push_str(&line);
            all.push('\n');
        }
        all
    });
    let mut seen = 0;
    while seen < progress {
        let line = lines
            .recv_timeout(Duration::from_secs(120))
            .expect("progress within two minutes");
        seen += usize::from(line.contains("left") || line.contains("until stopped"));
    }
    let sent = Command::new("kill")
        .args(["-INT", &child.id().to_string()])
        .status()
        .expect("runs kill");
    assert!(sent.success());
    let (tx, rx) = std::sync::mpsc::channel();
    std::thread::spawn(move || tx.send(child.wait_with_output()));
    let out = rx
        .recv_timeout(Duration::from_secs(120))
        .expect("it stops within two minutes of Ctrl-C")
        .expect("collects the output");
    let stderr = reader.join().expect("reads standard error");
    (out.status.code(), out.stdout, stderr)
}

#[test]
fn ctrl_c_stops_an_endless_simulation_and_writes_its_time_series() {
    let csv = std::env::temp_dir().join(format!("soak-interrupt-{}.csv", std::process::id()));
    let _ = std::fs::remove_file(&csv);
    let scene = scene("three_boxes.toml");
    let child = soak(&[
        "simulate".as_ref(),
        scene.as_os_str(),
        "--duration".as_ref(),
        "forever".as_ref(),
        "--csv".as_ref(),
        csv.as_os_str(),
    ]);
    let (code, stdout, stderr) = interrupt(child, 3);
    let stdout = String::from_utf8_lossy(&stdout);
    assert_eq!(code, Some(130), "{stderr}");
    // Progress: the simulated time and the pace, with no end to count to.
    assert!(
        stderr.contains("t = ") && stderr.contains("until stopped"),
        "{stderr}"
    );
    assert!(stderr.contains("stopped by Ctrl-C at t = "), "{stderr}");
    assert!(stdout.contains("three_boxes.toml after"), "{stdout}");
    let rows = std::fs::read_to_string(&csv).expect("the time series was written");
    assert!(rows.lines().count() > 10, "{} lines", rows.lines().count());
    let _ = std::fs::remove_file(&csv);
}

#[test]
fn ctrl_c_stops_the_stability_matrix_with_the_table_of_the_cells_run() {
    let child = soak(&[
        "stress".as_ref(),
        "--only".as_ref(),
        "sphere/".as_ref(),
        "--json".as_ref(),
    ]);
    let (code, stdout, stderr) = interrupt(child, 2);
    assert_eq!(code, Some(130), "{stderr}");
    // "stopped by Ctrl-C after N of M cells (…)"
    let counts: Vec<usize> = stderr
        .split("stopped by Ctrl-C after ")
        .nth(1)
        .expect("says where it stopped")
        .split_whitespace()
        .take(3)
        .filter_map(|w| w.parse().ok())
        .collect();
    let [ran, all] = counts[..] else {
        panic!("{stderr}")
    };
    assert!(ran > 0 && ran < all, "{stderr}");
    let cells: Vec<serde_json::Value> = serde_json::from_slice(&stdout).expect("JSON of the cells run");
    assert_eq!(cells.len(), ran);
    assert!(cells.iter().all(|c| c["pass"] == true));
}
