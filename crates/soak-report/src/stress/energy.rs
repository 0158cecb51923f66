//! The energy check: the body's specific energy, with the water columns'
//! potential, and how much of it the fluid may hand the body.

use nalgebra::Vector3;
use rapier3d::prelude::{PhysicsWorld, RigidBodyHandle};
use soak_rapier::{ForceGenerator, SoakId, convert};

use super::fixture::{Fixture, G, RHO_W, columns};
use super::matrix::WaterKind;

/// Specific energy `e = (KE + m g y + ρ_w g Σ −A_y d²/2) / m`, J/kg, of the
/// body: its kinetic energy (the spin's in the body's own axes), gravity's
/// potential at its centre of mass, and the water columns' potential, which
/// makes `e` constant for a body in calm water.
pub(crate) fn specific_energy(
    world: &PhysicsWorld,
    soak: &ForceGenerator,
    handle: RigidBodyHandle,
    id: SoakId,
    f: &Fixture,
) -> f64 {
    let rb = &world.bodies[handle];
    let body = soak.body(id).expect("registered");
    let mp = body.mass_properties();
    let pose = convert::pose(rb.position());
    let v: Vector3<f64> = convert::vector(rb.linvel());
    let w = pose.rotation.inverse() * convert::vector(rb.angvel());
    let com = pose * mp.center_of_mass;
    let (_, potential) = columns(&f.atlas, &pose, soak.water(), soak.time());
    let m = mp.mass;
    (0.5 * m * v.norm_squared() + 0.5 * w.dot(&(mp.inertia * w)) + m * G * com.y + RHO_W * G * potential) / m
}

/// The growth of specific energy a cell allows, J/kg (see docs/stress.md).
///
/// `2 %` of `g · size` for the integrator; a static height field can still
/// hand over `ρ_w g V (hi − lo)` of potential as the body moves across it,
/// and moving waves do work on the body, once per wave period (`periods`):
/// `g (hi − lo) periods / min(ρ, 1)` per kilogram for a body of relative
/// density `ρ` over a surface spanning `waves = hi − lo` metres.
pub(crate) fn allowance(size: f64, waves: f64, periods: f64, rho: f64) -> f64 {
    0.02 * G * size + G * waves * periods / rho.min(1.0)
}

/// The number of wave periods a run of `time` seconds spans in `water`
/// (one for static surfaces).
pub(crate) fn periods(water: WaterKind, time: f64, period: f64) -> f64 {
    match water {
        WaterKind::Sea | WaterKind::Ocean => (time / period).ceil(),
        _ => 1.0,
    }
}
