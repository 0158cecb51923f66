//! `radiation = true` on a scene body: its model is baked when the scene
//! is built (once for bodies of one mesh, mass and orientation), and a
//! buoy released above its draft on calm water decays as linear theory
//! says instead of bobbing forever.

use soak_rapier::{LoadedScene, Simulation};

fn scene(radiation: bool) -> String {
    format!(
        "dt = 0.0166667\nduration = 6.0\n[water]\nkind = \"plane\"\n\
         [[bodies]]\nname = \"a\"\nmesh = \"builtin:sphere:0.5\"\nresolution = 64\n\
         mass = {{ model = \"solid\", density = 500.0 }}\nposition = [0.0, 0.05, 0.0]\nradiation = {radiation}\n\
         [[bodies]]\nname = \"b\"\nmesh = \"builtin:sphere:0.5\"\nresolution = 64\n\
         mass = {{ model = \"solid\", density = 500.0 }}\nposition = [5.0, 0.05, 0.0]\nradiation = {radiation}\n"
    )
}

/// Heights of body 0's centre every step for `seconds`.
fn heave(radiation: bool, seconds: f64) -> (Vec<f64>, Simulation) {
    let loaded = LoadedScene::from_str(&scene(radiation), std::path::Path::new(".")).unwrap();
    let mut sim = Simulation::from_scene(&loaded).unwrap();
    let handle = sim.bodies[0].handle;
    let steps = (seconds / 0.0166667) as usize;
    let mut y = Vec::with_capacity(steps);
    for _ in 0..steps {
        sim.step().unwrap();
        y.push(sim.world.bodies[handle].translation().y as f64);
    }
    (y, sim)
}

/// Positive peaks of `x` after its start.
fn peaks(x: &[f64]) -> Vec<f64> {
    x.windows(3)
        .filter(|w| w[1] > w[0] && w[1] >= w[2] && w[1] > 0.0)
        .map(|w| w[1])
        .collect()
}

#[test]
fn a_buoy_with_radiation_decays_and_one_without_bobs_on() {
    let (with, sim) = heave(true, 6.0);
    let (without, _) = heave(false, 6.0);
    // One model for the two bodies of one mesh, mass and orientation.
    let a = sim
        .soak
        .body(sim.bodies[0].id.unwrap())
        .unwrap()
        .effects()
        .radiation
        .clone()
        .unwrap();
    let b = sim
        .soak
        .body(sim.bodies[1].id.unwrap())
        .unwrap()
        .effects()
        .radiation
        .clone()
        .unwrap();
    assert!(std::sync::Arc::ptr_eq(&a, &b));
    let (p_with, p_without) = (peaks(&with), peaks(&without));
    eprintln!("peaks with radiation {p_with:.4?}, without {p_without:.4?}");
    // A sphere half under water: its bob falls to about 0.58 a cycle
    // (radius 0.5 m: period about 1.4 s); without radiation it keeps
    // nearly all of it.
    assert!(p_with[1] / p_with[0] < 0.7, "{p_with:?}");
    assert!(p_with[2] < 0.3 * 0.05, "{p_with:?}");
    assert!(p_without[2] > 0.8 * 0.05 - 0.01, "{p_without:?}");
}
