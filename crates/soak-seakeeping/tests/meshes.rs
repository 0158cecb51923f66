//! Radiation problems straight from soak's meshes: a sphere mesh floating
//! half submerged against the hemisphere's references, and a box barge's
//! wetted panels against its exact geometry.

use nalgebra::{Isometry3, Point3, Vector3};
use soak_bake::builtin;
use soak_seakeeping::{Radiation, SeakeepingError, Surface, wetted_panels};
use std::f64::consts::PI;

#[test]
fn a_box_barges_wetted_panels_have_its_geometry() {
    // 4 × 1 × 2 m, floating 0.3 m deep, turned 30° about the vertical.
    let mesh = builtin::cuboid(4.0, 1.0, 2.0);
    let pose = Isometry3::new(Vector3::new(1.0, 0.2, -0.5), Vector3::y() * (PI / 6.0));
    let panels = wetted_panels(&mesh, &pose, 0.25).unwrap();
    let area: f64 = panels.iter().map(|p| p.area).sum();
    let expected = 4.0 * 2.0 + 2.0 * 0.3 * (4.0 + 2.0);
    assert!((area / expected - 1.0).abs() < 1e-9, "{area} vs {expected}");
    assert!(panels.iter().all(|p| p.vertices.iter().all(|v| v.y <= 1e-12)));
    assert!(panels.iter().all(|p| p.size() <= 0.25));
    // The displaced volume by the divergence theorem over the panels and
    // the waterplane (which adds nothing to ∫ y n_y).
    let volume: f64 = panels
        .iter()
        .map(|p| p.centroid.y * p.normal.y * p.area)
        .sum::<f64>();
    assert!((volume / (4.0 * 2.0 * 0.3) - 1.0).abs() < 1e-9, "{volume}");
}

#[test]
fn a_floating_sphere_mesh_matches_the_hemisphere() {
    let mesh = builtin::sphere(1.0, 48, 24);
    let panels = wetted_panels(&mesh, &Isometry3::identity(), 0.2).unwrap();
    let problem = Radiation::new(panels, Point3::origin(), 1000.0, 9.81).unwrap();
    let displaced = 1000.0 * 2.0 / 3.0 * PI;
    let infinite = problem.solve(Surface::InfiniteFrequency).unwrap();
    let heave = infinite.added_mass[(1, 1)] / displaced;
    // Hulme's Table 2 at Ka = 1: 0.5740.
    let surge = problem.solve(Surface::Wavenumber(1.0)).unwrap().added_mass[(0, 0)] / displaced;
    eprintln!(
        "{} panels: heave(∞) {heave:.4} (0.5), surge(Ka 1) {surge:.4} (0.5740)",
        problem.panels().len()
    );
    assert!((heave / 0.5 - 1.0).abs() < 0.02, "{heave}");
    assert!((surge / 0.574 - 1.0).abs() < 0.03, "{surge}");
}

#[test]
fn bad_input_is_refused() {
    let mesh = builtin::cuboid(1.0, 1.0, 1.0);
    assert!(matches!(
        wetted_panels(&mesh, &Isometry3::identity(), 0.0),
        Err(SeakeepingError::BadParameter { name: "max_size", .. })
    ));
    let mut broken = mesh.clone();
    broken.positions[3].y = f64::NAN;
    assert!(matches!(
        wetted_panels(&broken, &Isometry3::identity(), 0.5),
        Err(SeakeepingError::BadMesh { vertex: 3, .. })
    ));
    let mut dangling = mesh.clone();
    dangling.triangles[5][1] = 99;
    assert!(matches!(
        wetted_panels(&dangling, &Isometry3::identity(), 0.5),
        Err(SeakeepingError::BadTriangle {
            triangle: 5,
            vertex: 99,
            ..
        })
    ));
    // Too few samples to fit: no poles, no panic.
    assert!(soak_seakeeping::Kernel::fit(&[], 0.1, 4).poles.is_empty());
    assert!(soak_seakeeping::Kernel::fit(&[1.0, 0.5], 0.1, 4).poles.is_empty());
    // Wholly out of the water: nothing wetted.
    let lifted = wetted_panels(&mesh, &Isometry3::translation(0.0, 2.0, 0.0), 0.5).unwrap();
    assert!(matches!(
        Radiation::new(lifted, Point3::origin(), 1000.0, 9.81),
        Err(SeakeepingError::NoWettedSurface)
    ));
    let panels = wetted_panels(&mesh, &Isometry3::identity(), 0.5).unwrap();
    assert!(matches!(
        Radiation::new(panels.clone(), Point3::origin(), -1.0, 9.81),
        Err(SeakeepingError::BadParameter { name: "density", .. })
    ));
    let problem = Radiation::new(panels, Point3::origin(), 1000.0, 9.81).unwrap();
    assert!(matches!(
        problem.solve(Surface::Wavenumber(f64::NAN)),
        Err(SeakeepingError::BadParameter {
            name: "wavenumber",
            ..
        })
    ));
}
