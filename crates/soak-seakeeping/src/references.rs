//! Classical floating bodies: their panels and reference coefficients,
//! what this crate's panel method is checked against (its tests, and the
//! figure `cargo run --release -p soak-report --example
//! seakeeping_references` draws), and what a solver setup can be checked
//! against.

use std::f64::consts::PI;

use nalgebra::{Point3, Vector3};

use crate::{Panel, SeakeepingError};

/// Hulme (1982), J. Fluid Mech. 121, Table 2: the floating hemisphere of
/// radius `a` in surge, `(Ka, A11/(ρ⅔πa³), B11/(ρω⅔πa³))` with
/// `K = ω²/g` (the damping NaN beyond Ka 1.4, as far as the transcription
/// at hand gives it). The added mass at Ka = 0.7, 0.6682, breaks the
/// table's otherwise smooth curve (0.656 would be on it); it is kept as
/// published.
pub const HULME_SURGE: [(f64, f64, f64); 19] = [
    (0.1, 0.5223, 0.0010),
    (0.2, 0.5515, 0.0082),
    (0.3, 0.5848, 0.0255),
    (0.4, 0.6175, 0.0557),
    (0.5, 0.6439, 0.0987),
    (0.6, 0.6586, 0.1516),
    (0.7, 0.6682, 0.2092),
    (0.8, 0.6421, 0.2653),
    (0.9, 0.6127, 0.3145),
    (1.0, 0.5740, 0.3535),
    (1.2, 0.4860, 0.3978),
    (1.4, 0.4038, 0.4060),
    (1.6, 0.3371, f64::NAN),
    (1.8, 0.2866, f64::NAN),
    (2.0, 0.2493, f64::NAN),
    (2.5, 0.1961, f64::NAN),
    (3.0, 0.1720, f64::NAN),
    (3.4, 0.1634, f64::NAN),
    (4.0, 0.1620, f64::NAN),
];

/// A floating truncated vertical cylinder of radius `a` and draft `a` in
/// heave, `(Ka, A22/(ρπa³), B22/(ρωπa³))` with `K = ω²/g`, by matched
/// eigenfunction expansions (Yeung 1981, Appl. Ocean Res. 3: the
/// potential in separated variables beside and under the cylinder,
/// matched across its radius) in water 80 radii deep, computed by the
/// repository's `scripts/references/truncated_cylinder.py` (its damping
/// equals the energy the outgoing wave carries away; twice the terms or
/// half the depth move the added mass by at most 2e-4 and 1e-3 of it).
pub const TRUNCATED_CYLINDER_HEAVE: [(f64, f64, f64); 15] = [
    (0.1, 0.7297, 0.10952),
    (0.2, 0.6743, 0.15238),
    (0.3, 0.6230, 0.16012),
    (0.4, 0.5837, 0.15064),
    (0.5, 0.5563, 0.13369),
    (0.6, 0.5386, 0.11450),
    (0.8, 0.5229, 0.07884),
    (1.0, 0.5219, 0.05175),
    (1.2, 0.5270, 0.03313),
    (1.5, 0.5374, 0.01662),
    (2.0, 0.5519, 0.00518),
    (2.5, 0.5610, 0.00163),
    (3.0, 0.5666, 0.00052),
    (3.5, 0.5702, 0.00017),
    (4.0, 0.5726, 0.00005),
];

/// A panel through `quad` (a corner repeated next to itself dropped), its
/// normal turned along `outward`; `None` for a panel of no area.
fn oriented(mut quad: Vec<Point3<f64>>, outward: Vector3<f64>) -> Option<Panel> {
    quad.dedup_by(|p, q| (*p - *q).norm() < 1e-12);
    let panel = Panel::new(&quad)?;
    if panel.normal.dot(&outward) < 0.0 {
        quad.reverse();
        return Panel::new(&quad);
    }
    Some(panel)
}

/// Refuses a length that is not positive and finite, or a count of zero.
fn check(lengths: &[(&'static str, f64)], counts: &[(&'static str, usize)]) -> Result<(), SeakeepingError> {
    for &(name, value) in lengths {
        if !(value.is_finite() && value > 0.0) {
            return Err(SeakeepingError::BadParameter { name, value });
        }
    }
    for &(name, count) in counts {
        if count == 0 {
            return Err(SeakeepingError::BadParameter { name, value: 0.0 });
        }
    }
    Ok(())
}

/// The panels built, or the parameter that left one without area.
fn collect(
    panels: Vec<Option<Panel>>,
    name: &'static str,
    value: f64,
) -> Result<Vec<Panel>, SeakeepingError> {
    panels
        .into_iter()
        .collect::<Option<Vec<Panel>>>()
        .ok_or(SeakeepingError::BadParameter { name, value })
}

/// Quadrilateral panels on a sphere of radius `a` (m) centred at `centre`,
/// between polar angles (from −y) 0 and `top` (π/2: the hemisphere below
/// `centre.y`; π: the whole sphere), `rings` × `segments`, rings evenly
/// spaced in angle, normals out of the sphere.
///
/// # Errors
/// [`SeakeepingError::BadParameter`] naming `a`, `top`, `rings` or
/// `segments` where one is not positive (and finite), or the centre where
/// it is not finite.
pub fn sphere_panels(
    a: f64,
    centre: Point3<f64>,
    top: f64,
    rings: usize,
    segments: usize,
) -> Result<Vec<Panel>, SeakeepingError> {
    check(
        &[("sphere radius", a), ("sphere polar angle", top)],
        &[("rings", rings), ("segments", segments)],
    )?;
    if let Some(c) = centre.iter().find(|c| !c.is_finite()) {
        return Err(SeakeepingError::BadParameter {
            name: "sphere centre",
            value: *c,
        });
    }
    let point = |i: usize, j: usize| {
        let alpha = top * i as f64 / rings as f64;
        let phi = 2.0 * PI * j as f64 / segments as f64;
        centre
            + Vector3::new(
                a * alpha.sin() * phi.cos(),
                -a * alpha.cos(),
                a * alpha.sin() * phi.sin(),
            )
    };
    let mut panels = Vec::with_capacity(rings * segments);
    for i in 0..rings {
        for j in 0..segments {
            let quad = vec![point(i, j), point(i + 1, j), point(i + 1, j + 1), point(i, j + 1)];
            let mid = quad.iter().fold(Vector3::zeros(), |s, p| s + p.coords) / 4.0;
            panels.push(oriented(quad, mid - centre.coords));
        }
    }
    collect(panels, "sphere radius", a)
}

/// The wetted surface of a truncated vertical cylinder floating upright,
/// its axis along y through the origin, the still water at y = 0: the
/// side of `radius` (m) down to `draft` (m) in `bands`, the bottom in
/// `rings`, `segments` around, both graded towards the bottom's rim (where
/// the flow turns the corner; spacing as `sin` of even steps), normals out
/// of the body.
///
/// # Errors
/// [`SeakeepingError::BadParameter`] naming `radius`, `draft`, `bands`,
/// `rings` or `segments` where one is not positive (and finite).
pub fn truncated_cylinder_panels(
    radius: f64,
    draft: f64,
    bands: usize,
    rings: usize,
    segments: usize,
) -> Result<Vec<Panel>, SeakeepingError> {
    check(
        &[("cylinder radius", radius), ("cylinder draft", draft)],
        &[("bands", bands), ("rings", rings), ("segments", segments)],
    )?;
    let at = |r: f64, y: f64, j: usize| {
        let phi = 2.0 * PI * j as f64 / segments as f64;
        Point3::new(r * phi.cos(), y, r * phi.sin())
    };
    // From 0 (the waterline, the axis) to 1 (the rim).
    let graded = |i: usize, n: usize| (0.5 * PI * i as f64 / n as f64).sin();
    let mut panels = Vec::with_capacity((bands + rings) * segments);
    for i in 0..bands {
        let (y0, y1) = (-draft * graded(i, bands), -draft * graded(i + 1, bands));
        for j in 0..segments {
            let quad = vec![
                at(radius, y0, j),
                at(radius, y1, j),
                at(radius, y1, j + 1),
                at(radius, y0, j + 1),
            ];
            let phi = 2.0 * PI * (j as f64 + 0.5) / segments as f64;
            panels.push(oriented(quad, Vector3::new(phi.cos(), 0.0, phi.sin())));
        }
    }
    for i in 0..rings {
        let (r0, r1) = (radius * graded(i, rings), radius * graded(i + 1, rings));
        for j in 0..segments {
            let quad = vec![
                at(r0, -draft, j),
                at(r1, -draft, j),
                at(r1, -draft, j + 1),
                at(r0, -draft, j + 1),
            ];
            panels.push(oriented(quad, -Vector3::y()));
        }
    }
    collect(panels, "cylinder radius", radius)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Bad sizes are refused by name; good ones give closed panels' areas.
    #[test]
    fn bad_sizes_are_named_and_good_ones_have_the_right_area() {
        let name = |r: Result<Vec<Panel>, SeakeepingError>| match r {
            Err(SeakeepingError::BadParameter { name, .. }) => name,
            other => panic!("{:?}", other.map(|p| p.len())),
        };
        assert_eq!(
            name(sphere_panels(0.0, Point3::origin(), PI, 4, 8)),
            "sphere radius"
        );
        assert_eq!(name(sphere_panels(1.0, Point3::origin(), PI, 0, 8)), "rings");
        assert_eq!(
            name(sphere_panels(1.0, Point3::new(f64::NAN, 0.0, 0.0), PI, 4, 8)),
            "sphere centre"
        );
        assert_eq!(
            name(truncated_cylinder_panels(1.0, f64::INFINITY, 4, 4, 8)),
            "cylinder draft"
        );
        assert_eq!(name(truncated_cylinder_panels(1.0, 1.0, 4, 4, 0)), "segments");
        // The cylinder's wetted area: side 2π r d, bottom π r² (the
        // polygon's, 48 sides: a fraction (sin(2π/48)·48/(2π)) of it).
        let panels = truncated_cylinder_panels(1.0, 0.5, 6, 6, 48).unwrap();
        let area: f64 = panels.iter().map(|p| p.area).sum();
        let polygon = (2.0 * PI / 48.0).sin() * 48.0 / (2.0 * PI);
        let chord = (PI / 48.0).sin() * 48.0 / PI;
        let expected = 2.0 * PI * 0.5 * chord + PI * polygon;
        assert!((area - expected).abs() < 1e-9, "{area} vs {expected}");
        assert!(panels.iter().all(|p| p.normal.y <= 1e-12), "no panel faces up");
    }
}
