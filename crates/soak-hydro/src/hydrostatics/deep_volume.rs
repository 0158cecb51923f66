//! The deep-volume weight: the submerged volume of a body wholly under a
//! surface that is not a plane, moved towards the enclosed volume with depth.

use super::frame::Frame;
use super::sums::BuoyancySums;

/// The submerged volume Archimedes' force takes, m³: `Σ −A_y d`, but for a
/// body wholly under a surface that is not a plane, where that sum carries
/// the sampling error of a zero integral, it tends to the enclosed volume
/// as the body goes deeper.
///
/// Wholly under water, `Σ −A_y d = Σ −A_y (h − Y) + Σ A_y (y − Y)` with `h`
/// the surface's height over each texel and `Y` the atlas origin's: the
/// second sum is the volume the samples enclose (`Σ A_y r_y`, exact for
/// samples whose first moments are their triangles'), the first samples
/// `−∮ (h − Y) n_y dA`, which is zero for any closed surface since `h`
/// does not depend on `y`. Under a plane the samples integrate the affine
/// `h` exactly; under waves or a height field whose features are no
/// larger than the spacing of the samples (a 200:1 rod's few samples
/// straddling a step) it is not zero, and a sinking or neutral body feels
/// it as a force the water's potential does not have, all the way down.
/// The volume taken is `Σ −A_y d − φ E`, `E` that error, with
/// `φ = Π min(d_i/δ, 1)` over the texels (`δ` the body's mean thickness
/// `3V/A`, or `g dt²` where a step moves the body farther, at most its
/// bounding radius: [`deep_scale`]): 0 while any
/// texel is dry and continuous as the last one goes under, 1 once every
/// texel is deeper than `δ`. The force then differs from the derivative of
/// the columns' potential only within `δ` of the surface, by at most
/// `ρ_w g |E|`, so a body that sinks far gains at most `ρ_w g |E| δ` from
/// it. The thickness, not the bounding radius: a 200:1 rod's `E` is its
/// long faces' sampling error, a few parts in a hundred of its volume at
/// 32², and taken as far down as its half length it held a neutral rod 2 km
/// long up under a storm sea whose troughs are hundreds of
/// metres deep; its width bounds the excursion by the same `ρ_w g |E|`
/// over a two-hundredth of the depth. The step: a 2 mm rod 10 µm thick,
/// stepped at 1/240 s (`g dt²` = 0.17 mm), crossed its thickness' ramp
/// within a step or two and the volume its force took jumped by half the
/// body's between steps, pumping its heave; over `g dt²` it does not.
///
/// [`deep_scale`]: super::frame::deep_scale
///
/// Returns the volume and `φ` ([`HydroForces::deep`](crate::HydroForces::deep)).
pub(crate) fn deep_volume(frame: &Frame, s: &BuoyancySums, archimedes: bool) -> (f64, f64) {
    if frame.texels == 0 || s.count < frame.texels {
        return (s.vol, 0.0);
    }
    if frame.plane.is_some() || !archimedes {
        return (s.vol, 1.0);
    }
    let phi = s.slope.shallow.exp();
    let error = s.vol - s.slope.ayr;
    if !(phi > 0.0 && error.is_finite()) {
        // At the surface (φ = 0, or a sum that is not a number): the sum
        // as it is.
        return (s.vol, 0.0);
    }
    let phi = phi.min(1.0);
    (s.vol - phi * error, phi)
}
