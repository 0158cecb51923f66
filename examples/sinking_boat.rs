//! A boat holed below the waterline takes on water compartment by
//! compartment and sinks (thesis Figs. 7.4 and 7.5).
//!
//! ```text
//! cargo run --release --example sinking_boat                  # bow damage, starboard (Fig. 7.4)
//! cargo run --release --example sinking_boat -- --stern       # stern damage, both sides (Fig. 7.5)
//! cargo run --release --example sinking_boat -- --kappa 2e-6 --resolution 256 --csv boat.csv
//! ```
//!
//! The hull is `builtin:boat:4x1.2x0.6` (bow towards +x, keel at y = 0,
//! deck at y = 0.6), a 40 kg/m² shell; its liquid graph is the five
//! compartments of `data/graphs/boat.toml`. The boat settles for
//! `--punch` seconds, then a hole is punched: every texel within the hole's
//! radius gets permeability κ = `--kappa` m (κ = k/L, see
//! `soak_graph::Permeability`). Each step the liquid graph advances with the
//! body's pose and its water becomes extra mass, while the buoyancy stays
//! the hull's enclosed volume.
//!
//! The "top above" column is the height of the hull's highest point above
//! the water ([`highest_above_water`]). It rises while the boat floods: the
//! water runs to the holed end, the boat trims that way and lifts its other
//! end. The boat has sunk when it falls below zero, the whole hull under
//! water; `soak demo` reports its sinking boats' times by the same measure.

use std::io::Write;

use rapier3d::prelude::*;
use soak::bake::{Atlas, BakeOptions, builtin};
use soak::graph::{Flooding, FlowOptions, Permeability, load_graph};
use soak::hydro::{Drag, MassModel, Water};
use soak::rapier::hull::{heel_degrees, highest_above_water, pitch_degrees};
use soak::rapier::{BodyDesc, Effects, ForceGenerator};

/// Where the hull is holed: sphere centres (object space, m) and radius (m).
fn holes(stern: bool) -> (Vec<[f64; 3]>, f64) {
    if stern {
        // Both sides of the stern, below the waterline.
        (vec![[-1.6, 0.1, 0.2], [-1.6, 0.1, -0.2]], 0.12)
    } else {
        // Forward, starboard (+z), below the waterline.
        (vec![[1.5, 0.15, 0.125]], 0.15)
    }
}

struct Args {
    stern: bool,
    kappa: f64,
    resolution: u32,
    seconds: f64,
    punch: f64,
    csv: Option<String>,
}

fn args() -> Result<Args, String> {
    let mut a = Args {
        stern: false,
        kappa: 1e-6,
        resolution: 128,
        seconds: 600.0,
        punch: 5.0,
        csv: None,
    };
    let mut it = std::env::args().skip(1);
    while let Some(flag) = it.next() {
        let mut value = |name: &str| it.next().ok_or(format!("{name} needs a value"));
        match flag.as_str() {
            "--stern" => a.stern = true,
            "--bow" => a.stern = false,
            "--kappa" => a.kappa = value("--kappa")?.parse().map_err(|e| format!("--kappa: {e}"))?,
            "--resolution" => {
                a.resolution = value("--resolution")?
                    .parse()
                    .map_err(|e| format!("--resolution: {e}"))?
            }
            "--seconds" => {
                a.seconds = value("--seconds")?
                    .parse()
                    .map_err(|e| format!("--seconds: {e}"))?
            }
            "--punch" => a.punch = value("--punch")?.parse().map_err(|e| format!("--punch: {e}"))?,
            "--csv" => a.csv = Some(value("--csv")?),
            "-h" | "--help" => {
                println!(
                    "sinking_boat [--stern] [--kappa M] [--resolution N] [--seconds S] [--punch S] [--csv FILE]"
                );
                std::process::exit(0);
            }
            other => return Err(format!("unknown argument `{other}` (try --help)")),
        }
    }
    Ok(a)
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args = args()?;
    let mut world = PhysicsWorld::new();
    world.integration_parameters.dt = 1.0 / 30.0;
    let handle = world
        .bodies
        .insert(RigidBodyBuilder::dynamic().translation(Vector::new(0.0, -0.15, 0.0)));

    let mesh = builtin::boat(4.0, 1.2, 0.6);
    let atlas = Atlas::bake(&mesh, BakeOptions::square(args.resolution))?;
    let graph = load_graph(concat!(env!("CARGO_MANIFEST_DIR"), "/data/graphs/boat.toml"))?;
    let capacity = graph.total_capacity();
    let permeability = Permeability::watertight(&atlas);
    let flooding = Flooding::for_atlas(&atlas, graph, permeability, FlowOptions::default())?;

    let mut soak = ForceGenerator::new(Water::calm(0.0));
    let id = soak.register(
        &mut world.bodies,
        &world.colliders,
        handle,
        BodyDesc {
            name: "boat".into(),
            atlas: atlas.clone().into(),
            mass_model: MassModel::Shell { areal_density: 40.0 },
            effects: Effects::buoyancy()
                .with_drag(Drag {
                    coefficient: 1.0,
                    linear: 50.0,
                })
                .with_flooding(flooding),
        },
    )?;
    let hull_mass = soak.body(id).map_or(0.0, |b| b.mass_properties().mass);
    let (centres, radius) = holes(args.stern);
    println!(
        "{} damage: {} hole(s) of radius {radius} m, κ = {:e} m, punched at t = {} s; hull {hull_mass:.0} kg, \
         compartments {capacity:.3} m³, atlas {}² ({} texels)",
        if args.stern {
            "stern (both sides)"
        } else {
            "bow (starboard)"
        },
        centres.len(),
        args.kappa,
        args.punch,
        args.resolution,
        atlas.len()
    );
    let mut csv = match &args.csv {
        Some(path) => {
            let mut f = std::io::BufWriter::new(std::fs::File::create(path)?);
            writeln!(
                f,
                "t_s,inside_m3,mass_kg,pitch_deg,heel_deg,top_above_water_m,stern,aft,midship,fore,bow"
            )?;
            Some(f)
        }
        None => None,
    };
    println!(
        "{:>6}  {:>9}  {:>6}  {:>7}  {:>7}  {:>9}  compartments (% full: stern … bow)",
        "t (s)", "water m³", "%", "mass kg", "pitch°", "top above"
    );
    let dt = world.integration_parameters.dt as f64;
    let steps = (args.seconds / dt).round() as usize;
    let mut punched = false;
    let mut sunk_at = None;
    for step in 0..=steps {
        let t = soak.time();
        if !punched && t >= args.punch {
            let covered: usize = centres
                .iter()
                .map(|c| soak.punch(id, *c, radius, args.kappa))
                .sum::<Result<usize, _>>()?;
            println!("t = {t:.1} s: hole punched ({covered} texels)");
            punched = true;
        }
        let pose = *world.bodies[handle].position();
        let top = highest_above_water(&atlas, &pose, soak.water(), t);
        let flooding = soak.flooding(id).ok_or("no flooding")?;
        let inside = flooding.inside();
        let mass = soak.body(id).map_or(0.0, |b| b.mass_properties().mass);
        let fills: Vec<f64> = flooding.graph().nodes().map(|n| 100.0 * n.fill()).collect();
        if let Some(f) = &mut csv {
            writeln!(
                f,
                "{t:.4},{inside:.6},{mass:.3},{:.4},{:.4},{top:.4},{}",
                pitch_degrees(&pose),
                heel_degrees(&pose),
                fills
                    .iter()
                    .map(|x| format!("{x:.2}"))
                    .collect::<Vec<_>>()
                    .join(",")
            )?;
        }
        if step % 150 == 0 || (top < 0.0 && sunk_at.is_none()) {
            println!(
                "{t:>6.1}  {inside:>9.4}  {:>6.1}  {mass:>7.0}  {:>7.2}  {top:>9.3}  {}",
                100.0 * inside / capacity,
                pitch_degrees(&pose),
                fills
                    .iter()
                    .map(|x| format!("{x:>3.0}"))
                    .collect::<Vec<_>>()
                    .join(" ")
            );
        }
        if top < 0.0 {
            sunk_at = Some(t);
            break;
        }
        soak.step(&mut world)?;
    }
    let f = soak.flooding(id).ok_or("no flooding")?;
    println!(
        "water in {:.4} m³, out {:.4} m³, inside {:.4} m³: conservation error {:.1e} (relative)",
        f.ledger().entered(),
        f.ledger().left(),
        f.inside(),
        f.conservation_error()
    );
    match sunk_at {
        Some(t) => println!(
            "sank (whole hull under water) at t = {t:.1} s, {:.1} s after the hole was punched",
            t - args.punch
        ),
        None => println!("still afloat after {} s", args.seconds),
    }
    Ok(())
}
