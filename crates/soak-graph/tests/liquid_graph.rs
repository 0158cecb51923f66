//! Building liquid graphs: by hand, from files (with errors naming file,
//! line and node or edge), from an automatic segmentation; and the liquid's
//! mass properties.

use std::path::Path;

use nalgebra::{Matrix3, Point3};
use soak_graph::segment::{SegmentOptions, segment};
use soak_graph::{
    Format, GraphError, GraphFileError, LiquidGraph, Node, Pipe, SegmentGraphOptions, load_graph, parse_graph,
};

fn root() -> &'static Path {
    Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/../.."))
}

#[test]
fn every_hand_made_graph_loads() {
    let dir = root().join("data/graphs");
    let mut count = 0;
    for entry in std::fs::read_dir(&dir).unwrap() {
        let path = entry.unwrap().path();
        let graph = load_graph(&path).unwrap_or_else(|e| panic!("{e}"));
        assert!(graph.node_count() >= 2, "{}", path.display());
        count += 1;
    }
    assert!(count >= 5);
    let boat = load_graph(dir.join("boat.toml")).unwrap();
    assert_eq!(boat.node_count(), 5);
    assert_eq!(boat.edge_count(), 4);
    // Lengths default to the distance between the nodes.
    let (a, b, pipe) = boat.edges().next().unwrap();
    let d = (boat.node(a).unwrap().position - boat.node(b).unwrap().position).norm();
    assert!((pipe.length - d).abs() < 1e-12);
    assert_eq!(pipe.permeability, 1.0);
    // The compartments hold the hull's volume (builtin:boat:4x1.2x0.6).
    let mesh = soak_bake::builtin::boat(4.0, 1.2, 0.6);
    let v = mesh.volume();
    assert!(
        (boat.total_capacity() - v).abs() < 0.01 * v,
        "{} vs {v}",
        boat.total_capacity()
    );
}

#[test]
fn toml_and_json_round_trip() {
    let boat = load_graph(root().join("data/graphs/boat.toml")).unwrap();
    let p = Path::new("round.toml");
    let again = parse_graph(&soak_graph::to_toml(&boat), Format::Toml, p).unwrap();
    let json = parse_graph(&soak_graph::to_json(&boat), Format::Json, p).unwrap();
    for g in [&again, &json] {
        assert_eq!(
            g.nodes().cloned().collect::<Vec<_>>(),
            boat.nodes().cloned().collect::<Vec<_>>()
        );
        assert_eq!(
            g.edges().map(|(a, b, p)| (a, b, *p)).collect::<Vec<_>>(),
            boat.edges().map(|(a, b, p)| (a, b, *p)).collect::<Vec<_>>()
        );
    }
}

fn bad(name: &str) -> (String, GraphFileError) {
    let e = load_graph(root().join("data/bad").join(name)).unwrap_err();
    (e.to_string(), e)
}

#[test]
fn bad_files_name_the_file_the_line_and_the_culprit() {
    let (m, e) = bad("graph_unknown_key.toml");
    assert!(matches!(e, GraphFileError::Parse { line: 10, .. }), "{m}");
    assert!(
        m.contains("graph_unknown_key.toml") && m.contains("capacty"),
        "{m}"
    );

    let (m, e) = bad("graph_negative_capacity.toml");
    assert!(
        matches!(
            e,
            GraphFileError::Invalid {
                line: 7,
                source: GraphError::NodeValue {
                    node: 1,
                    field: "capacity",
                    ..
                },
                ..
            }
        ),
        "{m}"
    );
    assert!(m.contains("`hold`") && m.contains("-0.2"), "{m}");

    let (m, e) = bad("graph_unknown_node.toml");
    assert!(
        matches!(
            e,
            GraphFileError::UnknownNode {
                line: 12,
                edge: 0,
                ..
            }
        ),
        "{m}"
    );
    assert!(m.contains("`keel`"), "{m}");

    let (m, e) = bad("graph_self_loop.toml");
    assert!(
        matches!(
            e,
            GraphFileError::Invalid {
                line: 17,
                source: GraphError::SelfLoop { edge: 1, node: 1 },
                ..
            }
        ),
        "{m}"
    );

    let (m, e) = bad("graph_nan_position.toml");
    assert!(
        matches!(
            e,
            GraphFileError::Invalid {
                line: 2,
                source: GraphError::NodeValue {
                    node: 0,
                    field: "position",
                    ..
                },
                ..
            }
        ),
        "{m}"
    );

    let (m, e) = bad("graph_over_capacity.json");
    assert!(
        matches!(
            e,
            GraphFileError::Invalid {
                line: 4,
                source: GraphError::OverCapacity { node: 1, .. },
                ..
            }
        ),
        "{m}"
    );

    let (m, e) = bad("graph_negative_radius.json");
    assert!(
        matches!(
            e,
            GraphFileError::Invalid {
                line: 9,
                source: GraphError::EdgeValue {
                    edge: 1,
                    field: "radius",
                    ..
                },
                ..
            }
        ),
        "{m}"
    );

    let (m, e) = bad("graph_syntax.json");
    assert!(matches!(e, GraphFileError::Parse { line: 4, .. }), "{m}");

    let (m, e) = bad("graph_empty.toml");
    assert!(
        matches!(
            e,
            GraphFileError::Invalid {
                source: GraphError::Empty,
                ..
            }
        ),
        "{m}"
    );

    let e = load_graph(root().join("data/graphs/missing.toml")).unwrap_err();
    assert!(matches!(e, GraphFileError::Read { .. }), "{e}");
    let e = load_graph(root().join("data/tetra.obj")).unwrap_err();
    assert!(matches!(e, GraphFileError::UnknownFormat { .. }), "{e}");
}

#[test]
fn invalid_graphs_in_code_are_errors() {
    let n = |name: &str, y: f64| Node::new(name, Point3::new(0.0, y, 0.0), 1.0);
    assert!(matches!(LiquidGraph::new(vec![], vec![]), Err(GraphError::Empty)));
    assert!(matches!(
        LiquidGraph::new(vec![n("a", 0.0), n("a", 1.0)], vec![]),
        Err(GraphError::DuplicateName {
            node: 1,
            first: 0,
            ..
        })
    ));
    assert!(matches!(
        LiquidGraph::new(vec![n("a", 0.0)], vec![(0, 2, Pipe::new(0.1, 1.0))]),
        Err(GraphError::MissingNode { edge: 0, node: 2, .. })
    ));
    assert!(matches!(
        LiquidGraph::new(
            vec![n("a", 0.0), n("b", 1.0)],
            vec![(0, 1, Pipe::new(0.1, 1.0)), (1, 0, Pipe::new(0.1, 1.0))]
        ),
        Err(GraphError::DuplicateEdge {
            edge: 1,
            first: 0,
            ..
        })
    ));
    assert!(matches!(
        LiquidGraph::new(vec![n("a", 0.0), n("b", 1.0)], vec![(0, 1, Pipe::new(0.1, 0.0))]),
        Err(GraphError::EdgeValue { field: "length", .. })
    ));
    assert!(matches!(
        LiquidGraph::new(vec![n("a", 0.0).with_height(0.0)], vec![]),
        Err(GraphError::NodeValue { field: "height", .. })
    ));
    assert!(matches!(
        LiquidGraph::new(vec![n("a", 0.0).with_liquid(f64::NAN)], vec![]),
        Err(GraphError::NodeValue { field: "liquid", .. })
    ));
    let mut g = LiquidGraph::new(vec![n("a", 0.0)], vec![]).unwrap();
    assert_eq!(g.set_liquid(0, 7.0).unwrap(), 1.0);
    assert_eq!(g.set_liquid(0, -1.0).unwrap(), 0.0);
    assert!(g.set_liquid(1, 0.5).is_err());
    assert!(g.set_liquid(0, f64::INFINITY).is_err());
}

#[test]
fn liquid_mass_properties_are_point_masses_at_the_nodes() {
    let graph = LiquidGraph::new(
        vec![
            Node::new("a", Point3::new(1.0, 0.0, 0.0), 1.0).with_liquid(0.2),
            Node::new("b", Point3::new(-1.0, 0.0, 0.0), 1.0).with_liquid(0.2),
            Node::new("c", Point3::new(0.0, 2.0, 0.0), 1.0),
        ],
        vec![],
    )
    .unwrap();
    let m = graph.mass_properties(1000.0);
    assert!((m.mass - 400.0).abs() < 1e-9);
    assert!((m.center_of_mass - Point3::origin()).norm() < 1e-12);
    // Two 200 kg masses 1 m either side along x: I_yy = I_zz = 400 kg·m², I_xx = 0.
    let expected = Matrix3::from_diagonal(&nalgebra::Vector3::new(0.0, 400.0, 400.0));
    assert!((m.inertia - expected).norm() < 1e-9, "{}", m.inertia);
    let empty = LiquidGraph::new(vec![Node::new("e", Point3::new(3.0, 0.0, 0.0), 1.0)], vec![]).unwrap();
    assert_eq!(empty.mass_properties(1000.0).mass, 0.0);
}

#[test]
fn the_dumbbell_segmentation_becomes_three_nodes_in_a_chain() {
    let mesh = soak_bake::builtin::parse("builtin:dumbbell").unwrap();
    let seg = segment(&mesh, &SegmentOptions::default()).unwrap();
    let graph = LiquidGraph::from_segmentation(&seg, &SegmentGraphOptions::default()).unwrap();
    assert_eq!(graph.node_count(), 3);
    assert_eq!(graph.edge_count(), 2);
    assert!((graph.total_capacity() - mesh.volume()).abs() < 1e-9);
    // The neck's pipes are about as wide as the neck (radius 0.08 m).
    for (_, _, p) in graph.edges() {
        assert!((p.radius - 0.08).abs() < 0.02, "{p:?}");
    }
    let porous = LiquidGraph::from_segmentation(
        &seg,
        &SegmentGraphOptions {
            porosity: 0.9,
            ..SegmentGraphOptions::default()
        },
    )
    .unwrap();
    assert!((porous.total_capacity() - 0.9 * mesh.volume()).abs() < 1e-9);
    assert!(
        LiquidGraph::from_segmentation(
            &seg,
            &SegmentGraphOptions {
                porosity: 1.5,
                ..SegmentGraphOptions::default()
            }
        )
        .is_err()
    );
}

#[test]
fn inline_tables_report_their_own_lines() {
    let text = "nodes = [\n  { name = \"a\", position = [0.0, 0.0, 0.0], capacity = 1.0 },\n  { name = \"b\", position = [0.0, 0.0, 0.0], capacity = -1.0 },\n]\n";
    let e = parse_graph(text, Format::Toml, Path::new("inline.toml")).unwrap_err();
    assert!(matches!(e, GraphFileError::Invalid { line: 3, .. }), "{e}");
}
