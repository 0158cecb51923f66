//! Added mass: the inertia of the water a body must set moving when it
//! accelerates, from the body's equivalent ellipsoid and Lamb's
//! coefficients.
//!
//! A body accelerating through still water drags a mass of water with it:
//! the force the water opposes to an acceleration `a` is `−M_a a`, with
//! `M_a` the added-mass tensor (potential flow; Lamb, *Hydrodynamics*,
//! §373). A sphere's is `½ ρ V` in every direction, so a bubble released
//! from rest rises at no more than `2 g`. For an ellipsoid of semi-axes
//! `a, b, c` the tensor is diagonal in its axes, with
//!
//! - along `x`: `m_x = α₀/(2 − α₀) · ρ V`,
//! - about `x`: `I_x = (1/5) ρ V (b² − c²)² (γ₀ − β₀) / (2 (b² − c²) + (b² + c²)(β₀ − γ₀))`,
//!
//! and likewise for `y` and `z`, where `α₀ = abc ∫₀^∞ dλ / ((a² + λ) Δ)`,
//! `Δ = √((a² + λ)(b² + λ)(c² + λ))`, and `β₀`, `γ₀` the same with `b`,
//! `c` (`α₀ + β₀ + γ₀ = 2`). In Carlson's form `α₀ = (2/3) abc R_D(b², c², a²)`.
//!
//! Any other closed body is given the tensor of its **equivalent
//! ellipsoid**: the ellipsoid with the same centroid and the same second
//! moments of volume (axes the principal axes of the central second moment
//! `S = ∫ (x − c)(x − c)ᵀ dV`, semi-axes `√(5 λᵢ / V)`: a solid
//! ellipsoid's central second moment is `V diag(a², b², c²)/5`), with its
//! own volume `4/3 π abc`. For a sphere or an ellipsoid the result is
//! theirs up to the meshing; for a cube of side `s` it is `0.562 ρ s³` in
//! every direction against the `0.67 ρ s³` tabulated for a cube (DNV-RP-C205,
//! table A-2), 16 % low, and no rotational added inertia (a cube's is
//! small but not nil). See [`AddedMass::equivalent_ellipsoid`].

use nalgebra::{Matrix3, UnitQuaternion, Vector3};
use serde::{Deserialize, Serialize};
use soak_bake::Atlas;

use crate::error::HydroError;
use crate::mass::{VolumeMoments, volume_moments};

/// Lamb's coefficients `[α₀, β₀, γ₀]` of an ellipsoid of semi-axes `a`,
/// `b`, `c` (m; each finite and > 0): `α₀ = abc ∫₀^∞ dλ / ((a² + λ) Δ)`,
/// `Δ = √((a² + λ)(b² + λ)(c² + λ))`, through Carlson's `R_D`. They sum to
/// 2; a sphere's are `2/3` each.
///
/// # Errors
/// [`HydroError::AddedMass`] when a semi-axis is not finite and > 0.
pub fn lamb_coefficients(a: f64, b: f64, c: f64) -> Result<[f64; 3], HydroError> {
    for (axis, s) in [a, b, c].into_iter().enumerate() {
        if !(s.is_finite() && s > 0.0) {
            return Err(HydroError::AddedMass {
                reason: format!("semi-axis {axis} of the ellipsoid is {s} m (must be finite and > 0)"),
            });
        }
    }
    let (a2, b2, c2) = (a * a, b * b, c * c);
    let rd = |x: f64, y: f64, z: f64| {
        ellip::elliprd(x, y, z).map_err(|e| HydroError::AddedMass {
            reason: format!("Carlson's R_D({x}, {y}, {z}): {e}"),
        })
    };
    let k = 2.0 / 3.0 * a * b * c;
    Ok([k * rd(b2, c2, a2)?, k * rd(c2, a2, b2)?, k * rd(a2, b2, c2)?])
}

/// A body's added mass when wholly submerged, in its own axes, per unit
/// density of the fluid: multiply by the fluid's density (kg/m³) for kg
/// and kg·m². Scaled by the submerged fraction `V_s / volume` at each step
/// ([`AddedMass::scaled`]).
///
/// The translational part acts at the equivalent ellipsoid's centre, the
/// rotational part about it; the generator takes both about the body's
/// centre of mass and leaves out the coupling between translation and
/// rotation that the offset between the two would bring.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct AddedMass {
    /// Translational added volume, object axes, m³ (× ρ = kg).
    pub translation: Matrix3<f64>,
    /// Rotational added moment of volume, object axes, m⁵ (× ρ = kg·m²).
    pub rotation: Matrix3<f64>,
    /// The enclosed volume the submerged fraction is taken of, m³.
    pub volume: f64,
}

/// The ellipsoid a body's added mass was taken from.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct EquivalentEllipsoid {
    /// Semi-axes, m, along the columns of `axes`.
    pub semi_axes: Vector3<f64>,
    /// Its axes (orthonormal columns), object frame.
    pub axes: Matrix3<f64>,
    /// Translational added-mass coefficients `k = α₀/(2 − α₀)` along each
    /// axis: the added mass over `ρ 4/3 π abc`.
    pub coefficients: Vector3<f64>,
}

impl AddedMass {
    /// The added mass of an ellipsoid of `semi_axes` (m) along the columns
    /// of `axes` (orthonormal, object frame), with its submerged fraction
    /// taken of `volume` (m³; the body's enclosed volume).
    ///
    /// # Errors
    /// [`HydroError::AddedMass`] for a semi-axis or volume not finite and
    /// > 0.
    pub fn ellipsoid(
        semi_axes: Vector3<f64>,
        axes: Matrix3<f64>,
        volume: f64,
    ) -> Result<(Self, EquivalentEllipsoid), HydroError> {
        if !(volume.is_finite() && volume > 0.0) {
            return Err(HydroError::AddedMass {
                reason: format!("the body's enclosed volume is {volume} m³ (must be finite and > 0)"),
            });
        }
        let [a, b, c] = [semi_axes.x, semi_axes.y, semi_axes.z];
        let [alpha, beta, gamma] = lamb_coefficients(a, b, c)?;
        let v = 4.0 / 3.0 * std::f64::consts::PI * a * b * c;
        let k = Vector3::new(alpha, beta, gamma).map(|l| l / (2.0 - l));
        // About x: (1/5) V (b² − c²)² (γ₀ − β₀) / (2 (b² − c²) + (b² + c²)(β₀ − γ₀)),
        // which tends to 0 as b → c (no added inertia about an axis of symmetry).
        let turn = |p: f64, q: f64, lp: f64, lq: f64| {
            let d = p * p - q * q;
            if d.abs() <= 1e-12 * (p * p + q * q) {
                return 0.0;
            }
            0.2 * v * d * d * (lq - lp) / (2.0 * d + (p * p + q * q) * (lp - lq))
        };
        let j = Vector3::new(
            turn(b, c, beta, gamma),
            turn(c, a, gamma, alpha),
            turn(a, b, alpha, beta),
        );
        let rotate = |d: Vector3<f64>| axes * Matrix3::from_diagonal(&d) * axes.transpose();
        Ok((
            Self {
                translation: rotate(k * v),
                rotation: rotate(j),
                volume,
            },
            EquivalentEllipsoid {
                semi_axes,
                axes,
                coefficients: k,
            },
        ))
    }

    /// The added mass of the ellipsoid with the volume moments' centroid
    /// and central second moment (see [`lamb_coefficients`] and the crate's README for the shapes it is right for), for a body
    /// of their volume.
    ///
    /// # Errors
    /// [`HydroError::AddedMass`] for a volume not > 0 (an open mesh not
    /// capped) or a second moment with an axis of no extent (a flat body).
    pub fn equivalent_ellipsoid(moments: &VolumeMoments) -> Result<(Self, EquivalentEllipsoid), HydroError> {
        let v = moments.volume;
        if !(v.is_finite() && v > 0.0) {
            return Err(HydroError::AddedMass {
                reason: format!("the body encloses {v} m³ (a closed mesh, or an open one capped, is needed)"),
            });
        }
        let central = moments.second - moments.first * moments.first.transpose() / v;
        let eigen = central.symmetric_eigen();
        let mut semi = Vector3::zeros();
        for i in 0..3 {
            let l = eigen.eigenvalues[i];
            if !(l.is_finite() && l > 0.0) {
                return Err(HydroError::AddedMass {
                    reason: format!(
                        "the body's second moment of volume has no extent along an axis ({l} m⁵)"
                    ),
                });
            }
            semi[i] = (5.0 * l / v).sqrt();
        }
        Self::ellipsoid(semi, eigen.eigenvectors, v)
    }

    /// The equivalent ellipsoid's added mass of an atlas' enclosed volume
    /// ([`AddedMass::equivalent_ellipsoid`] of its [`volume_moments`]).
    ///
    /// # Errors
    /// As [`AddedMass::equivalent_ellipsoid`].
    pub fn of_atlas(atlas: &Atlas) -> Result<Self, HydroError> {
        Self::equivalent_ellipsoid(&volume_moments(atlas)).map(|(a, _)| a)
    }

    /// The submerged fraction `V_s / volume`, in `[0, 1]`.
    pub fn fraction(&self, submerged_volume: f64) -> f64 {
        if self.volume > 0.0 && submerged_volume > 0.0 {
            (submerged_volume / self.volume).min(1.0)
        } else {
            0.0
        }
    }

    /// Translational (world axes, kg) and rotational (object axes, kg·m²)
    /// added mass of the body turned by `rotation` in a fluid of `density`
    /// (kg/m³) with `submerged_volume` (m³) under water.
    pub fn scaled(
        &self,
        rotation: &UnitQuaternion<f64>,
        density: f64,
        submerged_volume: f64,
    ) -> (Matrix3<f64>, Matrix3<f64>) {
        let s = density * self.fraction(submerged_volume);
        let r = rotation.to_rotation_matrix().into_inner();
        (r * (self.translation * s) * r.transpose(), self.rotation * s)
    }

    /// Whether every entry is finite and the volume > 0.
    pub fn is_valid(&self) -> bool {
        self.volume.is_finite()
            && self.volume > 0.0
            && self
                .translation
                .iter()
                .chain(self.rotation.iter())
                .all(|x| x.is_finite())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Prolate spheroids of axis ratio `a/b` (eccentricity
    /// `e = √(1 − b²/a²)`) against the closed forms (Lamb, Hydrodynamics,
    /// §373; Newman, Marine Hydrodynamics, §4.13), which take the
    /// logarithm route rather than Carlson's: `α₀ = 2 (1 − e²)/e³ · (½ ln((1 + e)/(1 − e)) − e)`,
    /// `β₀ = 1/e² − (1 − e²)/(2 e³) ln((1 + e)/(1 − e))`, `k₁ = α₀/(2 − α₀)`
    /// along the axis, `k₂ = β₀/(2 − β₀)` across, and the rotational
    /// coefficient about a transverse axis (added inertia over the
    /// displaced fluid's `ρ V (a² + b²)/5`)
    /// `k' = e⁴ (β₀ − α₀) / ((2 − e²)(2 e² − (2 − e²)(β₀ − α₀)))`.
    /// At `a/b = 2` they are Lamb's tabulated 0.210, 0.704, 0.240.
    #[test]
    fn lamb_coefficients_match_the_closed_forms_for_prolate_spheroids() {
        for ratio in [1.2f64, 2.0, 4.0, 10.0] {
            let e: f64 = (1.0 - 1.0 / (ratio * ratio)).sqrt();
            let log = ((1.0 + e) / (1.0 - e)).ln();
            let alpha = 2.0 * (1.0 - e * e) / e.powi(3) * (0.5 * log - e);
            let beta = 1.0 / (e * e) - (1.0 - e * e) / (2.0 * e.powi(3)) * log;
            let (k1, k2) = (alpha / (2.0 - alpha), beta / (2.0 - beta));
            let e2 = e * e;
            let kr = e2 * e2 * (beta - alpha) / ((2.0 - e2) * (2.0 * e2 - (2.0 - e2) * (beta - alpha)));
            let (added, ell) =
                AddedMass::ellipsoid(Vector3::new(ratio, 1.0, 1.0), Matrix3::identity(), 1.0).unwrap();
            let v = 4.0 / 3.0 * std::f64::consts::PI * ratio;
            let close = |got: f64, want: f64, what: &str| {
                assert!(
                    (got - want).abs() <= 1e-9 * want.abs().max(1e-3),
                    "a/b {ratio}: {what} {got} vs {want}"
                );
            };
            close(ell.coefficients.x, k1, "k1");
            close(ell.coefficients.y, k2, "k2");
            close(added.translation[(2, 2)] / v, k2, "k3");
            close(
                added.rotation[(1, 1)] / (v * (ratio * ratio + 1.0) / 5.0),
                kr,
                "k'",
            );
            // No added inertia about the axis of symmetry.
            assert_eq!(added.rotation[(0, 0)], 0.0);
            let [a, b, c] = lamb_coefficients(ratio, 1.0, 1.0).unwrap();
            assert!((a + b + c - 2.0).abs() < 1e-12);
            if ratio == 2.0 {
                for (got, table) in [(k1, 0.210), (k2, 0.704), (kr, 0.240)] {
                    assert!((got - table).abs() < 6e-4, "Lamb's table {table}, {got}");
                }
            }
        }
        // A sphere: ½ along every axis, no rotational added inertia.
        let (added, ell) =
            AddedMass::ellipsoid(Vector3::new(1.0, 1.0, 1.0), Matrix3::identity(), 1.0).unwrap();
        assert!((ell.coefficients - Vector3::repeat(0.5)).norm() < 1e-12);
        assert_eq!(added.rotation, Matrix3::zeros());
    }

    #[test]
    fn bad_axes_and_volumes_are_typed_errors() {
        assert!(matches!(
            lamb_coefficients(1.0, 0.0, 1.0),
            Err(HydroError::AddedMass { .. })
        ));
        assert!(matches!(
            lamb_coefficients(f64::NAN, 1.0, 1.0),
            Err(HydroError::AddedMass { .. })
        ));
        assert!(AddedMass::ellipsoid(Vector3::new(1.0, 1.0, 1.0), Matrix3::identity(), 0.0).is_err());
    }
}
