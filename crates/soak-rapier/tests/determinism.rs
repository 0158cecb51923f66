//! Determinism and saved state: the same scene gives bit-identical runs on
//! any number of threads, and a run saved half-way and resumed continues
//! exactly as the uninterrupted one.

use std::hash::{Hash, Hasher};
use std::path::PathBuf;

use soak_rapier::{LoadedScene, SavedSimulation, Simulation};

fn data(name: &str) -> PathBuf {
    [env!("CARGO_MANIFEST_DIR"), "..", "..", "data", name]
        .iter()
        .collect()
}

/// Folds every body's pose, velocity, mass, liquid inside and liquid
/// texture (wet bodies) into `h`, bit for bit.
fn fold(sim: &Simulation, h: &mut impl Hasher) {
    for b in sim.soak.bodies() {
        if let Some(texture) = b.liquid() {
            for x in texture {
                x.to_bits().hash(h);
            }
        }
    }
    for r in sim.report() {
        let liquid = r.liquid_inside.unwrap_or(-1.0);
        let floats = r
            .position
            .iter()
            .chain(&r.rotation)
            .chain(&r.linear_velocity)
            .chain(&r.angular_velocity)
            .chain([&r.mass, &r.submerged_fraction, &liquid]);
        for x in floats {
            x.to_bits().hash(h);
        }
    }
}

/// Runs `steps` steps from `sim` and hashes the state after each one.
fn run(sim: &mut Simulation, steps: usize) -> u64 {
    let mut h = std::collections::hash_map::DefaultHasher::new();
    for _ in 0..steps {
        sim.step().unwrap();
        fold(sim, &mut h);
    }
    h.finish()
}

fn on_threads<T: Send>(threads: usize, f: impl FnOnce() -> T + Send) -> T {
    rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .unwrap()
        .install(f)
}

fn scene(name: &str) -> LoadedScene {
    LoadedScene::from_file(&data(name)).unwrap()
}

#[test]
fn a_thousand_steps_are_bit_identical_across_runs_and_thread_counts() {
    for name in [
        "scenes/buoy_on_waves.toml",
        "scenes/sinking_boat.toml",
        "scenes/wet_crate.toml",
        "scenes/spectral_sea.toml",
    ] {
        let s = scene(name);
        let hashes: Vec<u64> = [1, 2, 2, 4]
            .into_iter()
            .map(|threads| on_threads(threads, || run(&mut Simulation::from_scene(&s).unwrap(), 1000)))
            .collect();
        assert!(hashes.iter().all(|&x| x == hashes[0]), "{name}: {hashes:x?}");
    }
}

#[test]
fn a_run_saved_at_step_500_and_resumed_equals_the_uninterrupted_run() {
    for name in [
        "scenes/sinking_boat.toml",
        "scenes/three_boxes.toml",
        "scenes/wet_crate.toml",
        "scenes/spectral_sea.toml",
    ] {
        let s = scene(name);
        let mut straight = Simulation::from_scene(&s).unwrap();
        run(&mut straight, 500);
        let tail = run(&mut straight, 500);

        let mut first = Simulation::from_scene(&s).unwrap();
        run(&mut first, 500);
        let bytes = first.save(&s).unwrap().to_bytes().unwrap();
        drop(first);
        let saved = SavedSimulation::from_bytes(&bytes).unwrap();
        let mut resumed = Simulation::resume(&saved).unwrap();
        assert_eq!(resumed.steps_taken(), 500);
        assert_eq!(run(&mut resumed, 500), tail, "{name}: the resumed run diverged");
        let (a, b) = (straight.report(), resumed.report());
        assert_eq!(format!("{a:?}"), format!("{b:?}"));
        assert_eq!(straight.soak.state(), resumed.soak.state(), "{name}");
    }
}

#[test]
fn a_damaged_save_is_an_error_not_a_panic() {
    let s = scene("scenes/three_boxes.toml");
    let mut sim = Simulation::from_scene(&s).unwrap();
    run(&mut sim, 10);
    let bytes = sim.save(&s).unwrap().to_bytes().unwrap();
    for cut in [0, 1, bytes.len() / 3, bytes.len() - 1] {
        assert!(
            SavedSimulation::from_bytes(&bytes[..cut]).is_err(),
            "cut at {cut}"
        );
    }
    // A save from another scene does not fit this one's liquid bodies.
    let boat = scene("scenes/sinking_boat.toml");
    let mut saved = SavedSimulation::from_bytes(&bytes).unwrap();
    saved.scene_text = boat.text.clone();
    saved.scene_path = boat.path.clone();
    let e = Simulation::resume(&saved).unwrap_err().to_string();
    assert!(e.contains("saved state"), "{e}");
}
