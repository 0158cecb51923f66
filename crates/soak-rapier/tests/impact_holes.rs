//! Holes torn by hard contacts (`ImpactHoles`, scene key `impact_holes`): a
//! cannonball dropped into a rowing boat opens a hole where it lands and
//! the boat sinks; the run is bit-identical on any number of threads and a
//! run saved just before or just after the blow resumes bit for bit.

use std::hash::{Hash, Hasher};
use std::path::PathBuf;

use rapier3d::prelude::*;
use soak_bake::{Atlas, BakeOptions, builtin};
use soak_hydro::{MassModel, Water};
use soak_rapier::{
    BodyDesc, Effects, ForceGenerator, ImpactHoles, LoadedScene, SavedSimulation, Simulation, SoakError,
};

fn scene() -> LoadedScene {
    let path: PathBuf = [
        env!("CARGO_MANIFEST_DIR"),
        "..",
        "..",
        "data",
        "scenes",
        "cannonball.toml",
    ]
    .iter()
    .collect();
    LoadedScene::from_file(&path).unwrap()
}

#[derive(Debug, Default, PartialEq)]
struct Run {
    hash: u64,
    /// (step, impacts of that step).
    impacts: Vec<(u64, Vec<soak_rapier::Impact>)>,
}

/// Runs up to `to` steps, hashing the state after each one bit for bit.
fn run(sim: &mut Simulation, to: u64) -> Run {
    let mut h = std::collections::hash_map::DefaultHasher::new();
    let mut impacts = Vec::new();
    while sim.steps_taken() < to {
        sim.step().unwrap();
        if !sim.soak.impacts().is_empty() {
            impacts.push((sim.steps_taken(), sim.soak.impacts().to_vec()));
        }
        for r in sim.report() {
            let liquid = r.liquid_inside.unwrap_or(-1.0);
            for x in r
                .position
                .iter()
                .chain(&r.rotation)
                .chain(&r.linear_velocity)
                .chain([&r.mass, &liquid])
            {
                x.to_bits().hash(&mut h);
            }
        }
    }
    Run {
        hash: h.finish(),
        impacts,
    }
}

fn on_threads<T: Send>(threads: usize, f: impl FnOnce() -> T + Send) -> T {
    rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .unwrap()
        .install(f)
}

#[test]
fn a_cannonball_holes_the_boat_where_it_lands_and_the_boat_sinks() {
    let s = scene();
    let end = 2400; // 40 s
    let runs: Vec<(Run, f64)> = [1, 2]
        .into_iter()
        .map(|threads| {
            on_threads(threads, || {
                let mut sim = Simulation::from_scene(&s).unwrap();
                let r = run(&mut sim, end);
                let boat = sim.report().into_iter().find(|b| b.name == "boat").unwrap();
                (r, boat.position[1])
            })
        })
        .collect();
    assert_eq!(runs[0], runs[1], "the runs differ between 1 and 2 threads");
    let (r, sunk_to) = &runs[0];
    // One blow (the landing), in the boat's bottom under the ball.
    assert!(!r.impacts.is_empty(), "no hole was torn");
    let (step, first) = &r.impacts[0];
    let hole = first[0];
    println!(
        "hole torn at step {step} ({:.2} s): {hole:?}; the boat ends at y = {sunk_to:.2} m",
        hole.time
    );
    assert!(hole.impulse > 100.0 && hole.texels > 10);
    assert!(
        (hole.centre[0] - 0.2).abs() < 0.15 && hole.centre[2].abs() < 0.15,
        "{:?}",
        hole.centre
    );
    assert!(hole.centre[1] < 0.1, "not in the bottom: {:?}", hole.centre);
    assert!(*sunk_to < -2.0, "the boat is still at y = {sunk_to} m");
}

#[test]
fn a_run_saved_around_the_blow_resumes_bit_for_bit() {
    let s = scene();
    let end = 900;
    let mut straight = Simulation::from_scene(&s).unwrap();
    let whole = run(&mut straight, end);
    let (blow, _) = whole.impacts[0];
    for at in [blow - 1, blow + 1] {
        let mut first = Simulation::from_scene(&s).unwrap();
        let head = run(&mut first, at);
        let bytes = first.save(&s).unwrap().to_bytes().unwrap();
        drop(first);
        let mut resumed = Simulation::resume(&SavedSimulation::from_bytes(&bytes).unwrap()).unwrap();
        let tail = run(&mut resumed, end);
        // The impacts seen before and after the save are the whole run's.
        let seen: Vec<_> = head.impacts.iter().chain(&tail.impacts).cloned().collect();
        assert_eq!(seen, whole.impacts, "saved at step {at}");
        assert_eq!(straight.soak.state(), resumed.soak.state(), "saved at step {at}");
        assert_eq!(
            format!("{:?}", straight.report()),
            format!("{:?}", resumed.report())
        );
    }
}

#[test]
fn the_rule_needs_a_wall_and_sane_numbers() {
    let mut world = PhysicsWorld::new();
    let handle = world.bodies.insert(RigidBodyBuilder::dynamic());
    let atlas = Atlas::bake(&builtin::cuboid(1.0, 1.0, 1.0), BakeOptions::square(16)).unwrap();
    let mut soak = ForceGenerator::new(Water::calm(0.0));
    let desc = |rule| BodyDesc {
        name: "crate".into(),
        atlas: atlas.clone().into(),
        mass_model: MassModel::Solid { density: 500.0 },
        effects: Effects::buoyancy().with_impact_holes(rule),
    };
    let rule = ImpactHoles {
        impulse: 50.0,
        radius: 0.1,
    };
    let e = soak
        .register(&mut world.bodies, &world.colliders, handle, desc(rule))
        .unwrap_err();
    assert!(
        matches!(&e, SoakError::ImpactHoles { name, reason } if name == "crate" && reason.contains("flooding"))
    );
    let e = soak
        .register(
            &mut world.bodies,
            &world.colliders,
            handle,
            desc(ImpactHoles {
                impulse: -1.0,
                ..rule
            }),
        )
        .unwrap_err();
    assert!(e.to_string().contains("impulse -1"), "{e}");
    // In a scene: without `graph` or `open`, refused naming the key and line.
    let text = "dt = 0.02\nduration = 1.0\n[water]\nkind = \"plane\"\nlevel = 0.0\n[[bodies]]\nname = \"crate\"\n\
                mesh = \"builtin:box\"\nresolution = 16\nmass = { model = \"solid\", density = 500.0 }\n\
                impact_holes = { impulse = 50.0, radius = 0.1 }\n";
    let e = LoadedScene::from_str(text, "crate.toml".as_ref())
        .unwrap_err()
        .to_string();
    assert!(e.contains("impact_holes") && e.contains("line 11"), "{e}");
}

/// A hollow crate whose inside is one cavity (`graph = { cavity = true }`),
/// holed at t = 0.5 s by a scheduled opening (no `kappa`) under its bottom.
fn holed_crate(hole: &str) -> String {
    format!(
        "dt = 0.0166667\nduration = 4.0\n[water]\nkind = \"plane\"\nlevel = 0.0\n[[bodies]]\nname = \"crate\"\n\
         mesh = \"builtin:box\"\nresolution = 64\nmass = {{ model = \"shell\", areal_density = 20.0 }}\n\
         position = [0.0, 0.38, 0.0]\nrotation_deg = [0.0, 30.0, 0.0]\ngraph = {{ cavity = true }}\n\
         drag = {{ coefficient = 1.0, linear = 30.0 }}\npermeability = [{hole}]\n"
    )
}

#[test]
fn a_hole_opened_at_a_world_point_is_the_same_hole_as_in_the_body_frame() {
    let run = |hole: &str| {
        let text = holed_crate(hole);
        let s = LoadedScene::from_str(&text, "crate.toml".as_ref()).unwrap();
        let mut sim = Simulation::from_scene(&s).unwrap();
        // Up to the moment it opens: the crate still where it started.
        while sim.time() < 0.5 {
            sim.step().unwrap();
        }
        let id = sim.bodies[0].id.unwrap();
        let pose = soak_rapier::convert::pose(sim.world.bodies[sim.bodies[0].handle].position());
        sim.step().unwrap();
        let openings = sim
            .soak
            .flooding(id)
            .unwrap()
            .permeability()
            .unwrap()
            .openings()
            .to_vec();
        for _ in 0..120 {
            sim.step().unwrap();
        }
        (openings, pose, sim.soak.flooding(id).unwrap().inside())
    };
    // The world point under the crate's bottom centre, where it floats.
    let (_, pose, _) = run("{ centre = [0.0, -0.5, 0.0], radius = 0.1, at = 100.0 }");
    let world = pose * nalgebra::Point3::new(0.1, -0.5, 0.05);
    let (by_world, _, inside) = run(&format!(
        "{{ centre = [{}, {}, {}], radius = 0.12, at = 0.5, world = true }}",
        world.x, world.y, world.z
    ));
    let (by_body, _, _) = run("{ centre = [0.1, -0.5, 0.05], radius = 0.12, at = 0.5 }");
    assert!(by_world.len() > 10, "{} texels", by_world.len());
    assert_eq!(by_world, by_body);
    // An opening, not seepage: the bottom hole lets the crate fill fast.
    println!(
        "holed crate: {} opening texels, {inside:.3} m³ inside 2 s later",
        by_world.len()
    );
    assert!(inside > 0.05, "{inside} m³");
}
