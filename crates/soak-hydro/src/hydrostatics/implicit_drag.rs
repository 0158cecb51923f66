//! The implicit drag solve: drag integrated over the step so that it never
//! reverses a velocity.

use nalgebra::{Matrix3, Matrix6, Vector3, Vector6};

use super::body_state::BodyState;
use super::forces::Wrench;
use super::sums::DragSums;
use crate::mass::MassProperties;

/// `(applied, explicit)`: the applied drag is `M (q' − q)/dt` with
/// `q' = (M + dt K)⁻¹ (M q + dt b)`, which decays the relative velocity
/// without ever reversing it, for any `dt`. `M` is the body's mass and
/// inertia, plus `added` where the body has an added mass: its
/// translational part in world axes (kg) and its rotational part in
/// object axes (kg·m²).
pub(crate) fn implicit_drag(
    d: &DragSums,
    state: &BodyState,
    mass: &MassProperties,
    added: Option<&(Matrix3<f64>, Matrix3<f64>)>,
    dt: f64,
) -> (Wrench, Wrench) {
    let q = Vector6::new(
        state.linear_velocity.x,
        state.linear_velocity.y,
        state.linear_velocity.z,
        state.angular_velocity.x,
        state.angular_velocity.y,
        state.angular_velocity.z,
    );
    let explicit = d.b - d.k * q;
    let wrench = |v: &Vector6<f64>| Wrench {
        force: Vector3::new(v[0], v[1], v[2]),
        torque: Vector3::new(v[3], v[4], v[5]),
    };
    if dt.is_nan() || dt <= 0.0 || mass.mass <= 0.0 {
        return (wrench(&explicit), wrench(&explicit));
    }
    let rot = state.pose.rotation.to_rotation_matrix().into_inner();
    let (linear, inertia) = match added {
        None => (
            Matrix3::identity() * mass.mass,
            rot * mass.inertia * rot.transpose(),
        ),
        Some((linear, angular)) => (
            Matrix3::identity() * mass.mass + linear,
            rot * (mass.inertia + angular) * rot.transpose(),
        ),
    };
    let mut m = Matrix6::zeros();
    m.fixed_view_mut::<3, 3>(0, 0).copy_from(&linear);
    m.fixed_view_mut::<3, 3>(3, 3).copy_from(&inertia);
    // A massless rotational axis (point mass) gets no rotational drag.
    let sys = m + d.k * dt;
    let rhs = m * q + d.b * dt;
    let q_new = sys
        .cholesky()
        .map(|c| c.solve(&rhs))
        .or_else(|| sys.lu().solve(&rhs))
        .unwrap_or(q);
    let applied = m * (q_new - q) / dt;
    (wrench(&applied), wrench(&explicit))
}
