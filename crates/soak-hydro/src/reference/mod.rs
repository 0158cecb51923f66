//! Exact references every texel result is measured against.
//!
//! All in f64, all exact up to rounding for planar water, O(triangles):
//!
//! - [`ClipPlane`]: planar water, `normal · p < offset` under water.
//! - [`solid_mass_properties`] / [`shell_mass_properties`]: volume (or area),
//!   centroid and inertia of a closed mesh as a uniform solid or thin shell,
//!   from signed tetrahedra (triangles) with closed-form second moments.
//! - [`submerged_part`] / [`wetted_area`]: the exact part of a mesh at a pose
//!   below a plane (volume, centre of buoyancy, second moment), by clipping
//!   triangles and summing tetrahedra whose apex lies on the plane.
//! - [`per_triangle_buoyancy`]: the water-column method games use (AQUAS,
//!   Kerner), the baseline of the thesis' Fig. 7.10, with its known bias.
//! - [`analytic`]: closed forms for spheres, boxes and cylinders, whole and
//!   cut by horizontal water.
//!
//! Conventions: meshes are closed and wound counter-clockwise seen from
//! outside, in object space (m), y up; a pose maps object to world
//! (`nalgebra::Isometry3`); second moments are the covariance form
//! `∫ (x − c)(x − c)ᵀ dV` (m⁵) and inertia tensors `ρ (tr C 𝟙 − C)` (kg·m²),
//! both about the centroid.
//!
//! # Example
//! ```
//! use nalgebra::Isometry3;
//! use soak_hydro::reference::{ClipPlane, analytic, submerged_part};
//!
//! let ball = soak_bake::builtin::sphere(0.5, 128, 64);
//! let exact = submerged_part(&ball, &Isometry3::identity(), &ClipPlane::horizontal(0.1));
//! let smooth = analytic::sphere_submerged(0.5, 0.1);
//! // The polyhedral sphere is inscribed: slightly smaller, and converging.
//! assert!(exact.volume < smooth.volume);
//! assert!((exact.volume - smooth.volume).abs() < 1e-3 * smooth.volume);
//! ```

pub mod analytic;
mod baseline;
mod mass;
mod moments;
mod plane;
mod submerged;

pub use baseline::{BaselineBuoyancy, per_triangle_buoyancy};
pub use mass::{PolyMassProperties, ShellMassProperties, shell_mass_properties, solid_mass_properties};
pub use plane::ClipPlane;
pub use submerged::{SubmergedPart, submerged_part, wetted_area};
