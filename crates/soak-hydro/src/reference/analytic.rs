//! Closed-form references: spheres, boxes and cylinders, whole and cut by
//! horizontal water.
//!
//! Every shape is centred at the origin in its own frame, matching the
//! `soak_bake::builtin` fixtures; `water_height` is the height (m) of a
//! horizontal water surface `y = water_height` in that frame. Submerged parts
//! follow the [`SubmergedPart`] conventions: second moments about the
//! centroid in the covariance form `∫ (x − c)(x − c)ᵀ dV` (m⁵) and, when
//! nothing is under water, volume 0 with centroid `(0, water_height, 0)`
//! (the plane point nearest the shape's centre).

use std::f64::consts::{FRAC_PI_2, PI};

use nalgebra::{Matrix3, Point3};

use super::mass::{PolyMassProperties, ShellMassProperties};
use super::submerged::SubmergedPart;

fn dry(water_height: f64) -> SubmergedPart {
    SubmergedPart {
        volume: 0.0,
        centroid: Point3::new(0.0, water_height, 0.0),
        second_moment: Matrix3::zeros(),
    }
}

fn diagonal(x: f64, y: f64, z: f64) -> Matrix3<f64> {
    Matrix3::from_diagonal(&nalgebra::Vector3::new(x, y, z))
}

/// Solid sphere of `radius` (m) and `density` (kg/m³):
/// `V = 4/3 π r³`, `I = 2/5 M r²` about every axis.
///
/// # Example
/// ```
/// let s = soak_hydro::reference::analytic::sphere_mass_properties(1.0, 3.0 / (4.0 * std::f64::consts::PI));
/// assert!((s.mass - 1.0).abs() < 1e-15);
/// assert!((s.inertia[(2, 2)] - 0.4).abs() < 1e-15);
/// ```
pub fn sphere_mass_properties(radius: f64, density: f64) -> PolyMassProperties {
    let volume = 4.0 / 3.0 * PI * radius.powi(3);
    let mass = density * volume;
    PolyMassProperties {
        volume,
        mass,
        centroid: Point3::origin(),
        inertia: Matrix3::identity() * (0.4 * mass * radius * radius),
    }
}

/// Thin spherical shell of `radius` (m) and `surface_density` (kg/m²):
/// `A = 4 π r²`, `I = 2/3 M r²` about every axis.
pub fn sphere_shell_mass_properties(radius: f64, surface_density: f64) -> ShellMassProperties {
    let area = 4.0 * PI * radius * radius;
    let mass = surface_density * area;
    ShellMassProperties {
        area,
        mass,
        centroid: Point3::origin(),
        inertia: Matrix3::identity() * (2.0 / 3.0 * mass * radius * radius),
    }
}

/// The part of a sphere of `radius` (m) centred at the origin below the water
/// surface `y = water_height` (m): a spherical cap of submerged height
/// `h = clamp(r + water_height, 0, 2r)`.
///
/// With `u = y + r` the height above the bottom pole, slices are disks of area
/// `π (2 r u − u²)`, so
/// - `V = π h² (3r − h) / 3`,
/// - `∫ u dV = π (2 r h³/3 − h⁴/4)`: centroid `y = −r + ∫u dV / V`, which is
///   `−3 (2r − h)² / (4 (3r − h))` (the classical cap centroid),
/// - `∫ u² dV = π (r h⁴/2 − h⁵/5)`,
/// - `∫ x² dV = ∫ z² dV = (π/4)(4 r² h³/3 − r h⁴ + h⁵/5)`,
///
/// all taken about the pole so that small caps keep their relative accuracy.
///
/// # Example
/// ```
/// use soak_hydro::reference::analytic::sphere_submerged;
///
/// let half = sphere_submerged(0.5, 0.0);
/// assert!((half.volume - std::f64::consts::PI / 12.0).abs() < 1e-15); // 2/3 π r³
/// assert!((half.centroid.y + 3.0 * 0.5 / 8.0).abs() < 1e-15); // −3r/8
/// ```
pub fn sphere_submerged(radius: f64, water_height: f64) -> SubmergedPart {
    let r = radius;
    let h = (r + water_height).clamp(0.0, 2.0 * r);
    if h <= 0.0 {
        return dry(water_height);
    }
    let volume = PI * h * h * (3.0 * r - h) / 3.0;
    let mu = PI * (2.0 * r * h.powi(3) / 3.0 - h.powi(4) / 4.0);
    let muu = PI * (r * h.powi(4) / 2.0 - h.powi(5) / 5.0);
    let mxx = PI / 4.0 * (4.0 * r * r * h.powi(3) / 3.0 - r * h.powi(4) + h.powi(5) / 5.0);
    let u_bar = mu / volume;
    SubmergedPart {
        volume,
        centroid: Point3::new(0.0, u_bar - r, 0.0),
        second_moment: diagonal(mxx, muu - volume * u_bar * u_bar, mxx),
    }
}

/// Volume (m³) the per-triangle game method
/// ([`per_triangle_buoyancy`](super::per_triangle_buoyancy)) reports for an
/// exact sphere of `radius` (m) centred at the origin, water at `y = water_height`.
///
/// Below the equator (`water_height ≤ 0`) every submerged surface element faces
/// down and its column ends at the waterline inside the sphere: the cap volume
/// of [`sphere_submerged`]. Above, the columns over the whole lower hemisphere
/// reach the surface: `2/3 π r³ + π r² w`, an excess of `π w³/3` while the
/// sphere is partly out (`0 < w < r`), and linear growth `π r²` per metre of
/// depth beyond.
pub fn sphere_column_volume(radius: f64, water_height: f64) -> f64 {
    if water_height <= 0.0 {
        sphere_submerged(radius, water_height).volume
    } else {
        PI * radius * radius * (2.0 / 3.0 * radius + water_height)
    }
}

/// Solid axis-aligned box with full sizes `sx, sy, sz` (m) and `density`
/// (kg/m³): `V = sx sy sz`, `I_xx = M (sy² + sz²)/12` and cyclically.
pub fn cuboid_mass_properties(sx: f64, sy: f64, sz: f64, density: f64) -> PolyMassProperties {
    let volume = sx * sy * sz;
    let mass = density * volume;
    PolyMassProperties {
        volume,
        mass,
        centroid: Point3::origin(),
        inertia: diagonal(sy * sy + sz * sz, sx * sx + sz * sz, sx * sx + sy * sy) * (mass / 12.0),
    }
}

/// The part of an axis-aligned box with full sizes `sx, sy, sz` (m), centred at
/// the origin, below `y = water_height` (m): a box of height
/// `h = clamp(water_height + sy/2, 0, sy)`, so `V = sx h sz`, centroid
/// `(0, −sy/2 + h/2, 0)`, second moment `V diag(sx², h², sz²)/12`.
///
/// # Example
/// ```
/// use soak_hydro::reference::analytic::cuboid_submerged;
///
/// let part = cuboid_submerged(4.0, 1.0, 1.0, 0.25);
/// assert_eq!(part.volume, 3.0);
/// assert_eq!(part.centroid.y, -0.125);
/// ```
pub fn cuboid_submerged(sx: f64, sy: f64, sz: f64, water_height: f64) -> SubmergedPart {
    let h = (water_height + sy / 2.0).clamp(0.0, sy);
    if h <= 0.0 {
        return dry(water_height);
    }
    let volume = sx * h * sz;
    SubmergedPart {
        volume,
        centroid: Point3::new(0.0, -sy / 2.0 + h / 2.0, 0.0),
        second_moment: diagonal(sx * sx, h * h, sz * sz) * (volume / 12.0),
    }
}

/// Solid upright cylinder (axis y) of `radius` and `height` (m) and `density`
/// (kg/m³), centred at the origin: `V = π r² H`, `I_yy = M r²/2`,
/// `I_xx = I_zz = M (3 r² + H²)/12`.
pub fn cylinder_mass_properties(radius: f64, height: f64, density: f64) -> PolyMassProperties {
    let r2 = radius * radius;
    let volume = PI * r2 * height;
    let mass = density * volume;
    let side = mass * (3.0 * r2 + height * height) / 12.0;
    PolyMassProperties {
        volume,
        mass,
        centroid: Point3::origin(),
        inertia: diagonal(side, mass * r2 / 2.0, side),
    }
}

/// The part of an upright cylinder (axis y, centred at the origin) of `radius`
/// and `height` (m) below `y = water_height` (m): a cylinder of height
/// `h = clamp(water_height + H/2, 0, H)`, so `V = π r² h`, centroid
/// `(0, −H/2 + h/2, 0)`, second moment `V diag(r²/4, h²/12, r²/4)`.
pub fn cylinder_submerged(radius: f64, height: f64, water_height: f64) -> SubmergedPart {
    let h = (water_height + height / 2.0).clamp(0.0, height);
    if h <= 0.0 {
        return dry(water_height);
    }
    let r2 = radius * radius;
    let volume = PI * r2 * h;
    SubmergedPart {
        volume,
        centroid: Point3::new(0.0, -height / 2.0 + h / 2.0, 0.0),
        second_moment: diagonal(volume * r2 / 4.0, volume * h * h / 12.0, volume * r2 / 4.0),
    }
}

/// The part of a cylinder lying on its side (axis x, centred at the origin) of
/// `radius` and `length` (m) below `y = water_height` (m): a circular segment
/// extruded over the length.
///
/// With `w = clamp(water_height, −r, r)` and `φ = asin(w/r)` (the segment spans
/// `y = r sin ψ`, `ψ ∈ [−π/2, φ]`), per unit length
/// - area `A = r² (φ + π/2) + w √(r² − w²)` (= `r² acos(−w/r) + w √(r² − w²)`),
/// - `∫ y dA = −(2/3)(r² − w²)^{3/2}`,
/// - `∫ y² dA = (r⁴/4)(φ + π/2 − sin 4φ / 4)`,
/// - `∫ z² dA = (2/3) r⁴ (3 (φ + π/2)/8 + sin 2φ / 4 + sin 4φ / 32)`;
///
/// then `V = A L`, centroid `(0, ∫y dA / A, 0)`, second moment
/// `diag(V L²/12, L (∫y² dA − A ȳ²), L ∫z² dA)`. Very thin segments
/// (`h/r ≲ 1e-4`) lose relative accuracy to cancellation in `A`.
pub fn lying_cylinder_submerged(radius: f64, length: f64, water_height: f64) -> SubmergedPart {
    let r = radius;
    if water_height <= -r {
        return dry(water_height);
    }
    let w = water_height.min(r);
    let phi = (w / r).clamp(-1.0, 1.0).asin();
    let span = phi + FRAC_PI_2;
    let chord = (r * r - w * w).max(0.0).sqrt();
    let area = r * r * span + w * chord;
    if area <= 0.0 {
        return dry(water_height);
    }
    let my = -2.0 / 3.0 * chord.powi(3);
    let myy = r.powi(4) / 4.0 * (span - (4.0 * phi).sin() / 4.0);
    let mzz = 2.0 / 3.0 * r.powi(4) * (3.0 * span / 8.0 + (2.0 * phi).sin() / 4.0 + (4.0 * phi).sin() / 32.0);
    let y_bar = my / area;
    let volume = area * length;
    SubmergedPart {
        volume,
        centroid: Point3::new(0.0, y_bar, 0.0),
        second_moment: diagonal(
            volume * length * length / 12.0,
            length * (myy - area * y_bar * y_bar),
            length * mzz,
        ),
    }
}
