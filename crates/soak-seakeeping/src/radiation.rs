//! The radiation problem: a body forced to oscillate in each of its six
//! modes on still deep water, solved by a constant-strength source
//! distribution over its wetted panels.

use nalgebra::{DMatrix, Matrix6, Point3};
use num_complex::Complex64;
use rayon::prelude::*;

use crate::error::SeakeepingError;
use crate::green::{Panel, wave_part};

/// Which condition the water's surface sets on the radiated potential.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Surface {
    /// No free surface: the body alone in unbounded water (its panels may
    /// close it; the classical added mass of a body in an infinite fluid).
    Unbounded,
    /// Zero frequency: the surface a rigid wall (`∂φ/∂y = 0`).
    ZeroFrequency,
    /// Infinite frequency: the surface at constant pressure (`φ = 0`).
    InfiniteFrequency,
    /// Waves of this wavenumber `K = ω²/g`, 1/m (deep water).
    Wavenumber(f64),
}

/// Added mass and damping of the six rigid modes (translations along x, y
/// (heave) and z, then rotations about x, y (yaw) and z through the
/// reference point), as the force `F = −A ẍ − B ẋ` of the water on the
/// body.
#[derive(Clone, Debug, PartialEq)]
pub struct Coefficients {
    /// Angular frequency, rad/s (0 and `f64::INFINITY` for the limits).
    pub omega: f64,
    /// Added mass: kg, kg·m, kg·m² by block.
    pub added_mass: Matrix6<f64>,
    /// Wave damping: kg/s, kg·m/s, kg·m²/s by block (zero at the limits).
    pub damping: Matrix6<f64>,
}

/// The wetted panels of a body and the water it floats in, ready to solve
/// radiation problems at any frequency (the Rankine influences are
/// computed once and kept).
pub struct Radiation {
    panels: Vec<Panel>,
    /// The six modes' normal components at each panel (`n` and
    /// `(x − x_ref) × n`).
    modes: Vec<[f64; 6]>,
    density: f64,
    gravity: f64,
    /// `∫ 1/r` (direct) and `∫ 1/r₁` (image) of panel j at collocation i.
    direct: DMatrix<f64>,
    image: DMatrix<f64>,
    /// Their derivatives along panel j's normal (dipoles): solid angles,
    /// the principal value (0) for a panel's own.
    direct_dipole: DMatrix<f64>,
    image_dipole: DMatrix<f64>,
}

impl Radiation {
    /// Prepares the radiation problems of `panels` (the wetted surface,
    /// normals out of the body, every panel at or below y = 0), for water of
    /// `density` (kg/m³) under `gravity` (m/s², positive), rotations taken
    /// about `reference` (m).
    pub fn new(
        panels: Vec<Panel>,
        reference: Point3<f64>,
        density: f64,
        gravity: f64,
    ) -> Result<Radiation, SeakeepingError> {
        if panels.is_empty() {
            return Err(SeakeepingError::NoWettedSurface);
        }
        if !density.is_finite() || density <= 0.0 {
            return Err(SeakeepingError::BadParameter {
                name: "density",
                value: density,
            });
        }
        if !gravity.is_finite() || gravity <= 0.0 {
            return Err(SeakeepingError::BadParameter {
                name: "gravity",
                value: gravity,
            });
        }
        for (index, panel) in panels.iter().enumerate() {
            let highest = panel
                .vertices
                .iter()
                .map(|v| v.y)
                .fold(f64::NEG_INFINITY, f64::max);
            if highest.is_nan() || highest > 1e-9 * panel.size().max(1.0) {
                return Err(SeakeepingError::PanelAboveWater {
                    panel: index,
                    height: highest,
                });
            }
        }
        let modes = panels
            .iter()
            .map(|p| {
                let n = p.normal;
                let r = p.centroid - reference;
                let m = r.cross(&n);
                [n.x, n.y, n.z, m.x, m.y, m.z]
            })
            .collect();
        let count = panels.len();
        let rows: Vec<Vec<(f64, f64, f64, f64)>> = (0..count)
            .into_par_iter()
            .map(|i| {
                let x = panels[i].centroid;
                let mirrored = Point3::new(x.x, -x.y, x.z);
                panels
                    .iter()
                    .enumerate()
                    .map(|(j, panel)| {
                        let (d, _) = panel.rankine(&x, i == j);
                        // |x − ξ'| = |x' − ξ| with ' the mirror in y = 0.
                        let (m, _) = panel.rankine(&mirrored, false);
                        let dd = if i == j { 0.0 } else { panel.solid_angle(&x) };
                        (d, m, dd, panel.solid_angle(&mirrored))
                    })
                    .collect()
            })
            .collect();
        let direct = DMatrix::from_fn(count, count, |i, j| rows[i][j].0);
        let image = DMatrix::from_fn(count, count, |i, j| rows[i][j].1);
        let direct_dipole = DMatrix::from_fn(count, count, |i, j| rows[i][j].2);
        let image_dipole = DMatrix::from_fn(count, count, |i, j| rows[i][j].3);
        Ok(Radiation {
            panels,
            modes,
            density,
            gravity,
            direct,
            image,
            direct_dipole,
            image_dipole,
        })
    }

    /// The panels.
    pub fn panels(&self) -> &[Panel] {
        &self.panels
    }

    /// Added mass and damping for `surface`.
    pub fn solve(&self, surface: Surface) -> Result<Coefficients, SeakeepingError> {
        let count = self.panels.len();
        let (image_sign, k) = match surface {
            Surface::Unbounded => (0.0, None),
            Surface::ZeroFrequency => (1.0, None),
            Surface::InfiniteFrequency => (-1.0, None),
            Surface::Wavenumber(k) => {
                if !k.is_finite() || k <= 0.0 {
                    return Err(SeakeepingError::BadParameter {
                        name: "wavenumber",
                        value: k,
                    });
                }
                (1.0, Some(k))
            }
        };
        let omega = match surface {
            Surface::Unbounded | Surface::ZeroFrequency => 0.0,
            Surface::InfiniteFrequency => f64::INFINITY,
            Surface::Wavenumber(k) => (k * self.gravity).sqrt(),
        };
        // The wave parts, at the panels' centroids (one-point rule): G and
        // its derivative along the source panel's normal (G depends on the
        // horizontal offset x − ξ and on y_x + y_ξ).
        let waves: Option<Vec<Vec<(Complex64, Complex64)>>> = k.map(|k| {
            (0..count)
                .into_par_iter()
                .map(|i| {
                    let x = self.panels[i].centroid;
                    self.panels
                        .iter()
                        .map(|panel| {
                            let (g, gradient) = wave_part(k, &x, &panel.centroid);
                            let n = panel.normal;
                            let dn = -gradient.x * n.x + gradient.y * n.y - gradient.z * n.z;
                            (g * panel.area, dn * panel.area)
                        })
                        .collect()
                })
                .collect()
        });
        // Green's identity at each centroid (normals into the water):
        // 2π φ_i − Σ_j φ_j ∫_j ∂G/∂n_ξ = −Σ_j (∂φ/∂n)_j ∫_j G.
        let two_pi = 2.0 * std::f64::consts::PI;
        let system = DMatrix::from_fn(count, count, |i, j| {
            let mut dipole = Complex64::new(
                self.direct_dipole[(i, j)] + image_sign * self.image_dipole[(i, j)],
                0.0,
            );
            if let Some(waves) = &waves {
                dipole += waves[i][j].1;
            }
            let diagonal = if i == j { two_pi } else { 0.0 };
            Complex64::new(diagonal, 0.0) - dipole
        });
        let sources = DMatrix::from_fn(count, count, |i, j| {
            let mut value = Complex64::new(self.direct[(i, j)] + image_sign * self.image[(i, j)], 0.0);
            if let Some(waves) = &waves {
                value += waves[i][j].0;
            }
            -value
        });
        let normal_velocity = DMatrix::from_fn(count, 6, |i, m| Complex64::new(self.modes[i][m], 0.0));
        let rhs = sources * normal_velocity;
        let phi = system
            .lu()
            .solve(&rhs)
            .ok_or(SeakeepingError::Singular { omega })?;
        let mut added_mass = Matrix6::zeros();
        let mut damping = Matrix6::zeros();
        for m in 0..6 {
            for j in 0..6 {
                let mut sum = Complex64::new(0.0, 0.0);
                for (i, panel) in self.panels.iter().enumerate() {
                    sum += phi[(i, j)] * (self.modes[i][m] * panel.area);
                }
                added_mass[(m, j)] = -self.density * sum.re;
                if omega.is_finite() && omega > 0.0 {
                    damping[(m, j)] = -omega * self.density * sum.im;
                }
            }
        }
        if added_mass.iter().chain(damping.iter()).any(|v| !v.is_finite()) {
            return Err(SeakeepingError::Singular { omega });
        }
        Ok(Coefficients {
            omega,
            added_mass,
            damping,
        })
    }
}
