//! Communicating vessels (thesis §4.1.2 and Fig. 4.5): equal nodes level
//! out, a higher node drains into a lower one and never takes back, a node
//! behind a higher barrier keeps its liquid, and Algorithm 1 discharges
//! straight through full nodes.

use nalgebra::{Isometry3, Point3, UnitQuaternion, Vector3};
use soak_graph::{Flooding, FlowOptions, LiquidGraph, Node, Pipe, find_discharge, load_graph};
use soak_hydro::Water;

const DT: f64 = 1.0 / 30.0;

fn data(name: &str) -> String {
    format!("{}/../../data/graphs/{name}", env!("CARGO_MANIFEST_DIR"))
}

fn run(flow: &mut Flooding, pose: &Isometry3<f64>, steps: usize, mut each: impl FnMut(&Flooding)) {
    let water = Water::calm(0.0);
    for _ in 0..steps {
        flow.redistribute(pose, &water, DT).unwrap();
        for n in flow.graph().nodes() {
            assert!(n.liquid >= 0.0 && n.liquid <= n.capacity, "{n:?}");
        }
        each(flow);
    }
}

#[test]
fn two_equal_nodes_at_one_height_level_out() {
    let graph = load_graph(data("communicating_vessels.json")).unwrap();
    let mut flow = Flooding::sealed(graph, FlowOptions::default()).unwrap();
    let mut last_gap = f64::INFINITY;
    run(&mut flow, &Isometry3::identity(), 1800, |f| {
        let l = f.graph().liquids();
        let gap = l[0] - l[1];
        // Monotone approach, never past the level.
        assert!(
            gap >= -1e-12 && gap <= last_gap + 1e-15,
            "gap {gap} after {last_gap}"
        );
        last_gap = gap;
    });
    let l = flow.graph().liquids();
    assert!((l[0] - 0.5).abs() < 1e-9 && (l[1] - 0.5).abs() < 1e-9, "{l:?}");
    assert!(flow.conservation_error() < 1e-12);
}

#[test]
fn unequal_nodes_at_one_height_level_their_heads_not_their_volumes() {
    // A wide and a narrow vessel of equal height: equal heads mean equal fill fractions.
    let graph = LiquidGraph::new(
        vec![
            Node::new("wide", Point3::new(-1.0, 0.0, 0.0), 2.0)
                .with_height(1.0)
                .with_liquid(1.5),
            Node::new("narrow", Point3::new(1.0, 0.0, 0.0), 0.5).with_height(1.0),
        ],
        vec![(0, 1, Pipe::new(0.05, 2.0))],
    )
    .unwrap();
    let mut flow = Flooding::sealed(graph, FlowOptions::default()).unwrap();
    run(&mut flow, &Isometry3::identity(), 300, |_| {});
    let n: Vec<_> = flow.graph().nodes().cloned().collect();
    assert!((n[0].fill() - n[1].fill()).abs() < 1e-9, "{n:?}");
    assert!((n[0].fill() - 0.6).abs() < 1e-9);
}

#[test]
fn a_higher_node_drains_into_a_lower_one_and_never_back() {
    for (upper, lower_capacity) in [(0.6, 1.0), (0.9, 0.5)] {
        let graph = LiquidGraph::new(
            vec![
                Node::new("upper", Point3::new(0.0, 1.0, 0.0), 1.0)
                    .with_height(0.5)
                    .with_liquid(upper),
                Node::new("lower", Point3::new(0.3, 0.0, 0.0), lower_capacity).with_height(0.5),
            ],
            vec![(0, 1, Pipe::new(0.01, 1.0))],
        )
        .unwrap();
        let mut flow = Flooding::sealed(graph, FlowOptions::default()).unwrap();
        let mut last = flow.graph().liquids();
        run(&mut flow, &Isometry3::identity(), 3000, |f| {
            let l = f.graph().liquids();
            assert!(l[0] <= last[0] && l[1] >= last[1], "{last:?} -> {l:?}");
            last = l;
        });
        let l = flow.graph().liquids();
        let expected_lower = upper.min(lower_capacity);
        assert!((l[1] - expected_lower).abs() < 1e-9, "{l:?}");
        assert!((l[0] - (upper - expected_lower)).abs() < 1e-9, "{l:?}");
    }
}

#[test]
fn turning_the_body_over_reverses_the_flow() {
    // Heights are world heights: upside down, the old lower node drains back.
    let graph = LiquidGraph::new(
        vec![
            Node::new("top", Point3::new(0.0, 1.0, 0.0), 1.0).with_height(0.5),
            Node::new("bottom", Point3::new(0.0, -1.0, 0.0), 1.0)
                .with_height(0.5)
                .with_liquid(0.7),
        ],
        vec![(0, 1, Pipe::new(0.02, 2.0))],
    )
    .unwrap();
    let mut flow = Flooding::sealed(graph, FlowOptions::default()).unwrap();
    run(&mut flow, &Isometry3::identity(), 100, |_| {});
    assert_eq!(flow.graph().liquids(), vec![0.0, 0.7]);
    let flipped = Isometry3::from_parts(
        Vector3::new(5.0, 2.0, 0.0).into(),
        UnitQuaternion::from_axis_angle(&Vector3::x_axis(), std::f64::consts::PI),
    );
    run(&mut flow, &flipped, 1800, |_| {});
    let l = flow.graph().liquids();
    assert!((l[0] - 0.7).abs() < 1e-9 && l[1].abs() < 1e-9, "{l:?}");
}

#[test]
fn fig_4_5_cascade_discharges_through_the_full_node() {
    let graph = load_graph(data("fig4_5_cascade.toml")).unwrap();
    let (a, b, c) = (
        graph.find("A").unwrap(),
        graph.find("B").unwrap(),
        graph.find("C").unwrap(),
    );
    let options = FlowOptions::default();
    for seed in 0..8 {
        let found = find_discharge(&graph, &Isometry3::identity(), a, &options, seed).unwrap();
        assert_eq!(found.node, c);
        // Two pipes in series: twice one pipe's resistance.
        let one = Pipe::new(0.05, 1.0).resistance(options.viscosity);
        assert!((found.resistance - 2.0 * one).abs() < 1e-9 * one);
    }
    let mut flow = Flooding::sealed(graph, options).unwrap();
    run(&mut flow, &Isometry3::identity(), 600, |_| {});
    let l = flow.graph().liquids();
    // The lowest fills first: C full, the rest in B, A empty.
    assert!(
        l[a].abs() < 1e-9 && (l[b] - 0.4).abs() < 1e-9 && (l[c] - 1.0).abs() < 1e-12,
        "{l:?}"
    );
}

#[test]
fn fig_4_5_u_tube_levels_the_two_arms_through_the_full_bottom() {
    let graph = load_graph(data("fig4_5_u_tube.toml")).unwrap();
    let (a, b, c) = (
        graph.find("A").unwrap(),
        graph.find("B").unwrap(),
        graph.find("C").unwrap(),
    );
    let found = find_discharge(&graph, &Isometry3::identity(), a, &FlowOptions::default(), 3).unwrap();
    assert_eq!(found.node, c);
    // The full bottom cannot lift its liquid into either arm.
    assert_eq!(
        find_discharge(&graph, &Isometry3::identity(), b, &FlowOptions::default(), 3),
        None
    );
    let mut flow = Flooding::sealed(graph, FlowOptions::default()).unwrap();
    run(&mut flow, &Isometry3::identity(), 300, |f| {
        assert_eq!(f.graph().liquids()[b], 1.0);
    });
    let l = flow.graph().liquids();
    assert!((l[a] - 0.4).abs() < 1e-9 && (l[c] - 0.4).abs() < 1e-9, "{l:?}");
}

#[test]
fn a_node_behind_a_higher_barrier_keeps_its_liquid() {
    let graph = load_graph(data("fig4_5_barrier.toml")).unwrap();
    let (a, b, c) = (
        graph.find("A").unwrap(),
        graph.find("B").unwrap(),
        graph.find("C").unwrap(),
    );
    for seed in 0..8 {
        assert_eq!(
            find_discharge(&graph, &Isometry3::identity(), a, &FlowOptions::default(), seed),
            None
        );
    }
    let mut flow = Flooding::sealed(graph, FlowOptions::default()).unwrap();
    run(&mut flow, &Isometry3::identity(), 1800, |f| {
        assert_eq!(f.graph().liquids()[a], 0.5, "A passed liquid over the barrier");
    });
    let l = flow.graph().liquids();
    // B, higher than C, drained into it on its own.
    assert!(l[b].abs() < 1e-9 && (l[c] - 1.0).abs() < 1e-9, "{l:?}");
    // Lower the barrier below A's surface and A's liquid goes through.
    let lowered = load_graph(data("fig4_5_barrier.toml")).unwrap();
    let mut nodes: Vec<Node> = lowered.nodes().cloned().collect();
    nodes[b].position.y = 0.2; // bottom at −0.05, below A's head at 0
    nodes[b].liquid = 0.0;
    let edges = lowered.edges().map(|(x, y, p)| (x, y, *p)).collect();
    let lowered = LiquidGraph::new(nodes, edges).unwrap();
    let found = find_discharge(&lowered, &Isometry3::identity(), a, &FlowOptions::default(), 0);
    assert!(found.is_some());
}

#[test]
fn same_seed_same_run() {
    let make = |seed| {
        let graph = load_graph(data("boat.toml")).unwrap();
        let mut flow = Flooding::sealed(
            graph,
            FlowOptions {
                seed,
                ..FlowOptions::default()
            },
        )
        .unwrap();
        for i in 0..5 {
            flow.pour(i, 0.02 * (i + 1) as f64).unwrap();
        }
        let pose = Isometry3::rotation(Vector3::new(0.1, 0.0, -0.15));
        run(&mut flow, &pose, 200, |_| {});
        flow.graph().liquids()
    };
    let (x, y) = (make(5), make(5));
    assert_eq!(x, y);
}
