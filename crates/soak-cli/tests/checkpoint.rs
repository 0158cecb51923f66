//! Long runs that lose nothing: `soak simulate` killed with SIGKILL at
//! random steps and resumed from its last checkpoint ends with the CSV and
//! the state of the uninterrupted run, byte for byte; checkpoints that are
//! truncated, corrupted, of another scene or of other options are refused;
//! a duration that cannot end is refused up front.

use std::path::{Path, PathBuf};
use std::process::{Command, Output, Stdio};
use std::time::{Duration, Instant};

fn scene(name: &str) -> PathBuf {
    [env!("CARGO_MANIFEST_DIR"), "..", "..", "data", "scenes", name]
        .iter()
        .collect()
}

/// A fresh directory for one run.
fn directory(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("soak-checkpoint-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

/// The wet crate on its swell for 12 s (720 steps; wetting, radiation and
/// a sea to save), a checkpoint every simulated second, in `dir`, with
/// `extra` arguments.
fn command(dir: &Path, extra: &[&str]) -> Command {
    command_for(dir, "12", extra)
}

/// [`command`] for `duration` seconds.
fn command_for(dir: &Path, duration: &str, extra: &[&str]) -> Command {
    let mut c = Command::new(env!("CARGO_BIN_EXE_soak"));
    c.current_dir(dir)
        .arg("simulate")
        .arg(scene("wet_crate.toml"))
        .args([
            "--duration",
            duration,
            "--csv",
            "run.csv",
            "--checkpoint",
            "run.ckpt",
        ])
        .args(["--checkpoint-every", "1", "--out", "png", "--gltf", "run.glb"])
        .args(extra)
        .stdout(Stdio::piped())
        .stderr(Stdio::piped());
    c
}

fn finished(out: &Output) -> String {
    let text = format!(
        "{}{}",
        String::from_utf8_lossy(&out.stdout),
        String::from_utf8_lossy(&out.stderr)
    );
    assert!(out.status.success(), "{text}");
    text
}

/// Rows in the CSV so far (0 before it exists).
fn rows(path: &Path) -> usize {
    std::fs::read(path).map_or(0, |b| b.iter().filter(|&&c| c == b'\n').count())
}

/// A small deterministic generator for the kill points (seeded from the
/// clock, printed, so that a failing seed can be run again with
/// `SOAK_KILL_SEED`).
fn kill_points(count: usize, rows_max: usize) -> (u64, Vec<usize>) {
    let seed = std::env::var("SOAK_KILL_SEED")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or_else(|| {
            std::time::SystemTime::now()
                .duration_since(std::time::UNIX_EPOCH)
                .map_or(1, |d| d.as_nanos() as u64)
        });
    let mut x = seed | 1;
    let points = (0..count)
        .map(|_| {
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            // Past the first checkpoint (12 rows), before the end.
            15 + (x % (rows_max as u64 - 25)) as usize
        })
        .collect();
    (seed, points)
}

#[test]
fn a_run_killed_at_random_steps_and_resumed_ends_as_the_straight_run() {
    let straight = directory("straight");
    let said = finished(&command(&straight, &[]).output().unwrap());
    // The run says what its steps cost: all 720 of them, timed.
    let timing = said.lines().find(|l| l.contains("ms a step")).unwrap_or("");
    assert!(timing.contains("; 720 steps in "), "{said}");
    let csv = std::fs::read(straight.join("run.csv")).unwrap();
    let state = std::fs::read(straight.join("run.ckpt")).unwrap();
    let animation = std::fs::read(straight.join("run.glb")).unwrap();
    let total = rows(&straight.join("run.csv"));
    // The header, the start and a row every 6 of the 720 steps.
    assert_eq!(total, 122);
    let (seed, points) = kill_points(4, total);
    eprintln!("kill points (rows written; seed {seed}): {points:?}");
    for (n, &at) in points.iter().enumerate() {
        let dir = directory(&format!("killed-{n}"));
        let mut child = command(&dir, &[]).spawn().unwrap();
        let start = Instant::now();
        while rows(&dir.join("run.csv")) < at || !dir.join("run.ckpt").exists() {
            assert!(
                start.elapsed() < Duration::from_secs(300),
                "no progress to row {at}"
            );
            if child.try_wait().unwrap().is_some() {
                break;
            }
            std::thread::sleep(Duration::from_millis(5));
        }
        // SIGKILL: nothing of the process runs after it.
        child.kill().unwrap();
        let _ = child.wait();
        let killed_at = rows(&dir.join("run.csv"));
        let resumed = finished(&command(&dir, &["--resume", "run.ckpt"]).output().unwrap());
        assert!(resumed.contains("resuming"), "{resumed}");
        // A resumed run times the steps it took, not those it resumed.
        let timing = resumed.lines().find(|l| l.contains("ms a step")).unwrap_or("");
        assert!(!timing.contains("; 720 steps in "), "{resumed}");
        let line = resumed.lines().find(|l| l.contains("resuming")).unwrap_or("");
        eprintln!("killed with {killed_at} rows written; {line}");
        assert!(
            std::fs::read(dir.join("run.csv")).unwrap() == csv,
            "kill point {n} (row {at}): the CSV differs from the straight run's"
        );
        assert!(
            std::fs::read(dir.join("run.ckpt")).unwrap() == state,
            "kill point {n} (row {at}): the final state differs from the straight run's"
        );
        assert!(
            std::fs::read(dir.join("run.glb")).unwrap() == animation,
            "kill point {n} (row {at}): the glTF differs from the straight run's"
        );
        let _ = std::fs::remove_dir_all(&dir);
    }
    let _ = std::fs::remove_dir_all(&straight);
}

#[test]
fn damaged_or_foreign_checkpoints_are_refused_before_anything_runs() {
    let dir = directory("refused");
    finished(&command_for(&dir, "2", &[]).output().unwrap());
    let good = std::fs::read(dir.join("run.ckpt")).unwrap();
    let refused = |bytes: &[u8], extra: &[&str]| {
        std::fs::write(dir.join("bad.ckpt"), bytes).unwrap();
        let mut args = vec!["--resume", "bad.ckpt"];
        args.extend_from_slice(extra);
        let out = command_for(&dir, "2", &args).output().unwrap();
        assert!(!out.status.success());
        String::from_utf8_lossy(&out.stderr).to_string()
    };
    let truncated = refused(&good[..good.len() / 2], &[]);
    assert!(truncated.contains("is truncated"), "{truncated}");
    let mut flipped = good.clone();
    let middle = flipped.len() / 2;
    flipped[middle] ^= 0x20;
    let corrupted = refused(&flipped, &[]);
    assert!(corrupted.contains("is corrupted"), "{corrupted}");
    let mut newer = good.clone();
    newer[8] = newer[8].wrapping_add(1);
    let version = refused(&newer, &[]);
    assert!(version.contains("state format"), "{version}");
    let foreign = refused(b"t_s,body,x_m\n0,crate,1\n", &[]);
    assert!(foreign.contains("is not a soak checkpoint"), "{foreign}");
    // The same checkpoint under other options, or for an edited scene.
    let options = refused(&good, &["--liquid-png-every", "5"]);
    assert!(
        options.contains("--liquid-png-every was not given when the checkpoint was written, 5 now"),
        "{options}"
    );
    let edited = dir.join("edited.toml");
    let text = std::fs::read_to_string(scene("wet_crate.toml")).unwrap();
    std::fs::write(&edited, format!("{text}\n# edited\n")).unwrap();
    std::fs::write(dir.join("bad.ckpt"), &good).unwrap();
    let out = Command::new(env!("CARGO_BIN_EXE_soak"))
        .current_dir(&dir)
        .arg("simulate")
        .arg(&edited)
        .args(["--duration", "2", "--csv", "run.csv", "--checkpoint", "run.ckpt"])
        .args([
            "--checkpoint-every",
            "1",
            "--out",
            "png",
            "--gltf",
            "run.glb",
            "--resume",
            "bad.ckpt",
        ])
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(
        !out.status.success() && stderr.contains("edited since"),
        "{stderr}"
    );
    // Nothing was written over the run's outputs.
    assert_eq!(std::fs::read(dir.join("run.ckpt")).unwrap(), good);
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn a_duration_that_cannot_end_is_refused_up_front_unless_it_is_forever() {
    let dir = directory("forever");
    let start = Instant::now();
    // Three boxes for `duration` seconds: it must be refused; its message.
    let refused = |duration: &str| {
        let out = Command::new(env!("CARGO_BIN_EXE_soak"))
            .current_dir(&dir)
            .arg("simulate")
            .arg(scene("three_boxes.toml"))
            .args(["--duration", duration])
            .output()
            .unwrap();
        let stderr = String::from_utf8_lossy(&out.stderr).to_string();
        assert!(!out.status.success(), "{stderr}");
        stderr
    };
    let endless = refused("1e300");
    assert!(
        endless.contains("more than can be counted") && endless.contains("\"forever\""),
        "{endless}"
    );
    // Countable (6e13 steps), but refused from the pace of its first steps.
    let long = refused("1e12");
    assert!(
        long.contains("ms a step") && long.contains("shorten `duration`"),
        "{long}"
    );
    assert!(start.elapsed() < Duration::from_secs(60));
    let _ = std::fs::remove_dir_all(&dir);
}
