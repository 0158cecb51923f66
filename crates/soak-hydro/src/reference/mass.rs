//! Exact mass properties of a closed triangle mesh: as a solid and as a thin shell.

use nalgebra::{Isometry3, Matrix3, Point3};
use serde::{Deserialize, Serialize};
use soak_bake::Mesh;

use super::moments::{Moments, inertia_from_second_moment};

/// Mass properties of a solid of uniform density.
///
/// Produced exactly from a mesh by [`solid_mass_properties`] and analytically
/// by the shape functions in [`analytic`](super::analytic).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct PolyMassProperties {
    /// Enclosed volume, m³ (negative for an inside-out mesh).
    pub volume: f64,
    /// Mass, kg: density × volume.
    pub mass: f64,
    /// Centre of mass (the centroid of the volume), m.
    pub centroid: Point3<f64>,
    /// Inertia tensor about `centroid`, kg·m², in the frame of the input.
    pub inertia: Matrix3<f64>,
}

impl PolyMassProperties {
    /// The same body moved by `pose` (object → world): centroid mapped, inertia
    /// rotated as `R I Rᵀ`.
    pub fn transformed(&self, pose: &Isometry3<f64>) -> Self {
        let r = pose.rotation.to_rotation_matrix();
        Self {
            centroid: pose * self.centroid,
            inertia: r.matrix() * self.inertia * r.matrix().transpose(),
            ..*self
        }
    }
}

/// Mass properties of a thin shell: mass spread over the surface with uniform
/// surface density.
///
/// Produced exactly from a mesh by [`shell_mass_properties`] and analytically
/// by [`sphere_shell_mass_properties`](super::analytic::sphere_shell_mass_properties).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct ShellMassProperties {
    /// Surface area, m².
    pub area: f64,
    /// Mass, kg: surface density × area.
    pub mass: f64,
    /// Centre of mass (the centroid of the surface), m.
    pub centroid: Point3<f64>,
    /// Inertia tensor about `centroid`, kg·m², in the frame of the input.
    pub inertia: Matrix3<f64>,
}

impl ShellMassProperties {
    /// The same shell moved by `pose` (object → world).
    pub fn transformed(&self, pose: &Isometry3<f64>) -> Self {
        let r = pose.rotation.to_rotation_matrix();
        Self {
            centroid: pose * self.centroid,
            inertia: r.matrix() * self.inertia * r.matrix().transpose(),
            ..*self
        }
    }
}

/// The centre of the mesh's axis-aligned bounding box, m: the reference point
/// every exact sum is taken about, to avoid cancellation far from the origin.
pub(crate) fn reference_point(mesh: &Mesh) -> Point3<f64> {
    let (lo, hi) = mesh.bounds();
    nalgebra::center(&lo, &hi)
}

/// Volume moments of the whole mesh about `o`: one signed tetrahedron
/// `(o, a, b, c)` per triangle.
pub(crate) fn volume_moments(mesh: &Mesh, o: &Point3<f64>) -> Moments {
    let mut m = Moments::default();
    for t in 0..mesh.triangles.len() {
        let [a, b, c] = mesh.triangle_points(t);
        m.add_tetrahedron(&(a - o), &(b - o), &(c - o));
    }
    m
}

/// Exact mass properties of the solid bounded by a closed, outward-wound mesh
/// with uniform `density` (kg/m³), in the mesh's object frame.
///
/// Sums one signed tetrahedron per triangle, apex at the bounding-box centre,
/// with the closed-form tetrahedron moments `∫x = V s/4`,
/// `∫x xᵀ = V (Σ v vᵀ + s sᵀ)/20` (`s` the sum of the corners relative to the
/// apex); exact up to rounding. The inertia is
/// `ρ (tr C 𝟙 − C)` with `C = ∫ (x − c)(x − c)ᵀ dV`. A mesh enclosing no
/// volume gives zeros and the bounding-box centre as centroid.
///
/// # Example
/// ```
/// use soak_hydro::reference::solid_mass_properties;
///
/// let cube = soak_bake::builtin::cuboid(2.0, 2.0, 2.0);
/// let props = solid_mass_properties(&cube, 1000.0);
/// assert!((props.volume - 8.0).abs() < 1e-12);
/// assert!((props.mass - 8000.0).abs() < 1e-9);
/// // M (b² + c²) / 12 about every axis.
/// assert!((props.inertia[(0, 0)] - 8000.0 * 8.0 / 12.0).abs() < 1e-9);
/// ```
pub fn solid_mass_properties(mesh: &Mesh, density: f64) -> PolyMassProperties {
    let o = reference_point(mesh);
    let m = volume_moments(mesh, &o);
    let (centroid, c) = m.central(&o, &o);
    PolyMassProperties {
        volume: m.measure,
        mass: density * m.measure,
        centroid,
        inertia: inertia_from_second_moment(&c, density),
    }
}

/// Exact mass properties of the mesh's surface as a thin shell of uniform
/// `surface_density` (kg/m²), in the mesh's object frame.
///
/// Sums the closed-form triangle moments `∫x dA = A s/3`,
/// `∫x xᵀ dA = A (Σ v vᵀ + s sᵀ)/12` (`s` the sum of the corners relative to
/// the bounding-box centre); exact up to rounding. The mesh need not be closed.
///
/// # Example
/// ```
/// use soak_hydro::reference::shell_mass_properties;
///
/// let cube = soak_bake::builtin::cuboid(1.0, 1.0, 1.0);
/// let shell = shell_mass_properties(&cube, 2.0);
/// assert!((shell.area - 6.0).abs() < 1e-12);
/// // A cube shell of mass M and side a: I = 5 M a² / 18.
/// assert!((shell.inertia[(1, 1)] - 5.0 * 12.0 / 18.0).abs() < 1e-12);
/// ```
pub fn shell_mass_properties(mesh: &Mesh, surface_density: f64) -> ShellMassProperties {
    let o = reference_point(mesh);
    let mut m = Moments::default();
    for t in 0..mesh.triangles.len() {
        let [a, b, c] = mesh.triangle_points(t);
        m.add_triangle(&(a - o), &(b - o), &(c - o));
    }
    let (centroid, c) = m.central(&o, &o);
    ShellMassProperties {
        area: m.measure,
        mass: surface_density * m.measure,
        centroid,
        inertia: inertia_from_second_moment(&c, surface_density),
    }
}
