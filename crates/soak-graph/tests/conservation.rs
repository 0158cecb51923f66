//! Conservation: over any run, the liquid inside equals what was there
//! plus what entered minus what left, to 1e-9 relative (f64), also while
//! capacities cap the transfers; no node ever holds less than 0 or more
//! than its capacity; nothing becomes NaN.

use std::sync::OnceLock;

use nalgebra::{Isometry3, Point3, Translation3, UnitQuaternion, Vector3};
use proptest::prelude::*;
use soak_bake::{Atlas, BakeOptions, builtin};
use soak_graph::{Flooding, FlowOptions, LiquidGraph, Node, Permeability, Pipe};
use soak_hydro::{Gerstner, GerstnerWave, Water};

const TOLERANCE: f64 = 1e-9;

fn atlas() -> &'static Atlas {
    static ATLAS: OnceLock<Atlas> = OnceLock::new();
    ATLAS.get_or_init(|| Atlas::bake(&builtin::cuboid(2.0, 1.0, 1.0), BakeOptions::square(48)).unwrap())
}

#[derive(Clone, Debug)]
struct Case {
    nodes: Vec<(f64, f64, f64, f64, f64, f64)>,
    edges: Vec<(usize, usize, f64, f64)>,
    holes: Vec<(f64, f64, f64, f64, f64)>,
    rotation: (f64, f64, f64),
    height: f64,
    passes: u32,
    seed: u64,
    waves: bool,
}

fn case() -> impl Strategy<Value = Case> {
    (1usize..9).prop_flat_map(|n| {
        (
            prop::collection::vec(
                (
                    -1.0..1.0f64,
                    -0.5..0.5f64,
                    -0.5..0.5f64,
                    prop_oneof![Just(0.0), 0.001..0.4f64],
                    0.0..1.0f64,
                    0.05..1.0f64,
                ),
                n,
            ),
            prop::collection::vec(
                (0..n, 0..n, 0.0..0.08f64, prop_oneof![Just(0.0), 0.1..1.0f64]),
                0..2 * n,
            ),
            prop::collection::vec(
                (
                    -1.0..1.0f64,
                    -0.5..0.5f64,
                    -0.5..0.5f64,
                    0.05..0.6f64,
                    1e-7..1e-4f64,
                ),
                0..4,
            ),
            (-3.2..3.2f64, -3.2..3.2f64, -3.2..3.2f64),
            -1.5..1.5f64,
            1u32..4,
            any::<u64>(),
            any::<bool>(),
        )
            .prop_map(
                |(nodes, edges, holes, rotation, height, passes, seed, waves)| Case {
                    nodes,
                    edges,
                    holes,
                    rotation,
                    height,
                    passes,
                    seed,
                    waves,
                },
            )
    })
}

fn build(c: &Case) -> LiquidGraph {
    let nodes = c
        .nodes
        .iter()
        .enumerate()
        .map(|(i, &(x, y, z, cap, fill, h))| {
            let node = Node::new(format!("n{i}"), Point3::new(x, y, z), cap).with_liquid(cap * fill);
            if cap > 0.0 { node.with_height(h) } else { node }
        })
        .collect();
    let mut seen = std::collections::HashSet::new();
    let edges = c
        .edges
        .iter()
        .filter(|(a, b, _, _)| a != b && seen.insert((*a.min(b), *a.max(b))))
        .map(|&(a, b, r, p)| {
            (
                a,
                b,
                Pipe {
                    permeability: p,
                    radius: r,
                    length: 0.5,
                },
            )
        })
        .collect();
    LiquidGraph::new(nodes, edges).unwrap()
}

fn water(waves: bool) -> Water {
    if waves {
        let w = GerstnerWave {
            amplitude: 0.3,
            wavelength: 4.0,
            direction_deg: 30.0,
            steepness: 0.5,
            phase: 0.0,
        };
        Water::new(Gerstner::new(0.0, vec![w], 9.81).unwrap())
    } else {
        Water::calm(0.0)
    }
}

fn check_nodes(flow: &Flooding) {
    for (i, n) in flow.graph().nodes().enumerate() {
        assert!(
            n.liquid.is_finite() && n.liquid >= 0.0 && n.liquid <= n.capacity,
            "node {i}: {n:?}"
        );
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(96))]

    #[test]
    fn inside_is_entered_minus_left(c in case()) {
        let atlas = atlas();
        let graph = build(&c);
        let mut permeability = Permeability::watertight(atlas);
        for &(x, y, z, r, k) in &c.holes {
            permeability.paint(atlas, Point3::new(x, y, z), r, k).unwrap();
        }
        let options = FlowOptions { passes: c.passes, seed: c.seed, ..FlowOptions::default() };
        let mut flow = Flooding::for_atlas(atlas, graph, permeability, options).unwrap();
        let water = water(c.waves);
        let (r, p, y) = c.rotation;
        let mut pose = Isometry3::from_parts(
            Translation3::new(0.0, c.height, 0.0),
            UnitQuaternion::from_euler_angles(r, p, y),
        );
        let dt = 1.0 / 30.0;
        let mut worst: f64 = 0.0;
        for step in 0..90 {
            // Bob and roll so nodes fill, drain and swap heights.
            if step % 30 == 29 {
                pose = Isometry3::from_parts(
                    Translation3::new(0.0, -pose.translation.vector.y, 0.0),
                    UnitQuaternion::from_axis_angle(&Vector3::z_axis(), 1.3) * pose.rotation,
                );
            }
            flow.step(atlas, &pose, &water, step as f64 * dt, dt).unwrap();
            check_nodes(&flow);
            worst = worst.max(flow.conservation_error());
        }
        prop_assert!(worst < TOLERANCE, "relative error {worst:e}");
    }
}

/// A long run where every cap binds: tiny nodes behind a very permeable
/// wall, bobbing in and out of the water.
#[test]
fn caps_binding_for_ten_thousand_steps() {
    let atlas = atlas();
    let nodes = vec![
        Node::new("a", Point3::new(-0.8, 0.0, 0.0), 0.01),
        Node::new("b", Point3::new(0.0, 0.3, 0.0), 0.002),
        Node::new("c", Point3::new(0.8, -0.3, 0.0), 0.05),
        Node::new("junction", Point3::new(0.0, -0.3, 0.0), 0.0),
    ];
    let edges = vec![
        (0, 3, Pipe::new(0.05, 0.8)),
        (1, 3, Pipe::new(0.05, 0.6)),
        (2, 3, Pipe::new(0.05, 0.8)),
        (0, 1, Pipe::new(0.02, 0.8)),
    ];
    let graph = LiquidGraph::new(nodes, edges).unwrap();
    let permeability = Permeability::uniform(atlas, 1e-4).unwrap();
    let mut flow = Flooding::for_atlas(atlas, graph, permeability, FlowOptions::default()).unwrap();
    let water = Water::calm(0.0);
    let dt = 1.0 / 30.0;
    let (mut worst, mut capped_in, mut capped_out) = (0.0f64, 0, 0);
    for step in 0..10_000 {
        let t = step as f64 * dt;
        let pose = Isometry3::from_parts(
            Translation3::new(0.0, 1.2 * (0.7 * t).sin(), 0.0),
            UnitQuaternion::from_euler_angles(0.3 * (0.5 * t).sin(), 0.0, 0.8 * (0.3 * t).sin()),
        );
        let report = flow.step(atlas, &pose, &water, t, dt).unwrap();
        check_nodes(&flow);
        if report.routed > 0.0 {
            capped_in += 1;
        }
        if flow.graph().nodes().all(|n| n.is_full()) {
            capped_out += 1;
        }
        worst = worst.max(flow.conservation_error());
    }
    println!(
        "10 000 steps: entered {:.6} m³, left {:.6} m³, inside {:.6} m³, worst relative error {worst:.2e}, \
         {capped_in} steps routing past a full node, {capped_out} steps with every node full",
        flow.ledger().entered(),
        flow.ledger().left(),
        flow.inside()
    );
    assert!(flow.ledger().entered() > 1.0, "the run must move a lot of water");
    assert!(capped_out > 0 && capped_in > 0);
    assert!(worst < TOLERANCE, "{worst:e}");
}
