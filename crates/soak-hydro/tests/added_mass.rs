//! The equivalent ellipsoid's added mass of baked meshes against the
//! shapes whose added mass is known: a sphere (`½ ρ V`), prolate and oblate
//! spheroids (Lamb's closed forms) and a cube (0.67 ρ s³, DNV-RP-C205
//! table A-2). Prints the table the README quotes.

use nalgebra::{Matrix3, Point3, Vector3};
use soak_bake::{Atlas, BakeOptions, Mesh, builtin};
use soak_hydro::{AddedMass, VolumeMoments, volume_moments};

/// The closed-form coefficients `(k along the axis, k across)` of a
/// spheroid of axis ratio `ratio` (> 1 prolate, < 1 oblate): Lamb,
/// Hydrodynamics §373 (prolate) and §374 (oblate, with `e` the
/// eccentricity of the meridian: `α₀ = 2/e² − 2√(1 − e²)/e³ · asin e`).
fn spheroid(ratio: f64) -> (f64, f64) {
    let (alpha, beta) = if ratio > 1.0 {
        let e = (1.0 - 1.0 / (ratio * ratio)).sqrt();
        let log = ((1.0 + e) / (1.0 - e)).ln();
        (
            2.0 * (1.0 - e * e) / e.powi(3) * (0.5 * log - e),
            1.0 / (e * e) - (1.0 - e * e) / (2.0 * e.powi(3)) * log,
        )
    } else {
        // Oblate: the axis is the short one, c = ratio·a.
        let e = (1.0 - ratio * ratio).sqrt();
        let along = 2.0 / (e * e) - 2.0 * (1.0 - e * e).sqrt() / e.powi(3) * e.asin();
        (along, 0.5 * (2.0 - along))
    };
    (alpha / (2.0 - alpha), beta / (2.0 - beta))
}

fn stretched(mesh: Mesh, along_x: f64) -> Mesh {
    mesh.map_positions(|p| Point3::new(p.x * along_x, p.y, p.z))
}

#[test]
fn the_equivalent_ellipsoid_gives_the_known_added_masses() {
    println!("| shape | axis | soak k (added mass / ρ V) | reference | error |");
    println!("|---|---|---|---|---|");
    let row = |shape: &str, axis: &str, got: f64, want: f64, tolerance: f64| {
        let error = got / want - 1.0;
        println!(
            "| {shape} | {axis} | {got:.4} | {want:.4} | {:+.1} % |",
            100.0 * error
        );
        assert!(error.abs() <= tolerance, "{shape} {axis}: {got} vs {want}");
    };
    let k_of = |mesh: &Mesh| {
        let atlas = Atlas::bake(mesh, BakeOptions::square(256)).unwrap();
        let moments = volume_moments(&atlas);
        let (added, _) = AddedMass::equivalent_ellipsoid(&moments).unwrap();
        // Added mass per ρ over the body's own volume, along x, y, z.
        Vector3::new(
            added.translation[(0, 0)],
            added.translation[(1, 1)],
            added.translation[(2, 2)],
        ) / moments.volume
    };
    let sphere = k_of(&builtin::sphere(0.5, 64, 32));
    for (i, axis) in ["x", "y", "z"].into_iter().enumerate() {
        row("sphere r = 0.5 m", axis, sphere[i], 0.5, 0.01);
    }
    for ratio in [2.0, 0.5] {
        let k = k_of(&stretched(builtin::sphere(0.5, 64, 32), ratio));
        let (along, across) = spheroid(ratio);
        let name = if ratio > 1.0 {
            "prolate spheroid 2:1"
        } else {
            "oblate spheroid 1:2"
        };
        row(name, "x (axis)", k.x, along, 0.01);
        row(name, "y", k.y, across, 0.01);
    }
    // The cube: the equivalent ellipsoid is a sphere of radius √(5/12) s,
    // 0.5 × 1.124 s³ = 0.562 s³, against 0.67 tabulated: 16 % low.
    let cube = k_of(&builtin::cuboid(1.0, 1.0, 1.0));
    row("cube", "x", cube.x, 0.67, 0.17);
    assert!((cube.x - 0.5 * 4.0 / 3.0 * std::f64::consts::PI * (5.0f64 / 12.0).powf(1.5)).abs() < 1e-3);
}

#[test]
fn a_body_that_encloses_nothing_or_is_flat_is_a_typed_error() {
    let empty = VolumeMoments {
        origin: Point3::origin(),
        volume: 0.0,
        first: Vector3::zeros(),
        second: Matrix3::zeros(),
    };
    let e = AddedMass::equivalent_ellipsoid(&empty).unwrap_err();
    assert!(e.to_string().contains("encloses 0 m³"), "{e}");
    // A plate of no thickness: volume but no extent along y.
    let flat = VolumeMoments {
        volume: 1.0,
        second: Matrix3::from_diagonal(&Vector3::new(0.1, 0.0, 0.1)),
        ..empty
    };
    let e = AddedMass::equivalent_ellipsoid(&flat).unwrap_err();
    assert!(e.to_string().contains("no extent"), "{e}");
}
