//! The harbour example, run as a user runs it, on a virtual X server
//! (Xvfb) for a couple of seconds: it floats its bodies, saves the window,
//! and the picture shows the sea (blue) and the boat (red) on it.
//!
//! Without `xvfb-run` or a GPU adapter the test says so and skips, except
//! under `CI=true`, where it fails (scripts/setup.sh installs Xvfb and
//! Mesa's Vulkan driver).

use std::path::PathBuf;
use std::process::Command;

/// The example's binary, which `cargo test` builds beside the tests.
fn example() -> PathBuf {
    let exe = std::env::current_exe().expect("the test's path");
    // target/<profile>/deps/harbour-<hash> → target/<profile>/examples/harbour
    let profile = exe.parent().and_then(|d| d.parent()).expect("target/<profile>");
    profile
        .join("examples")
        .join(format!("harbour{}", std::env::consts::EXE_SUFFIX))
}

fn skip(why: &str) {
    assert!(
        std::env::var("CI").as_deref() != Ok("true"),
        "{why} under CI=true (scripts/setup.sh installs what the example needs)"
    );
    eprintln!("{why}: skipping");
}

#[test]
fn the_harbour_shows_the_sea_and_the_boat() {
    let found = Command::new("sh")
        .args(["-c", "command -v xvfb-run"])
        .output()
        .is_ok_and(|o| o.status.success());
    if !found {
        return skip("xvfb-run is missing");
    }
    let binary = example();
    assert!(
        binary.exists(),
        "{} is missing: `cargo test` builds the examples",
        binary.display()
    );
    let dir = std::env::temp_dir().join(format!("soak-harbour-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let shot = dir.join("harbour.png");
    let out = Command::new("xvfb-run")
        .args(["-a", "-s", "-screen 0 1280x1024x24"])
        .arg(&binary)
        .args(["--screenshot", shot.to_str().unwrap(), "--frames", "60"])
        .env("XDG_RUNTIME_DIR", &dir)
        .env("WGPU_BACKEND", "vulkan")
        .output()
        .expect("runs xvfb-run");
    let (stdout, stderr) = (
        String::from_utf8_lossy(&out.stdout),
        String::from_utf8_lossy(&out.stderr),
    );
    if !out.status.success()
        && (stderr.contains("Unable to find a GPU")
            || stderr.contains("No adapter")
            || stderr.contains("adapter"))
    {
        let _ = std::fs::remove_dir_all(&dir);
        return skip(&format!(
            "no GPU adapter draws ({})",
            stderr.lines().last().unwrap_or("")
        ));
    }
    assert!(out.status.success(), "{stdout}\n{stderr}");
    assert!(stdout.contains("harbour: t = "), "{stdout}\n{stderr}");
    println!("{}", stdout.trim());
    let image = image::open(&shot)
        .unwrap_or_else(|e| panic!("{}: {e}\n{stdout}\n{stderr}", shot.display()))
        .to_rgba8();
    let _ = std::fs::remove_dir_all(&dir);
    let (w, h) = image.dimensions();
    assert_eq!((w, h), (960, 540));
    let share = |f: &dyn Fn([i32; 3]) -> bool| {
        image
            .pixels()
            .filter(|p| f([i32::from(p[0]), i32::from(p[1]), i32::from(p[2])]))
            .count() as f64
            / f64::from(w * h)
    };
    // The sea: deep blue, much of the frame; the boat: red, some of it.
    let sea = share(&|[r, g, b]| b > r + 30 && b > g && b < 200);
    let boat = share(&|[r, g, b]| r > g + 60 && r > b + 60);
    println!("sea {sea:.3}, boat {boat:.4}");
    assert!(sea > 0.2, "sea {sea:.3} of the frame");
    assert!(boat > 0.002, "boat {boat:.4} of the frame");
    // The bodies floated: each is partly under water.
    let line = stdout.lines().find(|l| l.starts_with("harbour: t = ")).unwrap();
    assert!(line.contains("5 bodies floating"), "{line}");
}
