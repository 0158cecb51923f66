//! Water inside Rapier bodies (flooding, `Effects::with_flooding`): the undamaged boat
//! stays dry, the bow-damaged boat trims bow-down and the stern-damaged one
//! stern-down before they sink, sinking takes less time as the hole grows
//! more permeable, the liquid is conserved and its mass reaches Rapier, and
//! a plush toy soaks up water through a graph built by segmentation.
//!
//! Boat runs use `builtin:boat:4x1.2x0.6` at 128² texels, dt = 1/30 s, the
//! five-compartment graph of `data/graphs/boat.toml`; each run is a few
//! thousand steps (well under a second in the test profile).

use std::time::Instant;

use nalgebra::{Point3, Vector3};
use rapier3d::prelude::*;
use soak_bake::{Atlas, BakeOptions, Mesh, builtin};
use soak_graph::segment::{SegmentOptions, segment};
use soak_graph::{
    Flooding, FlowOptions, LiquidGraph, Permeability, SegmentGraphOptions, TexelNodes, load_graph,
};
use soak_hydro::{Drag, MassModel, Water};
use soak_rapier::hull::{highest_above_water, pitch_degrees};
use soak_rapier::{BodyDesc, Effects, ForceGenerator, SoakId};

const DT: f32 = 1.0 / 30.0;
const HULL_AREAL_DENSITY: f64 = 40.0;
/// Time the boat settles before it is holed, s.
const PUNCH: f64 = 5.0;

fn boat_graph() -> LiquidGraph {
    load_graph(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../data/graphs/boat.toml"
    ))
    .unwrap()
}

struct Boat {
    world: PhysicsWorld,
    soak: ForceGenerator,
    handle: RigidBodyHandle,
    id: SoakId,
    atlas: Atlas,
}

fn boat() -> Boat {
    let mut world = PhysicsWorld::new();
    world.integration_parameters.dt = DT;
    let handle = world
        .bodies
        .insert(RigidBodyBuilder::dynamic().translation(Vector::new(0.0, -0.15, 0.0)));
    let atlas = Atlas::bake(&builtin::boat(4.0, 1.2, 0.6), BakeOptions::square(128)).unwrap();
    let flooding = Flooding::for_atlas(
        &atlas,
        boat_graph(),
        Permeability::watertight(&atlas),
        FlowOptions::default(),
    )
    .unwrap();
    let mut soak = ForceGenerator::new(Water::calm(0.0));
    let id = soak
        .register(
            &mut world.bodies,
            &world.colliders,
            handle,
            BodyDesc {
                name: "boat".into(),
                atlas: atlas.clone().into(),
                mass_model: MassModel::Shell {
                    areal_density: HULL_AREAL_DENSITY,
                },
                effects: Effects::buoyancy()
                    .with_drag(Drag {
                        coefficient: 1.0,
                        linear: 50.0,
                    })
                    .with_flooding(flooding),
            },
        )
        .unwrap();
    Boat {
        world,
        soak,
        handle,
        id,
        atlas,
    }
}

/// Bow damage, starboard, below the waterline (thesis Fig. 7.4).
const BOW: (&[[f64; 3]], f64) = (&[[1.5, 0.15, 0.125]], 0.15);
/// Stern damage on both sides (thesis Fig. 7.5).
const STERN: (&[[f64; 3]], f64) = (&[[-1.6, 0.1, 0.2], [-1.6, 0.1, -0.2]], 0.12);
/// A hole in the topsides, amidships, well above the waterline.
const TOPSIDES: (&[[f64; 3]], f64) = (&[[0.0, 0.55, 0.6]], 0.08);

#[derive(Debug, Default)]
struct Run {
    /// Time the whole hull went under water, s.
    sunk_at: Option<f64>,
    /// Trim when the hole was punched, degrees.
    pitch_at_punch: f64,
    /// Trim when the water inside first reached a quarter of the compartments, degrees.
    pitch_at_quarter: Option<f64>,
    /// (t, water inside m³, pitch degrees) every step.
    trace: Vec<(f64, f64, f64)>,
    /// Worst |inside − (entered − left)| / entered over the run.
    worst_conservation: f64,
    /// Worst |mass − (hull + ρ·inside)| / mass over the run.
    worst_mass: f64,
    /// Smallest freeboard seen, m.
    lowest_freeboard: f64,
    wall_time: f64,
}

fn run(hole: (&[[f64; 3]], f64), kappa: f64, seconds: f64) -> Run {
    let start = Instant::now();
    let mut b = boat();
    let capacity = b.soak.flooding(b.id).unwrap().graph().total_capacity();
    let hull = b.soak.body(b.id).unwrap().mass_properties().mass;
    let mut out = Run {
        lowest_freeboard: f64::INFINITY,
        ..Run::default()
    };
    let steps = (seconds / DT as f64).round() as usize;
    for _ in 0..steps {
        let t = b.soak.time();
        let pose = *b.world.bodies[b.handle].position();
        if (t - PUNCH).abs() < 0.5 * DT as f64 && kappa > 0.0 {
            let p = b.soak.flooding_mut(b.id).unwrap().permeability_mut().unwrap();
            for c in hole.0 {
                let covered = p.paint(&b.atlas, Point3::from(*c), hole.1, kappa).unwrap();
                assert!(covered > 10, "the hole covers only {covered} texels");
            }
            out.pitch_at_punch = pitch_degrees(&pose);
        }
        let board = highest_above_water(&b.atlas, &pose, b.soak.water(), t);
        out.lowest_freeboard = out.lowest_freeboard.min(board);
        let f = b.soak.flooding(b.id).unwrap();
        let inside = f.inside();
        let pitch = pitch_degrees(&pose);
        out.trace.push((t, inside, pitch));
        out.worst_conservation = out.worst_conservation.max(f.conservation_error());
        let mass = b.soak.body(b.id).unwrap().mass_properties().mass;
        out.worst_mass = out.worst_mass.max((mass - (hull + 1000.0 * inside)).abs() / mass);
        for n in f.graph().nodes() {
            assert!(n.liquid >= 0.0 && n.liquid <= n.capacity, "{n:?}");
        }
        if out.pitch_at_quarter.is_none() && inside >= 0.25 * capacity {
            out.pitch_at_quarter = Some(pitch);
        }
        if board < 0.0 {
            out.sunk_at = Some(t - PUNCH);
            break;
        }
        b.soak.step(&mut b.world).unwrap();
    }
    out.wall_time = start.elapsed().as_secs_f64();
    out
}

#[test]
fn the_undamaged_boat_takes_no_water_in_five_minutes() {
    for (what, hole, kappa) in [
        ("intact", BOW, 0.0),
        ("holed above the waterline", TOPSIDES, 1e-6),
    ] {
        let r = run(hole, kappa, 300.0);
        let water = r.trace.iter().map(|s| s.1).fold(0.0, f64::max);
        println!(
            "{what}: 300 s simulated in {:.2} s; most water inside {water} m³, lowest freeboard {:.3} m",
            r.wall_time, r.lowest_freeboard
        );
        assert_eq!(r.sunk_at, None, "{what}");
        assert_eq!(water, 0.0, "{what}");
        assert!(r.lowest_freeboard > 0.3, "{what}: {}", r.lowest_freeboard);
        assert_eq!(r.trace.len(), 9000);
    }
}

/// Asserts the trim sign while the boat floods and before it sinks.
fn assert_trims(r: &Run, sign: f64, what: &str) {
    let sunk = r.sunk_at.unwrap_or_else(|| panic!("{what}: did not sink"));
    let quarter = r.pitch_at_quarter.expect("a quarter full");
    println!(
        "{what}: sank {sunk:.1} s after the hole; trim {:+.2}° at the hole, {quarter:+.2}° a quarter full; \
         conservation {:.1e}, mass {:.1e}; {:.2} s wall",
        r.pitch_at_punch, r.worst_conservation, r.worst_mass, r.wall_time
    );
    // The sign of the trim itself, not only its change.
    assert!(sign * quarter > 2.0, "{what}: pitch {quarter}° a quarter full");
    assert!(sign * (quarter - r.pitch_at_punch) > 2.0, "{what}");
    // From a tenth full to the end it never trims the other way.
    let tenth = r.trace.iter().map(|s| s.1).fold(0.0, f64::max) * 0.1;
    for &(t, inside, pitch) in &r.trace {
        if inside > tenth {
            assert!(sign * pitch > 0.0, "{what}: pitch {pitch}° at t = {t} s");
        }
    }
    assert!(r.worst_conservation < 1e-9, "{what}: {}", r.worst_conservation);
    assert!(r.worst_mass < 1e-9, "{what}: {}", r.worst_mass);
}

#[test]
fn the_bow_damaged_boat_trims_bow_down_before_it_sinks() {
    let r = run(BOW, 2e-7, 400.0);
    assert_trims(&r, -1.0, "bow damage");
}

#[test]
fn the_stern_damaged_boat_trims_stern_down_before_it_sinks() {
    let r = run(STERN, 2e-7, 400.0);
    assert_trims(&r, 1.0, "stern damage");
}

#[test]
fn sinking_time_shortens_as_the_hole_grows_more_permeable() {
    let kappas = [1e-7, 3e-7, 1e-6];
    let times: Vec<f64> = kappas
        .iter()
        .map(|&k| {
            let r = run(BOW, k, 600.0);
            let t = r.sunk_at.unwrap_or_else(|| panic!("κ = {k:e}: did not sink"));
            println!(
                "κ = {k:.0e} m: sank {t:.1} s after the hole ({:.2} s wall, conservation {:.1e})",
                r.wall_time, r.worst_conservation
            );
            assert!(r.worst_conservation < 1e-9);
            t
        })
        .collect();
    assert!(times.windows(2).all(|w| w[1] < w[0]), "{times:?}");
}

#[test]
fn flooding_moves_the_centre_of_mass_towards_the_hole() {
    let mut b = boat();
    let hull = *b.soak.body(b.id).unwrap().mass_properties();
    let covered = b.soak.punch(b.id, Point3::from(BOW.0[0]), BOW.1, 2e-7).unwrap();
    assert!(covered > 10, "the hole covers only {covered} texels");
    for _ in 0..300 {
        b.soak.step(&mut b.world).unwrap();
    }
    let now = *b.soak.body(b.id).unwrap().mass_properties();
    let liquid = b.soak.liquid_mass(b.id).unwrap();
    assert!(liquid.mass > 10.0, "{liquid:?}");
    assert!(now.center_of_mass.x > hull.center_of_mass.x + 0.05, "{now:?}");
    // Rapier has it too.
    let rb = &b.world.bodies[b.handle];
    assert!((rb.mass() as f64 - now.mass).abs() < 1e-3 * now.mass);
    let com = rb.mass_properties().local_mprops.local_com;
    assert!((com.x as f64 - now.center_of_mass.x).abs() < 1e-4);
    // The buoyancy is still the hull's: the force generator's volume is the atlas'.
    assert!((b.soak.body(b.id).unwrap().atlas().volume() - b.atlas.volume()).abs() < 1e-12);
}

/// A teddy-like toy: smooth union of a body sphere and offset spheres
/// (head, arms, legs), displacing a UV sphere (see `examples/plush_toy.rs`).
fn plush(segments: usize) -> Mesh {
    let body = 0.2;
    let parts: [(Vector3<f64>, f64, f64); 5] = [
        (Vector3::new(0.0, 1.0, 0.0), 0.24, 0.14),
        (Vector3::new(0.94, 0.34, 0.0), 0.21, 0.075),
        (Vector3::new(-0.94, 0.34, 0.0), 0.21, 0.075),
        (Vector3::new(0.5, -0.8, 0.33), 0.215, 0.085),
        (Vector3::new(-0.5, -0.8, 0.33), 0.215, 0.085),
    ];
    let radial = move |d: Vector3<f64>| -> f64 {
        let p = 10.0;
        let mut sum = body.powf(p);
        for (u, dist, r) in &parts {
            let c = d.dot(&u.normalize());
            let disc = r * r - dist * dist * (1.0 - c * c);
            if c > 0.0 && disc > 0.0 {
                sum += (dist * c + disc.sqrt()).powf(p);
            }
        }
        sum.powf(1.0 / p)
    };
    builtin::sphere(1.0, segments, segments / 2).map_positions(|q| {
        let d = q.coords.normalize();
        Point3::from(d * radial(d))
    })
}

#[test]
fn the_plush_toy_soaks_up_water_through_its_segmented_graph() {
    let start = Instant::now();
    let mesh = plush(96);
    let seg = segment(&mesh, &SegmentOptions::default()).unwrap();
    let graph = LiquidGraph::from_segmentation(
        &seg,
        &SegmentGraphOptions {
            porosity: 0.9,
            ..SegmentGraphOptions::default()
        },
    )
    .unwrap();
    // Body, head, two arms, two legs: six compartments, each limb and the
    // head joined to the body.
    assert_eq!(graph.node_count(), 6, "{:?}", graph.nodes().collect::<Vec<_>>());
    let body = (0..6)
        .max_by(|&a, &b| {
            graph
                .node(a)
                .unwrap()
                .capacity
                .total_cmp(&graph.node(b).unwrap().capacity)
        })
        .unwrap();
    assert!(graph.node(body).unwrap().position.coords.norm() < 0.05);
    assert!(graph.nodes().any(|n| n.position.y > 0.2), "a head");
    assert_eq!(graph.edge_count(), 5);
    assert!(graph.edges().all(|(a, b, _)| a == body || b == body));
    let atlas = Atlas::bake(&mesh, BakeOptions::square(64)).unwrap();
    let map = TexelNodes::from_segmentation(&atlas, &seg).unwrap();
    let flooding = Flooding::new(
        graph,
        Permeability::uniform(&atlas, 2e-9).unwrap(),
        map,
        FlowOptions::default(),
    )
    .unwrap();

    let mut world = PhysicsWorld::new();
    world.integration_parameters.dt = DT;
    let handle = world.bodies.insert(RigidBodyBuilder::dynamic());
    let mut soak = ForceGenerator::new(Water::calm(0.0));
    let id = soak
        .register(
            &mut world.bodies,
            &world.colliders,
            handle,
            BodyDesc {
                name: "plush".into(),
                atlas: atlas.clone().into(),
                mass_model: MassModel::Solid { density: 50.0 },
                effects: Effects::buoyancy()
                    .with_drag(Drag {
                        coefficient: 1.0,
                        linear: 20.0,
                    })
                    .with_flooding(flooding),
            },
        )
        .unwrap();
    let dry = soak.body(id).unwrap().mass_properties().mass;
    // Height of the toy's centre above the water, m.
    let mut height_dry = 0.0;
    for step in 0..(120 * 30) {
        if step == 150 {
            height_dry = world.bodies[handle].translation().y as f64;
        }
        soak.step(&mut world).unwrap();
        assert!(soak.flooding(id).unwrap().conservation_error() < 1e-9);
    }
    let wet = soak.body(id).unwrap().mass_properties().mass;
    let height_wet = world.bodies[handle].translation().y as f64;
    let f = soak.flooding(id).unwrap();
    println!(
        "plush: {} nodes; {:.2} kg dry, {:.2} kg after 120 s ({:.2} l inside); centre {:.3} m → {:.3} m above the water; {:.2} s wall",
        f.graph().node_count(),
        dry,
        wet,
        1e3 * f.inside(),
        height_dry,
        height_wet,
        start.elapsed().as_secs_f64()
    );
    assert!(wet > 3.0 * dry, "it grows heavy: {dry} → {wet} kg");
    assert!(
        height_wet < height_dry - 0.05,
        "it floats lower: {height_dry} → {height_wet} m"
    );
    assert!(f.ledger().left() >= 0.0 && f.conservation_error() < 1e-9);
}
