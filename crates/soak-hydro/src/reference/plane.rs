//! The clip plane: planar water as the exact references see it.

use nalgebra::{Isometry3, Point3, Unit, Vector3};
use serde::{Deserialize, Serialize};

/// A plane in world space that splits space into water and air.
///
/// `normal` is a unit vector pointing up, out of the water; the surface is the
/// set of points `p` with `normal · p = offset` (m). A point is **submerged**
/// when `normal · p < offset`; points exactly on the plane are on the surface
/// and count as neither wet nor dry (a face lying in the plane adds nothing).
///
/// # Example
/// ```
/// use nalgebra::Point3;
/// use soak_hydro::reference::ClipPlane;
///
/// let water = ClipPlane::horizontal(0.25);
/// assert_eq!(water.depth(&Point3::new(3.0, -0.75, 1.0)), 1.0);
/// assert!(water.is_submerged(&Point3::new(0.0, 0.0, 0.0)));
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct ClipPlane {
    /// Unit normal pointing out of the water (up), world frame.
    pub normal: Unit<Vector3<f64>>,
    /// Signed distance of the plane from the world origin along `normal`, m.
    pub offset: f64,
}

impl ClipPlane {
    /// The plane `normal · p = offset` (`offset` in m).
    pub fn new(normal: Unit<Vector3<f64>>, offset: f64) -> Self {
        Self { normal, offset }
    }

    /// A horizontal water surface at world height `height` (m), normal +y.
    pub fn horizontal(height: f64) -> Self {
        Self::new(Vector3::y_axis(), height)
    }

    /// The plane through `point` (world, m) with the given upward `normal`.
    pub fn through(point: &Point3<f64>, normal: Unit<Vector3<f64>>) -> Self {
        Self::new(normal, normal.dot(&point.coords))
    }

    /// Signed distance of `p` from the plane, m: negative under water.
    #[inline]
    pub fn signed_distance(&self, p: &Point3<f64>) -> f64 {
        self.normal.dot(&p.coords) - self.offset
    }

    /// Depth of `p` below the surface, m: positive under water, negative above.
    #[inline]
    pub fn depth(&self, p: &Point3<f64>) -> f64 {
        -self.signed_distance(p)
    }

    /// Whether `p` lies strictly below the surface.
    #[inline]
    pub fn is_submerged(&self, p: &Point3<f64>) -> bool {
        self.signed_distance(p) < 0.0
    }

    /// The point of the plane nearest to `p`, m.
    #[inline]
    pub fn project(&self, p: &Point3<f64>) -> Point3<f64> {
        p - self.normal.into_inner() * self.signed_distance(p)
    }

    /// The same plane with water and air swapped: what was dry is now submerged.
    pub fn flipped(&self) -> Self {
        Self::new(-self.normal, -self.offset)
    }

    /// This world-space plane expressed in the object frame of a body at `pose`
    /// (object → world).
    pub fn to_local(&self, pose: &Isometry3<f64>) -> Self {
        let normal = Unit::new_unchecked(pose.rotation.inverse_transform_vector(&self.normal));
        Self::new(normal, self.offset - self.normal.dot(&pose.translation.vector))
    }
}

impl Default for ClipPlane {
    /// Horizontal water at height 0.
    fn default() -> Self {
        Self::horizontal(0.0)
    }
}
