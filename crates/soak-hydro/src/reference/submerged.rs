//! The exact submerged part of a closed mesh under planar water.

use nalgebra::{Isometry3, Matrix3, Point3, Vector3};
use serde::{Deserialize, Serialize};
use soak_bake::Mesh;

use super::mass::{reference_point, volume_moments};
use super::moments::{Moments, Piece, clip_triangle, inertia_from_second_moment};
use super::plane::ClipPlane;

/// The part of a body below a water plane, in the world frame.
///
/// Produced exactly from a mesh by [`submerged_part`] and analytically by the
/// `*_submerged` functions of [`analytic`](super::analytic) (object frame =
/// world frame there).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct SubmergedPart {
    /// Submerged volume, m³.
    pub volume: f64,
    /// Centroid of the submerged volume (the centre of buoyancy), world frame, m.
    /// When nothing is submerged: the point of the plane nearest the body
    /// (nearest its bounding-box centre), so it is always finite.
    pub centroid: Point3<f64>,
    /// Second moment of the submerged volume about `centroid`,
    /// `∫ (x − c)(x − c)ᵀ dV`, world axes, m⁵ (the covariance form, not the
    /// inertia form: see [`SubmergedPart::inertia`]).
    pub second_moment: Matrix3<f64>,
}

impl SubmergedPart {
    /// First moment of the submerged volume about the world origin,
    /// `∫ x dV = V c`, m⁴.
    pub fn first_moment(&self) -> Vector3<f64> {
        self.centroid.coords * self.volume
    }

    /// Inertia tensor about `centroid` (kg·m²) of the submerged volume filled
    /// with a fluid of `density` (kg/m³): `ρ (tr C 𝟙 − C)`.
    pub fn inertia(&self, density: f64) -> Matrix3<f64> {
        inertia_from_second_moment(&self.second_moment, density)
    }

    /// Archimedes' force (N) for water of `water_density` (kg/m³) under
    /// gravity `gravity` (m/s², positive) acting against the plane normal:
    /// `ρ g V` along `plane.normal`, applied at `centroid`.
    pub fn buoyancy_force(&self, plane: &ClipPlane, water_density: f64, gravity: f64) -> Vector3<f64> {
        plane.normal.into_inner() * (water_density * gravity * self.volume)
    }
}

/// How a mesh at a pose sits against a plane, in the mesh's object frame.
pub(crate) struct Immersion {
    /// The plane in object coordinates.
    pub local: ClipPlane,
    /// Signed distance of each vertex (negative under water), m.
    pub distances: Vec<f64>,
    /// The point of the (local) plane nearest the bounding-box centre: apex of
    /// every tetrahedron and the dry-body fallback centroid.
    pub apex: Point3<f64>,
    /// The bounding-box centre, object frame.
    pub centre: Point3<f64>,
    /// Some vertex lies strictly under water.
    pub any_wet: bool,
    /// Some vertex lies strictly above water.
    pub any_dry: bool,
}

impl Immersion {
    pub fn new(mesh: &Mesh, pose: &Isometry3<f64>, plane: &ClipPlane) -> Self {
        let local = plane.to_local(pose);
        let distances: Vec<f64> = mesh.positions.iter().map(|p| local.signed_distance(p)).collect();
        let centre = reference_point(mesh);
        // Projecting twice puts the apex on the plane to the rounding of its own
        // coordinates rather than those of the (possibly far) centre.
        let apex = local.project(&local.project(&centre));
        Self {
            apex,
            any_wet: distances.iter().any(|&d| d < 0.0),
            any_dry: distances.iter().any(|&d| d > 0.0),
            local,
            distances,
            centre,
        }
    }

    /// The submerged piece of triangle `t` (object frame).
    #[inline]
    pub fn piece(&self, mesh: &Mesh, t: usize) -> Piece {
        let [a, b, c] = mesh.triangles[t];
        let s = [a, b, c].map(|v| self.distances[v as usize]);
        clip_triangle(&mesh.triangle_points(t), &s)
    }
}

/// Exact volume, centre of buoyancy and second moment of the part of a closed,
/// outward-wound `mesh` (object frame, m) placed at `pose` (object → world)
/// that lies below `plane` (world frame).
///
/// Every triangle is clipped against the plane (a corner under water keeps the
/// triangle, a quad is split into two triangles) and one signed tetrahedron
/// per piece is summed with its apex **on** the plane, at the plane point
/// nearest the mesh's bounding-box centre: the waterline cap then spans
/// zero-volume tetrahedra and need not be built. Vertices exactly on the plane
/// are on the surface; a face lying in the plane adds nothing; crossings are
/// computed identically from both sides of an edge, so the result is
/// continuous in the pose and the water height and never NaN. When every
/// vertex is at or below the surface the whole mesh is summed about its
/// bounding-box centre instead (same result, better rounding far down).
///
/// A dry mesh gives volume 0, a zero second moment and, as centroid, the plane
/// point nearest the mesh's bounding-box centre (world frame).
///
/// # Example
/// ```
/// use nalgebra::{Isometry3, Vector3};
/// use soak_hydro::reference::{ClipPlane, submerged_part};
///
/// // A unit cube centred at y = 0.2, water at y = 0: 0.3 m of it under water.
/// let cube = soak_bake::builtin::cuboid(1.0, 1.0, 1.0);
/// let pose = Isometry3::translation(0.0, 0.2, 0.0);
/// let part = submerged_part(&cube, &pose, &ClipPlane::horizontal(0.0));
/// assert!((part.volume - 0.3).abs() < 1e-12);
/// assert!((part.centroid.y + 0.15).abs() < 1e-12);
/// ```
pub fn submerged_part(mesh: &Mesh, pose: &Isometry3<f64>, plane: &ClipPlane) -> SubmergedPart {
    let im = Immersion::new(mesh, pose, plane);
    let (origin, m) = if !im.any_wet {
        (im.apex, Moments::default())
    } else if !im.any_dry {
        (im.centre, volume_moments(mesh, &im.centre))
    } else {
        let q = im.apex;
        let mut m = Moments::default();
        for t in 0..mesh.triangles.len() {
            for [a, b, c] in im.piece(mesh, t).triangles() {
                m.add_tetrahedron(&(a - q), &(b - q), &(c - q));
            }
        }
        (q, m)
    };
    let (centroid, c) = m.central(&origin, &im.apex);
    let r = pose.rotation.to_rotation_matrix();
    SubmergedPart {
        volume: m.measure,
        centroid: pose * centroid,
        second_moment: r.matrix() * c * r.matrix().transpose(),
    }
}

/// Wetted area, m²: the area of the mesh surface strictly below `plane` when
/// the mesh (object frame) is placed at `pose` (object → world). Faces lying in
/// the plane count as dry.
///
/// # Example
/// ```
/// use nalgebra::Isometry3;
/// use soak_hydro::reference::{ClipPlane, wetted_area};
///
/// let cube = soak_bake::builtin::cuboid(1.0, 1.0, 1.0);
/// let wet = wetted_area(&cube, &Isometry3::identity(), &ClipPlane::horizontal(0.0));
/// assert!((wet - 3.0).abs() < 1e-12); // the bottom and half of four sides
/// ```
pub fn wetted_area(mesh: &Mesh, pose: &Isometry3<f64>, plane: &ClipPlane) -> f64 {
    let im = Immersion::new(mesh, pose, plane);
    if !im.any_wet {
        return 0.0;
    }
    let mut area = 0.0;
    for t in 0..mesh.triangles.len() {
        for [a, b, c] in im.piece(mesh, t).triangles() {
            area += 0.5 * (b - a).cross(&(c - a)).norm();
        }
    }
    area
}
