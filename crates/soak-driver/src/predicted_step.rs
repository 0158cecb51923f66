//! The energy guard's prediction of the engine's step: [`Step`], a copy
//! of Rapier's substep integration of one body (symplectic Euler, the
//! gyroscopic correction, the cap on the spin), the check that the step
//! creates no energy ([`Step::without_energy_gain`]), and the same
//! prediction for adapters to test their engine against
//! ([`predict_step`]).

use nalgebra::{Isometry3, Matrix3, Point3, Quaternion, Translation3, UnitQuaternion, Vector3};
use soak_hydro::{BodyState, MassProperties, PrincipalInertia, Wrench};

use crate::engine::{EngineBody, StepParams};
use crate::inertial::Inertial;

/// The engine's step of one body as the driver predicts it: from the pose
/// now, under a constant buoyancy wrench, the drag and gravity, over
/// `substeps` substeps of symplectic Euler (`y' = y + dt v + c dt² a`,
/// `v' = v + dt a`, `c = (s + 1)/(2s)`; the turn with Rapier's
/// gyroscopic correction and cap on the spin, see [`Step::end`]).
pub(crate) struct Step<'a> {
    dt: f64,
    /// `(s + 1)/(2s)` for `s` substeps: the step moves the centre by
    /// `dt ((1 − c) v₀ + c v₁)`.
    c: f64,
    /// The body's mass and inertia, with the water's it sets moving.
    inertial: Inertial,
    /// Gravity along −y, m/s² (the body's gravity scale included).
    g: f64,
    /// World inertia tensor about the centre of mass at the pose now, and
    /// its inverse.
    inertia: Matrix3<f64>,
    inverse: Matrix3<f64>,
    /// Inertia tensor in the object's axes (the added rotational inertia
    /// included).
    body_inertia: Matrix3<f64>,
    /// Velocities and the pose now (the generator evaluated at a lookahead
    /// pose `β dt` ahead: back from it along the same velocities).
    v0: Vector3<f64>,
    w0: Vector3<f64>,
    com0: Point3<f64>,
    rot0: UnitQuaternion<f64>,
    /// Centre of mass, object frame.
    com: &'a Point3<f64>,
    drag: Wrench,
    substeps: usize,
    /// Rapier's cap on the angular speed, rad/s (`None` where the body
    /// allows fast rotation).
    max_angular_speed: Option<f64>,
    /// The body's principal inertia, where Rapier applies gyroscopic forces.
    gyroscopic: Option<PrincipalInertia>,
    /// With an added rotational inertia and the engine's gyroscopic term:
    /// the spin's acceleration the driver's torque adds so that the body
    /// turns as its whole inertia does ([`Inertial::spin_difference`]),
    /// rad/s², world.
    spin: Vector3<f64>,
}

/// Rapier's gyroscopic correction of `omega`, once per substep `h` of a
/// body turned by `rotation` with principal inertia `p`: the explicit term
/// `−ω × Iω h` added to the angular momentum in the principal frame, its
/// length kept.
fn gyroscopic(
    p: &PrincipalInertia,
    omega: &Vector3<f64>,
    rotation: &UnitQuaternion<f64>,
    h: f64,
) -> Vector3<f64> {
    let axes = rotation * p.frame;
    let w = axes.inverse() * omega;
    let momentum = p.moments.component_mul(&w);
    let total = momentum - w.cross(&momentum) * h;
    let squared = total.norm_squared();
    if squared == 0.0 || p.moments.iter().any(|&m| m <= 0.0) {
        return *omega;
    }
    let kept = total * (momentum.norm_squared() / squared).sqrt();
    axes * kept.component_div(&p.moments)
}

/// Where a predicted [`Step`] ends.
struct StepEnd {
    /// Linear and angular velocity, m/s and rad/s.
    v: Vector3<f64>,
    w: Vector3<f64>,
    /// Displacement of the centre of mass, m, and the sum of the substeps'
    /// turns `h ω`, rad.
    dx: Vector3<f64>,
    turn: Vector3<f64>,
    rotation: UnitQuaternion<f64>,
}

impl<'a> Step<'a> {
    #[allow(clippy::too_many_arguments)]
    pub(crate) fn new(
        state: &BodyState,
        mass: &'a MassProperties,
        inertial: Inertial,
        g: f64,
        drag: Wrench,
        dt: f64,
        substeps: f64,
        fast_rotation: bool,
        gyroscopic: bool,
    ) -> Option<Self> {
        let lookahead = (substeps - 1.0) / (2.0 * substeps) * dt;
        let (v0, w0) = (state.linear_velocity, state.angular_velocity);
        let com = &mass.center_of_mass;
        let rot0 = UnitQuaternion::from_scaled_axis(-w0 * lookahead) * state.pose.rotation;
        let r = rot0.to_rotation_matrix().into_inner();
        let inertia = r * inertial.inertia() * r.transpose();
        Some(Self {
            dt,
            c: (substeps + 1.0) / (2.0 * substeps),
            inertial,
            g,
            inertia,
            inverse: inertia.try_inverse()?,
            body_inertia: *inertial.inertia(),
            v0,
            w0,
            com0: state.pose * com - v0 * lookahead,
            rot0,
            com,
            drag,
            substeps: substeps as usize,
            max_angular_speed: (!fast_rotation).then(|| std::f64::consts::FRAC_PI_4 / dt),
            gyroscopic: gyroscopic.then(|| mass.principal()),
            spin: if gyroscopic {
                inertial.spin_difference(&mass.inertia, &state.pose.rotation, &w0)
            } else {
                Vector3::zeros()
            },
        })
    }

    /// Linear and angular acceleration under `w`, the drag and gravity.
    fn accelerations(&self, w: &Wrench) -> (Vector3<f64>, Vector3<f64>) {
        (
            self.inertial.acceleration(&(w.force + self.drag.force), self.g),
            self.inverse * (w.torque + self.drag.torque) + self.spin,
        )
    }

    /// Linear and angular velocity at the end of the step under `w`,
    /// uncapped.
    fn end_velocities(&self, w: &Wrench) -> (Vector3<f64>, Vector3<f64>) {
        let (a, alpha) = self.accelerations(w);
        (self.v0 + self.dt * a, self.w0 + self.dt * alpha)
    }

    /// The buoyancy wrench that ends the step with velocities `v1`, `w1`.
    fn wrench_for(&self, v1: &Vector3<f64>, w1: &Vector3<f64>) -> Wrench {
        Wrench {
            force: self.inertial.force_for(&((v1 - self.v0) / self.dt), self.g) - self.drag.force,
            torque: self.inertia * ((w1 - self.w0) / self.dt - self.spin) - self.drag.torque,
        }
    }

    /// The energy the step under `w` creates, J: kinetic energy, gravity's
    /// potential and the columns' potential `u` at the end, less the
    /// same now (`u0`), less the work of the drag and of the buoyancy's
    /// sideways force. The columns' potential is taken at the end pose
    /// moved back sideways: Archimedes' force is vertical, so moving
    /// sideways over a surface that is not flat changes the potential
    /// without its force doing that work (see `soak stress`' energy
    /// allowance); what the check follows is heave, pitch and roll.
    fn energy_gain(
        &self,
        w: &Wrench,
        u0: f64,
        u: &impl Fn(Isometry3<f64>) -> Option<(f64, bool)>,
    ) -> Option<f64> {
        let end = self.end(w);
        let centre = self.com0 + Vector3::y() * end.dx.y;
        let u1 = u(Isometry3::from_parts(
            Translation3::from(centre.coords - end.rotation * self.com.coords),
            end.rotation,
        ))?
        .0;
        // The spin's energy in the body's own axes: ½ ωᵀ I ω with I turned
        // to each end's pose.
        let spin = |rotation: &UnitQuaternion<f64>, w: &Vector3<f64>| {
            let local = rotation.inverse() * w;
            0.5 * local.dot(&(self.body_inertia * local))
        };
        let kinetic = self.inertial.kinetic_change(&end.v, &self.v0) + spin(&end.rotation, &end.w)
            - spin(&self.rot0, &self.w0);
        let sideways = Vector3::new(end.dx.x, 0.0, end.dx.z);
        let gain = kinetic + self.inertial.mass() * self.g * end.dx.y + u1
            - u0
            - self.drag.force.dot(&end.dx)
            - self.drag.torque.dot(&end.turn)
            - w.force.dot(&sideways);
        gain.is_finite().then_some(gain)
    }

    /// Where the step under `w` ends: Rapier's substeps of symplectic
    /// Euler, each correcting ω for the gyroscopic forces (where the body
    /// has them), capping the angular speed at `π/4` per step (unless the
    /// body allows fast rotation) and turning by `h ω` through `(1, h ω/2)`
    /// normalised.
    fn end(&self, w: &Wrench) -> StepEnd {
        let (a, alpha) = self.accelerations(w);
        let h = self.dt / self.substeps as f64;
        let (mut v, mut omega) = (self.v0, self.w0);
        let (mut dx, mut turn, mut rotation) = (Vector3::zeros(), Vector3::zeros(), self.rot0);
        for _ in 0..self.substeps {
            v += h * a;
            omega += h * alpha;
            if let Some(p) = &self.gyroscopic {
                omega = gyroscopic(p, &omega, &rotation, h);
            }
            let speed = omega.norm();
            if let Some(cap) = self.max_angular_speed
                && speed > cap
            {
                omega *= cap / speed;
            }
            dx += h * v;
            turn += h * omega;
            let half = 0.5 * h * omega;
            rotation = UnitQuaternion::new_normalize(Quaternion::new(1.0, half.x, half.y, half.z)) * rotation;
        }
        StepEnd {
            v,
            w: omega,
            dx,
            turn,
            rotation,
        }
    }

    /// `w`, or where the step under it would create energy, the step whose
    /// end velocities `q(s) = q_h + s (q₁ − q_h)` are the largest blend
    /// `s ∈ [0, 1]` (to 2⁻⁸) that creates none, between the velocities
    /// `q₁` the step under `w` ends with and those that leave the body
    /// where it is, `q_h = −(1 − c) q₀ / c` (Rapier moves the centre by
    /// `dt ((1 − c) q₀ + c q₁)`). Held in place, the body keeps its
    /// potential and ends with `((1 − c)/c)²` of its kinetic energy (0.36
    /// at four substeps); if even that step would create energy (the turn
    /// is not exactly nil where Rapier caps the spin), the one of the two
    /// that creates less is taken.
    ///
    /// The stiff step cannot be exact: the buoyancy of a body whose heave,
    /// pitch or roll period is shorter than the step changes far more over
    /// the step than its linearisation says (a rod pitched 5° with one end
    /// under water, a square rod rolling over to float on an edge: the
    /// pitch–roll stiffness has a negative eigenvalue, and backward Euler
    /// with it divides by `I − c dt² |K|`). The check keeps such a step
    /// from ever handing the body energy the water did not: where the
    /// prediction says the step gains, the motion it would end with is
    /// damped instead. Where the body is deep now (`u` says it is not at
    /// the surface: see `HydroForces::deep`) or its potential cannot be
    /// evaluated, `w` is returned.
    pub(crate) fn without_energy_gain(
        &self,
        w: Wrench,
        u: impl Fn(Isometry3<f64>) -> Option<(f64, bool)>,
    ) -> Wrench {
        // Deep under water now, the buoyancy has no stiffness, and the
        // potential's terms grow with the depth squared: no check. Wholly
        // under a surface that is not a plane but within the body's radius
        // of it, the samples can see the surface's steps (a rod across a
        // cliff), and the step is checked.
        let Some((u0, true)) = u(Isometry3::from_parts(
            Translation3::from(self.com0.coords - self.rot0 * self.com.coords),
            self.rot0,
        )) else {
            return w;
        };
        match self.energy_gain(&w, u0, &u) {
            Some(gain) if gain > 0.0 => {}
            _ => return w,
        }
        // The end velocities that leave the body where it is: Rapier moves
        // it by dt ((1 − c) q₀ + c q₁), zero for q₁ = −(1 − c) q₀ / c.
        let hold = -(1.0 - self.c) / self.c;
        let (v1, w1) = self.end_velocities(&w);
        let (vh, wh) = (hold * self.v0, hold * self.w0);
        let blend = |s: f64| self.wrench_for(&(vh + s * (v1 - vh)), &(wh + s * (w1 - wh)));
        let gain = |s: f64| self.energy_gain(&blend(s), u0, &u);
        if !matches!(gain(0.0), Some(g) if g <= 0.0) {
            // Even held in place the step would create energy (the
            // potential's sampling, or a velocity Rapier caps): whichever
            // of the two creates less.
            let held = blend(0.0);
            return match (gain(0.0), gain(1.0)) {
                (Some(h), Some(g)) if h < g && held.is_finite() => held,
                _ => w,
            };
        }
        let (mut lo, mut hi) = (0.0, 1.0);
        for _ in 0..8 {
            let s = 0.5 * (lo + hi);
            match gain(s) {
                Some(g) if g <= 0.0 => lo = s,
                _ => hi = s,
            }
        }
        let damped = blend(lo);
        if damped.is_finite() { damped } else { w }
    }
}

/// Where the engine's step takes a body, as the driver predicts it
/// ([`predict_step`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PredictedStep {
    /// The pose of the body's own frame at the end of the step, world, m.
    pub pose: Isometry3<f64>,
    /// Linear velocity of the centre of mass at the end of the step, m/s.
    pub linear_velocity: Vector3<f64>,
    /// Angular velocity at the end of the step, rad/s.
    pub angular_velocity: Vector3<f64>,
}

/// The engine's step of `body` (mass properties `mass`, the body's own
/// frame) under the constant `wrench` (world, about the centre of mass)
/// and gravity `gravity` (m/s² along −y, the body's gravity scale
/// applied here), as the driver predicts it to keep stiff bodies stable
/// and to check that no step creates energy: `step.substeps` substeps
/// `h` of symplectic Euler, each adding `h a` to the velocities, turning
/// ω by the explicit gyroscopic term (where `body.gyroscopic`), capping
/// `|ω|` at `π/(4 dt)` (unless `body.fast_rotation`), moving the centre
/// by `h v` and turning by `(1, h ω/2)` normalised. This is Rapier's
/// integrator (and bevy_rapier's); an adapter for another engine should
/// test that its engine steps a body as this says (soak-rapier's
/// `predicted_step` test does, to 1e-4 relative). `None` for an inertia
/// that cannot be inverted.
pub fn predict_step(
    body: &EngineBody,
    mass: &MassProperties,
    wrench: &Wrench,
    gravity: f64,
    step: &StepParams,
) -> Option<PredictedStep> {
    let (dt, substeps) = (step.dt, step.substeps_f64());
    // The step is built from the state the driver evaluates at, β dt ahead.
    let lookahead = (substeps - 1.0) / (2.0 * substeps) * dt;
    let (v0, w0) = (body.linear_velocity, body.angular_velocity);
    let rotation = UnitQuaternion::from_scaled_axis(w0 * lookahead) * body.pose.rotation;
    let com = (body.pose * mass.center_of_mass).coords + v0 * lookahead;
    let state = BodyState {
        pose: Isometry3::from_parts(
            Translation3::from(com - rotation * mass.center_of_mass.coords),
            rotation,
        ),
        linear_velocity: v0,
        angular_velocity: w0,
    };
    let predicted = Step::new(
        &state,
        mass,
        Inertial::plain(body.mass, &mass.inertia),
        gravity * body.gravity_scale,
        Wrench::default(),
        dt,
        substeps,
        body.fast_rotation,
        body.gyroscopic,
    )?;
    let end = predicted.end(wrench);
    let centre = predicted.com0 + end.dx;
    Some(PredictedStep {
        pose: Isometry3::from_parts(
            Translation3::from(centre.coords - end.rotation * mass.center_of_mass.coords),
            end.rotation,
        ),
        linear_velocity: end.v,
        angular_velocity: end.w,
    })
}
