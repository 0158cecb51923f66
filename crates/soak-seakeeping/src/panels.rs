//! The wetted panels of a mesh floating at a pose.

use nalgebra::{Isometry3, Point3};
use soak_bake::Mesh;

use crate::error::SeakeepingError;
use crate::green::Panel;

/// The part of `mesh` (placed by `pose` in the water's frame: y up, still
/// water at y = 0) below the still water plane, as flat panels no larger
/// than `max_size` (m, the longest edge): each triangle clipped by the
/// plane, the part below kept, and split in four at its edges' midpoints
/// until small enough (a quadrilateral left by the clip is cut in two
/// first). The mesh's triangles are counter-clockwise seen from outside,
/// so the panels' normals point into the water.
pub fn wetted_panels(
    mesh: &Mesh,
    pose: &Isometry3<f64>,
    max_size: f64,
) -> Result<Vec<Panel>, SeakeepingError> {
    if !max_size.is_finite() || max_size <= 0.0 {
        return Err(SeakeepingError::BadParameter {
            name: "max_size",
            value: max_size,
        });
    }
    let world: Vec<Point3<f64>> = mesh.positions.iter().map(|p| pose * p).collect();
    if let Some(vertex) = world.iter().position(|p| !p.coords.iter().all(|c| c.is_finite())) {
        return Err(SeakeepingError::BadMesh {
            mesh: mesh.name.clone(),
            vertex,
        });
    }
    let mut panels = Vec::new();
    for (index, triangle) in mesh.triangles.iter().enumerate() {
        if let Some(&vertex) = triangle.iter().find(|&&i| i as usize >= world.len()) {
            return Err(SeakeepingError::BadTriangle {
                mesh: mesh.name.clone(),
                triangle: index,
                vertex: vertex as usize,
            });
        }
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
        // A sliver the plane shaves off a triangle lying along it (a ring
        // of vertices a rounding error below the water) has no area to
        // carry and no plane to project on: dropped.
        let whole = (corners[1] - corners[0]).cross(&(corners[2] - corners[0])).norm();
        let left: f64 = (1..kept.len().saturating_sub(1))
            .map(|k| (kept[k] - kept[0]).cross(&(kept[k + 1] - kept[0])).norm())
            .sum();
        if left <= 1e-6 * whole {
            continue;
        }
        match kept.len() {
            3 => split(&[kept[0], kept[1], kept[2]], max_size, &mut panels),
            4 => {
                split(&[kept[0], kept[1], kept[2]], max_size, &mut panels);
                split(&[kept[0], kept[2], kept[3]], max_size, &mut panels);
            }
            _ => {}
        }
    }
    Ok(panels)
}

/// Splits a triangle in four until its longest edge is at most `max_size`.
fn split(t: &[Point3<f64>; 3], max_size: f64, out: &mut Vec<Panel>) {
    let longest = (0..3).map(|i| (t[(i + 1) % 3] - t[i]).norm()).fold(0.0, f64::max);
    if longest <= max_size {
        if let Some(panel) = Panel::new(t) {
            out.push(panel);
        }
        return;
    }
    let m = |i: usize| {
        let mut p = Point3::from((t[i].coords + t[(i + 1) % 3].coords) / 2.0);
        // Keep the waterline exactly on the plane.
        if t[i].y == 0.0 && t[(i + 1) % 3].y == 0.0 {
            p.y = 0.0;
        }
        p
    };
    let (m0, m1, m2) = (m(0), m(1), m(2));
    split(&[t[0], m0, m2], max_size, out);
    split(&[m0, t[1], m1], max_size, out);
    split(&[m2, m1, t[2]], max_size, out);
    split(&[m0, m1, m2], max_size, out);
}
