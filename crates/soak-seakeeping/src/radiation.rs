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
    /// Points on the interior waterplane (the lid), where the exterior
    /// potential's Green identity must give zero: extra equations that
    /// remove the irregular frequencies (Schenck's CHIEF on the lid).
    lid: Vec<Point3<f64>>,
    /// `∫ 1/r` and the solid angle of panel j at lid point i (a lid point
    /// is its own mirror: the image terms equal these).
    lid_direct: DMatrix<f64>,
    lid_dipole: DMatrix<f64>,
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
            if highest.is_nan() || highest > 1e-6 * panel.size().max(1.0) {
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
        let lid = lid_points(&panels);
        let lid_direct = DMatrix::from_fn(lid.len(), count, |i, j| panels[j].rankine(&lid[i], false).0);
        let lid_dipole = DMatrix::from_fn(lid.len(), count, |i, j| panels[j].solid_angle(&lid[i]));
        Ok(Radiation {
            panels,
            modes,
            density,
            gravity,
            direct,
            image,
            direct_dipole,
            image_dipole,
            lid,
            lid_direct,
            lid_dipole,
        })
    }

    /// Gravity, m/s².
    pub fn gravity(&self) -> f64 {
        self.gravity
    }

    /// The panels.
    pub fn panels(&self) -> &[Panel] {
        &self.panels
    }

    /// Added mass and damping for `surface`.
    pub fn solve(&self, surface: Surface) -> Result<Coefficients, SeakeepingError> {
        let potentials = self.potentials(surface)?;
        Ok(self.coefficients(&potentials))
    }

    /// The radiation potentials of the six modes for `surface`, at the
    /// panels' centroids (per unit velocity: m²/s per m/s).
    pub fn potentials(&self, surface: Surface) -> Result<Potentials, SeakeepingError> {
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
        // With waves, the lid's points add equations (the irregular
        // frequencies are those of the interior free-surface problem).
        let lid = if k.is_some() { self.lid.len() } else { 0 };
        let rows = count + lid;
        let point = |r: usize| {
            if r < count {
                self.panels[r].centroid
            } else {
                self.lid[r - count]
            }
        };
        // The wave parts, at the panels' centroids (one-point rule): G and
        // its derivative along the source panel's normal (G depends on the
        // horizontal offset x − ξ and on y_x + y_ξ).
        let waves: Option<Vec<Vec<(Complex64, Complex64)>>> = k.map(|k| {
            (0..rows)
                .into_par_iter()
                .map(|r| {
                    let x = point(r);
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
        let rankine = |r: usize, j: usize| {
            if r < count {
                (
                    self.direct[(r, j)] + image_sign * self.image[(r, j)],
                    self.direct_dipole[(r, j)] + image_sign * self.image_dipole[(r, j)],
                )
            } else {
                let l = r - count;
                (
                    (1.0 + image_sign) * self.lid_direct[(l, j)],
                    (1.0 + image_sign) * self.lid_dipole[(l, j)],
                )
            }
        };
        // Green's identity at each centroid (normals into the water):
        // 2π φ_i − Σ_j φ_j ∫_j ∂G/∂n_ξ = −Σ_j (∂φ/∂n)_j ∫_j G,
        // and at each lid point the same with 0 for 2π φ (a point inside
        // the body).
        let two_pi = 2.0 * std::f64::consts::PI;
        let system = DMatrix::from_fn(rows, count, |r, j| {
            let mut dipole = Complex64::new(rankine(r, j).1, 0.0);
            if let Some(waves) = &waves {
                dipole += waves[r][j].1;
            }
            let diagonal = if r == j { two_pi } else { 0.0 };
            Complex64::new(diagonal, 0.0) - dipole
        });
        let sources = DMatrix::from_fn(rows, count, |r, j| {
            let mut value = Complex64::new(rankine(r, j).0, 0.0);
            if let Some(waves) = &waves {
                value += waves[r][j].0;
            }
            -value
        });
        let normal_velocity = DMatrix::from_fn(count, 6, |i, m| Complex64::new(self.modes[i][m], 0.0));
        let rhs = sources * normal_velocity;
        let phi = if rows == count {
            system.lu().solve(&rhs)
        } else {
            // Least squares: QR of the tall system (Householder
            // reflections applied to the right-hand sides, Q never formed).
            let qr = system.qr();
            let mut projected = rhs;
            qr.q_tr_mul(&mut projected);
            qr.r()
                .solve_upper_triangular(&projected.rows(0, count).into_owned())
        }
        .ok_or(SeakeepingError::Singular { omega })?;
        if phi.iter().any(|v| !v.re.is_finite() || !v.im.is_finite()) {
            return Err(SeakeepingError::Singular { omega });
        }
        Ok(Potentials {
            omega,
            wavenumber: k,
            phi,
        })
    }

    /// Added mass and damping from the potentials: the pressure
    /// `iωρφ` integrated over the wetted panels.
    pub fn coefficients(&self, potentials: &Potentials) -> Coefficients {
        let (omega, phi) = (potentials.omega, &potentials.phi);
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
        Coefficients {
            omega,
            added_mass,
            damping,
        }
    }

    /// The Kochin function of mode `mode` (0–5) in direction `heading`
    /// (rad, from +x toward +z): the far-field amplitude of the radiated
    /// waves, `H(β) = ∫ (φ ∂E/∂n − ∂φ/∂n E) dS` with
    /// `E = e^{Ky − iK(x cos β + z sin β)}`; the radiated potential far
    /// away is `(iK/2) √(2/(πKR)) e^{i(KR − π/4)} e^{Ky} H(β)`. `None`
    /// without waves.
    pub fn kochin(&self, potentials: &Potentials, mode: usize, heading: f64) -> Option<Complex64> {
        let k = potentials.wavenumber?;
        let (cos, sin) = (heading.cos(), heading.sin());
        let mut sum = Complex64::new(0.0, 0.0);
        for (i, panel) in self.panels.iter().enumerate() {
            let c = panel.centroid;
            let e = Complex64::new(k * c.y, -k * (c.x * cos + c.z * sin)).exp();
            let n = panel.normal;
            let dn = e * Complex64::new(k * n.y, -k * (n.x * cos + n.z * sin));
            sum += (potentials.phi[(i, mode)] * dn - e * self.modes[i][mode]) * panel.area;
        }
        Some(sum)
    }

    /// The wave excitation force and moment on the body held still in
    /// regular waves of unit amplitude travelling along `heading` (rad,
    /// from +x toward +z), by the Haskind relation: `X_j = ρ g H_j(β + π)`
    /// (N per m of amplitude, N·m per m for the moments; the phase is
    /// relative to the incident elevation at the origin, `Re{e^{−iωt}}`).
    /// `None` without waves.
    pub fn excitation(&self, potentials: &Potentials, heading: f64) -> Option<[Complex64; 6]> {
        let mut out = [Complex64::new(0.0, 0.0); 6];
        for (mode, value) in out.iter_mut().enumerate() {
            *value = self.kochin(potentials, mode, heading + std::f64::consts::PI)?
                * (self.density * self.gravity);
        }
        Some(out)
    }

    /// The wave damping of each mode from the energy its waves carry away
    /// (`B = (ρωK/4π) ∫₀^{2π} |H(β)|² dβ`, the Kochin function over 360
    /// headings): an independent check of the damping from the pressure.
    /// `None` without waves.
    pub fn far_field_damping(&self, potentials: &Potentials) -> Option<[f64; 6]> {
        let k = potentials.wavenumber?;
        let headings = 360;
        let step = 2.0 * std::f64::consts::PI / f64::from(headings);
        let mut out = [0.0; 6];
        for (mode, value) in out.iter_mut().enumerate() {
            let integral: f64 = (0..headings)
                .map(|h| {
                    self.kochin(potentials, mode, f64::from(h) * step)
                        .map_or(0.0, |v| v.norm_sqr())
                        * step
                })
                .sum();
            *value = self.density * potentials.omega * k / (4.0 * std::f64::consts::PI) * integral;
        }
        Some(out)
    }
}

/// The radiation potentials of the six modes at the wetted panels'
/// centroids, per unit velocity of each mode.
#[derive(Clone, Debug)]
pub struct Potentials {
    /// Angular frequency, rad/s.
    pub omega: f64,
    /// Wavenumber `ω²/g`, 1/m; `None` at the limits and in unbounded
    /// water.
    pub wavenumber: Option<f64>,
    /// φ (m²/s per unit velocity), one row per panel, one column per mode.
    pub phi: DMatrix<Complex64>,
}

/// Points on the interior waterplane of `panels` (the lid): a grid at
/// about the panels' size inside the waterline (the panel edges on
/// y = 0), kept half a step from it. None for a body whose waterline
/// does not close (wholly submerged, or an open hull).
fn lid_points(panels: &[Panel]) -> Vec<Point3<f64>> {
    let mut segments: Vec<(f64, f64, f64, f64)> = Vec::new();
    let mut size: f64 = 0.0;
    for panel in panels {
        let n = panel.vertices.len();
        for i in 0..n {
            let (a, b) = (panel.vertices[i], panel.vertices[(i + 1) % n]);
            let tolerance = 1e-9 * panel.size().max(1e-3);
            if a.y.abs() <= tolerance && b.y.abs() <= tolerance && (a - b).norm() > 0.0 {
                segments.push((a.x, a.z, b.x, b.z));
                size = size.max((a - b).norm());
            }
        }
    }
    if segments.len() < 3 {
        return Vec::new();
    }
    let (mut min_x, mut max_x, mut min_z, mut max_z) =
        (f64::INFINITY, f64::NEG_INFINITY, f64::INFINITY, f64::NEG_INFINITY);
    for &(ax, az, bx, bz) in &segments {
        min_x = min_x.min(ax.min(bx));
        max_x = max_x.max(ax.max(bx));
        min_z = min_z.min(az.min(bz));
        max_z = max_z.max(az.max(bz));
    }
    // About one lid point per four waterplane panels' area, at most 400.
    let step = (2.0 * size).max(((max_x - min_x) * (max_z - min_z) / 400.0).sqrt());
    let inside = |x: f64, z: f64| {
        let mut crossings = 0;
        let mut nearest = f64::INFINITY;
        for &(ax, az, bx, bz) in &segments {
            if (az > z) != (bz > z) && x < ax + (z - az) / (bz - az) * (bx - ax) {
                crossings += 1;
            }
            let (dx, dz) = (bx - ax, bz - az);
            let t = (((x - ax) * dx + (z - az) * dz) / (dx * dx + dz * dz)).clamp(0.0, 1.0);
            nearest = nearest.min((ax + t * dx - x).hypot(az + t * dz - z));
        }
        crossings % 2 == 1 && nearest > 0.5 * step
    };
    let mut points = Vec::new();
    let mut x = min_x + 0.5 * step;
    while x < max_x {
        let mut z = min_z + 0.5 * step;
        while z < max_z {
            if inside(x, z) {
                points.push(Point3::new(x, 0.0, z));
            }
            z += step;
        }
        x += step;
    }
    points
}
