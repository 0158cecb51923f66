//! Hard cases of the liquid graph: zero-capacity nodes, a disconnected
//! graph, cycles, a boat upside down, every node full, a single node,
//! closed pipes, no gravity, an unbounded fluid. Each must conserve liquid,
//! keep every node within [0, capacity], never panic and never produce NaN.

use nalgebra::{Isometry3, Point3, Translation3, UnitQuaternion, Vector3};
use soak_bake::{Atlas, BakeOptions, builtin};
use soak_graph::{Flooding, FlowOptions, LiquidGraph, Node, Permeability, Pipe, load_graph};
use soak_hydro::Water;

const DT: f64 = 1.0 / 30.0;

fn data(name: &str) -> String {
    format!("{}/../../data/graphs/{name}", env!("CARGO_MANIFEST_DIR"))
}

fn settle(flow: &mut Flooding, pose: &Isometry3<f64>, steps: usize) {
    let water = Water::calm(0.0);
    for _ in 0..steps {
        flow.redistribute(pose, &water, DT).unwrap();
        for n in flow.graph().nodes() {
            assert!(
                n.liquid.is_finite() && n.liquid >= 0.0 && n.liquid <= n.capacity,
                "{n:?}"
            );
        }
    }
    assert!(flow.conservation_error() < 1e-12, "{}", flow.conservation_error());
}

#[test]
fn zero_capacity_junctions_pass_liquid_but_hold_none() {
    // upper → junction → lower, the junction a pipe crossing with no room.
    let graph = LiquidGraph::new(
        vec![
            Node::new("upper", Point3::new(0.0, 1.0, 0.0), 0.5).with_liquid(0.5),
            Node::new("junction", Point3::new(0.0, 0.5, 0.0), 0.0),
            Node::new("lower", Point3::new(0.0, -0.5, 0.0), 0.5),
        ],
        vec![(0, 1, Pipe::new(0.03, 0.5)), (1, 2, Pipe::new(0.03, 1.0))],
    )
    .unwrap();
    assert_eq!(graph.node(1).unwrap().height, 0.0);
    let mut flow = Flooding::sealed(graph, FlowOptions::default()).unwrap();
    settle(&mut flow, &Isometry3::identity(), 600);
    assert_eq!(flow.graph().liquids(), vec![0.0, 0.0, 0.5]);
    // Pouring into the junction finds no room.
    assert_eq!(flow.pour(1, 0.1).unwrap(), 0.0);
}

#[test]
fn a_disconnected_graph_levels_each_part_on_its_own() {
    let graph = LiquidGraph::new(
        vec![
            Node::new("a0", Point3::new(-2.0, 0.0, 0.0), 1.0).with_liquid(1.0),
            Node::new("a1", Point3::new(-1.0, 0.0, 0.0), 1.0),
            Node::new("b0", Point3::new(1.0, 0.0, 0.0), 1.0).with_liquid(0.2),
            Node::new("b1", Point3::new(2.0, 0.0, 0.0), 1.0),
            Node::new("alone", Point3::new(0.0, 3.0, 0.0), 1.0).with_liquid(0.3),
        ],
        vec![(0, 1, Pipe::new(0.05, 1.0)), (2, 3, Pipe::new(0.05, 1.0))],
    )
    .unwrap();
    let mut flow = Flooding::sealed(graph, FlowOptions::default()).unwrap();
    settle(&mut flow, &Isometry3::identity(), 300);
    let l = flow.graph().liquids();
    for (got, want) in l.iter().zip([0.5, 0.5, 0.1, 0.1, 0.3]) {
        assert!((got - want).abs() < 1e-9, "{l:?}");
    }
}

#[test]
fn cycles_level_out_without_circulating() {
    // A ring of six equal nodes at one height, all liquid in one: it spreads
    // evenly and then stops (no endless loop of transfers around the ring).
    let n = 6;
    let nodes = (0..n)
        .map(|i| {
            let a = std::f64::consts::TAU * i as f64 / n as f64;
            let node = Node::new(format!("r{i}"), Point3::new(a.cos(), 0.0, a.sin()), 1.0);
            if i == 0 { node.with_liquid(0.9) } else { node }
        })
        .collect();
    let mut edges: Vec<_> = (0..n).map(|i| (i, (i + 1) % n, Pipe::new(0.05, 1.0))).collect();
    edges.push((0, 3, Pipe::new(0.05, 2.0))); // a chord: two cycles
    let graph = LiquidGraph::new(nodes, edges).unwrap();
    let mut flow = Flooding::sealed(graph, FlowOptions::default()).unwrap();
    settle(&mut flow, &Isometry3::identity(), 1200);
    for l in flow.graph().liquids() {
        assert!((l - 0.15).abs() < 1e-6, "{:?}", flow.graph().liquids());
    }
    let report = flow
        .redistribute(&Isometry3::identity(), &Water::calm(0.0), DT)
        .unwrap();
    assert!(report.moved < 1e-9, "still moving {} m³ per step", report.moved);
}

#[test]
fn a_boat_upside_down_drains_towards_its_deck() {
    // Keel-side liquid of the boat graph, turned over: it now lies above
    // the deck-side; in the real hull it all falls to the (now low) deck.
    // The boat graph has one layer, so add deck nodes above each compartment.
    let boat = load_graph(data("boat.toml")).unwrap();
    let mut nodes: Vec<Node> = boat.nodes().cloned().collect();
    let mut edges: Vec<_> = boat.edges().map(|(a, b, p)| (a, b, *p)).collect();
    let k = nodes.len();
    for i in 0..k {
        let below = nodes[i].clone();
        nodes[i].height = 0.3;
        nodes[i].position.y = 0.15;
        nodes[i].capacity *= 0.5;
        nodes[i].liquid = nodes[i].capacity * 0.5;
        let mut deck = below;
        deck.name = format!("{} deck", deck.name);
        deck.height = 0.3;
        deck.position.y = 0.45;
        deck.capacity *= 0.5;
        nodes.push(deck);
        edges.push((i, k + i, Pipe::new(0.05, 0.3)));
    }
    let graph = LiquidGraph::new(nodes, edges).unwrap();
    let total = graph.total_liquid();
    let mut flow = Flooding::sealed(graph, FlowOptions::default()).unwrap();
    settle(&mut flow, &Isometry3::identity(), 300);
    // Upright: nothing moves up.
    assert!(flow.graph().liquids()[k..].iter().all(|&l| l == 0.0));
    let capsized = Isometry3::from_parts(
        Translation3::new(0.0, 0.3, 0.0),
        UnitQuaternion::from_axis_angle(&Vector3::x_axis(), std::f64::consts::PI),
    );
    settle(&mut flow, &capsized, 3000);
    let deck: f64 = flow.graph().liquids()[k..].iter().sum();
    assert!(
        (deck - total).abs() < 1e-6 * total,
        "deck holds {deck} of {total}"
    );
}

#[test]
fn every_node_full_nothing_moves_and_nothing_more_enters() {
    let atlas = Atlas::bake(&builtin::cuboid(2.0, 1.0, 1.0), BakeOptions::square(32)).unwrap();
    let boat = load_graph(data("fig4_5_cascade.toml")).unwrap();
    let nodes: Vec<Node> = boat
        .nodes()
        .map(|n| {
            let mut n = n.clone();
            n.position *= 0.2;
            n.liquid = n.capacity;
            n
        })
        .collect();
    let edges = boat.edges().map(|(a, b, p)| (a, b, *p)).collect();
    let graph = LiquidGraph::new(nodes, edges).unwrap();
    let permeability = Permeability::uniform(&atlas, 1e-5).unwrap();
    let mut flow = Flooding::for_atlas(&atlas, graph, permeability, FlowOptions::default()).unwrap();
    let before = flow.graph().liquids();
    let deep = Isometry3::translation(0.0, -5.0, 0.0);
    for step in 0..100 {
        let r = flow
            .step(&atlas, &deep, &Water::calm(0.0), step as f64 * DT, DT)
            .unwrap();
        assert_eq!(r.entered, 0.0);
        assert_eq!(r.moved, 0.0);
    }
    assert_eq!(flow.graph().liquids(), before);
    // Lifted out of the water, it drains through the wall.
    let lifted = Isometry3::translation(0.0, 5.0, 0.0);
    for step in 0..3000 {
        flow.step(&atlas, &lifted, &Water::calm(0.0), step as f64 * DT, DT)
            .unwrap();
    }
    assert!(flow.inside() < 1e-9, "{}", flow.inside());
    assert!((flow.ledger().left() - 3.0).abs() < 1e-9);
    assert!(flow.conservation_error() < 1e-12);
}

#[test]
fn one_node_fills_to_the_waterline_and_no_further() {
    // A 1 m cube, one node of its volume, holes all round: it fills until
    // its inside level meets the outside one.
    let atlas = Atlas::bake(&builtin::cuboid(1.0, 1.0, 1.0), BakeOptions::square(64)).unwrap();
    let graph = LiquidGraph::new(
        vec![Node::new("only", Point3::origin(), 1.0).with_height(1.0)],
        vec![],
    )
    .unwrap();
    let permeability = Permeability::uniform(&atlas, 1e-6).unwrap();
    let mut flow = Flooding::for_atlas(&atlas, graph, permeability, FlowOptions::default()).unwrap();
    let water = Water::calm(0.0);
    for draft in [0.3, 0.5, 0.8] {
        let pose = Isometry3::translation(0.0, 0.5 - draft, 0.0);
        for step in 0..900 {
            flow.step(&atlas, &pose, &water, step as f64 * DT, DT).unwrap();
        }
        assert!(
            (flow.inside() - draft).abs() < 1e-6,
            "draft {draft}: {}",
            flow.inside()
        );
    }
    assert!(flow.conservation_error() < 1e-12);
}

#[test]
fn closed_pipes_no_gravity_and_open_air_move_nothing() {
    let graph = LiquidGraph::new(
        vec![
            Node::new("high", Point3::new(0.0, 1.0, 0.0), 1.0).with_liquid(1.0),
            Node::new("low", Point3::new(0.0, -1.0, 0.0), 1.0),
        ],
        vec![(
            0,
            1,
            Pipe {
                permeability: 0.0,
                radius: 0.05,
                length: 2.0,
            },
        )],
    )
    .unwrap();
    let mut flow = Flooding::sealed(graph.clone(), FlowOptions::default()).unwrap();
    settle(&mut flow, &Isometry3::identity(), 100);
    assert_eq!(flow.graph().liquids(), vec![1.0, 0.0]);

    let open = LiquidGraph::new(
        graph.nodes().cloned().collect(),
        vec![(0, 1, Pipe::new(0.05, 2.0))],
    )
    .unwrap();
    let mut flow = Flooding::sealed(open, FlowOptions::default()).unwrap();
    for _ in 0..100 {
        flow.redistribute(&Isometry3::identity(), &Water::calm(0.0).with_gravity(0.0), DT)
            .unwrap();
    }
    assert_eq!(flow.graph().liquids(), vec![1.0, 0.0]);

    // In air (no free surface) the wall passes nothing.
    let atlas = Atlas::bake(&builtin::sphere(0.5, 24, 12), BakeOptions::square(32)).unwrap();
    let permeability = Permeability::uniform(&atlas, 1e-5).unwrap();
    let single = LiquidGraph::new(vec![Node::new("in", Point3::origin(), 0.1)], vec![]).unwrap();
    let mut flow = Flooding::for_atlas(&atlas, single, permeability, FlowOptions::default()).unwrap();
    let r = flow
        .step(&atlas, &Isometry3::identity(), &Water::air(), 0.0, DT)
        .unwrap();
    assert_eq!(r.entered, 0.0);
}

#[test]
fn bad_step_inputs_are_errors_and_change_nothing() {
    let atlas = Atlas::bake(&builtin::cuboid(1.0, 1.0, 1.0), BakeOptions::square(32)).unwrap();
    let graph = LiquidGraph::new(
        vec![Node::new("in", Point3::origin(), 0.5).with_liquid(0.1)],
        vec![],
    )
    .unwrap();
    let permeability = Permeability::uniform(&atlas, 1e-6).unwrap();
    let mut flow = Flooding::for_atlas(&atlas, graph, permeability, FlowOptions::default()).unwrap();
    let water = Water::calm(0.0);
    let pose = Isometry3::identity();
    assert!(flow.step(&atlas, &pose, &water, 0.0, f64::NAN).is_err());
    assert!(flow.step(&atlas, &pose, &water, 0.0, -1.0).is_err());
    assert!(
        flow.step(&atlas, &pose, &water.with_density(-1.0), 0.0, DT)
            .is_err()
    );
    let nan_pose = Isometry3::translation(f64::NAN, 0.0, 0.0);
    assert!(flow.step(&atlas, &nan_pose, &Water::calm(0.0), 0.0, DT).is_err());
    let other = Atlas::bake(&builtin::cuboid(1.0, 1.0, 1.0), BakeOptions::square(16)).unwrap();
    let e = flow.step(&other, &pose, &Water::calm(0.0), 0.0, DT).unwrap_err();
    assert!(e.to_string().contains("permeability channel"), "{e}");
    assert_eq!(flow.inside(), 0.1);
    assert!(
        Flooding::sealed(
            flow.graph().clone(),
            FlowOptions {
                viscosity: 0.0,
                ..FlowOptions::default()
            }
        )
        .is_err()
    );
    assert!(flow.pour(3, 0.1).is_err());
    assert!(flow.pour(0, f64::NAN).is_err());
}
