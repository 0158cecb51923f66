//! Panels of spheres and hemispheres for the tests.

// Each test binary uses some of these.
#![allow(dead_code)]

use nalgebra::Point3;
use soak_seakeeping::Radiation;
use std::f64::consts::PI;

pub use soak_seakeeping::references::sphere_panels;

/// The floating unit hemisphere in water of 1000 kg/m³ under 9.81 m/s².
pub fn hemisphere(rings: usize, segments: usize) -> Radiation {
    let panels =
        sphere_panels(1.0, Point3::origin(), PI / 2.0, rings, segments).expect("the hemisphere's panels");
    Radiation::new(panels, Point3::origin(), 1000.0, 9.81).expect("a radiation problem")
}
