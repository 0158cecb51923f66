//! The implicit heave, pitch and roll integrator: the buoyancy of a body
//! stiff for the step, solved at the pose the step would end at
//! ([`implicit_heave`]), and how implicit the step is ([`implicit_weight`]).

use nalgebra::{Isometry3, Matrix3, Translation3, UnitQuaternion, Vector3};
use soak_hydro::{BodyState, BuoyancyMode, HydroOptions, SurfaceKind, Water, Wrench};

use crate::body::{Shape, SoakBody};
use crate::engine::EngineBody;
use crate::inertial::Inertial;
use crate::predicted_step::Step;

/// Below this weight `θ` of the implicit part of the heave step (see
/// [`implicit_heave`]) the step is left explicit, and the evaluations the
/// implicit solve needs are saved: it would change the net vertical force
/// by about `θ` of itself.
pub(crate) const IMPLICIT_NEGLIGIBLE: f64 = 1e-3;

/// `θ = w⁴/(1 + w⁴)`, `w = c ρ_w g A dt²/m` with `A` the bound
/// [`Shape::water_plane`]: how implicit the heave step is (see
/// [`implicit_heave`]).
pub(crate) fn implicit_weight(water: &Water, shape: &Shape, m: f64, dt: f64, substeps: f64) -> f64 {
    let c = (substeps + 1.0) / (2.0 * substeps);
    let w = c * water.density * water.gravity * shape.water_plane * dt * dt / m;
    let w4 = (w * w) * (w * w);
    w4 / (1.0 + w4)
}

/// The buoyancy with its restoring part integrated implicitly in heave,
/// where the body is stiff for the step.
///
/// The engine holds the force constant over the step, so a buoyancy whose heave
/// period is shorter than the step (a light millimetre body at dt = 1/10 s)
/// is applied far beyond the pose it was evaluated at and flings the body
/// out of the water, or lets it fall for a whole step before the water
/// answers. The engine's symplectic Euler (Rapier's) over `s` substeps `h = dt/s` with a
/// constant acceleration `a` moves the centre of mass to
///
/// `y' = y + dt v + c dt² a`, `c = (s + 1)/(2s)`.
///
/// Backward Euler on that step evaluates the vertical force at `y'` itself:
/// `a = F_y(y')/m − g`. Linearised, `F_y(y) ≈ F₀ − k (y − y₀)` with
/// `k = ρ_w g A_wp` and `y₀ = y + β dt v` the predicted pose the generator
/// evaluates at, that is
///
/// `F − m g = ((F₀ − m g) − k (1 − β) dt v) / (1 + c k dt²/m)`,
///
/// stable for any `dt` (the heave mode lands on its equilibrium in one step
/// when `k dt²/m ≫ 1`). But it damps heave (damping ratio about `ω dt / 2`),
/// which the explicit lookahead step does not do, and buoyancy is far from
/// linear over a stiff step (a body dropping out of the air and under the
/// surface within one step). So the generator blends and solves the
/// nonlinear equation instead: the vertical force is evaluated at
///
/// `y_e = y₀ + θ ((1 − β) dt v + c dt² a)`, `a = F_y(y_e)/m − g`,
///
/// with `θ = w⁴/(1 + w⁴)` and `w = c ρ_w g A dt²/m` (`A` the bound of
/// [`water_plane_bound`] on the water-plane area, so that `w` bounds
/// `c k dt²/m`). `θ = 0` is the explicit lookahead step, `θ = 1` backward
/// Euler; for `w ≪ 1` the change is of order `w⁴` (no visible damping nor
/// frequency shift at ordinary steps), and for `w ≫ 1` the step is fully
/// implicit. `F_y` decreases with depth, so the residual
/// `y_e − y₀ − θ ((1 − β) dt v + c dt² (F_y(y_e)/m − g))` increases with
/// `y_e`; `F_y ∈ [0, F_max]` brackets its root, which a safeguarded secant
/// (Illinois) finds in a few evaluations. The wrench applied is the
/// buoyancy evaluated at `y_e` (force and torque). The drag applied in the
/// same step (`drag`, already implicit in the velocity) is part of `a` and
/// of the angular acceleration: without it, a light stiff body's drag and
/// buoyancy each stopped the same motion and together overshot it.
///
/// With an added mass (see [`Inertial`]) the step moves the body and the
/// water it sets moving: `m` above is the mass a vertical force moves
/// ([`Inertial::vertical`]), `a = (F_y + D_y − m_b g)/m` with `m_b` the
/// body's own mass, and the pitch and roll turn the inertia with its
/// rotational added part. The wrench returned is the one that moves the
/// two; [`Inertial::for_engine`] makes it the one the engine, moving the body
/// alone, must be given.
///
/// Last, the step is checked for energy ([`Step::without_energy_gain`]):
/// the driver predicts the engine's step from the pose now under the
/// wrench, and where the body would end it with more energy than it began
/// with (kinetic, gravity's and the columns'
/// [`HydroForces::potential`](soak_hydro::HydroForces::potential),
/// less the drag's work), the velocities it would end with are blended
/// towards those that hold the body where it is until it does not. A step
/// whose linearisation is far from the truth (a rod pitched with one end
/// in the water, a square rod rolling over) then damps the motion instead
/// of flinging the body.
#[allow(clippy::too_many_arguments)]
pub(crate) fn implicit_heave<H>(
    b: &SoakBody<H>,
    rb: &EngineBody,
    water: &Water,
    state: &BodyState,
    options: &HydroOptions,
    t: f64,
    substeps: f64,
    limit: f64,
    buoyancy: Wrench,
    drag: Wrench,
    inertial: &Inertial,
) -> Wrench {
    let dt = options.dt;
    // The mass a vertical force moves: the body's, or with the water's it
    // sets moving.
    let m = inertial.vertical();
    let radius = b.atlas.bounding_radius();
    if !(dt > 0.0 && m > 0.0 && radius > 0.0 && limit.is_finite()) || options.buoyancy == BuoyancyMode::Off {
        return buoyancy;
    }
    let c = (substeps + 1.0) / (2.0 * substeps);
    let beta = (substeps - 1.0) / (2.0 * substeps);
    let theta = implicit_weight(water, &b.shape, m, dt, substeps);
    if theta.is_nan() || theta < IMPLICIT_NEGLIGIBLE {
        return buoyancy;
    }
    let g = water.gravity * rb.gravity_scale;
    let v = state.linear_velocity.y;
    let options = HydroOptions {
        drag: None,
        ..*options
    };
    let com = b.mass.center_of_mass;
    let posed = |dy: f64, turn: Vector3<f64>| {
        let rotation = UnitQuaternion::from_scaled_axis(turn) * state.pose.rotation;
        let centre = state.pose * com + Vector3::new(0.0, dy, 0.0);
        Isometry3::from_parts(
            Translation3::from(centre.coords - rotation * com.coords),
            rotation,
        )
    };
    let at_forces = |pose: Isometry3<f64>| {
        let shifted = BodyState { pose, ..*state };
        let r = match &b.tiled {
            Some(tiled) => tiled.evaluate(&b.atlas, water, &shifted, &b.mass, t, &options),
            None => soak_hydro::evaluate(&b.atlas, water, &shifted, &b.mass, t, &options),
        };
        r.ok()
    };
    let at_pose = |pose: Isometry3<f64>| {
        at_forces(pose)
            .map(|f| f.buoyancy)
            .filter(|w| w.is_finite() && (0.0..=limit).contains(&w.force.y))
    };
    let rot = state.pose.rotation.to_rotation_matrix().into_inner();
    let inertia = rot * inertial.inertia() * rot.transpose();
    // The implicit wrench; every way out of it goes through the energy
    // check below.
    let implicit = (|| {
        let at = |dy: f64| at_pose(posed(dy, Vector3::zeros()));
        // The shift the step would make with vertical buoyancy f.
        let target = |f: f64| {
            let a = inertial
                .acceleration(&Vector3::new(0.0, f + drag.force.y, 0.0), g)
                .y;
            theta * ((1.0 - beta) * dt * v + c * dt * dt * a)
        };
        let residual = |dy: f64, f: f64| dy - target(f);
        // Bracket: no buoyancy (residual ≤ 0) and the most there can be (≥ 0).
        let (mut lo, mut hi) = (target(0.0), target(limit));
        let (mut r_lo, mut r_hi) = (f64::NAN, f64::NAN);
        let tolerance = 1e-6 * radius;
        let mut best = buoyancy;
        let mut solved_dy = None;
        let mut best_residual = residual(0.0, buoyancy.force.y).abs();
        let mut side = 0i8;
        for _ in 0..64 {
            let dy = if r_lo.is_finite() && r_hi.is_finite() && r_hi > r_lo {
                lo - r_lo * (hi - lo) / (r_hi - r_lo)
            } else {
                0.5 * (lo + hi)
            };
            let Some(wrench) = at(dy) else {
                return buoyancy;
            };
            let r = residual(dy, wrench.force.y);
            if r.abs() < best_residual {
                best = wrench;
                solved_dy = Some(dy);
                best_residual = r.abs();
            }
            if r.abs() <= tolerance || (hi - lo).abs() <= tolerance {
                break;
            }
            // Illinois: halve the stale end's residual when one side repeats.
            if r < 0.0 {
                lo = dy;
                r_lo = r;
                if side == -1 && r_hi.is_finite() {
                    r_hi *= 0.5;
                }
                side = -1;
            } else {
                hi = dy;
                r_hi = r;
                if side == 1 && r_lo.is_finite() {
                    r_lo *= 0.5;
                }
                side = 1;
            }
        }
        // Pitch and roll, linearised about the solved heave: the torque's
        // stiffness `K` from central differences of small turns about the
        // horizontal axes through the centre of mass, and the same blend,
        // `τ = τ₀ − θ K ((1 − β) dt ω + c dt² α)` with `α = I⁻¹ τ`, that is
        // `α = (I + θ c dt² K)⁻¹ (τ₀ − θ (1 − β) dt K ω)`, `τ = I α`.
        let Some(solved) = solved_dy else {
            return best;
        };
        // A turn that moves no point by more than a tenth of the body's
        // thickness 3V/A (its radius for a sphere; a 200:1 rod's width), so
        // that the difference sees the torque's slope, not its saturation.
        let turn = (0.1 * b.shape.thickness / radius).min(0.01);
        // Yaw too where the surface is not flat: a slope makes a yaw torque
        // that can be as stiff as pitch and roll (over a flat surface there is
        // none, and its difference would only be noise).
        let flat = matches!(water.surface.kind(t), SurfaceKind::Plane { normal, .. } if normal.x == 0.0 && normal.z == 0.0);
        let axes: &[usize] = if flat { &[0, 2] } else { &[0, 1, 2] };
        let mut k = Matrix3::zeros();
        for &axis in axes {
            let mut e = Vector3::zeros();
            e[axis] = turn;
            let (Some(plus), Some(minus)) = (at_pose(posed(solved, e)), at_pose(posed(solved, -e))) else {
                return best;
            };
            k.set_column(axis, &(-(plus.torque - minus.torque) / (2.0 * turn)));
        }
        // The drag's torque acts over the step too: α counts it, the buoyancy
        // torque applied is what is left of I α.
        let rhs = best.torque + drag.torque - theta * (1.0 - beta) * dt * (k * state.angular_velocity);
        let system = inertia + theta * c * dt * dt * k;
        match system.lu().solve(&rhs) {
            Some(alpha) if alpha.iter().all(|a| a.is_finite()) => Wrench {
                force: best.force,
                torque: inertia * alpha - drag.torque,
            },
            _ => best,
        }
    })();
    let Some(step) = Step::new(
        state,
        &b.mass,
        *inertial,
        g,
        drag,
        dt,
        substeps,
        rb.fast_rotation,
        rb.gyroscopic,
    ) else {
        return implicit;
    };
    // The columns' potential at a pose, and whether the body is at the
    // surface there (partly dry, or within its radius of a surface that is
    // not a plane: see `HydroForces::deep`).
    let potential = |pose: Isometry3<f64>| {
        at_forces(pose)
            .filter(|f| f.potential.is_finite())
            .map(|f| (f.potential, f.deep < 1.0))
    };
    step.without_energy_gain(implicit, potential)
}
