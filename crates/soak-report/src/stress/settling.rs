//! The settling check: a body floats, sinks or hovers as its relative
//! density says, within bounds its energy and the surface allow.

use super::fixture::G;
use super::matrix::{Level, WaterKind};
use super::outcome::Expect;

/// What a run measured that the settling check judges.
#[derive(Clone, Copy)]
pub(crate) struct Motion {
    /// What physics says the body does.
    pub(crate) expect: Expect,
    /// The fluid.
    pub(crate) water: WaterKind,
    /// The effects.
    pub(crate) level: Level,
    /// Nominal size `V^(1/3)`, m.
    pub(crate) size: f64,
    /// Natural time `√(size/g)`, s.
    pub(crate) tau: f64,
    /// Simulated time, s.
    pub(crate) time: f64,
    /// The surface's span `hi − lo`, m.
    pub(crate) waves: f64,
    /// How far the centre of mass can lie from a surface the body touches,
    /// in sizes.
    pub(crate) reach: f64,
    /// Specific energy gained at most, J/kg (may be negative).
    pub(crate) energy_gained: f64,
    /// Relative density at the end.
    pub(crate) density_end: f64,
    /// Mean depth of the centre of mass under the surface over the last
    /// half, in sizes.
    pub(crate) mean_centre_depth: f64,
    /// Mean displaced fraction over the last half.
    pub(crate) mean_fraction: f64,
    /// Displaced fraction at the end.
    pub(crate) final_fraction: f64,
    /// The vertical velocity judged, over `√(g·size)`.
    pub(crate) vy: f64,
    /// Which vertical velocity that is.
    pub(crate) vy_label: &'static str,
    /// Height at the end less at the start, in sizes.
    pub(crate) dy: f64,
    /// Whether the centre of mass lies at the centre of the closed shape
    /// (within 1 % of the size): true for the matrix's solids, false for
    /// the open containers' walls.
    pub(crate) centred: bool,
}

/// Whether the body settled as physics says, what was measured, and the
/// displaced fraction expected.
pub(crate) fn settle(m: &Motion) -> (bool, String, f64) {
    let Motion {
        expect,
        water,
        level,
        size,
        tau,
        time,
        waves,
        reach,
        energy_gained,
        density_end,
        mean_centre_depth,
        mean_fraction,
        final_fraction,
        vy,
        vy_label,
        dy,
        centred,
    } = *m;
    match expect {
        Expect::Floats => {
            // At the surface over the last half: neither sunk nor flown off.
            // A floating body moves away from the surface only with energy:
            // having gained Δe per kilogram (≥ 0, bounded by the energy
            // check), its centre can go below the surface over it by at most
            // ρ Δe / ((1 − ρ) g) more than it floats at (the net lift of a
            // submerged body is (1/ρ − 1) g per kilogram), and above it by
            // at most Δe / g; the surface itself spans hi − lo. A body that
            // touches the surface has its centre within its reach of it (one
            // size V^(1/3) for a compact body; a tilted rod's centre can lie
            // deeper, up to its half length). So the mean centre depth over
            // the last half must lie within the larger of one size and the
            // reach, plus the surface's span plus those excursions, either
            // way. On calm water, where there is no energy to gain, it must
            // also, in a run of at least 10 natural times (long enough for
            // what the 5 % deeper start throws up to come back down), be
            // partly and never wholly under water on average. A run can end with
            // a light body in the air on a ballistic arc (a wave or the cliff
            // threw it): that is not flying off if its energy allowed it.
            let gained = energy_gained.max(0.0);
            let span = reach.max(1.0) + waves / size;
            let dive = span + density_end * gained / ((1.0 - density_end).max(1e-9) * G * size);
            let rise = span + gained / (G * size);
            let mut ok = mean_centre_depth <= dive
                && -mean_centre_depth <= rise
                && (water != WaterKind::Plane
                    || time < 10.0 * tau
                    || (mean_fraction > 0.0 && mean_fraction < 0.999));
            let mut note = format!(
                "mean centre depth {mean_centre_depth:.3} sizes in [−{rise:.3}, {dive:.3}], mean fraction {mean_fraction:.3}"
            );
            if water == WaterKind::Plane && level >= Level::Drag && time >= 20.0 * tau {
                let tol = 0.05 + 0.1 * density_end;
                ok &= (final_fraction - density_end).abs() <= tol;
                note = format!(
                    "{note}; final fraction {final_fraction:.3}, expected {density_end:.3} ± {tol:.3}"
                );
            }
            (ok, note, density_end)
        }
        Expect::Sinks => {
            // No sea bed: a sinking body is below where it started and still
            // going down (in the sea, on average over the last half: in the
            // orbits of a wave drag can lift it for a moment).
            // In the sea, going down over the last half of the run (its
            // mean velocity there) is what is asked: a hull that floated
            // until it filled can have been lifted above where it started
            // by the waves, whose surface rises and falls by more than the
            // body's size in a period.
            // With added mass the body answers more slowly (a third more
            // inertia for a sphere, half again for a flooded container):
            // in a run shorter than it takes to rise to its floating level,
            // fill and go under (1.25 s at 1/240 s), it must be going down
            // and not above its floating level (it started 5 % of its size
            // below it).
            let slow = level >= Level::AddedMass && dy < 0.05;
            let ok = vy < 0.0 && (dy < 0.0 || slow || water.moves());
            (
                ok,
                format!("{vy_label} {vy:.3} √(g·size), {dy:.3} sizes from the start"),
                1.0,
            )
        }
        Expect::Neutral => {
            // Stays under without rising; on calm water it also does not sink.
            // Waves and the cliff bare it in their troughs, where it is heavier
            // than the water it displaces: there it may drift down. In the
            // sea its velocity is taken on average over the last half: in a
            // wave's orbits drag carries it up and down with the water.
            // A body whose centre of mass is off the centre of its shape
            // (an open container's walls) feels a couple of its weight and
            // its buoyancy: it swings like a pendulum, bares its ends at the
            // surface and drifts down; it must only not rise, which a
            // neutral body cannot do (its buoyancy never exceeds its weight).
            if !centred {
                return (
                    vy < 0.1,
                    format!("off-centre: mean fraction {mean_fraction:.3}, {vy_label} {vy:.3} √(g·size)"),
                    1.0,
                );
            }
            let sinking_allowed = water != WaterKind::Plane;
            let ok = mean_fraction > 0.85 && vy < 0.1 && (sinking_allowed || vy > -0.1);
            (
                ok,
                format!("mean fraction {mean_fraction:.3}, {vy_label} {vy:.3} √(g·size)"),
                1.0,
            )
        }
    }
}
