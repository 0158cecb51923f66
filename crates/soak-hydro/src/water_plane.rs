//! The water-plane of a body: the horizontal projection of where the
//! water's surface cuts it ([`water_plane`]), and the added mass of that
//! cut as a flat plate on a free surface ([`WaterPlane::plate_added_mass`]),
//! the added mass that grows as a body enters the water (slamming).
//!
//! The cut is never built: for any `φ(x, z)` the field `(0, φ, 0)` has no
//! divergence, so over the part of the body under the surface and the
//! patch of surface inside it, `∮ φ n_y dA = 0`, and the patch's
//! `∫ φ n_y dA` is `∫ φ dx dz` over its horizontal projection. Hence the
//! projection's area and moments are sums over the submerged texels:
//! `A = Σ −A_y`, `∫ x dA = Σ −A_y x`, `∫ x² dA = Σ −A_y x²`, … (`A_y` the
//! vertical part of a texel's outward area vector), exact under calm water
//! and under a surface that is a height field.

use nalgebra::{Matrix2, Point3, Vector2};
use serde::Serialize;
use soak_bake::Atlas;

use crate::error::HydroError;
use crate::hydrostatics::body_state::BodyState;
use crate::hydrostatics::frame::texel;
use crate::water::Water;

/// The horizontal projection of the region where the water's surface cuts
/// a body, world frame.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize)]
pub struct WaterPlane {
    /// Area, m² (0 for a body dry or wholly under water).
    pub area: f64,
    /// Centroid `(x, z)`, world, m (the body's origin when the area is 0).
    pub centroid: Vector2<f64>,
    /// Second moment about the centroid, `∫ (x − c)(x − c)ᵀ dA` over
    /// `(x, z)`, m⁴.
    pub second: Matrix2<f64>,
    /// The mean height of the surface over the cut, m (the area-weighted
    /// height of the submerged texels' surface points).
    pub height: f64,
}

/// The water-plane of the body `atlas` at `state` in `water` at time `t`:
/// one pass over the texels. The cut is never built: for any `φ(x, z)` the
/// field `(0, φ, 0)` has no divergence, so the projection's area and
/// moments are sums over the submerged texels, `A = Σ −A_y`,
/// `∫ x dA = Σ −A_y x`, `∫ x² dA = Σ −A_y x²`, … (`A_y` the vertical part of
/// a texel's outward area vector), exact under calm water and under a
/// surface that is a height field.
///
/// # Errors
/// [`HydroError::NonFiniteState`] for a pose that is not finite.
pub fn water_plane(
    atlas: &Atlas,
    water: &Water,
    state: &BodyState,
    t: f64,
) -> Result<WaterPlane, HydroError> {
    state.check()?;
    let rot = state.pose.rotation.to_rotation_matrix().into_inner();
    let ow = (state.pose * atlas.origin()).coords;
    // Sums of w, w x, w z, w x², w x z, w z², w h with w = −A_y.
    let mut s = [0.0f64; 7];
    for i in 0..atlas.len() {
        let (x, a) = texel(atlas, i);
        let p = rot * x + ow;
        let depth = water.surface.depth(&Point3::from(p), t);
        // Dry (or a depth that is not a number): not under the cut.
        if depth.is_nan() || depth <= 0.0 {
            continue;
        }
        let w = -(rot * a).y;
        s[0] += w;
        s[1] += w * p.x;
        s[2] += w * p.z;
        s[3] += w * p.x * p.x;
        s[4] += w * p.x * p.z;
        s[5] += w * p.z * p.z;
        s[6] += w * (p.y + depth);
    }
    let area = s[0];
    // Sums of texels on opposite sides cancel to the texels' rounding when
    // the body is dry or wholly under: a cut of no area.
    if area.is_nan() || area <= 1e-9 * atlas.area() {
        return Ok(WaterPlane {
            centroid: Vector2::new(ow.x, ow.z),
            height: ow.y,
            ..WaterPlane::default()
        });
    }
    let c = Vector2::new(s[1] / area, s[2] / area);
    let xx = s[3] - area * c.x * c.x;
    let xz = s[4] - area * c.x * c.y;
    let zz = s[5] - area * c.y * c.y;
    Ok(WaterPlane {
        area,
        centroid: c,
        second: Matrix2::new(xx, xz, xz, zz),
        height: s[6] / area,
    })
}

impl WaterPlane {
    /// The semi-axes `(a, b)`, `a ≥ b` (m), of the ellipse with the cut's
    /// second moments (an ellipse's are `π a³ b/4` and `π a b³/4` about its
    /// axes), or `None` for a cut of no area or no width.
    pub fn ellipse(&self) -> Option<(f64, f64)> {
        let eigen = self.second.symmetric_eigen();
        let (l1, l2) = (eigen.eigenvalues.max(), eigen.eigenvalues.min());
        if !(self.area > 0.0 && l2 > 0.0 && l1.is_finite()) {
            return None;
        }
        // λ₁ λ₂ = π² (ab)⁴/16, λ₁ = π a² (ab)/4.
        let ab = 2.0 * (l1 * l2).sqrt().sqrt() / std::f64::consts::PI.sqrt();
        let a = (4.0 * l1 / (std::f64::consts::PI * ab)).sqrt();
        let b = (4.0 * l2 / (std::f64::consts::PI * ab)).sqrt();
        Some((a, b))
    }

    /// The added mass (kg) of the cut as a flat plate moving across a free
    /// surface in a fluid of `density` (kg/m³): half that of the elliptic
    /// plate with the cut's second moments in an unbounded fluid,
    /// `(2/3) π ρ a b² / E(e)`, `E` the complete elliptic integral of the
    /// second kind of the eccentricity `e² = 1 − b²/a²` (a disc of radius
    /// `r`: `(4/3) ρ r³`; a long strip of half-width `c`, per length:
    /// `½ π ρ c²`, von Kármán's). Zero for a cut of no area or width.
    pub fn plate_added_mass(&self, density: f64) -> f64 {
        let Some((a, b)) = self.ellipse() else {
            return 0.0;
        };
        let m = (1.0 - (b * b) / (a * a)).clamp(0.0, 1.0);
        match ellip::ellipe(m) {
            Ok(e) if e > 0.0 => 2.0 / 3.0 * std::f64::consts::PI * density * a * b * b / e,
            _ => 0.0,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn plate(second: Matrix2<f64>, area: f64) -> WaterPlane {
        WaterPlane {
            area,
            second,
            ..WaterPlane::default()
        }
    }

    /// A disc of radius r: `(4/3) ρ r³` (half of Lamb's `(8/3) ρ r³`); a
    /// long ellipse tends to von Kármán's strip, `½ π ρ b²` per length
    /// averaged over the ellipse's widths `b √(1 − x²/a²)`: `(2/3)·½ π ρ b² · 2a`.
    #[test]
    fn plates_have_their_added_masses() {
        let r: f64 = 0.7;
        let pi = std::f64::consts::PI;
        let disc = plate(Matrix2::identity() * (pi * r.powi(4) / 4.0), pi * r * r);
        let (a, b) = disc.ellipse().unwrap();
        assert!((a - r).abs() < 1e-12 && (b - r).abs() < 1e-12);
        let m = disc.plate_added_mass(1000.0);
        assert!((m / (4.0 / 3.0 * 1000.0 * r.powi(3)) - 1.0).abs() < 1e-12, "{m}");
        let (a, b): (f64, f64) = (50.0, 0.5);
        let long = plate(
            Matrix2::new(pi * a.powi(3) * b / 4.0, 0.0, 0.0, pi * a * b.powi(3) / 4.0),
            pi * a * b,
        );
        let strip = 2.0 / 3.0 * 0.5 * pi * 1000.0 * b * b * 2.0 * a;
        let m = long.plate_added_mass(1000.0);
        assert!((m / strip - 1.0).abs() < 2e-3, "{m} vs {strip}");
        assert_eq!(plate(Matrix2::zeros(), 0.0).plate_added_mass(1000.0), 0.0);
    }
}
