//! Panels of spheres and hemispheres for the tests.

// Each test binary uses some of these.
#![allow(dead_code)]

use nalgebra::Point3;
use soak_seakeeping::{Panel, Radiation};
use std::f64::consts::PI;

/// Quadrilateral panels on a sphere of radius `a` centred at `centre`,
/// between polar angles (from −y) 0 and `top` (π/2: the hemisphere below
/// y = centre.y; π: the whole sphere), `rings` × `segments`. Rings are
/// spaced evenly in angle.
pub fn sphere_panels(a: f64, centre: Point3<f64>, top: f64, rings: usize, segments: usize) -> Vec<Panel> {
    let point = |i: usize, j: usize| {
        let alpha = top * i as f64 / rings as f64;
        let phi = 2.0 * PI * j as f64 / segments as f64;
        centre
            + nalgebra::Vector3::new(
                a * alpha.sin() * phi.cos(),
                -a * alpha.cos(),
                a * alpha.sin() * phi.sin(),
            )
    };
    let mut panels = Vec::new();
    for i in 0..rings {
        for j in 0..segments {
            let mut quad = vec![point(i, j), point(i + 1, j), point(i + 1, j + 1), point(i, j + 1)];
            quad.dedup_by(|p, q| (*p - *q).norm() < 1e-12);
            let mut panel = Panel::new(&quad).expect("a panel");
            if panel.normal.dot(&(panel.centroid - centre)) < 0.0 {
                quad.reverse();
                panel = Panel::new(&quad).expect("a panel");
            }
            panels.push(panel);
        }
    }
    panels
}

/// The floating unit hemisphere in water of 1000 kg/m³ under 9.81 m/s².
pub fn hemisphere(rings: usize, segments: usize) -> Radiation {
    let panels = sphere_panels(1.0, Point3::origin(), PI / 2.0, rings, segments);
    Radiation::new(panels, Point3::origin(), 1000.0, 9.81).expect("a radiation problem")
}
