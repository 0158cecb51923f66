//! A world of your own in the window (`run_world`): a Rapier world built
//! by hand, soak's generator on it, shown on a virtual X server (Xvfb)
//! for a few frames; the frame it presented, read back from the window,
//! shows the floating crate over the water, the world stepped, and a mesh
//! list that does not match the bodies is refused.
//!
//! The test runs itself again under `xvfb-run` (the window needs a
//! display): without `xvfb-run` or a GPU adapter it says so and skips,
//! except under `CI=true`, where it fails.

use std::process::Command;
use std::sync::Arc;

use rapier3d::prelude::*;
use soak_bake::{Atlas, BakeOptions, builtin};
use soak_hydro::{Drag, MassModel, Water};
use soak_rapier::{BodyDesc, Effects, ForceGenerator, SimBody, Simulation};
use soak_view::{ViewError, ViewOptions, run_world};

/// Set in the run under Xvfb.
const CHILD: &str = "SOAK_VIEW_OWN_WORLD_CHILD";

/// A crate floating on calm water, its mesh.
fn world() -> (Simulation, Arc<soak_bake::Mesh>) {
    let mesh = Arc::new(builtin::cuboid(1.0, 0.5, 0.8));
    let mut world = PhysicsWorld::new();
    world.integration_parameters.dt = 1.0 / 60.0;
    let handle = world.bodies.insert(RigidBodyBuilder::dynamic());
    let mut soak = ForceGenerator::new(Water::calm(0.0));
    let id = soak
        .register(
            &mut world.bodies,
            &world.colliders,
            handle,
            BodyDesc {
                name: "crate".into(),
                atlas: Atlas::bake(&mesh, BakeOptions::square(64)).unwrap().into(),
                mass_model: MassModel::Solid { density: 500.0 },
                effects: Effects::buoyancy().with_drag(Drag::default()),
            },
        )
        .unwrap();
    let bodies = vec![SimBody {
        name: "crate".into(),
        handle,
        id: Some(id),
        resolution: 64,
    }];
    (Simulation::from_parts(world, soak, bodies, 10.0), mesh)
}

#[test]
fn a_world_of_your_own_is_shown_in_the_window() {
    if std::env::var(CHILD).is_ok() {
        return shown();
    }
    let found = Command::new("sh")
        .args(["-c", "command -v xvfb-run"])
        .output()
        .is_ok_and(|o| o.status.success());
    if !found {
        assert!(
            std::env::var("CI").as_deref() != Ok("true"),
            "xvfb-run is missing under CI=true (scripts/setup.sh installs it)"
        );
        eprintln!("xvfb-run is missing: skipping (scripts/setup.sh installs it)");
        return;
    }
    let runtime = std::env::temp_dir().join(format!("soak-view-own-{}", std::process::id()));
    std::fs::create_dir_all(&runtime).unwrap();
    let out = Command::new("xvfb-run")
        .args(["-a", "-s", "-screen 0 1280x1024x24"])
        .arg(std::env::current_exe().unwrap())
        .args([
            "--exact",
            "a_world_of_your_own_is_shown_in_the_window",
            "--nocapture",
            "--test-threads=1",
        ])
        .env(CHILD, "1")
        .env("XDG_RUNTIME_DIR", &runtime)
        .output()
        .expect("runs xvfb-run");
    let (stdout, stderr) = (
        String::from_utf8_lossy(&out.stdout),
        String::from_utf8_lossy(&out.stderr),
    );
    let _ = std::fs::remove_dir_all(&runtime);
    if stdout.contains("no adapter draws") || stderr.contains("no adapter draws") {
        assert!(
            std::env::var("CI").as_deref() != Ok("true"),
            "no GPU adapter under CI=true: {stdout}{stderr}"
        );
        eprintln!("no GPU adapter: skipping");
        return;
    }
    assert!(out.status.success(), "{stdout}\n{stderr}");
    assert!(stdout.contains("shown: "), "{stdout}\n{stderr}");
}

/// Under Xvfb: the window on the hand-built world.
fn shown() {
    let (sim, mesh) = world();
    let (bare, _) = world();
    // One mesh per body, or a typed error.
    let e = run_world(bare, vec![], ViewOptions::default()).unwrap_err();
    assert!(matches!(e, ViewError::Meshes { bodies: 1, meshes: 0 }), "{e}");
    let shot = std::env::temp_dir().join(format!("soak-view-own-{}.png", std::process::id()));
    let csv = std::env::temp_dir().join(format!("soak-view-own-{}.csv", std::process::id()));
    let report = run_world(
        sim,
        vec![mesh],
        ViewOptions {
            size: (320, 180),
            overlay: false,
            frames: Some(30),
            screenshot: Some(shot.clone()),
            csv: Some(csv.clone()),
            ..ViewOptions::default()
        },
    )
    .unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(report.frames, 30);
    assert!(report.time > 0.0, "the world stepped: {report:?}");
    // The series: the header, then a row per step from the window's
    // opening (the world samples every step), its time rising to the end.
    let text = std::fs::read_to_string(&csv).unwrap();
    let _ = std::fs::remove_file(&csv);
    let mut lines = text.lines();
    assert!(lines.next().unwrap().starts_with("t_s,body,x_m,"));
    let times: Vec<f64> = lines
        .map(|l| {
            assert!(l.split(',').nth(1) == Some("crate"), "{l}");
            l.split(',').next().unwrap().parse().unwrap()
        })
        .collect();
    assert!(times.len() >= 2, "{text}");
    assert_eq!(times[0], 0.0);
    assert!(times.windows(2).all(|w| w[1] > w[0]), "{times:?}");
    assert!(
        (times[times.len() - 1] - report.time).abs() < 1e-4,
        "{} {}",
        times[times.len() - 1],
        report.time
    );
    let image = image::open(&shot).unwrap().to_rgba8();
    let _ = std::fs::remove_file(&shot);
    assert_eq!(image.dimensions(), (320, 180));
    // The crate (wood, warm brown) covers part of the frame, the water
    // (blue) much of the rest.
    let share = |f: &dyn Fn([i32; 3]) -> bool| {
        image
            .pixels()
            .filter(|p| f([i32::from(p[0]), i32::from(p[1]), i32::from(p[2])]))
            .count() as f64
            / (320.0 * 180.0)
    };
    let wood = share(&|[r, g, b]| r > g + 15 && g > b + 15 && r > 90);
    let water = share(&|[r, _, b]| b > r + 20);
    assert!(wood > 0.02 && water > 0.2, "wood {wood:.3}, water {water:.3}");
    println!(
        "shown: {} frames, t = {:.2} s, wood {wood:.3}, water {water:.3}",
        report.frames, report.time
    );
}
