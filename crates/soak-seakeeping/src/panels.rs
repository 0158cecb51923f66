//! The wetted panels of a mesh floating at a pose.

use nalgebra::{Isometry3, Point3};
use soak_bake::Mesh;

use crate::green::Panel;

/// The part of `mesh` (placed by `pose` in the water's frame: y up, still
/// water at y = 0) below the still water plane, as flat panels: each
/// triangle clipped by the plane (a triangle or a quadrilateral kept).
/// The mesh's triangles are counter-clockwise seen from outside, so the
/// panels' normals point into the water.
pub fn wetted_panels(mesh: &Mesh, pose: &Isometry3<f64>) -> Vec<Panel> {
    let world: Vec<Point3<f64>> = mesh.positions.iter().map(|p| pose * p).collect();
    let mut panels = Vec::new();
    for triangle in &mesh.triangles {
        let corners = triangle.map(|i| world[i as usize]);
        let mut kept: Vec<Point3<f64>> = Vec::with_capacity(4);
        for i in 0..3 {
            let a = corners[i];
            let b = corners[(i + 1) % 3];
            if a.y <= 0.0 {
                kept.push(a);
            }
            if (a.y < 0.0 && b.y > 0.0) || (a.y > 0.0 && b.y < 0.0) {
                let t = a.y / (a.y - b.y);
                let mut crossing = a + (b - a) * t;
                crossing.y = 0.0;
                kept.push(crossing);
            }
        }
        if let Some(panel) = Panel::new(&kept) {
            panels.push(panel);
        }
    }
    panels
}
