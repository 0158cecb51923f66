//! The wetted panels of a mesh floating at a pose.

use nalgebra::{Isometry3, Point3};
use soak_bake::Mesh;

use crate::error::SeakeepingError;
use crate::green::Panel;

/// The part of `mesh` (placed by `pose` in the water's frame: y up, still
/// water at y = 0) below the still water plane, as flat panels no larger
/// than `max_size` (m, the longest edge): each triangle clipped by the
/// plane, the part below kept, and split into `n²` congruent triangles
/// with the fewest `n` that make them small enough (a quadrilateral left
/// by the clip is cut in two first). The mesh's triangles are counter-clockwise seen from outside,
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

/// Splits a triangle into `n²` congruent ones, `n` the fewest that bring
/// its longest edge to at most `max_size` (points on an edge lying in the
/// water plane stay exactly on it).
fn split(t: &[Point3<f64>; 3], max_size: f64, out: &mut Vec<Panel>) {
    let longest = (0..3).map(|i| (t[(i + 1) % 3] - t[i]).norm()).fold(0.0, f64::max);
    let n = (longest / max_size).ceil().clamp(1.0, 4096.0) as usize;
    let on_plane = [
        t[0].y == 0.0 && t[1].y == 0.0,
        t[0].y == 0.0 && t[2].y == 0.0,
        t[1].y == 0.0 && t[2].y == 0.0,
    ];
    let point = |i: usize, j: usize| {
        let (a, b) = (i as f64 / n as f64, j as f64 / n as f64);
        let mut p = Point3::from(t[0].coords + (t[1] - t[0]) * a + (t[2] - t[0]) * b);
        if (j == 0 && on_plane[0]) || (i == 0 && on_plane[1]) || (i + j == n && on_plane[2]) {
            p.y = 0.0;
        }
        p
    };
    for i in 0..n {
        for j in 0..n - i {
            if let Some(panel) = Panel::new(&[point(i, j), point(i + 1, j), point(i, j + 1)])
                && !waterline_strip(&panel)
            {
                out.push(panel);
            }
            if i + j + 1 < n
                && let Some(panel) = Panel::new(&[point(i + 1, j), point(i + 1, j + 1), point(i, j + 1)])
                && !waterline_strip(&panel)
            {
                out.push(panel);
            }
        }
    }
}

/// Whether `panel` is a strip along the water-plane thinner than a
/// twentieth of its length: what the clip leaves of a triangle with a
/// corner just under the water (a vertex a millimetre below the surface
/// of a metre-long hull). Its collocation point lies so close to its own
/// image in the surface that, against the rigid lid of infinite
/// frequency, its row of the system is all but singular: its potential
/// came out hundreds of times too large, and the added mass it carried
/// broke the matrix's symmetry (a boat's sway–heave term 1,600 kg one
/// way, 2 kg the other). Its area, under 2.5 % of its length squared, is
/// left out.
fn waterline_strip(panel: &Panel) -> bool {
    let v = &panel.vertices;
    let longest = (0..v.len())
        .map(|k| (v[(k + 1) % v.len()] - v[k]).norm())
        .fold(0.0, f64::max);
    let touches = v.iter().any(|p| p.y.abs() <= 1e-12 * longest);
    let depth = v.iter().map(|p| -p.y).fold(0.0, f64::max);
    touches && depth < 0.05 * longest
}

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::Point3;

    /// One upright triangle, a metre along the water, its lower edge
    /// `depth` (m) under it.
    fn triangle(depth: f64) -> Mesh {
        Mesh::new(
            "triangle".to_string(),
            vec![
                Point3::new(0.0, -depth, 0.0),
                Point3::new(1.0, -depth, 0.0),
                Point3::new(0.5, 0.5, 0.0),
            ],
            None,
            vec![[0, 1, 2]],
        )
    }

    #[test]
    fn a_strip_the_water_plane_leaves_along_a_shallow_edge_is_left_out() {
        // 1 mm deep and a metre long: a strip, dropped.
        let strip = wetted_panels(&triangle(0.001), &Isometry3::identity(), 10.0).unwrap();
        assert!(strip.is_empty(), "{} panels", strip.len());
        // 20 cm deep: kept whole (two panels of the clipped quadrilateral).
        let kept = wetted_panels(&triangle(0.2), &Isometry3::identity(), 10.0).unwrap();
        assert_eq!(kept.len(), 2);
        let area: f64 = kept.iter().map(|p| p.area).sum();
        // The trapezoid under the water: 0.2 m deep, 1 m and 0.8286 m wide.
        let top = 1.0 - 0.2 / 0.7;
        assert!((area - 0.2 * (1.0 + top) / 2.0).abs() < 1e-12, "{area}");
    }
}
