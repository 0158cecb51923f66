//! The water's side of a radiating body's step: the motion of the water
//! it radiates against and, on a sea of known waves, the part of linear
//! theory's wave excitation the hydrostatic texels do not give.

use nalgebra::{Point3, UnitQuaternion, Vector3};
use soak_hydro::{Gerstner, Water, Wrench};
use soak_seakeeping::RadiationModel;

/// The water's velocity (m/s) and its rate of change (m/s², central
/// difference over `dt`) at `point` at time `t`; zero where either is not
/// finite.
pub(crate) fn water_motion(
    water: &Water,
    point: &Point3<f64>,
    t: f64,
    dt: f64,
) -> (Vector3<f64>, Vector3<f64>) {
    let u = water.surface.velocity(point, t);
    let h = 0.5 * dt.max(1e-6);
    let a = (water.surface.velocity(point, t + h) - water.surface.velocity(point, t - h)) / (2.0 * h);
    let finite = |v: Vector3<f64>| {
        if v.iter().all(|c| c.is_finite()) {
            v
        } else {
            Vector3::zeros()
        }
    };
    (finite(u), finite(a))
}

/// On a [`Gerstner`] sea, the heave force linear theory's excitation adds
/// to the texels' hydrostatic columns, summed over the waves: for each,
/// `a Re{ΔX(ω, β) e^{iθ}}` with `ΔX` the model's
/// [`excitation_beyond_columns`](RadiationModel::excitation_beyond_columns)
/// (the wave pressure's decay with depth and the diffraction), `β` the
/// wave's heading in the body's axes at rest as it is turned now, and `θ`
/// the wave's phase at the centre of mass `center` (m, world) at time `t`
/// (s); `rotation` is the body's as the model reads it
/// ([`RadiationModel::heading`]). Vertical. `None` on any other surface: there the body radiates
/// against the water's own vertical motion instead (see the step).
pub(crate) fn sea_excitation(
    water: &Water,
    model: &RadiationModel,
    rotation: &UnitQuaternion<f64>,
    center: &Point3<f64>,
    t: f64,
) -> Option<Wrench> {
    let sea = water.surface.as_any()?.downcast_ref::<Gerstner>()?;
    // The body's turn from its rest orientation, in the water's axes.
    let frame = rotation * model.rotation().inverse();
    let mut heave = 0.0;
    for wave in sea.waves.iter().filter(|w| w.amplitude > 0.0) {
        let k = wave.wavenumber();
        let omega = (sea.gravity * k).sqrt();
        let (sin, cos) = wave.direction_deg.to_radians().sin_cos();
        let along = frame.inverse() * Vector3::new(cos, 0.0, sin);
        let heading = along.z.atan2(along.x);
        let phase = k * (cos * center.x + sin * center.z) - omega * t + wave.phase;
        let difference = model.excitation_beyond_columns(1, omega, heading);
        let (s, c) = phase.sin_cos();
        heave += wave.amplitude * (difference.re * c - difference.im * s);
    }
    let force = frame * Vector3::new(0.0, heave, 0.0);
    Some(Wrench {
        force,
        torque: Vector3::zeros(),
    })
}
