//! Openings: liquid through a hole or over a rim follows the orifice and
//! weir laws (independent references: Torricelli's efflux integrated over
//! the fill, and the rectangular weir's `(2/3) C_d L √(2g) H^{3/2}`), not
//! Darcy seepage.

use nalgebra::{Isometry3, Point3, Vector3};
use soak_bake::{Atlas, BakeOptions, builtin, cap_openings};
use soak_graph::{Flooding, FlowOptions, LiquidGraph, Node, Permeability};
use soak_hydro::Water;

const G: f64 = 9.81;

fn cube(n: u32) -> Atlas {
    Atlas::bake(&builtin::cuboid(1.0, 1.0, 1.0), BakeOptions::square(n)).unwrap()
}

fn one_node() -> LiquidGraph {
    LiquidGraph::new(
        vec![Node::new("inside", Point3::origin(), 1.0).with_height(1.0)],
        vec![],
    )
    .unwrap()
}

#[test]
fn a_tank_fills_through_a_bottom_hole_in_the_orifice_laws_time() {
    let atlas = cube(256);
    let mut wall = Permeability::watertight(&atlas);
    let hole = wall.open(&atlas, Point3::new(0.0, -0.5, 0.0), 0.06).unwrap();
    assert!(hole > 20 && wall.permeable().is_empty());
    let area: f64 = wall
        .openings()
        .iter()
        .map(|&i| atlas.areas()[i as usize] as f64)
        .sum();
    let options = FlowOptions::default();
    let cd = options.discharge_coefficient;
    let mut flooding = Flooding::for_atlas(&atlas, one_node(), wall, options).unwrap();
    // Held with its bottom 2.5 m deep: dh/dt = C_d A √(2g (D − h)) / S.
    let pose = Isometry3::translation(0.0, -2.0, 0.0);
    let water = Water::calm(0.0);
    let (depth, level) = (2.5f64, 0.9);
    let expected = 2.0 * (depth.sqrt() - (depth - level).sqrt()) / (cd * area * (2.0 * G).sqrt());
    let dt = 1.0 / 60.0;
    let mut t = 0.0;
    while flooding.inside() < level {
        flooding.step(&atlas, &pose, &water, t, dt).unwrap();
        t += dt;
        assert!(t < 3.0 * expected, "not filled after {t} s");
    }
    let error = (t - expected).abs() / expected;
    println!(
        "orifice: filled in {t:.3} s, the law {expected:.3} s ({:.2} %)",
        100.0 * error
    );
    assert!(
        error < 0.03,
        "filled to {level} m in {t:.2} s, the orifice law says {expected:.2} s"
    );
    // Darcy seepage through a wall with the same hole as κ = 10⁻⁹ m (a leaking
    // seam) would take thousands of times longer: openings are not seepage.
    assert!(expected < 60.0);
    assert!(flooding.conservation_error() < 1e-12);
}

#[test]
fn a_slot_in_the_side_passes_the_weir_flow() {
    // A vertical slot 0.4 m wide in the +x face, above the box's mid-height;
    // the box's middle sits 0.3 m under the surface, so the water stands
    // H = 0.3 m over the slot's sill and the empty box takes the weir flow.
    let atlas = cube(256);
    let mut wall = Permeability::watertight(&atlas);
    let slot: Vec<u32> = (0..atlas.len() as u32)
        .filter(|&i| {
            let p = atlas.position(i as usize);
            let a = atlas.area_vectors().get(i as usize);
            a[0] > 0.0 && p.y > 0.0 && p.z.abs() < 0.2
        })
        .collect();
    wall.open_texels(slot).unwrap();
    let options = FlowOptions::default();
    let cd = options.discharge_coefficient;
    let mut flooding = Flooding::for_atlas(&atlas, one_node(), wall, options).unwrap();
    let pose = Isometry3::translation(0.0, -0.3, 0.0);
    let dt = 1e-3;
    let report = flooding.step(&atlas, &pose, &Water::calm(0.0), 0.0, dt).unwrap();
    let (width, head) = (0.4f64, 0.3f64);
    let weir = 2.0 / 3.0 * cd * width * (2.0 * G).sqrt() * head.powf(1.5) * dt;
    let error = (report.entered - weir).abs() / weir;
    println!(
        "weir: {:.5e} m³ against {weir:.5e} m³ ({:.2} %)",
        report.entered,
        100.0 * error
    );
    assert!(
        error < 0.02,
        "entered {:.4e} m³, the weir law {weir:.4e} m³",
        report.entered
    );
}

#[test]
fn an_open_box_pours_out_when_tipped_past_its_rim() {
    let closed = cap_openings(&builtin::open_box(1.0, 0.5, 1.0)).unwrap();
    let atlas = Atlas::bake(&closed, BakeOptions::square(128)).unwrap();
    let graph = LiquidGraph::cavity(&atlas, 0.0).unwrap();
    // Four layers of a quarter of the box each, bottom first.
    let capacities: Vec<f64> = graph.nodes().map(|n| n.capacity).collect();
    assert_eq!(capacities.len(), soak_graph::CAVITY_LAYERS);
    for c in &capacities {
        assert!((c - 0.125).abs() < 1e-5, "{capacities:?}");
    }
    let mut flooding = Flooding::for_atlas(
        &atlas,
        graph,
        Permeability::open_mesh(&atlas),
        FlowOptions::default(),
    )
    .unwrap();
    let mut poured = 0.0;
    for node in 0..capacities.len() {
        poured += flooding.pour(node, 0.3 - poured).unwrap();
    }
    assert!((poured - 0.3).abs() < 1e-12);
    let water = Water::calm(-10.0); // far below: only the box's own liquid moves
    let dt = 1.0 / 60.0;
    // Upright it holds its liquid.
    let upright = Isometry3::identity();
    for k in 0..120 {
        flooding
            .step(&atlas, &upright, &water, k as f64 * dt, dt)
            .unwrap();
    }
    assert!((flooding.inside() - 0.3).abs() < 1e-12);
    // On its side its rim is below the liquid's head: it empties.
    let tipped = Isometry3::new(Vector3::zeros(), Vector3::z() * 1.6);
    for k in 0..600 {
        flooding.step(&atlas, &tipped, &water, k as f64 * dt, dt).unwrap();
    }
    assert!(flooding.inside() < 0.02, "{} m³ left", flooding.inside());
    assert!(flooding.ledger().left() > 0.28 && flooding.conservation_error() < 1e-12);
}
