//! The wetted panels of a mesh floating at a pose.

use nalgebra::{Isometry3, Point3};
use soak_bake::Mesh;

use crate::error::SeakeepingError;
use crate::green::Panel;

/// The part of `mesh` (placed by `pose` in the water's frame: y up, still
/// water at y = 0) below the still water plane, as flat panels no larger
/// than `max_size` (m, the longest edge): each triangle clipped by the
/// plane, the part below kept, and its longest edge halved until every
/// edge is short enough (a quadrilateral left by the clip is cut in two
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

/// Splits a triangle by halving its longest edge, again and again, until
/// no edge is longer than `max_size` (points on an edge lying in the
/// water plane stay exactly on it). Halving keeps a triangle's shape
/// within a few classes (a right triangle's quarters are like it), so a
/// long thin triangle (a hull's strip from bow to stern) gives panels
/// about as thin as itself; what the halving bounds is their longest
/// edge, which sets the shortest wave they resolve.
fn split(t: &[Point3<f64>; 3], max_size: f64, out: &mut Vec<Panel>) {
    let mut pending = vec![(*t, 0u32)];
    while let Some((t, depth)) = pending.pop() {
        let edge = |i: usize| (t[(i + 1) % 3] - t[i]).norm();
        let k = (0..3).fold(0, |k, i| if edge(i) > edge(k) { i } else { k });
        // 2²⁴ pieces at most from one triangle, as `n` ≤ 4096 bounded them.
        if edge(k) <= max_size || depth >= 24 {
            if let Some(panel) = Panel::new(&t)
                && !waterline_strip(&panel)
                && !needle(&panel, edge(k))
            {
                out.push(panel);
            }
            continue;
        }
        let (a, b, c) = (t[k], t[(k + 1) % 3], t[(k + 2) % 3]);
        let mut middle = Point3::from((a.coords + b.coords) * 0.5);
        if a.y == 0.0 && b.y == 0.0 {
            middle.y = 0.0;
        }
        pending.push(([a, middle, c], depth + 1));
        pending.push(([middle, b, c], depth + 1));
    }
}

/// Whether `panel`, whose longest edge is `longest` (m), is a needle:
/// an area under a millionth of its longest edge squared (a millionth
/// as wide as long). What the clip and the halving leave of a triangle
/// cut a rounding error from one of its corners; its normal is the
/// rounding error's direction, its area nothing against the hull's.
fn needle(panel: &Panel, longest: f64) -> bool {
    panel.area < 1e-6 * longest * longest
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

    #[test]
    fn a_kilometre_sliver_a_kilometre_away_keeps_its_waterline_on_the_water() {
        // A hull's side a kilometre long and 3 m deep, leaning 1e-4 out of
        // the vertical, placed a kilometre from the origin: halved into
        // panels 20 m long, each as thin as a rounding error allows.
        let (x, z) = (1.0e3, 2.0e3);
        let mesh = Mesh::new(
            "side".to_string(),
            vec![
                Point3::new(x, -3.0, z),
                Point3::new(x + 1.0e3, -3.0, z + 3.0e-4),
                Point3::new(x + 1.0e3, 1.0, z - 1.0e-4),
                Point3::new(x, 1.0, z - 1.0e-4),
            ],
            None,
            vec![[0, 1, 2], [0, 2, 3]],
        );
        let panels = wetted_panels(&mesh, &Isometry3::identity(), 20.0).unwrap();
        assert!(panels.len() > 100, "{} panels", panels.len());
        for (i, panel) in panels.iter().enumerate() {
            let highest = panel.vertices.iter().map(|v| v.y).fold(f64::MIN, f64::max);
            assert!(highest <= 0.0, "panel {i} reaches {highest} m above the water");
            assert!(
                panel.area >= 1e-6 * 20.0 * 20.0 * 1e-3,
                "panel {i}: {}",
                panel.area
            );
            // Every panel's normal is the side's (to its thinness' rounding).
            assert!(panel.normal.z.abs() > 1.0 - 1e-6, "panel {i}: {}", panel.normal);
        }
        // Less the strips along the waterline (a twentieth as deep as
        // long: see `waterline_strip`).
        let area: f64 = panels.iter().map(|p| p.area).sum();
        assert!(area <= 3.0e3 && area > 0.9 * 3.0e3, "{area}");
    }
}
