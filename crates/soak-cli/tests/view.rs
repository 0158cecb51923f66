//! `soak view` in a window on a virtual X server (Xvfb, Mesa's software
//! adapter): the frame it presents, read back from the window's surface,
//! is the frame `soak render` draws offscreen for the same step; a scene
//! file edited while it runs reloads, a broken edit is named with its file
//! and line and the last good scene keeps running; mouse drags sent by
//! xdotool reach it and turn the camera.
//!
//! Needs `xvfb-run` and `xdotool` (`scripts/setup.sh` installs them) and a
//! GPU adapter: without them the tests say so and skip, except under
//! `CI=true`, where they fail.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};
use std::time::Duration;

fn data(name: &str) -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("../../data")
        .join(name)
}

fn out_dir(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("soak-view-test-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// Whether `tool` is on the `PATH`; when not, a notice outside CI and a
/// failure under `CI=true`.
fn have(tool: &str) -> bool {
    let found = Command::new("sh")
        .args(["-c", &format!("command -v {tool}")])
        .output()
        .is_ok_and(|o| o.status.success());
    if !found {
        assert!(
            std::env::var("CI").as_deref() != Ok("true"),
            "`{tool}` is missing under CI=true (scripts/setup.sh installs it)"
        );
        eprintln!("`{tool}` is missing: skipping (scripts/setup.sh installs it)");
    }
    found
}

/// Runs `script` (sh, with `$SOAK` the binary) on a fresh virtual X
/// server; `None` (with a notice) without an adapter outside CI.
fn on_xvfb(script: &str) -> Option<Output> {
    let runtime = out_dir("runtime");
    let out = Command::new("xvfb-run")
        .args(["-a", "-s", "-screen 0 1280x1024x24", "sh", "-c", script])
        .env("SOAK", env!("CARGO_BIN_EXE_soak"))
        .env("XDG_RUNTIME_DIR", &runtime)
        .output()
        .expect("runs xvfb-run");
    let stderr = String::from_utf8_lossy(&out.stderr);
    if !out.status.success() && (stderr.contains("no GPU adapter") || stderr.contains("no adapter draws")) {
        assert!(
            std::env::var("CI").as_deref() != Ok("true"),
            "no GPU adapter under CI=true: {stderr}"
        );
        eprintln!("no GPU adapter: skipping ({stderr})");
        return None;
    }
    Some(out)
}

fn check(out: &Output) -> String {
    let stdout = String::from_utf8_lossy(&out.stdout).into_owned();
    assert!(
        out.status.success(),
        "{stdout}\n{}",
        String::from_utf8_lossy(&out.stderr)
    );
    stdout
}

fn load(path: &Path) -> image::RgbaImage {
    image::open(path)
        .unwrap_or_else(|e| panic!("{}: {e}", path.display()))
        .to_rgba8()
}

/// The fraction of pixels the colour of the boat's planks (a warm brown:
/// red over green over blue, well apart).
fn wood(image: &image::RgbaImage) -> f64 {
    let n = image
        .pixels()
        .filter(|p| {
            let [r, g, b, _] = p.0.map(i32::from);
            r > g + 15 && g > b + 15 && r > 90
        })
        .count();
    n as f64 / f64::from(image.width() * image.height())
}

#[test]
fn the_window_presents_the_frame_the_offscreen_renderer_draws() {
    if !have("xvfb-run") {
        return;
    }
    let dir = out_dir("frame");
    let scene = data("scenes/sinking_boat.toml");
    let script = format!(
        "\"$SOAK\" view '{scene}' --steps 120 --frames 3 --no-overlay --width 640 --height 360 \
         --screenshot '{dir}/window.png' && \"$SOAK\" render '{scene}' --frame 120 --out '{dir}/render'",
        scene = scene.display(),
        dir = dir.display()
    );
    let Some(out) = on_xvfb(&script) else {
        return;
    };
    let stdout = check(&out);
    assert!(stdout.contains("3 frame(s)"), "{stdout}");
    let window = load(&dir.join("window.png"));
    let offscreen = load(&dir.join("render/frame_000120.png"));
    assert_eq!(window.dimensions(), (640, 360));
    assert_eq!(window.dimensions(), offscreen.dimensions());
    // The same renderer on the same device kind: the same pixels, but for
    // a level here and there.
    let (mut sum, mut far) = (0u64, 0usize);
    for (a, b) in window.pixels().zip(offscreen.pixels()) {
        for c in 0..3 {
            let d = (i32::from(a[c]) - i32::from(b[c])).unsigned_abs();
            sum += u64::from(d);
            far += usize::from(d > 8);
        }
    }
    let mean = sum as f64 / (3.0 * 640.0 * 360.0);
    assert!(
        mean < 0.5 && far < 100,
        "mean difference {mean:.3}, {far} channels off by more than 8"
    );
    // And what both show is the boat: its planks cover part of the frame.
    let planks = wood(&window);
    assert!(planks > 0.02, "{:.1} % of the frame is wood", 100.0 * planks);
    std::fs::remove_dir_all(dir).ok();
}

#[test]
fn an_edited_scene_reloads_and_a_broken_edit_is_named_while_the_last_good_one_runs() {
    if !have("xvfb-run") {
        return;
    }
    let dir = out_dir("reload");
    let scene = dir.join("boxes.toml");
    let good = std::fs::read_to_string(data("scenes/three_boxes.toml")).unwrap();
    std::fs::write(&scene, &good).unwrap();
    // Edits while the window runs: a good scene with a longer duration
    // (reloaded: the world starts again), then a value out of range
    // (refused: the reloaded world keeps running).
    let edits = {
        let scene = scene.clone();
        let good = good.clone();
        std::thread::spawn(move || {
            std::thread::sleep(Duration::from_secs(3));
            let longer = good.replacen("duration = 30.0", "duration = 300.0", 1);
            std::fs::write(&scene, &longer).unwrap();
            std::thread::sleep(Duration::from_secs(3));
            std::fs::write(&scene, longer.replacen("density = ", "density = -", 1)).unwrap();
        })
    };
    let script = format!(
        "\"$SOAK\" view '{}' --seconds 11 --width 320 --height 180 --time-scale 4",
        scene.display()
    );
    let Some(out) = on_xvfb(&script) else {
        edits.join().unwrap();
        return;
    };
    edits.join().unwrap();
    let stdout = check(&out);
    assert!(stdout.contains("1 reload(s), 1 refused"), "{stdout}");
    let refused = stdout
        .lines()
        .find(|l| l.starts_with("reload refused:"))
        .unwrap_or_else(|| panic!("no refusal named: {stdout}"));
    assert!(
        refused.contains("boxes.toml") && refused.contains("line") && refused.contains("density"),
        "{refused}"
    );
    // The reloaded world ran on after the refused edit: about 8 s of the
    // clock at four times real time since the reload, 4 s of them after
    // the refusal (a world that had stopped at the refusal would be at
    // about 12 s).
    let t: f64 = stdout
        .split("; t = ")
        .nth(1)
        .and_then(|r| r.split(' ').next())
        .and_then(|v| v.parse().ok())
        .unwrap_or_else(|| panic!("no time in {stdout}"));
    assert!(t > 16.0, "the world stopped at t = {t} s: {stdout}");
    std::fs::remove_dir_all(dir).ok();
}

/// A pixel of the sinking boat's planks in its frame at step 60 (640×360).
const BOAT: (u32, u32) = (330, 150);

#[test]
fn mouse_drags_reach_the_window_and_turn_the_camera_and_a_click_selects() {
    if !have("xvfb-run") || !have("xdotool") {
        return;
    }
    let dir = out_dir("mouse");
    let scene = data("scenes/sinking_boat.toml");
    // The same frame without and with drags across the window.
    let view = |shot: &str, until: &str| {
        format!(
            "\"$SOAK\" view '{}' --steps 60 {until} --no-overlay --width 640 --height 360 --screenshot '{}/{shot}'",
            scene.display(),
            dir.display()
        )
    };
    let script = format!(
        "{still} && ({moved} & pid=$!; sleep 2; xdotool mousemove 320 180; \
         for i in 1 2 3 4 5; do xdotool mousedown 1; sleep 0.05; xdotool mousemove_relative 25 4; \
         sleep 0.2; xdotool mouseup 1; sleep 0.2; done; wait $pid) && \
         ({picked} & pid=$!; sleep 2; xdotool mousemove {x} {y} click 1; wait $pid)",
        still = view("still.png", "--frames 3"),
        moved = view("moved.png", "--seconds 6"),
        picked = view("picked.png", "--seconds 4"),
        x = BOAT.0,
        y = BOAT.1,
    );
    let Some(out) = on_xvfb(&script) else {
        return;
    };
    let stdout = check(&out);
    // The second run measured the drags: input to frame is reported.
    let second = stdout
        .lines()
        .filter(|l| l.contains("frame(s) on"))
        .nth(1)
        .unwrap_or_default();
    assert!(
        second.contains("input to frame") && !second.contains("at most 0)"),
        "{stdout}"
    );
    let (still, moved) = (load(&dir.join("still.png")), load(&dir.join("moved.png")));
    // A click on the boat selects it.
    assert!(stdout.contains("selected: boat"), "{stdout}");
    let p = still.get_pixel(BOAT.0, BOAT.1);
    assert!(p[0] > p[2], "the click aims at the boat's planks, not at {p:?}");
    let differ = still.pixels().zip(moved.pixels()).filter(|(a, b)| a != b).count();
    assert!(
        differ > 640 * 360 / 10,
        "the camera did not turn: {differ} pixels differ"
    );
    std::fs::remove_dir_all(dir).ok();
}
