//! Archimedes' torque beyond the force at the centre of buoyancy: the terms
//! that make it the derivative of the water's potential.

use nalgebra::Vector3;

use super::frame::Frame;
use super::sums::BuoyancySums;

/// What Archimedes' torque needs, over `ρ_w g`, beyond `ρ_w g V_s` at the
/// centre of buoyancy, to be the derivative of the water's potential as the
/// texels sample it.
///
/// Under a static surface `h(x, z)` the water's potential is the columns'
/// `U = ρ_w g Σ (−A_y) d²/2`. Archimedes' vertical force is `−∂U/∂y`; the
/// torque that makes the pair conserve energy is `−∂U/∂θ` about the centre
/// of mass, `ρ_w g Σ [(d²/2) A × ŷ + A_y d ρ × (s − ŷ)]`: the force at the
/// centre of buoyancy plus `ρ_w g (Σ (d²/2) A × ŷ − Σ w ρ × s)`. Without
/// the second term a floating body pitching over a slope takes in energy
/// every swing. Under flat water `s = 0`, and `Σ (d²/2) A` of the exact
/// surface is vertical (the divergence theorem: `−ŷ ∫ d dV`), so the term
/// vanishes in the limit; but a body's samples can leave it a torque the
/// potential does not have (a sliver triangle's few samples sit off its
/// middle line), and one about an axis of small inertia spins the body.
/// Summed from the same samples, the torque is the derivative of their
/// potential whatever their placement. A body wholly under water keeps
/// the classic torque of `ρ_w g V` at its centre of buoyancy: real pressure
/// forgets the surface's shape with depth, and the columns' terms would be
/// differences of numbers that grow with the depth squared. A tilted
/// plane's slope is the same everywhere: `Σ w ρ × s = (Σ w ρ) × s`.
pub(crate) fn slope_torque(frame: &Frame, s: &BuoyancySums) -> Vector3<f64> {
    if s.count >= frame.texels {
        return Vector3::zeros();
    }
    let columns = s.d2a.cross(&Vector3::y());
    match frame.plane {
        Some((n, _)) if n.x == 0.0 && n.z == 0.0 => columns,
        Some((n, _)) => {
            let slope = Vector3::new(-n.x / n.y, 0.0, -n.z / n.y);
            let wrho = s.wr - s.vol * (frame.com - frame.ow);
            columns - wrho.cross(&slope)
        }
        None => columns - s.slope.wrs,
    }
}
