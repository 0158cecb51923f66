//! A floating body's radiation baked for the time domain
//! ([`RadiationModel`]): where it floats at rest, its hydrostatic
//! stiffness, its added mass and damping over frequencies, A∞ and the
//! fitted retardation kernels; and a body's running memory of its motion
//! ([`RadiationState`]).

use nalgebra::{Isometry3, Matrix3, Matrix6, Point3, Translation3, UnitQuaternion, Vector3, Vector6};
use num_complex::Complex64;
use serde::{Deserialize, Serialize};
use soak_bake::Mesh;

use crate::error::SeakeepingError;
use crate::green::Panel;
use crate::memory::{Kernel, KernelStep, Memory, Sweep};
use crate::panels::wetted_panels;
use crate::radiation::Radiation;
use std::sync::{Arc, Mutex};

/// A body as it floats: its mesh (object frame), mass, centre of mass and
/// inertia, and how it is turned at rest.
#[derive(Clone, Copy, Debug)]
pub struct FloatingBody<'a> {
    /// The closed mesh, object frame, m.
    pub mesh: &'a Mesh,
    /// Mass, kg (with whatever it carries).
    pub mass: f64,
    /// Centre of mass, object frame, m.
    pub center_of_mass: Point3<f64>,
    /// Inertia about the centre of mass, object axes, kg·m².
    pub inertia: Matrix3<f64>,
    /// The orientation to float it from (object axes → the water's; y
    /// up): the bake tilts it to the stable orientation nearest this one
    /// ([`RadiationModel::rotation`]; a square log of half the water's
    /// density placed flat rolls 45° onto an edge), keeping its heading. The radiation
    /// force is taken in the body's axes at rest, turned with the body.
    pub rotation: UnitQuaternion<f64>,
}

/// How finely a [`RadiationModel`] is baked.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct RadiationSettings {
    /// Fluid density, kg/m³ (> 0). Default 1000.
    pub density: f64,
    /// Gravity, m/s² (> 0). Default 9.80665 (standard gravity, as
    /// soak's `Water::calm`).
    pub gravity: f64,
    /// About how many panels the wetted surface is cut into (≥ 8): the
    /// solve's cost grows as its square per frequency. A mesh with more
    /// wetted triangles than that is simplified first
    /// ([`Mesh::simplified`](soak_bake::Mesh::simplified)). Default 300, which puts a
    /// hemisphere's heave and surge within 2 % of the published
    /// coefficients.
    pub panels: usize,
    /// How many frequencies the sweep solves (≥ 8), evenly from
    /// `0.24 √(g/L)` (`L` the radius of a disc of the water-plane's area;
    /// KL ≈ 0.06) to `3.36 √(g/L)` (KL ≈ 11, where a surface body's
    /// damping has died out) or to the shortest wave six panels resolve,
    /// whichever is lower. Default 40.
    pub frequencies: usize,
    /// At most how many poles each retardation kernel is fitted with
    /// (≥ 1). Default 10.
    pub poles: usize,
}

impl Default for RadiationSettings {
    fn default() -> Self {
        Self {
            density: 1000.0,
            gravity: 9.80665,
            panels: 300,
            frequencies: 40,
            poles: 10,
        }
    }
}

/// The water-plane and the volume under it of a body floating at rest,
/// and the stiffness they give (the body's frame at rest: y up, the centre
/// of mass at x = z = 0).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct Hydrostatics {
    /// Displaced volume, m³.
    pub volume: f64,
    /// Centre of buoyancy, m.
    pub center_of_buoyancy: Point3<f64>,
    /// Height of the centre of mass above the still water plane, m.
    pub center_of_mass_height: f64,
    /// Water-plane area, m².
    pub waterplane_area: f64,
    /// Water-plane second moments about x = 0 and z = 0, `∫ x² dA` and
    /// `∫ z² dA`, m⁴.
    pub waterplane_moments: [f64; 2],
    /// The restoring stiffness of heave (N/m) and of the rotations about
    /// x and z (N·m/rad), about the centre of mass, with their couplings
    /// (N/rad, N·m/m: `ρ g ∫ x dA` couples heave and the rotation about z
    /// when the water-plane's centre is not under the centre of mass).
    pub stiffness: Matrix6<f64>,
}

/// A floating body's radiation for the time domain: its rest pose and
/// hydrostatics, A(ω) and B(ω) over frequencies, A∞ and one fitted
/// retardation kernel per mode. Modes are surge x, heave y, sway z and
/// the rotations about x, y (yaw) and z, about the centre of mass, in the
/// body's axes at rest ([`FloatingBody::rotation`]). The cross-couplings
/// between modes (surge–pitch, sway–roll) are computed and reported but
/// left out of the time domain: each mode radiates on its own.
#[derive(Clone, Debug)]
pub struct RadiationModel {
    rotation: UnitQuaternion<f64>,
    center_of_mass: Point3<f64>,
    mass: f64,
    inertia: Matrix3<f64>,
    hydrostatics: Hydrostatics,
    sweep: Sweep,
    /// Per frequency of the sweep, per heading (every 45° from +x toward
    /// +z), the excitation of each mode per metre of wave amplitude.
    excitation: Vec<[[Complex64; 6]; HEADINGS]>,
    /// The same for the hydrostatic columns' wave force (see
    /// [`RadiationModel::column_excitation`]), per frequency and heading.
    columns: Vec<[[Complex64; 6]; HEADINGS]>,
    /// Quadrature points of the wetted panels (each triangle's edge
    /// midpoints, a third of its area each): x and z (m), `−n_y` × the
    /// weight (m², the water-plane seen through the hull), `n_y y` × it
    /// (m³, the share of `∫_V dV`) and `n_y (y²/2 − h y)` × it (m⁴, of
    /// `∫_V (y − h) dV`, h the centre of mass' height); see
    /// [`column_forces`].
    waterline: Vec<[f64; 5]>,
    kernels: Vec<Kernel>,
    kernel_step: f64,
    length: f64,
    panels: usize,
    density: f64,
    gravity: f64,
    /// The step factors of the lengths bodies step it by, shared by every
    /// body of the model (see [`RadiationState::record`]).
    steps: SharedSteps,
}

impl RadiationModel {
    /// Floats `body` at rest in still water (the draft where it displaces
    /// its mass, by bisection on the exact volume of the clipped mesh),
    /// cuts its wetted surface into about `settings.panels` panels, and
    /// solves the radiation problem at `settings.frequencies` frequencies
    /// and at infinite frequency; fits each mode's retardation kernel.
    ///
    /// # Errors
    /// Settings or a body out of range ([`SeakeepingError::BadParameter`]),
    /// a mesh that is not finite or names missing vertices, a body too
    /// heavy to float ([`SeakeepingError::Sinks`]), a singular solve.
    pub fn bake(body: &FloatingBody<'_>, settings: &RadiationSettings) -> Result<Self, SeakeepingError> {
        let positive = [
            ("density", settings.density),
            ("gravity", settings.gravity),
            ("mass", body.mass),
        ];
        for (name, value) in positive {
            if !(value.is_finite() && value > 0.0) {
                return Err(SeakeepingError::BadParameter { name, value });
            }
        }
        for (name, value, least) in [
            ("panels", settings.panels, 8),
            ("frequencies", settings.frequencies, 8),
            ("poles", settings.poles, 1),
        ] {
            if value < least {
                return Err(SeakeepingError::BadParameter {
                    name,
                    value: value as f64,
                });
            }
        }
        if !body.center_of_mass.coords.iter().all(|c| c.is_finite())
            || !body.inertia.iter().all(|c| c.is_finite())
            || !body.rotation.coords.iter().all(|c| c.is_finite())
        {
            return Err(SeakeepingError::BadParameter {
                name: "center_of_mass, inertia or rotation",
                value: f64::NAN,
            });
        }
        let (g, rho) = (settings.gravity, settings.density);
        let target = body.mass / rho;
        // The stable orientation nearest the one given, found on a coarser
        // copy of a fine mesh (its energy is a smooth function of the tilt).
        let coarse_mesh;
        let search = if body.mesh.triangles.len() > 2000 {
            coarse_mesh = body.mesh.simplified(2000);
            &coarse_mesh
        } else {
            body.mesh
        };
        let rotation = settle(body, search, target)?;
        let body = &FloatingBody { rotation, ..*body };
        let height = float_height(body, &rotation, target)?;
        let mut pose = rest_pose(body, &rotation, height);
        let mut height = height;
        let mut coarse = wetted_panels(body.mesh, &pose, 1e9)?;
        // A mesh finer than the panels asked for is simplified first (a
        // deviation of at most 0.5 % of its extent: the simplifier keeps
        // more triangles than asked rather than lose the hull's shape),
        // and floated again: the model's hydrostatics are its own hull's
        // at the draft where that hull displaces the mass.
        let simplified;
        let mut mesh = body.mesh;
        if coarse.len() > settings.panels * 3 / 2 {
            let share = settings.panels as f64 / coarse.len() as f64;
            simplified = body.mesh.simplified_within(
                ((body.mesh.triangles.len() as f64 * share) as usize).max(8),
                0.005,
            );
            mesh = &simplified;
            let hull = FloatingBody { mesh, ..*body };
            height = float_height(&hull, &rotation, target)?;
            pose = rest_pose(&hull, &rotation, height);
            coarse = wetted_panels(mesh, &pose, 1e9)?;
        }
        let wetted: f64 = coarse.iter().map(|p| p.area).sum();
        // The panel size that cuts the wetted surface into about the count
        // asked for: a few corrections of the size by the count's square root.
        let largest = coarse
            .iter()
            .flat_map(|p| {
                let v = &p.vertices;
                (0..v.len()).map(move |k| (v[(k + 1) % v.len()] - v[k]).norm())
            })
            .fold(0.0, f64::max);
        let wanted = settings.panels as f64;
        let mut size = (2.0 * wetted / wanted).sqrt().min(largest);
        let mut panels = wetted_panels(mesh, &pose, size)?;
        for _ in 0..6 {
            let ratio = panels.len() as f64 / wanted;
            if (0.8..=1.25).contains(&ratio) || (ratio < 1.0 && size >= largest) {
                break;
            }
            size = (size * ratio.sqrt()).min(largest);
            panels = wetted_panels(mesh, &pose, size)?;
        }
        let hydrostatics = hydrostatics(&panels, height, rho, g);
        let length = (hydrostatics.waterplane_area / std::f64::consts::PI)
            .sqrt()
            .max((hydrostatics.volume).cbrt() * 0.5);
        let scale = (g / length).sqrt();
        // From KL ≈ 0.06 (below, B falls to 0 and A is held: see
        // `Sweep::at`) to KL ≈ 11 or to the shortest wave three panels
        // resolve, evenly. Three, not more: the halving bounds every panel's
        // longest edge (see `wetted_panels`), and the boat's 295 matched an
        // independent boundary-element code within a few percent where
        // its longest are half a wave; at six the boat's sweep stopped
        // below its heave resonance, and its time domain, whose kernel
        // then rested on the extrapolated tail, missed its period by 7 %.
        let finest = (g * std::f64::consts::TAU / (3.0 * size)).sqrt();
        let (low, high) = (0.24 * scale, (3.36 * scale).min(finest).max(0.48 * scale));
        let count = settings.frequencies;
        let omegas: Vec<f64> = (0..count)
            .map(|n| low + (high - low) * n as f64 / (count - 1) as f64)
            .collect();
        let count = panels.len();
        let waterline: Vec<[f64; 5]> = panels
            .iter()
            .flat_map(|p| {
                // The edge-midpoint rule of `quadratic`, point by point.
                edge_midpoints(p).flat_map(move |(third, midpoints)| {
                    let w = p.normal.y * third;
                    midpoints.map(|m| [m.x, m.z, -w, w * m.y, w * m.y * (0.5 * m.y - height)])
                })
            })
            .collect();
        let problem = Radiation::new(panels, Point3::new(0.0, height, 0.0), rho, g)?;
        // Each frequency's potentials give its coefficients and the wave
        // excitation at every 45° of heading.
        let infinite = problem
            .solve(crate::radiation::Surface::InfiniteFrequency)?
            .added_mass;
        reciprocal(&infinite)?;
        // Potential theory makes A∞ symmetric; the panel solve leaves it out
        // by up to a few parts in a thousand of its diagonal (the drift
        // test's small ball's by 5e-4, the model tests' sphere's by 2e-3 in
        // its surge–sway pair). The time domain takes its symmetric part, the
        // nearest symmetric matrix: a mass matrix that is not symmetric
        // does not keep the kinetic energy it stands for.
        let infinite = (infinite + infinite.transpose()) * 0.5;
        let mut frequencies = Vec::with_capacity(omegas.len());
        let mut excitation = Vec::with_capacity(omegas.len());
        let mut columns = Vec::with_capacity(omegas.len());
        for &omega in &omegas {
            let potentials = problem.potentials(crate::radiation::Surface::Wavenumber(omega * omega / g))?;
            frequencies.push(problem.coefficients(&potentials));
            let mut per_heading = [[Complex64::new(0.0, 0.0); 6]; HEADINGS];
            for (n, forces) in per_heading.iter_mut().enumerate() {
                let heading = n as f64 * std::f64::consts::TAU / HEADINGS as f64;
                *forces = problem
                    .excitation(&potentials, heading)
                    .ok_or(SeakeepingError::Singular { omega })?;
            }
            excitation.push(per_heading);
            columns.push(std::array::from_fn(|n| {
                column_forces(
                    &waterline,
                    omega * omega / g,
                    n as f64 * std::f64::consts::TAU / HEADINGS as f64,
                    rho * g,
                )
            }));
        }
        let sweep = Sweep {
            infinite,
            frequencies,
        };
        // The kernels: 250 samples over about 30 √(L/g).
        let kernel_step = 0.125 / scale;
        let times: Vec<f64> = (0..=250).map(|n| n as f64 * kernel_step).collect();
        let kernels = (0..6)
            .map(|mode| {
                let samples = sweep.kernel(mode, mode, &times);
                let peak = samples.iter().fold(0.0f64, |m, v| m.max(v.abs()));
                // A mode that radiates nothing (a sphere's yaw) gets no
                // states: below 1e-4 of a unit scale for its block.
                let unit =
                    rho * hydrostatics.volume * scale * scale * length.powi(if mode < 3 { 0 } else { 2 });
                if peak < 1e-4 * unit {
                    Kernel {
                        poles: Vec::new(),
                        residues: Vec::new(),
                    }
                } else {
                    let fit = Kernel::fit(&samples, kernel_step, settings.poles);
                    // The poles of the samples' fit, the residues refitted
                    // to the computed A and B (and, a tenth as much, to the
                    // tail's B beyond): fitted to the samples alone, the
                    // residues followed B over every frequency, its
                    // extrapolated tail included, and the added mass they
                    // make by Kramers–Kronig missed the computed one near
                    // the end of the sweep (the boat's heave by some 90 kg
                    // at its resonance, its period by 7 %). Kept only if it
                    // dissipates at every frequency (see `passive`).
                    let a_inf = sweep.infinite[(mode, mode)];
                    let last = sweep.frequencies.last().map_or(0.0, |c| c.omega);
                    let response: Vec<(f64, Complex64, f64)> = sweep
                        .frequencies
                        .iter()
                        .map(|c| {
                            let (a, b) = (c.added_mass[(mode, mode)], c.damping[(mode, mode)]);
                            (c.omega, Complex64::new(b, -c.omega * (a - a_inf)), 1.0)
                        })
                        .chain((1..=16).map(|k| {
                            let omega = last * (1.0 + k as f64 / 8.0);
                            (
                                omega,
                                Complex64::new(sweep.at(mode, mode, omega).1, f64::NAN),
                                0.1,
                            )
                        }))
                        .collect();
                    let refit = fit.refit(&response);
                    if passive(&refit, last) { refit } else { fit }
                }
            })
            .collect();
        let turn = body.rotation.to_rotation_matrix().into_inner();
        let model = Self {
            rotation: body.rotation,
            center_of_mass: body.center_of_mass,
            mass: body.mass,
            inertia: turn * body.inertia * turn.transpose(),
            hydrostatics,
            sweep,
            excitation,
            columns,
            waterline,
            kernels,
            kernel_step,
            length,
            panels: count,
            density: rho,
            gravity: g,
            steps: SharedSteps::default(),
        };
        Ok(model)
    }

    /// The body's orientation at rest (object axes → the water's): the
    /// stable one nearest [`FloatingBody::rotation`].
    pub fn rotation(&self) -> &UnitQuaternion<f64> {
        &self.rotation
    }
    /// The centre of mass it was baked with, object frame, m.
    pub fn center_of_mass(&self) -> &Point3<f64> {
        &self.center_of_mass
    }
    /// The mass it was baked with, kg.
    pub fn mass(&self) -> f64 {
        self.mass
    }
    /// The inertia about the centre of mass, axes at rest, kg·m².
    pub fn inertia(&self) -> &Matrix3<f64> {
        &self.inertia
    }
    /// The body at rest: volume, water-plane, stiffness.
    pub fn hydrostatics(&self) -> &Hydrostatics {
        &self.hydrostatics
    }
    /// A(ω), B(ω) at each frequency solved, and A∞ (its symmetric part,
    /// see [`RadiationModel::infinite`]).
    pub fn sweep(&self) -> &Sweep {
        &self.sweep
    }
    /// The infinite-frequency added mass, 6×6 (kg, kg·m, kg·m² by block):
    /// the symmetric part of the panel solve's, which potential theory
    /// makes symmetric and the panels leave out by up to a few parts in a
    /// thousand of its diagonal (a solve further out than a fifth of its
    /// scale is refused).
    pub fn infinite(&self) -> &Matrix6<f64> {
        &self.sweep.infinite
    }
    /// Mode `mode`'s fitted retardation kernel (no poles: it radiates nothing).
    pub fn kernel(&self, mode: usize) -> &Kernel {
        &self.kernels[mode]
    }
    /// Mode `mode`'s own added mass and damping at `omega` (rad/s), as the
    /// model has them: the sweep's ([`Sweep::at`]) up to its last
    /// frequency, and beyond it the fitted kernel's (`A = A∞ − Im T / ω`,
    /// `B = Re T`, [`Kernel::transform`]), which the time domain sees and
    /// which agree with each other by construction; the sweep's tails
    /// where the mode has no kernel.
    pub fn coefficients(&self, mode: usize, omega: f64) -> (f64, f64) {
        let kernel = &self.kernels[mode];
        let last = self.sweep.frequencies.last().map_or(f64::INFINITY, |c| c.omega);
        if omega <= last || kernel.poles.is_empty() {
            return self.sweep.at(mode, mode, omega);
        }
        let t = kernel.transform(omega);
        (self.sweep.infinite[(mode, mode)] - t.im / omega, t.re)
    }
    /// The kernels' sampling step, s.
    pub fn kernel_step(&self) -> f64 {
        self.kernel_step
    }
    /// The length the frequencies are scaled by, m: the radius of a disc
    /// of the water-plane's area.
    pub fn length(&self) -> f64 {
        self.length
    }
    /// Whether a time step of `dt` (s) resolves the body's own motion:
    /// `dt √(g/L) ≤ 1` ([`RadiationModel::length`]), the step no longer
    /// than the body's natural time. A step that does not (a millimetre
    /// body at 1/10 s) cannot follow the waves it makes: the time domain
    /// leaves its radiation out (the implicit heave step damps such a body
    /// by itself).
    pub fn resolved_by(&self, dt: f64) -> bool {
        dt * (self.gravity / self.length).sqrt() <= 1.0
    }
    /// How many panels the wetted surface was cut into.
    pub fn panel_count(&self) -> usize {
        self.panels
    }
    /// Fluid density, kg/m³.
    pub fn density(&self) -> f64 {
        self.density
    }
    /// Gravity, m/s².
    pub fn gravity(&self) -> f64 {
        self.gravity
    }
    /// The states the time domain carries per body: the kernels' poles.
    pub fn state_count(&self) -> usize {
        self.kernels.iter().map(|k| k.poles.len()).sum()
    }

    /// The mass (or inertia) of `mode` in its own direction, kg or kg·m²:
    /// the body's, axes at rest.
    pub fn mode_inertia(&self, mode: usize) -> f64 {
        if mode < 3 {
            self.mass
        } else {
            self.inertia[(mode - 3, mode - 3)]
        }
    }

    /// The motion of `mode` released from `x0` (m or rad) at rest, at each
    /// of `times` (s), from the frequency-domain coefficients: `x(t) = x0
    /// (1 − (S(t) C)_mm)`, `S` the response to a unit step force, `S(t) =
    /// (2/π) ∫₀^∞ Re H(ω) sin ωt / ω dω` with `H = (C − ω² (M + A(ω)) − i ω
    /// B(ω))⁻¹` over the six modes. The modes are coupled as the time
    /// domain couples them: through the stiffness (a water-plane whose
    /// centre is not under the centre of mass couples heave and pitch),
    /// through A∞'s translational and rotational blocks; each mode's
    /// memory is its own (`A(ω) − A∞` and `B(ω)` on the diagonal). `None`
    /// for a mode without stiffness (surge, sway, yaw).
    pub fn release(&self, mode: usize, x0: f64, times: &[f64]) -> Option<Vec<f64>> {
        let stiffness = &self.hydrostatics.stiffness;
        if stiffness[(mode, mode)] <= 0.0 {
            return None;
        }
        let top = 12.0
            * (0..6)
                .filter(|&m| stiffness[(m, m)] > 0.0)
                .map(|m| (stiffness[(m, m)] / (self.mode_inertia(m) + self.sweep.infinite[(m, m)])).sqrt())
                .fold(0.0, f64::max);
        let steps = 30_000;
        let d_omega = top / steps as f64;
        let inertia = self.coupled_inertia();
        let force: nalgebra::Vector6<Complex64> = stiffness.column(mode).map(|c| Complex64::new(c, 0.0));
        let response: Vec<(f64, f64)> = (1..=steps)
            .filter_map(|n| {
                let omega = n as f64 * d_omega;
                let y = self.impedance(&inertia, omega).lu().solve(&force)?;
                Some((omega, y[mode].re))
            })
            .collect();
        Some(
            times
                .iter()
                .map(|&t| {
                    let s: f64 = response
                        .iter()
                        .map(|&(w, re)| re * (w * t).sin() / w)
                        .sum::<f64>()
                        * d_omega
                        * 2.0
                        / std::f64::consts::PI;
                    x0 * (1.0 - s)
                })
                .collect(),
        )
    }

    /// The inertia the time domain gives the six modes: the body's mass
    /// and inertia with A∞'s translational and rotational blocks (its
    /// cross blocks left out, as the time domain leaves them).
    fn coupled_inertia(&self) -> Matrix6<f64> {
        let infinite = &self.sweep.infinite;
        Matrix6::from_fn(|i, j| {
            let own = match (i < 3, j < 3) {
                (true, true) if i == j => self.mass,
                (false, false) => self.inertia[(i - 3, j - 3)],
                _ => 0.0,
            };
            let blocks = if (i < 3) == (j < 3) { infinite[(i, j)] } else { 0.0 };
            own + blocks
        })
    }

    /// `C − ω² (M + A∞ + A(ω) − A∞) − i ω B(ω)` over the six modes as the
    /// time domain couples them: `inertia` from
    /// [`coupled_inertia`](Self::coupled_inertia), each mode's memory on
    /// the diagonal.
    fn impedance(&self, inertia: &Matrix6<f64>, omega: f64) -> nalgebra::Matrix6<Complex64> {
        let stiffness = &self.hydrostatics.stiffness;
        let infinite = &self.sweep.infinite;
        nalgebra::Matrix6::<Complex64>::from_fn(|i, j| {
            let (a, b) = if i == j {
                let (a, b) = self.coefficients(i, omega);
                (a - infinite[(i, i)], b)
            } else {
                (0.0, 0.0)
            };
            Complex64::new(
                stiffness[(i, j)] - omega * omega * (inertia[(i, j)] + a),
                -omega * b,
            )
        })
    }

    /// The wave excitation of `mode` (N or N·m per metre of wave
    /// amplitude; phase relative to the incident crest at the centre of
    /// mass) in regular waves of frequency `omega` (rad/s) travelling along
    /// `heading` (rad, from +x toward +z, axes at rest): diffraction and
    /// Froude–Krylov together, by the Haskind relation. Linear in ω between
    /// the frequencies solved and in heading between every 45°; `None`
    /// outside the frequencies solved.
    pub fn excitation(&self, mode: usize, omega: f64, heading: f64) -> Option<Complex64> {
        self.interpolate(&self.excitation, mode, omega, heading)
    }

    /// The linear part of the wave force and moments soak's texels give,
    /// their pressure hydrostatic under the local surface (no decay of the
    /// wave's pressure with depth and no diffraction), in the same regular
    /// waves as [`RadiationModel::excitation`]: for heave the columns of
    /// water under the surface, `ρ g ∫ e^{i k·x} dA` over the water-plane;
    /// for surge and sway the push the sloping surface gives the hull,
    /// `−i k (cos β, sin β) ρ g ∫_V e^{i k·x} dV` over the displaced
    /// volume; for roll, yaw and pitch the moments of both about the
    /// centre of mass. In long waves roll and pitch are the restoring
    /// moment `ρ g V GM` times the surface's slope. N or N·m per metre of
    /// wave amplitude, same phase. `None` outside the frequencies solved.
    pub fn column_excitation(&self, mode: usize, omega: f64, heading: f64) -> Option<Complex64> {
        self.interpolate(&self.columns, mode, omega, heading)
    }

    /// What linear theory's excitation adds to the columns' force in
    /// regular waves of frequency `omega` (rad/s) along `heading` (rad,
    /// axes at rest), per metre of amplitude, phase relative to the crest
    /// at the centre of mass ([`RadiationModel::excitation`] −
    /// [`RadiationModel::column_excitation`]): the pressure's decay with
    /// depth (the Smith effect) and the diffraction. It vanishes in long
    /// waves: below the frequencies solved it falls as ω² to none at
    /// ω = 0; above them the excitation is taken to fall on as
    /// `e^{−k d}` (d the centre of buoyancy's depth) from the last one
    /// solved and the columns' force is summed panel by panel. Zero for
    /// a mode out of range or a frequency that is not finite and positive.
    pub fn excitation_beyond_columns(&self, mode: usize, omega: f64, heading: f64) -> Complex64 {
        if mode >= 6 {
            return Complex64::new(0.0, 0.0);
        }
        self.excitations_beyond_columns(omega, heading)[mode]
    }

    /// [`RadiationModel::excitation_beyond_columns`] of the six modes at
    /// once (past the sweep the texels' part is summed over the panels
    /// once for all six).
    pub fn excitations_beyond_columns(&self, omega: f64, heading: f64) -> [Complex64; 6] {
        let zero = Complex64::new(0.0, 0.0);
        let f = &self.sweep.frequencies;
        let (Some(first), Some(last)) = (f.first(), f.last()) else {
            return [zero; 6];
        };
        if !(omega.is_finite() && omega > 0.0) {
            return [zero; 6];
        }
        let difference = |mode: usize, omega: f64| {
            self.excitation(mode, omega, heading).unwrap_or(zero)
                - self.column_excitation(mode, omega, heading).unwrap_or(zero)
        };
        if omega < first.omega {
            std::array::from_fn(|mode| difference(mode, first.omega) * (omega / first.omega).powi(2))
        } else if omega <= last.omega {
            std::array::from_fn(|mode| difference(mode, omega))
        } else {
            let g = self.gravity;
            let (k, k_last) = (omega * omega / g, last.omega * last.omega / g);
            let depth = (-self.hydrostatics.center_of_buoyancy.y).max(0.0);
            let columns = column_forces(&self.waterline, k, heading, self.density * g);
            std::array::from_fn(|mode| {
                let x = self.excitation(mode, last.omega, heading).unwrap_or(zero)
                    * (-(k - k_last) * depth).exp();
                x - columns[mode]
            })
        }
    }

    /// `table` (per frequency, per heading, per mode) linear in ω between
    /// the frequencies solved and in heading between every 45°.
    fn interpolate(
        &self,
        table: &[[[Complex64; 6]; HEADINGS]],
        mode: usize,
        omega: f64,
        heading: f64,
    ) -> Option<Complex64> {
        let f = &self.sweep.frequencies;
        let (first, last) = (f.first()?.omega, f.last()?.omega);
        if !(omega >= first && omega <= last) || mode >= 6 || !heading.is_finite() {
            return None;
        }
        let k = f.partition_point(|c| c.omega <= omega).clamp(1, f.len() - 1) - 1;
        let t = (omega - f[k].omega) / (f[k + 1].omega - f[k].omega);
        let turn = heading.rem_euclid(std::f64::consts::TAU) / (std::f64::consts::TAU / HEADINGS as f64);
        let h = (turn.floor() as usize).min(HEADINGS - 1);
        let u = turn - h as f64;
        let at = |k: usize| table[k][h][mode] * (1.0 - u) + table[k][(h + 1) % HEADINGS][mode] * u;
        Some(at(k) * (1.0 - t) + at(k + 1) * t)
    }

    /// The response amplitude operator of `mode` alone (its couplings
    /// left out; [`RadiationModel::coupled_rao`] moves heave, roll and
    /// pitch together as the time domain does): `|X / (C − ω² (M + A) −
    /// i ω B)|`,
    /// m or rad per metre of wave amplitude, in regular waves of frequency
    /// `omega` along `heading` (see [`RadiationModel::excitation`]).
    pub fn rao(&self, mode: usize, omega: f64, heading: f64) -> Option<f64> {
        let x = self.excitation(mode, omega, heading)?;
        let (a, b) = self.coefficients(mode, omega);
        let c = self.hydrostatics.stiffness[(mode, mode)];
        let h = Complex64::new(c - omega * omega * (self.mode_inertia(mode) + a), -omega * b);
        Some((x / h).norm())
    }

    /// The response amplitude operators of heave, roll and pitch moving
    /// together, as the time domain moves them (m or rad per metre of wave
    /// amplitude, `[heave, roll, pitch]`), in regular waves of frequency
    /// `omega` (rad/s) along `heading` (rad, axes at rest): `|ξ|` of `Z ξ
    /// = X` over the three modes with stiffness, `Z` the impedance the
    /// release integrates (the stiffness' couplings, A∞'s blocks, each
    /// mode's memory its own) and `X` their wave excitation. Surge, sway
    /// and yaw are left out: the time domain gives them the texels'
    /// forces, not linear theory's. For a body symmetric about its centre
    /// of mass each is [`RadiationModel::rao`]. `None` outside the
    /// frequencies solved.
    pub fn coupled_rao(&self, omega: f64, heading: f64) -> Option<[f64; 3]> {
        const MODES: [usize; 3] = [1, 3, 5];
        let z = self.impedance(&self.coupled_inertia(), omega);
        let z = nalgebra::Matrix3::<Complex64>::from_fn(|i, j| z[(MODES[i], MODES[j])]);
        let mut x = nalgebra::Vector3::<Complex64>::zeros();
        for (i, &mode) in MODES.iter().enumerate() {
            x[i] = self.excitation(mode, omega, heading)?;
        }
        let xi = z.lu().solve(&x)?;
        Some([xi[0].norm(), xi[1].norm(), xi[2].norm()])
    }

    /// The orientation the model reads a body turned by `rotation` (object
    /// → water) in: its rest orientation turned about the vertical by the
    /// body's yaw from it (the twist about y of `rotation · rest⁻¹`). The
    /// wetted hull of a floating body tilts little from its rest, and
    /// linear theory's modes are the water's: a ball rolling over keeps its
    /// heave vertical and a boat its roll about its own length as it turns.
    /// The rest orientation itself where the yaw is undefined (a body
    /// turned upside down about a horizontal axis).
    pub fn heading(&self, rotation: &UnitQuaternion<f64>) -> UnitQuaternion<f64> {
        let turn = rotation * self.rotation.inverse();
        let q = turn.quaternion();
        let twist = nalgebra::Quaternion::new(q.w, 0.0, q.j, 0.0);
        if twist.norm() < 1e-9 {
            return self.rotation;
        }
        UnitQuaternion::from_quaternion(twist) * self.rotation
    }

    /// A∞'s translational block in the water's axes for a body turned by
    /// `rotation` (object → water), kg, and its rotational block in object
    /// axes, kg·m² (the cross blocks are left out, see [`RadiationModel`]).
    pub fn infinite_blocks(&self, rotation: &UnitQuaternion<f64>) -> (Matrix3<f64>, Matrix3<f64>) {
        let a = &self.sweep.infinite;
        let linear: Matrix3<f64> = a.fixed_view::<3, 3>(0, 0).into();
        let angular: Matrix3<f64> = a.fixed_view::<3, 3>(3, 3).into();
        let frame = (rotation * self.rotation.inverse())
            .to_rotation_matrix()
            .into_inner();
        let rest = self.rotation.to_rotation_matrix().into_inner();
        (
            frame * linear * frame.transpose(),
            rest.transpose() * angular * rest,
        )
    }
}

/// Checks that `added` (6×6) is symmetric as theory says: each pair of
/// modes within 0.2 of `√(A_ii A_jj)` (pairs whose scale is below 1e-9 of
/// the largest such product are not judged: a sphere's roll has none).
fn reciprocal(added: &Matrix6<f64>) -> Result<(), SeakeepingError> {
    let scale = |i: usize, j: usize| (added[(i, i)] * added[(j, j)]).max(0.0).sqrt();
    let largest = (0..6)
        .flat_map(|i| (0..6).map(move |j| (i, j)))
        .map(|(i, j)| scale(i, j))
        .fold(0.0, f64::max);
    for i in 0..6 {
        for j in i + 1..6 {
            let s = scale(i, j);
            let difference = (added[(i, j)] - added[(j, i)]).abs();
            if s > 1e-9 * largest && difference > 0.2 * s || !difference.is_finite() {
                return Err(SeakeepingError::NotReciprocal {
                    i,
                    j,
                    ratio: difference / s,
                });
            }
        }
    }
    Ok(())
}

/// Whether `kernel` takes energy from every motion, to within a hundredth
/// of its largest damping: its `Re T(ω)` over 400 frequencies to 8×
/// `last` (rad/s, the sweep's last; past them the fit's poles decay it).
/// A kernel with a band of negative damping feeds a body moving at those
/// frequencies; the refits of the boat, the barge and the sphere dip
/// below zero by a few thousandths of their peak, below 2 rad/s where
/// B vanishes.
fn passive(kernel: &Kernel, last: f64) -> bool {
    let damping: Vec<f64> = (1..=400)
        .map(|n| kernel.transform(last * 8.0 * n as f64 / 400.0).re)
        .collect();
    let largest = damping.iter().fold(0.0f64, |m, b| m.max(b.abs()));
    damping.iter().all(|&b| b.is_finite() && b >= -0.01 * largest)
}

/// The period (s: the mean spacing of the first four downward zero
/// crossings) and the decay per cycle (the mean ratio of the first two
/// pairs of successive positive peaks, the release `x[0]` counted as the
/// first) of a free decay `x` sampled every `dt` (s) from a positive
/// release. A peak below a tenth of the release ends both: a heave
/// damped a quarter of critical (a boat's) falls to a fifth in its first
/// cycle, and its next peak and the crossings after it, at a few
/// thousandths of the release, measure more of what is not the linear
/// decay (a hull's flare, the last millimetre of its rest, a fit's
/// residual) than of the decay: two curves a hundredth of the release
/// apart gave periods 2 % apart from their third and fourth crossings.
/// `None` with fewer than two crossings before that peak.
pub fn decay_measure(x: &[f64], dt: f64) -> Option<(f64, f64)> {
    let release = *x.first()?;
    let floor = 0.1 * release;
    // The positive peaks after the release, with their samples.
    let peaks: Vec<(usize, f64)> = x
        .windows(3)
        .enumerate()
        .filter(|(_, w)| w[1] > w[0] && w[1] >= w[2] && w[1] > 0.0)
        .map(|(n, w)| (n + 1, w[1]))
        .collect();
    let end = peaks.iter().find(|p| p.1 < floor).map_or(x.len(), |p| p.0);
    let crossings: Vec<f64> = x[..end]
        .windows(2)
        .enumerate()
        .filter(|(_, w)| w[0] > 0.0 && w[1] <= 0.0)
        .map(|(n, w)| (n as f64 + w[0] / (w[0] - w[1])) * dt)
        .take(4)
        .collect();
    if crossings.len() < 2 {
        return None;
    }
    let period = (crossings[crossings.len() - 1] - crossings[0]) / (crossings.len() - 1) as f64;
    let ratios: Vec<f64> = std::iter::once(release)
        .chain(peaks.iter().map(|p| p.1))
        .collect::<Vec<_>>()
        .windows(2)
        .take(2)
        .take_while(|p| p[1] >= floor)
        .map(|p| p[1] / p[0])
        .collect();
    (!ratios.is_empty()).then(|| (period, ratios.iter().sum::<f64>() / ratios.len() as f64))
}

/// How many headings the excitation is computed at (every 45°).
const HEADINGS: usize = 8;

/// The linear wave force and moments per metre of amplitude of a
/// pressure hydrostatic under the surface (`p = ρ g (a f − y)`, `f =
/// e^{i k (x cos β + z sin β)}`), in regular waves of wavenumber `k` (1/m)
/// along `heading` β (rad), `weight` = ρ g, about the centre of mass at
/// (0, h, 0). The wetted hull and the lid at y = 0 close the displaced
/// volume V, so over the hull `−∫ p n dS = ρ g a (∫_lid f ŷ dA − ∫_V ∇f
/// dV)` and `−∫ p r × n dS = ρ g a (∫_lid f r × ŷ dA + ∫_V ∇f × r dV)`:
/// heave is the water-plane's columns, `ρ g ∫ f dA` (summed over the
/// panels as `Σ (−n_y A) f`: the lid's integral of a function of x and z
/// is minus the hull's); roll and pitch are the columns' moments (`−∫ z f
/// dA`, `∫ x f dA`) and the moment of the horizontal push `−ρ g ∫_V ∇f
/// dV`, `−i k sin β ∫_V f (y − h) dV` about x and `i k cos β ∫_V f (y −
/// h) dV` about z (`∫_V g(x, z) (y − h) dV = ∮ g (y²/2 − h y) n_y dS`),
/// the push itself `−i k (cos β, 0, sin β) ρ g ∫_V f dV` (`∫_V g dV = ∮
/// g y n_y dS`) and its moment about y `i k ρ g ∫_V f (x sin β − z cos β)
/// dV`; each integral by the edge-midpoint rule. Long waves tilt the
/// water as a slope would: roll and pitch are then the restoring moment
/// `ρ g V GM` times the slope, where the columns alone give `ρ g V BM`,
/// and the push is the displaced water's weight times the slope.
fn column_forces(waterline: &[[f64; 5]], k: f64, heading: f64, weight: f64) -> [Complex64; 6] {
    let (cos, sin) = (heading.cos(), heading.sin());
    let mut out = [Complex64::new(0.0, 0.0); 6];
    let ik = Complex64::new(0.0, k);
    for &[x, z, area, volume, lever] in waterline {
        let (s, c) = (k * (x * cos + z * sin)).sin_cos();
        let f = Complex64::new(c, s) * weight;
        let push = ik * f * lever;
        let along = ik * f * volume;
        out[0] -= along * cos;
        out[1] += f * area;
        out[2] -= along * sin;
        out[3] -= f * area * z + push * sin;
        out[4] += along * (x * sin - z * cos);
        out[5] += f * area * x + push * cos;
    }
    out
}

/// The pose of `body` turned by `rotation` with its centre of mass at
/// (0, `height`, 0).
fn rest_pose(body: &FloatingBody<'_>, rotation: &UnitQuaternion<f64>, height: f64) -> Isometry3<f64> {
    let com = rotation * body.center_of_mass.coords;
    Isometry3::from_parts(
        Translation3::from(Vector3::new(-com.x, height - com.y, -com.z)),
        *rotation,
    )
}

/// The orientation `body` floats stably in nearest `body.rotation`: the
/// least potential energy of body and water, `m g (y_G − y_B)` with the
/// draft that displaces its mass at each orientation, by a compass search
/// over tilts about the world's x and z axes from `body.rotation` (steps
/// from 15° down to 0.01°; only a lower energy moves it, so a body already
/// stable, or indifferent like a sphere, stays as it is). A body placed in
/// an unstable balance (a square log upright) rolls off it.
fn settle(body: &FloatingBody<'_>, mesh: &Mesh, target: f64) -> Result<UnitQuaternion<f64>, SeakeepingError> {
    let probe = FloatingBody { mesh, ..*body };
    let energy = |tilt: [f64; 2]| -> Result<f64, SeakeepingError> {
        let rotation = turned(&body.rotation, tilt);
        let height = float_height(&probe, &rotation, target)?;
        let panels = wetted_panels(mesh, &rest_pose(&probe, &rotation, height), 1e9)?;
        let volume = displaced(&panels);
        let moment: f64 = panels
            .iter()
            .map(|p| p.normal.y * quadratic(p, |q| 0.5 * q.y * q.y))
            .sum();
        Ok(height - moment / volume)
    };
    let mut at = [0.0, 0.0];
    let mut best = energy(at)?;
    let mut step = 15f64.to_radians();
    // Only a clear improvement moves it: rounding in an indifferent
    // body's energy must not.
    let scale = body
        .mesh
        .positions
        .iter()
        .map(|p| (p - body.center_of_mass).norm())
        .fold(0.0f64, f64::max);
    while step > 0.01f64.to_radians() {
        let mut moved = false;
        for (axis, sign) in [(0, 1.0), (0, -1.0), (1, 1.0), (1, -1.0)] {
            let mut next = at;
            next[axis] += sign * step;
            let e = energy(next)?;
            if e < best - 1e-9 * scale {
                (at, best, moved) = (next, e, true);
                break;
            }
        }
        if !moved {
            step *= 0.5;
        }
    }
    Ok(turned(&body.rotation, at))
}

/// `rotation` tilted by `tilt[0]` about the world's x axis, then
/// `tilt[1]` about its z axis, rad.
fn turned(rotation: &UnitQuaternion<f64>, tilt: [f64; 2]) -> UnitQuaternion<f64> {
    UnitQuaternion::from_axis_angle(&Vector3::z_axis(), tilt[1])
        * UnitQuaternion::from_axis_angle(&Vector3::x_axis(), tilt[0])
        * rotation
}

/// `∫ y n_y dS` over `panels`: the volume under y = 0 they close with
/// the still water plane (exact: y is linear on a flat panel).
fn displaced(panels: &[Panel]) -> f64 {
    panels.iter().map(|p| p.area * p.normal.y * p.centroid.y).sum()
}

/// The height of the centre of mass at which `body` turned by `rotation`
/// displaces `target` m³, by bisection.
fn float_height(
    body: &FloatingBody<'_>,
    rotation: &UnitQuaternion<f64>,
    target: f64,
) -> Result<f64, SeakeepingError> {
    let com = rotation * body.center_of_mass.coords;
    let reach = body
        .mesh
        .positions
        .iter()
        .map(|p| (rotation * p.coords - com).norm())
        .fold(0.0f64, f64::max);
    if !reach.is_finite() || reach <= 0.0 {
        return Err(SeakeepingError::BadParameter {
            name: "mesh extent",
            value: reach,
        });
    }
    let volume = |height: f64| -> Result<f64, SeakeepingError> {
        match wetted_panels(body.mesh, &rest_pose(body, rotation, height), 1e9) {
            Ok(panels) => Ok(displaced(&panels)),
            Err(SeakeepingError::NoWettedSurface) => Ok(0.0),
            Err(e) => Err(e),
        }
    };
    let (mut low, mut high) = (-1.01 * reach, 1.01 * reach);
    let whole = volume(low)?;
    // Neutral within 0.1 % floats with no water-plane: refused with the
    // heavy ones.
    if target >= (1.0 - 1e-3) * whole {
        return Err(SeakeepingError::Sinks {
            displaced: target,
            volume: whole,
        });
    }
    for _ in 0..60 {
        let mid = 0.5 * (low + high);
        if volume(mid)? > target {
            low = mid;
        } else {
            high = mid;
        }
    }
    Ok(0.5 * (low + high))
}

/// The edge-midpoint rule over a flat polygon: per fan triangle, a third
/// of its area (m²) and its three edge midpoints (exact for quadratics).
fn edge_midpoints(panel: &Panel) -> impl Iterator<Item = (f64, [Point3<f64>; 3])> + '_ {
    let v = &panel.vertices;
    (1..v.len().saturating_sub(1)).map(move |k| {
        let (a, b, c) = (v[0], v[k], v[k + 1]);
        let area = 0.5 * (b - a).cross(&(c - a)).norm();
        let mid = |p: Point3<f64>, q: Point3<f64>| Point3::from((p.coords + q.coords) * 0.5);
        (area / 3.0, [mid(a, b), mid(b, c), mid(c, a)])
    })
}

/// Exact integral over a flat polygon of a quadratic `f`
/// ([`edge_midpoints`]).
fn quadratic(panel: &Panel, f: impl Fn(&Point3<f64>) -> f64) -> f64 {
    edge_midpoints(panel)
        .map(|(third, [a, b, c])| third * (f(&a) + f(&b) + f(&c)))
        .sum()
}

fn hydrostatics(panels: &[Panel], height: f64, rho: f64, g: f64) -> Hydrostatics {
    let volume = displaced(panels);
    // ∫_V x dV = ∮ x y n_y dS, ∫_V y dV = ∮ ½ y² n_y dS; the lid at y = 0
    // adds nothing to either.
    let moment = |f: &dyn Fn(&Point3<f64>) -> f64| -> f64 {
        panels.iter().map(|p| p.normal.y * quadratic(p, f)).sum()
    };
    let bx = moment(&|p| p.x * p.y) / volume;
    let by = moment(&|p| 0.5 * p.y * p.y) / volume;
    let bz = moment(&|p| p.z * p.y) / volume;
    // The lid's integrals: ∮ f n_y dS = 0 for f independent of y.
    let area = -panels.iter().map(|p| p.area * p.normal.y).sum::<f64>();
    let xx = -moment(&|p| p.x * p.x);
    let zz = -moment(&|p| p.z * p.z);
    let (x1, z1, xz) = (-moment(&|p| p.x), -moment(&|p| p.z), -moment(&|p| p.x * p.z));
    let mut stiffness = Matrix6::zeros();
    stiffness[(1, 1)] = rho * g * area;
    // Rotation about x tilts z into y, about z tilts x: the water-plane's
    // moment, plus the displaced volume's lever between buoyancy and
    // weight (the two equal at rest: m g = ρ g V).
    let lever = volume * (by - height);
    stiffness[(3, 3)] = rho * g * (zz + lever);
    stiffness[(5, 5)] = rho * g * (xx + lever);
    // A water-plane whose centre is not under the centre of mass couples
    // them: a point (x, z) of it rises by `η + x θ_z − z θ_x`.
    for (i, j, c) in [(1, 3, -z1), (1, 5, x1), (3, 5, -xz)] {
        stiffness[(i, j)] = rho * g * c;
        stiffness[(j, i)] = rho * g * c;
    }
    Hydrostatics {
        volume,
        center_of_buoyancy: Point3::new(bx, by, bz),
        center_of_mass_height: height,
        waterplane_area: area,
        waterplane_moments: [xx, zz],
        stiffness,
    }
}

/// A body's memory of its motion for its [`RadiationModel`]: one state
/// per kernel pole, and the last velocity recorded and when. Saved and
/// restored bit for bit with serde.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct RadiationState {
    memory: Vec<Memory>,
    /// The last velocity, axes at rest (m/s and rad/s), and when, s.
    last: Option<([f64; 6], f64)>,
    /// The velocity recorded before the last, and when.
    #[serde(default)]
    previous: Option<([f64; 6], f64)>,
    /// The step factors of the last step's length, per mode (not state:
    /// not saved, never compared).
    #[serde(skip)]
    steps: StepCache,
}

/// The factors of the last step's length and of the last look ahead
/// ([`RadiationState::force_ahead`]), the model's shared copy: looked up
/// again when either changes.
#[derive(Clone, Debug, Default)]
struct StepCache {
    step: Option<Factors>,
    ahead: Option<Factors>,
}

/// A length's bits and the factors of every mode's kernel for it.
type Factors = (u64, Arc<[KernelStep]>);

/// The factors of the few step lengths a model's bodies step it by,
/// computed once for all of them: a thousand bodies of one mesh read one
/// copy (each body's own copy of its factors made the memory's step read
/// kilobytes per body that no cache kept). Not state: a clone starts
/// empty.
#[derive(Default)]
struct SharedSteps(Mutex<Vec<Factors>>);

/// How many step lengths a model keeps factors for: the step's and the
/// look ahead's, and room for a change of step.
const SHARED_STEPS: usize = 4;

impl SharedSteps {
    /// The factors for `dt` (s), computed from `kernels` if none are kept.
    fn get(&self, kernels: &[Kernel], dt: f64) -> Arc<[KernelStep]> {
        // A poisoned lock holds factors still whole (they are pushed once
        // computed): read on.
        let mut kept = self.0.lock().unwrap_or_else(std::sync::PoisonError::into_inner);
        if let Some((_, factors)) = kept.iter().find(|(bits, _)| *bits == dt.to_bits()) {
            return Arc::clone(factors);
        }
        let factors: Arc<[KernelStep]> = kernels.iter().map(|k| k.step(dt)).collect();
        if kept.len() == SHARED_STEPS {
            kept.remove(0);
        }
        kept.push((dt.to_bits(), Arc::clone(&factors)));
        factors
    }
}

impl Clone for SharedSteps {
    fn clone(&self) -> Self {
        Self::default()
    }
}

impl std::fmt::Debug for SharedSteps {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("SharedSteps").finish_non_exhaustive()
    }
}

/// `cached`'s factors for `dt`, taken from the model's if they were for
/// another length (the same arithmetic either way, so the memory does
/// not depend on what was cached).
fn factors<'a>(cached: &'a mut Option<Factors>, model: &RadiationModel, dt: f64) -> &'a [KernelStep] {
    if !matches!(cached, Some((bits, _)) if *bits == dt.to_bits()) {
        *cached = Some((dt.to_bits(), model.steps.get(&model.kernels, dt)));
    }
    cached.as_ref().map_or(&[], |(_, f)| &f[..])
}

impl PartialEq for StepCache {
    fn eq(&self, _: &Self) -> bool {
        true
    }
}

impl RadiationState {
    /// At rest, no history.
    pub fn new(model: &RadiationModel) -> Self {
        Self {
            memory: model.kernels.iter().map(Memory::new).collect(),
            last: None,
            previous: None,
            steps: StepCache::default(),
        }
    }

    /// Whether it fits `model` (as many states per mode).
    pub fn fits(&self, model: &RadiationModel) -> bool {
        self.memory.len() == model.kernels.len()
            && self
                .memory
                .iter()
                .zip(&model.kernels)
                .all(|(m, k)| m.len() == k.poles.len())
    }

    /// The body's velocity in the axes at rest turned with the body:
    /// `v` (m/s, of the centre of mass) and `w` (rad/s), world, for a body
    /// turned by `rotation` (object → world).
    pub fn local_velocity(
        model: &RadiationModel,
        rotation: &UnitQuaternion<f64>,
        v: &Vector3<f64>,
        w: &Vector3<f64>,
    ) -> [f64; 6] {
        let frame = rotation * model.rotation.inverse();
        let (v, w) = (frame.inverse() * v, frame.inverse() * w);
        [v.x, v.y, v.z, w.x, w.y, w.z]
    }

    /// Whether it has recorded a velocity (a body that has stepped with
    /// it at least once).
    pub fn has_history(&self) -> bool {
        self.last.is_some()
    }

    /// Takes the body's velocity now (axes at rest, [`Self::local_velocity`])
    /// at `time` (s): the memory advances from the last time exactly for a
    /// velocity linear in between. The first call only records it; a time
    /// not after the last replaces the last velocity without advancing. A
    /// velocity or time that is not finite is refused (nothing changes).
    pub fn record(&mut self, model: &RadiationModel, velocity: [f64; 6], time: f64) {
        if !(velocity.iter().all(|v| v.is_finite()) && time.is_finite()) {
            return;
        }
        if let Some((last, then)) = self.last
            && time > then
        {
            let steps = factors(&mut self.steps.step, model, time - then);
            for ((memory, step), (v0, v1)) in
                self.memory.iter_mut().zip(steps).zip(last.iter().zip(&velocity))
            {
                memory.advance_by(step, *v0, *v1);
            }
            self.previous = self.last;
        }
        self.last = Some((velocity, time));
    }

    /// The memory force now, `−∫ K(t − τ) ẋ(τ) dτ` per mode (N, N·m),
    /// axes at rest.
    pub fn force(&self, model: &RadiationModel) -> Vector6<f64> {
        Vector6::from_fn(|mode, _| -self.memory[mode].force(&model.kernels[mode]))
    }

    /// The memory force `h` (s) after the last velocity recorded, the
    /// velocity carried on at the rate it changed since the one before
    /// (N, N·m; axes at rest). The engine holds a force over its step:
    /// the memory's at the step's middle is the one that step should hold
    /// (`h = dt/2`). Held at the step's start instead, the force lagged
    /// the motion by half a step, as much as taking `B dt/2` off the
    /// inertia: a boat's heave, damped a quarter of critical at 0.7 Hz,
    /// came out 3.4 % short in period at dt = 1/60 s, and 1.1 % short
    /// (as at 1/960 s) taken at the middle. [`Self::force`] before two
    /// velocities are recorded or for `h` not positive.
    pub fn force_ahead(&mut self, model: &RadiationModel, h: f64) -> Vector6<f64> {
        let (Some((v, t)), Some((p, tp))) = (self.last, self.previous) else {
            return self.force(model);
        };
        if !(t > tp && h > 0.0 && h.is_finite()) {
            return self.force(model);
        }
        let ahead = factors(&mut self.steps.ahead, model, h);
        Vector6::from_fn(|mode, _| {
            let change = (v[mode] - p[mode]) / (t - tp) * h;
            -self.memory[mode].force_after(&ahead[mode], v[mode], v[mode] + change)
        })
    }

    /// [`Self::force_ahead`] in the world, as [`Self::world_force`].
    pub fn world_force_ahead(
        &mut self,
        model: &RadiationModel,
        rotation: &UnitQuaternion<f64>,
        h: f64,
    ) -> (Vector3<f64>, Vector3<f64>) {
        let f = self.force_ahead(model, h);
        let frame = rotation * model.rotation.inverse();
        (
            frame * Vector3::new(f[0], f[1], f[2]),
            frame * Vector3::new(f[3], f[4], f[5]),
        )
    }

    /// The memory force as a force and torque in the world (N, N·m about
    /// the centre of mass) for a body turned by `rotation`.
    pub fn world_force(
        &self,
        model: &RadiationModel,
        rotation: &UnitQuaternion<f64>,
    ) -> (Vector3<f64>, Vector3<f64>) {
        let f = self.force(model);
        let frame = rotation * model.rotation.inverse();
        (
            frame * Vector3::new(f[0], f[1], f[2]),
            frame * Vector3::new(f[3], f[4], f[5]),
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_kernel_that_feeds_motion_is_not_passive() {
        // K(t) = e^{−t}: damping 1/(1 + ω²) at every frequency.
        let one = |c: f64| Kernel {
            poles: vec![Complex64::new(-1.0, 0.0)],
            residues: vec![Complex64::new(c, 0.0)],
        };
        assert!(passive(&one(1.0), 5.0));
        assert!(!passive(&one(-1.0), 5.0));
        // A damped oscillation at 2 rad/s on top, whose damping is
        // negative over a band: passive while the band dips less than a
        // hundredth of the largest damping.
        let with = |c: f64| Kernel {
            poles: vec![
                Complex64::new(-1.0, 0.0),
                Complex64::new(-0.05, 2.0),
                Complex64::new(-0.05, -2.0),
            ],
            residues: vec![
                Complex64::new(1.0, 0.0),
                Complex64::new(0.0, c),
                Complex64::new(0.0, -c),
            ],
        };
        assert!(passive(&with(0.0), 5.0));
        assert!(!passive(&with(0.5), 5.0));
        let dip = (1..=400)
            .map(|n| with(0.5).transform(40.0 * n as f64 / 400.0).re)
            .fold(f64::INFINITY, f64::min);
        assert!(dip < -0.01, "{dip}");
    }

    #[test]
    fn an_added_mass_that_is_not_symmetric_is_refused() {
        // A sphere's: symmetric, no rotational part (judged on its
        // translations alone).
        let sphere = Matrix6::from_diagonal(&Vector6::new(72.4, 129.1, 71.1, 0.0, 0.0, 0.0));
        assert_eq!(reciprocal(&sphere), Ok(()));
        // A boat's, within a few parts in a thousand: accepted.
        let mut boat = Matrix6::from_diagonal(&Vector6::new(25.9, 934.3, 332.1, 9.6, 308.7, 469.8));
        boat[(0, 5)] = -74.8;
        boat[(5, 0)] = -74.4;
        boat[(2, 3)] = 42.4;
        boat[(3, 2)] = 42.3;
        assert_eq!(reciprocal(&boat), Ok(()));
        // The same boat with the waterline strip's sway-heave term:
        // −1,589 kg one way, 1.6 kg the other.
        let mut broken = boat;
        broken[(2, 1)] = -1588.6;
        broken[(1, 2)] = 1.6;
        match reciprocal(&broken) {
            Err(SeakeepingError::NotReciprocal { i: 1, j: 2, ratio }) => {
                assert!(
                    (ratio - 1590.2 / (934.3f64 * 332.1).sqrt()).abs() < 1e-9,
                    "{ratio}"
                );
            }
            other => panic!("{other:?}"),
        }
        let mut nan = boat;
        nan[(4, 1)] = f64::NAN;
        assert!(matches!(
            reciprocal(&nan),
            Err(SeakeepingError::NotReciprocal { i: 1, j: 4, .. })
        ));
    }
}
