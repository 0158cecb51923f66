//! The per-triangle buoyancy games use: water columns over downward faces.
//!
//! This is the method of AQUAS (2020, Unity) that the thesis compares against
//! in its Fig. 7.10, in the style of J. Kerner's "water interaction model for
//! boats": clip the hull triangles at the waterline, and for every submerged
//! piece that faces down push up with the weight of the water column above it.
//! Upward-facing pieces are ignored, so the method is exact for a convex body
//! whose submerged surface all faces down (less than half of a sphere under
//! water) and over-estimates otherwise; fully submerged, its volume keeps
//! growing linearly with depth (by the body's projected area per metre).

use nalgebra::{Isometry3, Point3, Vector3};
use serde::{Deserialize, Serialize};
use soak_bake::Mesh;

use super::plane::ClipPlane;
use super::submerged::Immersion;

/// Result of the per-triangle game method, world frame.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct BaselineBuoyancy {
    /// Total water-column volume the method counts, m³ (what it takes for the
    /// submerged volume).
    pub volume: f64,
    /// Point of application of the total force, world frame, m: the
    /// column-volume-weighted mean of the piece centroids, so the single force
    /// there has the same torque as the per-piece forces. It lies on the hull,
    /// not at the centre of buoyancy. With no column at all: the plane point
    /// nearest the mesh's bounding-box centre.
    pub centre: Point3<f64>,
    /// Total force, N: `ρ g volume` along the plane normal (up).
    pub force: Vector3<f64>,
}

impl BaselineBuoyancy {
    /// Torque of the force about `point` (world frame, m), N·m.
    pub fn torque_about(&self, point: &Point3<f64>) -> Vector3<f64> {
        (self.centre - point).cross(&self.force)
    }
}

/// The per-triangle game method on `mesh` (object frame, m) placed at `pose`
/// (object → world) in water below `plane`, with water density
/// `water_density` (kg/m³) and gravity `gravity` (m/s², positive, acting
/// against the plane normal).
///
/// Triangles are clipped at the waterline exactly as in
/// [`submerged_part`](super::submerged_part) (a quad split into two
/// triangles). A piece with world area vector `A` faces down when
/// `A · n < 0` (`n` the plane normal; `A_y < 0` for horizontal water); it adds
/// the column `(−A · n) d_c` (m³), `d_c` the depth of the piece centroid below
/// the surface, and the force `ρ g (−A · n) d_c n` at its centroid. Depth being
/// affine over a flat piece, the column volume is exact for that piece.
///
/// # Example
/// ```
/// use nalgebra::Isometry3;
/// use soak_hydro::reference::{ClipPlane, per_triangle_buoyancy};
///
/// // A unit cube fully submerged 2 m deep: the bottom face's column is 2.5 m tall,
/// // so the method reports 2.5 m³ where the true volume is 1 m³.
/// let cube = soak_bake::builtin::cuboid(1.0, 1.0, 1.0);
/// let b = per_triangle_buoyancy(&cube, &Isometry3::identity(), &ClipPlane::horizontal(2.0), 1000.0, 9.81);
/// assert!((b.volume - 2.5).abs() < 1e-12);
/// assert!((b.force.y - 1000.0 * 9.81 * 2.5).abs() < 1e-9);
/// ```
pub fn per_triangle_buoyancy(
    mesh: &Mesh,
    pose: &Isometry3<f64>,
    plane: &ClipPlane,
    water_density: f64,
    gravity: f64,
) -> BaselineBuoyancy {
    let im = Immersion::new(mesh, pose, plane);
    let n = im.local.normal;
    let mut volume = 0.0;
    let mut moment = Vector3::zeros();
    if im.any_wet {
        for t in 0..mesh.triangles.len() {
            for [a, b, c] in im.piece(mesh, t).triangles() {
                let down = -0.5 * (b - a).cross(&(c - a)).dot(&n);
                if down <= 0.0 {
                    continue;
                }
                let centroid = Point3::from((a.coords + b.coords + c.coords) / 3.0);
                let depth = im.local.depth(&centroid).max(0.0);
                let column = down * depth;
                volume += column;
                moment += (centroid - im.apex) * column;
            }
        }
    }
    let local_centre = if volume > 0.0 {
        im.apex + moment / volume
    } else {
        im.apex
    };
    BaselineBuoyancy {
        volume,
        centre: pose * local_centre,
        force: plane.normal.into_inner() * (water_density * gravity * volume),
    }
}
