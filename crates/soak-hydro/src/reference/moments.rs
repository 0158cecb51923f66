//! Exact moments of simplices and the clipping of one triangle by a plane.
//!
//! For a simplex of dimension `n` with vertices `v_0..v_n` and measure `m`
//! (area or volume), the integrals of 1, `x` and `x xᵀ` are
//! `m`, `m s / (n+1)` and `m (Σ v_i v_iᵀ + s sᵀ) / ((n+1)(n+2))` with
//! `s = Σ v_i` (the canonical-simplex covariance formula). Tetrahedra here
//! always have their fourth vertex at the local origin, which drops out of
//! both sums.

use nalgebra::{Matrix3, Point3, Vector3};

/// Running integrals `∫ dμ`, `∫ x dμ` and `∫ x xᵀ dμ` of a body (μ = volume)
/// or a surface (μ = area), with `x` relative to a fixed reference point.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Moments {
    /// `∫ dμ`: m³ for volumes, m² for surfaces.
    pub measure: f64,
    /// `∫ x dμ`.
    pub first: Vector3<f64>,
    /// `∫ x xᵀ dμ`.
    pub second: Matrix3<f64>,
}

impl Default for Moments {
    fn default() -> Self {
        Self {
            measure: 0.0,
            first: Vector3::zeros(),
            second: Matrix3::zeros(),
        }
    }
}

impl Moments {
    /// Adds the signed tetrahedron `(0, a, b, c)`: positive when `a, b, c`
    /// wind counter-clockwise seen from outside the origin's side.
    #[inline]
    pub fn add_tetrahedron(&mut self, a: &Vector3<f64>, b: &Vector3<f64>, c: &Vector3<f64>) {
        let v = a.dot(&b.cross(c)) / 6.0;
        let s = a + b + c;
        self.measure += v;
        self.first += s * (v / 4.0);
        self.second +=
            (a * a.transpose() + b * b.transpose() + c * c.transpose() + s * s.transpose()) * (v / 20.0);
    }

    /// Adds the (unsigned) area of triangle `(a, b, c)` as a thin sheet.
    #[inline]
    pub fn add_triangle(&mut self, a: &Vector3<f64>, b: &Vector3<f64>, c: &Vector3<f64>) {
        let area = 0.5 * (b - a).cross(&(c - a)).norm();
        let s = a + b + c;
        self.measure += area;
        self.first += s * (area / 3.0);
        self.second +=
            (a * a.transpose() + b * b.transpose() + c * c.transpose() + s * s.transpose()) * (area / 12.0);
    }

    /// Centroid (absolute, given the reference point `origin`) and second
    /// moment about the centroid. A zero measure gives `fallback` and zeros.
    pub fn central(&self, origin: &Point3<f64>, fallback: &Point3<f64>) -> (Point3<f64>, Matrix3<f64>) {
        if self.measure == 0.0 || !self.measure.is_finite() {
            return (*fallback, Matrix3::zeros());
        }
        let d = self.first / self.measure;
        let c = self.second - d * d.transpose() * self.measure;
        (origin + d, 0.5 * (c + c.transpose()))
    }
}

/// Inertia tensor `ρ (tr C 𝟙 − C)` (kg·m²) from a second moment `C = ∫ x xᵀ`
/// and a density `ρ` (kg/m³ for volumes, kg/m² for surfaces).
#[inline]
pub(crate) fn inertia_from_second_moment(c: &Matrix3<f64>, density: f64) -> Matrix3<f64> {
    (Matrix3::identity() * c.trace() - c) * density
}

/// The submerged part of one triangle: up to four vertices of a convex polygon
/// in the triangle's winding order.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Piece {
    pts: [Point3<f64>; 4],
    len: usize,
}

impl Piece {
    fn push(&mut self, p: Point3<f64>) {
        self.pts[self.len] = p;
        self.len += 1;
    }

    /// The piece as a fan of triangles (none, one or two).
    pub fn triangles(&self) -> impl Iterator<Item = [Point3<f64>; 3]> + '_ {
        (1..self.len.saturating_sub(1)).map(|k| [self.pts[0], self.pts[k], self.pts[k + 1]])
    }
}

/// Clips triangle `p` to the submerged side, given each corner's signed
/// distance `s` from the plane (negative under water).
///
/// Corners with `s = 0` lie on the surface: they are kept as polygon vertices
/// but never produce crossings, so there are no duplicate points. A triangle
/// without a corner strictly under water gives nothing (a face lying in the
/// plane adds nothing). Crossings are computed from the wet end of the edge
/// to the dry end, so both triangles sharing an edge get bit-identical points
/// and the clipped surface stays watertight.
pub(crate) fn clip_triangle(p: &[Point3<f64>; 3], s: &[f64; 3]) -> Piece {
    let mut out = Piece {
        pts: [Point3::origin(); 4],
        len: 0,
    };
    if !s.iter().any(|&d| d < 0.0) {
        return out;
    }
    for i in 0..3 {
        let j = (i + 1) % 3;
        if s[i] <= 0.0 {
            out.push(p[i]);
        }
        if (s[i] < 0.0 && s[j] > 0.0) || (s[i] > 0.0 && s[j] < 0.0) {
            let (w, sw, d, sd) = if s[i] < 0.0 {
                (p[i], s[i], p[j], s[j])
            } else {
                (p[j], s[j], p[i], s[i])
            };
            let t = sw / (sw - sd);
            out.push(w + (d - w) * t);
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    fn tri() -> [Point3<f64>; 3] {
        [
            Point3::new(0.0, 0.0, 0.0),
            Point3::new(1.0, 0.0, 0.0),
            Point3::new(0.0, 1.0, 0.0),
        ]
    }

    #[test]
    fn clip_counts() {
        let p = tri();
        assert_eq!(clip_triangle(&p, &[1.0, 1.0, 1.0]).len, 0);
        assert_eq!(clip_triangle(&p, &[0.0, 0.0, 0.0]).len, 0);
        assert_eq!(clip_triangle(&p, &[0.0, 0.0, 1.0]).len, 0);
        assert_eq!(clip_triangle(&p, &[-1.0, -1.0, -1.0]).len, 3);
        assert_eq!(clip_triangle(&p, &[-1.0, -1.0, 1.0]).len, 4);
        assert_eq!(clip_triangle(&p, &[-1.0, 1.0, 1.0]).len, 3);
        assert_eq!(clip_triangle(&p, &[0.0, -1.0, 1.0]).len, 3);
        assert_eq!(clip_triangle(&p, &[0.0, 1.0, -1.0]).len, 3);
        assert_eq!(clip_triangle(&p, &[0.0, 0.0, -1.0]).len, 3);
    }

    #[test]
    fn crossing_is_independent_of_edge_direction() {
        let a = Point3::new(0.1, -0.3, 0.7);
        let b = Point3::new(0.9, 0.4, -0.2);
        let c = Point3::new(-0.5, 0.2, 0.1);
        let (sa, sb, sc) = (-0.3, 0.4, 0.2);
        let one = clip_triangle(&[a, b, c], &[sa, sb, sc]);
        let two = clip_triangle(&[b, a, c], &[sb, sa, sc]);
        // The a-b crossing is second in one piece and first in the other.
        assert_eq!(one.pts[1], two.pts[0]);
        // The c-a crossing comes last in both.
        assert_eq!(one.pts[2], two.pts[2]);
    }

    #[test]
    fn unit_tetrahedron_moments() {
        let mut m = Moments::default();
        m.add_tetrahedron(&Vector3::x(), &Vector3::y(), &Vector3::z());
        assert!((m.measure - 1.0 / 6.0).abs() < 1e-16);
        assert!((m.first.x - 1.0 / 24.0).abs() < 1e-16);
        assert!((m.second[(0, 0)] - 1.0 / 60.0).abs() < 1e-16);
        assert!((m.second[(0, 1)] - 1.0 / 120.0).abs() < 1e-16);
    }
}
