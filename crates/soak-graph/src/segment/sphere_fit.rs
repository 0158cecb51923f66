//! Least-squares spheres through weighted point sets.
//!
//! [`fit_sphere`] is the algebraic (Kåsa) fit: it minimises
//! `Σ wᵢ (|pᵢ − c|² − r²)²`, which is linear in `(c, r² − |c|²)` and so has a
//! closed form; points are centred and scaled first for conditioning.
//! [`fit_radius`] fits only the radius about a given centre (the thesis'
//! node sphere, "centrada en el centro geométrico de la sub-malla").

use nalgebra::{Matrix4, Point3, Vector3, Vector4};
use serde::Serialize;

/// Singular values below this fraction of the largest make the fit
/// degenerate (coplanar or collinear points).
pub const RANK_TOLERANCE: f64 = 1e-9;

/// A sphere in object space.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Sphere {
    /// Centre, m.
    pub centre: Point3<f64>,
    /// Radius, m.
    pub radius: f64,
}

/// The weighted mean of `points` (weights ≥ 0, not all zero), m.
pub fn weighted_mean(points: &[Point3<f64>], weights: &[f64]) -> Option<Point3<f64>> {
    let total: f64 = weights.iter().sum();
    if total.is_nan() || total <= 0.0 {
        return None;
    }
    let sum = points
        .iter()
        .zip(weights)
        .fold(Vector3::zeros(), |s, (p, w)| s + p.coords * *w);
    Some(Point3::from(sum / total))
}

/// The algebraic least-squares sphere through `points` weighted by
/// `weights`, or `None` if the points do not determine a sphere (fewer than
/// four, coplanar, collinear, or all weights zero).
///
/// # Example
/// ```
/// use nalgebra::Point3;
/// use soak_graph::segment::sphere_fit::fit_sphere;
/// let c = Point3::new(1.0, 2.0, 3.0);
/// let pts: Vec<_> = [[1., 0., 0.], [-1., 0., 0.], [0., 1., 0.], [0., -1., 0.], [0., 0., 1.], [0., 0., -1.]]
///     .iter().map(|d| c + nalgebra::Vector3::from(*d) * 0.5).collect();
/// let s = fit_sphere(&pts, &[1.0; 6]).unwrap();
/// assert!((s.centre - c).norm() < 1e-12 && (s.radius - 0.5).abs() < 1e-12);
/// ```
pub fn fit_sphere(points: &[Point3<f64>], weights: &[f64]) -> Option<Sphere> {
    if points.len() < 4 || points.len() != weights.len() {
        return None;
    }
    let mean = weighted_mean(points, weights)?;
    let total: f64 = weights.iter().sum();
    let spread = (points
        .iter()
        .zip(weights)
        .map(|(p, w)| w * (p - mean).norm_squared())
        .sum::<f64>()
        / total)
        .sqrt();
    if spread.is_nan() || spread <= 0.0 {
        return None;
    }
    // Rows [2q, 1] · (c, d) = |q|², q = (p − mean)/spread, d = r² − |c|².
    let mut m = Matrix4::<f64>::zeros();
    let mut b = Vector4::<f64>::zeros();
    for (p, &w) in points.iter().zip(weights) {
        let q = (p - mean) / spread;
        let row = Vector4::new(2.0 * q.x, 2.0 * q.y, 2.0 * q.z, 1.0);
        m += row * row.transpose() * w;
        b += row * (w * q.norm_squared());
    }
    let svd = m.svd(true, true);
    let max = svd.singular_values.max();
    if max.is_nan() || max <= 0.0 || svd.singular_values.min() < RANK_TOLERANCE * max {
        return None;
    }
    let x = svd.solve(&b, 0.0).ok()?;
    let c = Vector3::new(x[0], x[1], x[2]);
    let r2 = x[3] + c.norm_squared();
    if !r2.is_finite() || r2 <= 0.0 {
        return None;
    }
    Some(Sphere {
        centre: mean + c * spread,
        radius: r2.sqrt() * spread,
    })
}

/// The radius minimising `Σ wᵢ (|pᵢ − centre| − r)²`: the weighted mean
/// distance, m (0 without weight).
pub fn fit_radius(centre: &Point3<f64>, points: &[Point3<f64>], weights: &[f64]) -> f64 {
    let total: f64 = weights.iter().sum();
    if total.is_nan() || total <= 0.0 {
        return 0.0;
    }
    points
        .iter()
        .zip(weights)
        .map(|(p, w)| w * (p - centre).norm())
        .sum::<f64>()
        / total
}
