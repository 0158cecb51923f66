//! The deep-water free-surface Green function and the Rankine integrals
//! over flat panels.
//!
//! Coordinates are soak's: y up, the still water plane at y = 0, the fluid
//! below. Time dependence `Re{φ e^{−iωt}}`. For a source at ξ and a field
//! point x, with `K = ω²/g`, `R` the horizontal distance and
//! `v = y_x + y_ξ ≤ 0`,
//!
//! `G = 1/r + 1/r₁ + 2K PV∫₀^∞ e^{kv} J₀(kR)/(k − K) dk + 2πiK e^{Kv} J₀(KR)`
//!
//! (`r₁` the distance to the source's image above the surface). With
//! `X = KR`, `Y = −Kv`, the wave part is `2K F(X, Y) + 2πiK e^{−Y} J₀(X)`,
//! `F(X, Y) = PV∫₀^∞ e^{−tY} J₀(tX)/(t − 1) dt`. Writing J₀ as its integral
//! over an angle turns F into an integral of the exponential integral of
//! a complex argument (Delhommeau's form):
//! `F = (2/π) ∫₀^{π/2} Re[e^{w}(E₁(w) + iπ)] dθ`, `w = −Y + iX cos θ`,
//! and `F₁(X, Y) = PV∫₀^∞ e^{−tY} J₁(tX)/(t − 1) dt` the same with
//! `cos θ · Im[…]`. Their derivatives follow without more integrals:
//! `∂F/∂Y = −F − 1/ρ` and `∂F/∂X = −X/(ρ(ρ + Y)) − F₁`, `ρ = √(X² + Y²)`.

use nalgebra::{Point3, Vector3};
use num_complex::Complex64;
use rayon::prelude::*;
use std::sync::OnceLock;

use crate::special::{exp_e1, tanh_sinh_unit};

/// The span of the table of `F` and `F₁`: `0 ≤ X, Y ≤ TABLE_SPAN`.
const TABLE_SPAN: f64 = 20.0;
/// Its step in X and Y.
const TABLE_STEP: f64 = 0.05;
/// Below this distance `ρ = √(X² + Y²)` from the singular point the
/// integrals are evaluated directly (F₁ has no limit there: 1 along
/// Y = 0, 0 along X = 0).
const TABLE_NEAR: f64 = 0.1;

/// `F(X, Y)` and `F₁(X, Y)` (module docs), for `X ≥ 0`, `Y > 0` (or
/// `Y = 0` with `X > 0`): from a table interpolated by bicubic
/// (Catmull–Rom) patches, built once per process, or by direct
/// quadrature near the singular point and beyond the table.
///
/// The table holds `F + ln(ρ + Y)` (continuous at the origin, where F
/// grows as `−ln ρ`) and `F₁`. Its row `Y = 0` is integrated directly;
/// the rows above follow from the exact relations
/// `∂F/∂Y = −F − 1/ρ` and `∂F₁/∂Y = −F₁ − X/(ρ(ρ + Y))`, integrated
/// step by step with the factor `e^{−ΔY}` exact and the rest by a
/// 16-point Gauss rule (and the column `X = 0` is `−e^{−Y} Ei(Y)` and 0).
pub fn wave_integrals(x: f64, y: f64) -> (f64, f64) {
    let rho = x.hypot(y);
    if rho < TABLE_NEAR || x > TABLE_SPAN - 2.0 * TABLE_STEP || y > TABLE_SPAN - 2.0 * TABLE_STEP {
        return wave_integrals_direct(x, y);
    }
    let table = table();
    let (fx, fy) = (x / TABLE_STEP, y / TABLE_STEP);
    let (ix, iy) = (fx.floor() as usize, fy.floor() as usize);
    let (tx, ty) = (fx - ix as f64, fy - iy as f64);
    let wx = catmull_rom(tx);
    let wy = catmull_rom(ty);
    let mut r = 0.0;
    let mut f1 = 0.0;
    for (a, wxa) in wx.iter().enumerate() {
        // Nodes ix−1 … ix+2 and iy−1 … iy+2; below 0 mirrored (F is even
        // in X, F₁ odd; in Y the row 0 is extended linearly).
        let (column, sign) = mirror(ix as isize - 1 + a as isize);
        for (b, wyb) in wy.iter().enumerate() {
            let w = wxa * wyb;
            let (vr, vf1) = match iy as isize - 1 + b as isize {
                -1 => {
                    let (r0, f0) = table.values[column];
                    let (r1, f1) = table.values[table.width + column];
                    (2.0 * r0 - r1, 2.0 * f0 - f1)
                }
                row => table.values[row as usize * table.width + column],
            };
            r += w * vr;
            f1 += w * sign * vf1;
        }
    }
    (r - (rho + y).ln(), f1)
}

/// A node index on the X axis mirrored about 0, with the sign of F₁
/// there.
fn mirror(index: isize) -> (usize, f64) {
    if index < 0 {
        ((-index) as usize, -1.0)
    } else {
        (index as usize, 1.0)
    }
}

/// Catmull–Rom weights of the four nodes around a point at `t ∈ [0, 1)`
/// from the second.
pub(crate) fn catmull_rom(t: f64) -> [f64; 4] {
    let t2 = t * t;
    let t3 = t2 * t;
    [
        0.5 * (-t3 + 2.0 * t2 - t),
        0.5 * (3.0 * t3 - 5.0 * t2 + 2.0),
        0.5 * (-3.0 * t3 + 4.0 * t2 + t),
        0.5 * (t3 - t2),
    ]
}

struct Table {
    width: usize,
    /// `(F + ln(ρ + Y), F₁)` row by row (Y), column by column (X).
    values: Vec<(f64, f64)>,
}

/// 16-point Gauss–Legendre nodes and weights on [0, 1].
const GAUSS16: [(f64, f64); 8] = [
    (0.989_400_934_991_649_9, 0.027_152_459_411_754_1),
    (0.944_575_023_073_232_6, 0.062_253_523_938_647_9),
    (0.865_631_202_387_831_7, 0.095_158_511_682_492_8),
    (0.755_404_408_355_003, 0.124_628_971_255_533_9),
    (0.617_876_244_402_643_7, 0.149_595_988_816_576_7),
    (0.458_016_777_657_227_4, 0.169_156_519_395_002_5),
    (0.281_603_550_779_258_9, 0.182_603_415_044_923_6),
    (0.095_012_509_837_637_4, 0.189_450_610_455_068_5),
];

fn table() -> &'static Table {
    static TABLE: OnceLock<Table> = OnceLock::new();
    TABLE.get_or_init(|| {
        let width = (TABLE_SPAN / TABLE_STEP).round() as usize + 1;
        let h = TABLE_STEP;
        let columns: Vec<Vec<(f64, f64)>> = (0..width)
            .into_par_iter()
            .map(|column| {
                let x = column as f64 * h;
                (0..width)
                    .scan(None, |state: &mut Option<(f64, f64)>, row| {
                        let y = row as f64 * h;
                        let (f, f1) = if column == 0 {
                            // X = 0: F = −e^{−Y} Ei(Y) (the principal value
                            // on the cut), F₁ = 0; at the origin R's limit.
                            if row == 0 {
                                *state = Some((0.0, 0.0));
                                return Some((std::f64::consts::LN_2 - 0.577_215_664_901_532_9, 0.0));
                            }
                            (exp_e1(Complex64::new(-y, 0.0)).re, 0.0)
                        } else if let Some((f_prev, f1_prev)) = *state {
                            let y0 = y - h;
                            let decay = (-h).exp();
                            let (mut i_f, mut i_f1) = (0.0, 0.0);
                            for &(node, weight) in &GAUSS16 {
                                for s in [0.5 * h * (1.0 - node), 0.5 * h * (1.0 + node)] {
                                    let yy = y0 + s;
                                    let rho = x.hypot(yy);
                                    let e = (s - h).exp() * 0.5 * h * weight;
                                    i_f += e / rho;
                                    i_f1 += e * x / (rho * (rho + yy));
                                }
                            }
                            (decay * f_prev - i_f, decay * f1_prev - i_f1)
                        } else {
                            wave_integrals_direct(x, 0.0)
                        };
                        *state = Some((f, f1));
                        Some((f + (x.hypot(y) + y).ln(), f1))
                    })
                    .collect()
            })
            .collect();
        let mut values = vec![(0.0, 0.0); width * width];
        for (column, entries) in columns.into_iter().enumerate() {
            for (row, value) in entries.into_iter().enumerate() {
                values[row * width + column] = value;
            }
        }
        Table { width, values }
    })
}

/// `F(X, Y)` and `F₁(X, Y)` by a tanh–sinh rule over the angle.
pub fn wave_integrals_direct(x: f64, y: f64) -> (f64, f64) {
    static RULES: OnceLock<[Vec<(f64, f64, f64)>; 4]> = OnceLock::new();
    let rules = RULES.get_or_init(|| {
        [
            tanh_sinh_unit(4),
            tanh_sinh_unit(5),
            tanh_sinh_unit(6),
            tanh_sinh_unit(7),
        ]
    });
    // The angle integral oscillates as e^{iX cos θ}: finer rules for far
    // points.
    let rule = &rules[if x < 6.0 {
        0
    } else if x < 25.0 {
        1
    } else if x < 80.0 {
        2
    } else {
        3
    }];
    angle_integral(x, y, rule)
}

/// F and F₁ by `rule` (tanh–sinh nodes `(s, 1 − s, weight)` on [0, 1],
/// θ = (π/2) s).
fn angle_integral(x: f64, y: f64, rule: &[(f64, f64, f64)]) -> (f64, f64) {
    let half_pi = std::f64::consts::FRAC_PI_2;
    let (mut f, mut f1) = (0.0, 0.0);
    for &(_, to_one, weight) in rule {
        // θ = (π/2) s; cos θ = sin((π/2)(1 − s)), exact near θ = π/2.
        let cos = (half_pi * to_one).sin();
        let w = Complex64::new(-y, x * cos);
        let mut value = exp_e1(w);
        if w.im > 0.0 {
            value += Complex64::new(0.0, std::f64::consts::PI) * w.exp();
        }
        f += weight * value.re;
        f1 += weight * cos * value.im;
    }
    (f, f1)
}

/// The wave part of G and its gradient with respect to the field point,
/// for wavenumber `k` (1/m), field point `x` and source `source` (m).
pub fn wave_part(k: f64, x: &Point3<f64>, source: &Point3<f64>) -> (Complex64, Vector3<Complex64>) {
    let dx = x.x - source.x;
    let dz = x.z - source.z;
    let r = (dx * dx + dz * dz).sqrt();
    let v = x.y + source.y;
    let big_x = k * r;
    let big_y = -k * v;
    let rho = big_x.hypot(big_y);
    let (f, f1) = wave_integrals(big_x, big_y);
    let decay = (-big_y).exp();
    let j0 = libm::j0(big_x);
    let j1 = libm::j1(big_x);
    let two_pi_k = 2.0 * std::f64::consts::PI * k;
    let g = Complex64::new(2.0 * k * f, two_pi_k * decay * j0);
    let f_y = -f - 1.0 / rho;
    let f_x = -big_x / (rho * (rho + big_y)) - f1;
    let d_r = Complex64::new(2.0 * k * k * f_x, -two_pi_k * k * decay * j1);
    let d_y = Complex64::new(-2.0 * k * k * f_y, two_pi_k * k * decay * j0);
    let (ux, uz) = if r > 0.0 { (dx / r, dz / r) } else { (0.0, 0.0) };
    (g, Vector3::new(d_r * ux, d_y, d_r * uz))
}

/// A flat polygonal panel (3 or 4 vertices, counter-clockwise about its
/// normal, which points out of the body into the water).
#[derive(Clone, Debug)]
pub struct Panel {
    /// Vertices, m (in the panel's plane).
    pub vertices: Vec<Point3<f64>>,
    /// Unit normal, out of the body.
    pub normal: Vector3<f64>,
    /// Centroid, m: the collocation point.
    pub centroid: Point3<f64>,
    /// Area, m².
    pub area: f64,
}

impl Panel {
    /// A panel from a polygon's vertices (counter-clockwise about the
    /// outward normal), projected onto its mean plane; `None` when its
    /// area is zero. A triangle is its own plane and keeps its corners as
    /// given: a corner on the water plane stays exactly on it, however
    /// thin the triangle and however far from the origin (projected, a
    /// kilometre-long sliver's corners moved by its normal's rounding
    /// error, a quarter of a millimetre).
    pub fn new(vertices: &[Point3<f64>]) -> Option<Panel> {
        let n = vertices.len();
        if n < 3 {
            return None;
        }
        // The fan's cross products about the first corner: the same vector
        // area as about the origin, without the rounding of coordinates a
        // kilometre from it.
        let first = vertices[0].coords;
        let mut normal = Vector3::zeros();
        for i in 1..n - 1 {
            normal += (vertices[i].coords - first).cross(&(vertices[i + 1].coords - first));
        }
        let twice_area = normal.norm();
        if !twice_area.is_finite() || twice_area <= 0.0 {
            return None;
        }
        normal /= twice_area;
        let projected: Vec<Point3<f64>> = if n == 3 {
            vertices.to_vec()
        } else {
            let mean = vertices.iter().fold(Vector3::zeros(), |s, p| s + p.coords) / n as f64;
            vertices
                .iter()
                .map(|p| Point3::from(p.coords - normal * (p.coords - mean).dot(&normal)))
                .collect()
        };
        // Area-weighted centroid of the fan.
        let mut centroid = Vector3::zeros();
        let mut area = 0.0;
        for i in 1..n - 1 {
            let a = projected[0].coords;
            let b = projected[i].coords;
            let c = projected[i + 1].coords;
            let t = 0.5 * (b - a).cross(&(c - a)).dot(&normal);
            centroid += (a + b + c) / 3.0 * t;
            area += t;
        }
        if !area.is_finite() || area <= 0.0 {
            return None;
        }
        Some(Panel {
            vertices: projected,
            normal,
            centroid: Point3::from(centroid / area),
            area,
        })
    }

    /// A length of the panel's size: the largest distance from its centroid
    /// to a vertex, m.
    pub fn size(&self) -> f64 {
        self.vertices
            .iter()
            .map(|v| (v - self.centroid).norm())
            .fold(0.0, f64::max)
    }

    /// `∫ 1/|p − ξ| dS_ξ` over the panel and its gradient with respect to
    /// `p` (Hess and Smith's closed forms: edge logarithms and the solid
    /// angle). `own` says that `p` is the panel's own centroid: the normal
    /// component is then the limit from the water side, `−2π`.
    pub fn rankine(&self, p: &Point3<f64>, own: bool) -> (f64, Vector3<f64>) {
        let n = self.vertices.len();
        let z = (p - self.vertices[0]).dot(&self.normal);
        let mut potential = 0.0;
        let mut gradient = Vector3::zeros();
        for i in 0..n {
            let a = self.vertices[i];
            let b = self.vertices[(i + 1) % n];
            let edge = b - a;
            let length = edge.norm();
            if length == 0.0 {
                continue;
            }
            let m = (edge / length).cross(&self.normal);
            let ra = (p - a).norm();
            let rb = (p - b).norm();
            let q = ((ra + rb + length) / (ra + rb - length).max(1e-300 * length)).ln();
            potential += (a - p).dot(&m) * q;
            gradient -= m * q;
        }
        let omega = if own {
            2.0 * std::f64::consts::PI
        } else {
            self.solid_angle(p)
        };
        potential -= z * omega;
        gradient -= self.normal * omega;
        (potential, gradient)
    }

    /// The solid angle the panel subtends at `p`, positive on the side its
    /// normal points to (Van Oosterom and Strackee over a fan): the
    /// integral over the panel of `∂(1/|p − ξ|)/∂n_ξ`, a normal dipole's
    /// potential.
    pub fn solid_angle(&self, p: &Point3<f64>) -> f64 {
        let a = self.vertices[0] - p;
        let la = a.norm();
        let mut omega = 0.0;
        for i in 1..self.vertices.len() - 1 {
            let b = self.vertices[i] - p;
            let c = self.vertices[i + 1] - p;
            let (lb, lc) = (b.norm(), c.norm());
            let numerator = a.dot(&b.cross(&c));
            let denominator = la * lb * lc + a.dot(&b) * lc + a.dot(&c) * lb + b.dot(&c) * la;
            omega -= 2.0 * numerator.atan2(denominator);
        }
        omega
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `F` and `F₁` by direct integration in t: the pole subtracted over
    /// [0, 2], the tail over [2, T] (Y > 0: it decays as e^{−tY}); Simpson
    /// with libm's Bessel functions.
    fn direct(x: f64, y: f64, bessel: fn(f64) -> f64) -> f64 {
        let f = |t: f64| (-t * y).exp() * bessel(t * x);
        let simpson = |g: &dyn Fn(f64) -> f64, a: f64, b: f64, n: usize| {
            let h = (b - a) / n as f64;
            let mut sum = g(a) + g(b);
            for i in 1..n {
                sum += if i % 2 == 1 { 4.0 } else { 2.0 } * g(a + i as f64 * h);
            }
            sum * h / 3.0
        };
        let f1 = f(1.0);
        // At the pole the quotient's limit, f'(1).
        let slope = (f(1.0 + 1e-6) - f(1.0 - 1e-6)) / 2e-6;
        let near = simpson(
            &|t: f64| {
                if (t - 1.0).abs() < 1e-12 {
                    slope
                } else {
                    (f(t) - f1) / (t - 1.0)
                }
            },
            0.0,
            2.0,
            20_000,
        );
        let end = 2.0 + 45.0 / y;
        let tail = simpson(&|t: f64| f(t) / (t - 1.0), 2.0, end, 400_000);
        near + tail
    }

    #[test]
    fn wave_integrals_match_direct_integration() {
        for &(x, y) in &[
            (0.0, 0.5),
            (0.3, 0.4),
            (1.0, 1.0),
            (2.5, 0.3),
            (6.0, 0.6),
            (12.0, 1.5),
            (30.0, 0.8),
            (0.05, 3.0),
        ] {
            let (f, f1) = wave_integrals_direct(x, y);
            let f_ref = direct(x, y, libm::j0);
            let f1_ref = direct(x, y, libm::j1);
            assert!(
                (f - f_ref).abs() < 2e-7 * f_ref.abs().max(1.0),
                "F({x}, {y}) = {f}, direct {f_ref}"
            );
            assert!(
                (f1 - f1_ref).abs() < 2e-7 * f1_ref.abs().max(1.0),
                "F1({x}, {y}) = {f1}, direct {f1_ref}"
            );
        }
    }

    #[test]
    fn the_table_matches_direct_quadrature() {
        let mut worst: f64 = 0.0;
        for i in 0..200 {
            // A scatter of points over the table, off its nodes.
            let x = (i as f64 * 0.618_034).fract() * 19.0;
            let y = (i as f64 * 0.414_214).fract() * 19.0;
            if x.hypot(y) < TABLE_NEAR {
                continue;
            }
            let (f, f1) = wave_integrals(x, y);
            let (g, g1) = wave_integrals_direct(x, y);
            let scale = g.abs().max(g1.abs()).max(0.1);
            worst = worst.max((f - g).abs().max((f1 - g1).abs()) / scale);
        }
        assert!(worst < 5e-5, "worst relative error {worst}");
    }

    #[test]
    fn direct_quadrature_converges() {
        // Level 4 against level 7 of the rule, where each is used.
        for &(x, y) in &[(0.1, 0.2), (3.0, 0.01), (5.9, 0.0), (20.0, 0.3), (70.0, 1.0)] {
            let (f, f1) = wave_integrals_direct(x, y);
            let (g, g1) = angle_integral(x, y, &tanh_sinh_unit(8));
            assert!(
                (f - g).abs() < 1e-8 * g.abs().max(1.0) && (f1 - g1).abs() < 1e-8 * g1.abs().max(1.0),
                "({x}, {y}): {f} {f1} vs {g} {g1}"
            );
        }
    }

    #[test]
    fn wave_part_gradient_matches_finite_differences() {
        // Near the source (evaluated directly: the formulas for the
        // derivatives) and farther (from the table: its interpolation,
        let source = Point3::new(0.2, -0.35, -0.1);
        // and near the origin of the table, where F₁ varies fastest).
        for (k, x, tolerance) in [
            (0.1, Point3::new(-0.1, -0.2, 0.3), 1e-6),
            (0.3, Point3::new(-0.1, -0.2, 0.3), 5e-3),
            (1.3, Point3::new(-0.4, -0.2, 0.5), 1e-3),
        ] {
            let (_, gradient) = wave_part(k, &x, &source);
            let h = 1e-5;
            for axis in 0..3 {
                let mut plus = x;
                let mut minus = x;
                plus[axis] += h;
                minus[axis] -= h;
                let fd = (wave_part(k, &plus, &source).0 - wave_part(k, &minus, &source).0) / (2.0 * h);
                assert!(
                    (fd - gradient[axis]).norm() < tolerance * gradient.norm(),
                    "K {k} axis {axis}: {fd} vs {}",
                    gradient[axis]
                );
            }
        }
    }

    #[test]
    fn wave_part_meets_the_free_surface_condition() {
        // ∂G/∂y = K G on y = 0 (for the whole G; the Rankine part 1/r + 1/r₁
        // has ∂/∂y = 0 there, so the wave part's ∂/∂y equals K G).
        let k = 0.8;
        let source = Point3::new(0.0, -0.5, 0.0);
        for x in [Point3::new(0.7, -1e-9, 0.2), Point3::new(2.0, -1e-9, -1.5)] {
            let (g_wave, gradient) = wave_part(k, &x, &source);
            let r = (x - source).norm();
            let rankine = 2.0 / r;
            let g = g_wave + rankine;
            assert!(
                (gradient.y - k * g).norm() < 1e-6 * g.norm(),
                "{} vs {}",
                gradient.y,
                k * g
            );
        }
    }

    #[test]
    fn rankine_integral_matches_quadrature_and_its_gradient() {
        let panel = Panel::new(&[
            Point3::new(0.0, 0.0, 0.0),
            Point3::new(1.0, 0.1, 0.0),
            Point3::new(1.1, 0.3, 0.9),
            Point3::new(-0.1, 0.2, 1.0),
        ])
        .unwrap();
        for p in [
            Point3::new(0.3, 0.8, 0.4),
            Point3::new(2.0, -1.0, 0.5),
            Point3::new(0.5, 0.05, 0.5),
        ] {
            let (phi, grad) = panel.rankine(&p, false);
            // Fine midpoint quadrature over the fan.
            let mut q = 0.0;
            let n = 400;
            let v = &panel.vertices;
            for tri in 1..v.len() - 1 {
                let (a, b, c) = (v[0], v[tri], v[tri + 1]);
                let area = 0.5 * (b - a).cross(&(c - a)).norm();
                for i in 0..n {
                    for j in 0..n - i {
                        for (u, w, weight) in [
                            ((i as f64 + 1.0 / 3.0), (j as f64 + 1.0 / 3.0), 1.0),
                            ((i as f64 + 2.0 / 3.0), (j as f64 + 2.0 / 3.0), 1.0),
                        ] {
                            if u + w > n as f64 {
                                continue;
                            }
                            let point = a + (b - a) * (u / n as f64) + (c - a) * (w / n as f64);
                            q += weight * area / (n * n) as f64 / (p - point).norm();
                        }
                    }
                }
            }
            assert!((phi - q).abs() < 2e-3 * q, "{phi} vs {q}");
            let h = 1e-6;
            for axis in 0..3 {
                let mut plus = p;
                let mut minus = p;
                plus[axis] += h;
                minus[axis] -= h;
                let fd = (panel.rankine(&plus, false).0 - panel.rankine(&minus, false).0) / (2.0 * h);
                assert!(
                    (fd - grad[axis]).abs() < 1e-5 * grad.norm(),
                    "axis {axis}: {fd} vs {}",
                    grad[axis]
                );
            }
        }
    }
}
