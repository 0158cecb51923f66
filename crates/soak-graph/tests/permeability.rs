//! The permeability channel: from an image, from painted regions, changed
//! at run time; typed errors for values, sizes and regions.

use nalgebra::{Isometry3, Point3};
use soak_bake::{Atlas, BakeOptions, builtin};
use soak_graph::{Flooding, FlowOptions, LiquidGraph, Node, Permeability, PermeabilityError};
use soak_hydro::Water;

fn atlas() -> Atlas {
    Atlas::bake(&builtin::cuboid(1.0, 1.0, 1.0), BakeOptions::square(64)).unwrap()
}

#[test]
fn from_an_image_laid_over_the_uv_square() {
    let atlas = atlas();
    // Left half of the UV square permeable, right half not; 2×1 pixels.
    let p = Permeability::from_image(&atlas, &[1.0, 0.0], 2, 1, 3e-7).unwrap();
    for (i, t) in atlas.texels().iter().enumerate() {
        let left = (t[0] as f64 + 0.5) / atlas.width() as f64 <= 0.5;
        assert_eq!(p.get(i), if left { 3e-7 } else { 0.0 }, "texel {i} at {t:?}");
    }
    assert!(!p.is_watertight() && p.permeable().len() < atlas.len());
    assert!(matches!(
        Permeability::from_image(&atlas, &[1.0, 0.0, 1.0], 2, 1, 1.0),
        Err(PermeabilityError::ImageSize { len: 3, .. })
    ));
    assert!(matches!(
        Permeability::from_image(&atlas, &[], 0, 0, 1.0),
        Err(PermeabilityError::ImageSize { .. })
    ));
    assert!(matches!(
        Permeability::from_image(&atlas, &[1.0, -2.0], 2, 1, 1.0),
        Err(PermeabilityError::Value { texel: 1, .. })
    ));
    assert!(Permeability::from_image(&atlas, &[1.0, 0.0], 2, 1, f64::NAN).is_err());
}

#[test]
fn a_painted_region_is_every_texel_within_its_radius() {
    let atlas = atlas();
    let mut p = Permeability::watertight(&atlas);
    assert!(p.is_watertight());
    let centre = Point3::new(0.5, 0.2, 0.0);
    let n = p.paint(&atlas, centre, 0.3, 1e-6).unwrap();
    let expected = (0..atlas.len())
        .filter(|&i| (atlas.position(i) - centre).norm() <= 0.3)
        .count();
    assert_eq!(n, expected);
    assert_eq!(p.permeable().len(), expected);
    // Its conductance is κ times the painted area.
    let area: f64 = p
        .permeable()
        .iter()
        .map(|&i| atlas.areas()[i as usize] as f64)
        .sum();
    assert!((p.conductance(&atlas) - 1e-6 * area).abs() < 1e-18);
    // Painting 0 over it seals it again.
    p.paint(&atlas, centre, 0.3, 0.0).unwrap();
    assert!(p.is_watertight());
    assert!(matches!(
        p.paint(&atlas, centre, -1.0, 1e-6),
        Err(PermeabilityError::Region { .. })
    ));
    assert!(matches!(
        p.paint(&atlas, Point3::new(f64::NAN, 0.0, 0.0), 0.1, 1e-6),
        Err(PermeabilityError::Region { .. })
    ));
    assert!(matches!(
        p.paint(&atlas, centre, 0.1, -1e-6),
        Err(PermeabilityError::Value { .. })
    ));
    let other = Atlas::bake(&builtin::cuboid(1.0, 1.0, 1.0), BakeOptions::square(16)).unwrap();
    assert!(matches!(
        p.paint(&other, centre, 0.1, 1e-6),
        Err(PermeabilityError::Length { .. })
    ));
    assert!(matches!(
        p.set(atlas.len(), 1.0),
        Err(PermeabilityError::NoSuchTexel { .. })
    ));
    p.set(3, 2e-6).unwrap();
    assert_eq!(p.permeable(), &[3]);
    assert!(matches!(
        Permeability::from_values(&atlas, vec![0.0; 5]),
        Err(PermeabilityError::Length { len: 5, .. })
    ));
}

#[test]
fn a_hole_punched_at_run_time_lets_water_in() {
    let atlas = atlas();
    let graph = LiquidGraph::new(
        vec![Node::new("hold", Point3::origin(), 1.0).with_height(1.0)],
        vec![],
    )
    .unwrap();
    let mut flow = Flooding::for_atlas(
        &atlas,
        graph,
        Permeability::watertight(&atlas),
        FlowOptions::default(),
    )
    .unwrap();
    let water = Water::calm(0.0);
    let pose = Isometry3::translation(0.0, 0.2, 0.0); // bottom 0.3 m under water
    let dt = 1.0 / 30.0;
    for step in 0..300 {
        flow.step(&atlas, &pose, &water, step as f64 * dt, dt).unwrap();
    }
    assert_eq!(flow.inside(), 0.0);
    // A hole 10 cm across in the bottom face, below the waterline.
    flow.permeability_mut()
        .unwrap()
        .paint(&atlas, Point3::new(0.0, -0.5, 0.0), 0.05, 1e-6)
        .unwrap();
    let first = flow.step(&atlas, &pose, &water, 10.0, dt).unwrap();
    // Darcy: (κ a / μ) ρ g d Δt with d = 0.3 m over the hole's area.
    let area: f64 = flow
        .permeability()
        .unwrap()
        .permeable()
        .iter()
        .map(|&i| atlas.areas()[i as usize] as f64)
        .sum();
    let expected = 1e-6 * area / 1e-3 * 1000.0 * 9.80665 * 0.3 * dt;
    assert!(
        (first.entered - expected).abs() < 1e-3 * expected,
        "{} vs {expected}",
        first.entered
    );
    for step in 0..9000 {
        flow.step(&atlas, &pose, &water, 10.0 + step as f64 * dt, dt)
            .unwrap();
    }
    assert!((flow.inside() - 0.3).abs() < 1e-6, "{}", flow.inside());
}
