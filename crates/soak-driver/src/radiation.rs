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

/// On a [`Gerstner`] sea, the force and moment (about the centre of
/// mass) linear theory's excitation adds to what the texels' hydrostatic
/// pressure under the surface gives, summed over the waves: for each,
/// `a Re{ΔX(ω, β) e^{iθ}}` with `ΔX` the model's
/// [`excitation_beyond_columns`](RadiationModel::excitation_beyond_columns)
/// (the wave pressure's decay with depth and the diffraction), `β` the
/// wave's heading in the body's axes at rest as it is turned now, and `θ`
/// the wave's phase at the centre of mass `center` (m, world) at time `t`
/// (s); `rotation` is the body's as the model reads it
/// ([`RadiationModel::heading`]). Along the surface, texels whose
/// pressure is summed as it acts (`pushed`) give the push of its slope
/// (the water's pressure gradient on the displaced volume) and linear
/// theory adds the diffraction, which carries a small body along with the
/// water's orbit as the radiation damps it. Archimedes' buoyancy acts
/// straight up by design (no sideways force, no drift of its own): such a
/// body takes linear theory's heave, roll and pitch, none of its surge,
/// sway and yaw (the diffraction's yaw is the moment of its sway), and
/// its back-and-forth is left to its drag. (Given linear theory's whole
/// push and diffraction, a 10 cm ball on the steep swell drifted at 0.63
/// of the Stokes drift, where with its pressure summed it drifts at 1.0
/// and with neither at 0.83; given the diffraction's yaw without its
/// sway, a metre-long needle on the stability matrix's breaking-limit sea
/// spun up.) `None` on any other surface: there the body radiates
/// against the water's own vertical motion instead (see the step).
pub(crate) fn sea_excitation(
    water: &Water,
    model: &RadiationModel,
    rotation: &UnitQuaternion<f64>,
    center: &Point3<f64>,
    t: f64,
    pushed: bool,
) -> Option<Wrench> {
    let sea = water.surface.as_any()?.downcast_ref::<Gerstner>()?;
    // The body's turn from its rest orientation, in the water's axes.
    let frame = rotation * model.rotation().inverse();
    let mut added = [0.0; 6];
    for wave in sea.waves.iter().filter(|w| w.amplitude > 0.0) {
        let k = wave.wavenumber();
        let omega = (sea.gravity * k).sqrt();
        let (sin, cos) = wave.direction_deg.to_radians().sin_cos();
        let along = frame.inverse() * Vector3::new(cos, 0.0, sin);
        let heading = along.z.atan2(along.x);
        let phase = k * (cos * center.x + sin * center.z) - omega * t + wave.phase;
        let (s, c) = phase.sin_cos();
        let differences = model.excitations_beyond_columns(omega, heading);
        for (mode, (added, difference)) in added.iter_mut().zip(differences).enumerate() {
            if !pushed && matches!(mode, 0 | 2 | 4) {
                continue;
            }
            *added += wave.amplitude * (difference.re * c - difference.im * s);
        }
    }
    Some(Wrench {
        force: frame * Vector3::new(added[0], added[1], added[2]),
        torque: frame * Vector3::new(added[3], added[4], added[5]),
    })
}

/// The part of the entry's momentum a body gives the water whose inertia
/// it gains (see the step): `(a / (m + a))³` for an added inertia `a` and
/// the body's own `m` (kg, or kg·m² turning); 0 where either is not a
/// positive finite number. Whole for a body much lighter than its water,
/// negligible for one as heavy as it or heavier.
pub(crate) fn entry_weight(added: f64, own: f64) -> f64 {
    if !(added > 0.0 && own > 0.0 && added.is_finite() && own.is_finite()) {
        return 0.0;
    }
    (added / (own + added)).powi(3)
}

#[cfg(test)]
mod tests {
    use super::entry_weight;

    #[test]
    fn the_entry_weight_is_whole_for_light_bodies_and_small_for_heavy_ones() {
        // A body a hundred times lighter than its water: 97 %.
        assert!((entry_weight(100.0, 1.0) - (100.0f64 / 101.0).powi(3)).abs() < 1e-15);
        assert!(entry_weight(100.0, 1.0) > 0.97);
        // As heavy as its water: an eighth; four times heavier: 1/125.
        assert!((entry_weight(1.0, 1.0) - 0.125).abs() < 1e-15);
        assert!((entry_weight(1.0, 4.0) - 0.008).abs() < 1e-15);
        // Nothing added, nothing taken; nothing finite, nothing taken.
        assert_eq!(entry_weight(0.0, 1.0), 0.0);
        assert_eq!(entry_weight(f64::NAN, 1.0), 0.0);
        assert_eq!(entry_weight(1.0, 0.0), 0.0);
        assert_eq!(entry_weight(f64::INFINITY, 1.0), 0.0);
    }
}
