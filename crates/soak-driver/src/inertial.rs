//! The inertia a step moves ([`Inertial`]): the body's mass and inertia,
//! plus the added mass of the water it sets moving where it has one
//! ([`Effects::added_mass`](crate::Effects::added_mass)), and the wrench
//! that makes the engine, which moves the body's mass alone, move the body as
//! the two would move ([`Inertial::for_engine`]).

use nalgebra::{Matrix3, UnitQuaternion, Vector3};
use soak_hydro::{AddedMass, Wrench};

/// What a step accelerates: the body's mass `m` (which gravity pulls) and
/// its inertia, plus, with an added mass `M_a`, the water's: a force `F`
/// (gravity aside) then accelerates the body by `(m I + M_a)⁻¹ (F − m g ŷ)`.
///
/// The added mass enters the step implicitly: the water's reaction
/// `−M_a a` is taken at the acceleration the step itself ends with, which
/// is the same as moving the larger mass. It can only slow the body's
/// answer to a force, never make it overshoot, at any time step.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Inertial {
    /// The body's mass, kg.
    mass: f64,
    /// The inertia about the centre of mass, object axes, kg·m²: the
    /// body's, plus the rotational added mass.
    inertia: Matrix3<f64>,
    /// With an added mass: `m I + M_a` (world axes, kg) and its inverse.
    linear: Option<(Matrix3<f64>, Matrix3<f64>)>,
}

impl Inertial {
    /// The body's own mass (kg) and inertia (object axes, kg·m²).
    pub(crate) fn plain(mass: f64, inertia: &Matrix3<f64>) -> Self {
        Self {
            mass,
            inertia: *inertia,
            linear: None,
        }
    }

    /// The body's mass and inertia with `added` scaled to the fluid's
    /// `density` (kg/m³) and the body's `submerged_volume` (m³), turned by
    /// `rotation`. Where the added mass is nil (the body dry) or the sum
    /// cannot be inverted, the body's own.
    pub(crate) fn with_added(
        mass: f64,
        inertia: &Matrix3<f64>,
        added: &AddedMass,
        rotation: &UnitQuaternion<f64>,
        density: f64,
        submerged_volume: f64,
    ) -> Self {
        if added.fraction(submerged_volume) <= 0.0 {
            return Self::plain(mass, inertia);
        }
        let (linear, angular) = added.scaled(rotation, density, submerged_volume);
        Self::with_blocks(mass, inertia, &linear, &angular)
    }

    /// The body's mass and inertia with a translational added mass
    /// `linear` (world axes, kg) and a rotational one `angular` (object
    /// axes, kg·m²). Where the sum cannot be inverted, the body's own.
    pub(crate) fn with_blocks(
        mass: f64,
        inertia: &Matrix3<f64>,
        linear: &Matrix3<f64>,
        angular: &Matrix3<f64>,
    ) -> Self {
        let total = Matrix3::identity() * mass + linear;
        match total.try_inverse() {
            Some(inverse)
                if inverse.iter().all(|x| x.is_finite()) && angular.iter().all(|x| x.is_finite()) =>
            {
                Self {
                    mass,
                    inertia: inertia + angular,
                    linear: Some((total, inverse)),
                }
            }
            _ => Self::plain(mass, inertia),
        }
    }

    /// The body's mass, kg.
    pub(crate) fn mass(&self) -> f64 {
        self.mass
    }

    /// The inertia a torque turns, object axes, kg·m².
    pub(crate) fn inertia(&self) -> &Matrix3<f64> {
        &self.inertia
    }

    /// The mass a vertical force alone accelerates, kg: `m`, or
    /// `1/((m I + M_a)⁻¹)_yy`.
    pub(crate) fn vertical(&self) -> f64 {
        match &self.linear {
            None => self.mass,
            Some((_, inverse)) => 1.0 / inverse[(1, 1)],
        }
    }

    /// The linear acceleration under `force` (N, gravity aside) and gravity
    /// `g` (m/s², along −y).
    pub(crate) fn acceleration(&self, force: &Vector3<f64>, g: f64) -> Vector3<f64> {
        match &self.linear {
            None => force / self.mass - Vector3::y() * g,
            Some((_, inverse)) => inverse * (force - Vector3::y() * (self.mass * g)),
        }
    }

    /// The force (gravity aside) that accelerates the body by `a` under
    /// gravity `g`: the inverse of [`Inertial::acceleration`].
    pub(crate) fn force_for(&self, a: &Vector3<f64>, g: f64) -> Vector3<f64> {
        match &self.linear {
            None => self.mass * (a + Vector3::y() * g),
            Some((total, _)) => total * a + Vector3::y() * (self.mass * g),
        }
    }

    /// The change of the translational kinetic energy from `v0` to `v1`
    /// (m/s), the water's included, J.
    pub(crate) fn kinetic_change(&self, v1: &Vector3<f64>, v0: &Vector3<f64>) -> f64 {
        match &self.linear {
            None => 0.5 * self.mass * (v1.norm_squared() - v0.norm_squared()),
            Some((total, _)) => 0.5 * (v1.dot(&(total * v1)) - v0.dot(&(total * v0))),
        }
    }

    /// What the body and its water turning together add to the spin's
    /// acceleration beyond what an engine applying the gyroscopic term of
    /// the body's `own` inertia `I` (object axes) alone does, at angular
    /// velocity `omega` (world, rad/s) of a body turned by `rotation`:
    /// `(I⁻¹ − J⁻¹) (ω × I ω)`, rad/s², for the spin `J ω̇ = τ − ω × I ω`
    /// of the whole inertia `J = I + A` (zero without an added mass, or
    /// where either inertia cannot be inverted). See
    /// [`Inertial::for_engine`].
    pub(crate) fn spin_difference(
        &self,
        own: &Matrix3<f64>,
        rotation: &UnitQuaternion<f64>,
        omega: &Vector3<f64>,
    ) -> Vector3<f64> {
        if self.linear.is_none() {
            return Vector3::zeros();
        }
        let r = rotation.to_rotation_matrix().into_inner();
        let whole = r * self.inertia * r.transpose();
        let body = r * own * r.transpose();
        spin_difference(&body, whole.try_inverse().as_ref(), omega)
    }

    /// The wrench the engine must be given, moving the body's `own` inertia
    /// (object axes) and its mass alone, for the body to move as the body
    /// and the water it sets moving would under `w` (about the centre of
    /// mass, world) and gravity `g`: the same linear and angular
    /// accelerations. `map` is the body's turn and spin
    /// ([`Inertial::engine_map`]); without an added mass there is none,
    /// and the engine takes `w` itself.
    ///
    /// The map's `spin` is the body's angular velocity (world, rad/s) where the
    /// engine applies the gyroscopic term `−ω × I ω` of the body's own
    /// inertia `I` (Rapier's default): the body and its water then turn as
    /// `J ω̇ = τ − ω × I ω` (`J = I + A`), so the engine is handed
    /// `I J⁻¹ (τ − ω × I ω) + ω × I ω`, and the kinetic energy `½ ω·J ω`
    /// changes by the torque's work alone (no gyroscopic term `ω × X ω`
    /// does work). The water takes its share of every torque and adds no
    /// gyroscopic term of its own: Euler's equations of `J` itself,
    /// `J ω̇ = τ − ω × J ω`, conserve that energy as well, but `J` need
    /// not be the inertia of any rigid body (a rod's added inertia about
    /// its length is nil, about its breadth several times its own, far
    /// outside the triangle inequality of a body's principal moments),
    /// and through them the water's turning spun a light rod about its
    /// length faster than any step resolves, gaining energy every step.
    /// (Handed `I J⁻¹ τ`, the engine's gyroscopic term would act on `J`'s
    /// answer, a mismatch that does work on a spinning body whose added
    /// inertia is not a multiple of its own: a light hull rolling and
    /// yawing gained energy every turn.) `None` where the engine leaves
    /// the term out: `I J⁻¹ τ`, which conserves that energy as well.
    pub(crate) fn for_engine(&self, map: &EngineMap, w: &Wrench, own: &Matrix3<f64>, g: f64) -> Wrench {
        let a = self.acceleration(&w.force, g);
        let torque = map
            .whole_inverse
            .map(|inverse| map.body * (inverse * w.torque + map.turn))
            .filter(|t| t.iter().all(|x| x.is_finite()))
            .unwrap_or(w.torque);
        Wrench {
            force: Inertial::plain(self.mass, own).force_for(&a, g),
            torque,
        }
    }

    /// What [`Inertial::for_engine`] needs of the body turned by
    /// `rotation`, whose own inertia is `own` (object axes), spinning at
    /// `spin` (see there), made before the wrench is known (the step makes
    /// it for every radiating body in parallel): `None` without an added
    /// mass, whose wrench the engine takes as it is.
    pub(crate) fn engine_map(
        &self,
        own: &Matrix3<f64>,
        rotation: &UnitQuaternion<f64>,
        spin: Option<&Vector3<f64>>,
    ) -> Option<EngineMap> {
        self.linear.as_ref()?;
        let r = rotation.to_rotation_matrix().into_inner();
        let whole = r * self.inertia * r.transpose();
        let body = r * own * r.transpose();
        let whole_inverse = whole.try_inverse();
        Some(EngineMap {
            body,
            whole_inverse,
            turn: spin.map_or_else(Vector3::zeros, |omega| {
                spin_difference(&body, whole_inverse.as_ref(), omega)
            }),
        })
    }
}

/// [`Inertial::spin_difference`] of the body's own inertia `body` and the
/// whole's inverse `whole_inverse` (world axes).
fn spin_difference(
    body: &Matrix3<f64>,
    whole_inverse: Option<&Matrix3<f64>>,
    omega: &Vector3<f64>,
) -> Vector3<f64> {
    match (whole_inverse, body.try_inverse()) {
        (Some(j), Some(i)) => {
            let gyro = omega.cross(&(body * omega));
            let d = (i - j) * gyro;
            if d.iter().all(|x| x.is_finite()) {
                d
            } else {
                Vector3::zeros()
            }
        }
        _ => Vector3::zeros(),
    }
}

/// The part of [`Inertial::for_engine`] that does not depend on the
/// wrench: the body's own inertia in world axes, the inverse of the whole
/// (body and water, `None` where it has none) and the spin's difference
/// ([`Inertial::spin_difference`]).
#[derive(Clone, Copy, Debug)]
pub(crate) struct EngineMap {
    body: Matrix3<f64>,
    whole_inverse: Option<Matrix3<f64>>,
    turn: Vector3<f64>,
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A sphere's added mass, `½ ρ V`, in every direction: a force moves
    /// the body as it would move `m + ½ ρ V`, and the engine's wrench gives
    /// the body's own mass that acceleration.
    #[test]
    fn a_spheres_added_mass_slows_every_answer_by_the_same_factor() {
        let volume = 4.0 / 3.0 * std::f64::consts::PI * 0.125;
        let (added, _) = AddedMass::ellipsoid(Vector3::repeat(0.5), Matrix3::identity(), volume).unwrap();
        let (m, rho, g) = (52.0, 1000.0, 9.81);
        let inertia = Matrix3::identity() * 5.2;
        let inertial = Inertial::with_added(m, &inertia, &added, &UnitQuaternion::identity(), rho, 1.0);
        let total = m + 0.5 * rho * volume;
        assert!((inertial.vertical() - total).abs() < 1e-9 * total);
        let w = Wrench {
            force: Vector3::new(10.0, rho * g * volume, -3.0),
            torque: Vector3::new(1.0, 2.0, 3.0),
        };
        let a = inertial.acceleration(&w.force, g);
        let want = (w.force - Vector3::y() * m * g) / total;
        assert!((a - want).norm() < 1e-12 * want.norm());
        assert!((inertial.force_for(&a, g) - w.force).norm() < 1e-9 * w.force.norm());
        let map = inertial
            .engine_map(&inertia, &UnitQuaternion::identity(), None)
            .unwrap();
        let engine = inertial.for_engine(&map, &w, &inertia, g);
        assert!((engine.force / m - Vector3::y() * g - want).norm() < 1e-9 * want.norm());
        // A sphere has no rotational added mass: the torque is untouched.
        assert!((engine.torque - w.torque).norm() < 1e-12);
        // Dry: the body's own.
        let dry = Inertial::with_added(m, &inertia, &added, &UnitQuaternion::identity(), rho, 0.0);
        assert!(
            dry.engine_map(&inertia, &UnitQuaternion::identity(), None)
                .is_none()
        );
    }
}
