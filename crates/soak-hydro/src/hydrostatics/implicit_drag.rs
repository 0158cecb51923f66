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
    let sys = m + d.k * dt;
    let rhs = m * q + d.b * dt;
    let finite = |v: Vector6<f64>| v.iter().all(|c| c.is_finite()).then_some(v);
    // Where the whole system is singular (a point mass, no inertia, whose
    // drag has no turning part), the translation alone: a body with no
    // inertia takes no torque, but its drag still slows it.
    let q_new = solve_blocks(&sys, &rhs)
        .or_else(|| sys.lu().solve(&rhs).and_then(finite))
        .or_else(|| translation_alone(&sys, &rhs, &q))
        .unwrap_or(q);
    let applied = m * (q_new - q) / dt;
    (wrench(&applied), wrench(&explicit))
}

/// The velocity with its translation solved from the first three rows of
/// `a x = r` and its rotation kept at `q`'s: `x₁ = p⁻¹ (r₁ − b q₂)`.
/// `None` where `p` is singular too or the solution is not finite.
fn translation_alone(a: &Matrix6<f64>, r: &Vector6<f64>, q: &Vector6<f64>) -> Option<Vector6<f64>> {
    let p: Matrix3<f64> = a.fixed_view::<3, 3>(0, 0).into_owned();
    let b: Matrix3<f64> = a.fixed_view::<3, 3>(0, 3).into_owned();
    let x = p.try_inverse()? * (r.fixed_rows::<3>(0) - b * q.fixed_rows::<3>(3));
    let out = Vector6::new(x.x, x.y, x.z, q[3], q[4], q[5]);
    out.iter().all(|v| v.is_finite()).then_some(out)
}

/// `x` with `a x = r`, by the 3 × 3 blocks `a = [[p, b], [c, s]]`:
/// `y = (s − c p⁻¹ b)⁻¹ (r₂ − c p⁻¹ r₁)`, `x₁ = p⁻¹ (r₁ − b y)`, each 3 × 3
/// inverse in closed form. `None` where either block to invert is
/// singular or the solution is not finite (the caller then factors the
/// whole matrix). A quarter of the time of a 6 × 6 Cholesky factor and its
/// two triangular solves (40 ns against 165 ns in one run), which every
/// body with drag took each step; and, unlike that factor (which reads
/// the lower triangle alone), exact for a matrix that is not symmetric: an
/// added mass estimated from a mesh need not be (the drift test's small
/// ball's is asymmetric by 5e-4 of its size).
fn solve_blocks(a: &Matrix6<f64>, r: &Vector6<f64>) -> Option<Vector6<f64>> {
    let p: Matrix3<f64> = a.fixed_view::<3, 3>(0, 0).into_owned();
    let b: Matrix3<f64> = a.fixed_view::<3, 3>(0, 3).into_owned();
    let c: Matrix3<f64> = a.fixed_view::<3, 3>(3, 0).into_owned();
    let s: Matrix3<f64> = a.fixed_view::<3, 3>(3, 3).into_owned();
    let (r1, r2) = (
        r.fixed_rows::<3>(0).into_owned(),
        r.fixed_rows::<3>(3).into_owned(),
    );
    let p_inv = p.try_inverse()?;
    let c_p_inv = c * p_inv;
    let y = (s - c_p_inv * b).try_inverse()? * (r2 - c_p_inv * r1);
    let x = p_inv * (r1 - b * y);
    let out = Vector6::new(x.x, x.y, x.z, y.x, y.y, y.z);
    out.iter().all(|v| v.is_finite()).then_some(out)
}

#[cfg(test)]
mod tests {
    use nalgebra::{Isometry3, Matrix3, Matrix6, Point3, Vector3, Vector6};

    use super::{implicit_drag, solve_blocks};
    use crate::hydrostatics::body_state::BodyState;
    use crate::hydrostatics::sums::DragSums;
    use crate::mass::MassProperties;

    /// A small deterministic generator (no dependency for a test).
    fn next(seed: &mut u64) -> f64 {
        *seed = seed
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        ((*seed >> 11) as f64 / (1u64 << 53) as f64) * 2.0 - 1.0
    }

    #[test]
    fn the_block_solve_agrees_with_lu_over_scales() {
        // `M + dt K` as the implicit drag makes it, for bodies of length
        // `l` from a millimetre to a kilometre: a block-diagonal mass (the
        // mass, and a world inertia of order `m l²`, a rod's a millionth
        // of that about its length) plus a symmetric positive semi-definite
        // drag whose couplings scale with `l` and whose turning part with
        // `l²`; each entry then pushed out of symmetry by up to 1e-3 of
        // itself. The velocities solved for are of order 1 m/s and 1/l
        // rad/s: each half is held to LU's against its own size.
        let mut seed = 7;
        for &(l, mass, drag) in &[
            (1e-3, 5e-7, 1e-9),
            (1e-3, 5e-7, 1e-3),
            (1.0, 150.0, 40.0),
            (1.0, 150.0, 1e5),
            (1e3, 5e11, 1e9),
        ] {
            for rod in [1.0, 1e-6] {
                for _ in 0..50 {
                    let lever = Matrix6::from_diagonal(&Vector6::new(1.0, 1.0, 1.0, l, l, l));
                    let g = Matrix6::from_fn(|_, _| next(&mut seed));
                    let k = lever * g * g.transpose() * lever * drag;
                    let turn = Matrix6::from_fn(|_, _| next(&mut seed))
                        .fixed_view::<3, 3>(0, 0)
                        .into_owned();
                    let turn = nalgebra::Rotation3::from_matrix(&turn).into_inner();
                    let axes = Matrix3::from_diagonal(&Vector3::new(1.0, 1.0, rod)) * mass * l * l;
                    let mut m = Matrix6::zeros();
                    m.fixed_view_mut::<3, 3>(0, 0).fill_diagonal(mass);
                    m.fixed_view_mut::<3, 3>(3, 3)
                        .copy_from(&(turn * axes * turn.transpose()));
                    let skew = Matrix6::from_fn(|_, _| next(&mut seed)) * 1e-3;
                    let a = m + k + skew.component_mul(&(m + k));
                    let q = Vector6::from_fn(|i, _| next(&mut seed) / if i < 3 { 1.0 } else { l });
                    let r = a * q;
                    let want = a.lu().solve(&r).unwrap();
                    let got = solve_blocks(&a, &r).unwrap();
                    for half in [0, 3] {
                        let (w, x) = (want.fixed_rows::<3>(half), got.fixed_rows::<3>(half));
                        assert!(
                            (x - w).amax() <= 1e-9 * w.amax(),
                            "l {l}, rod {rod}, rows {half}..: {x} vs {w}"
                        );
                    }
                }
            }
        }
    }

    #[test]
    fn a_singular_block_falls_back() {
        // A point mass (no inertia) without rotational drag: the lower
        // block is zero, and the caller's factorisation decides.
        let mut a = Matrix6::zeros();
        a.fixed_view_mut::<3, 3>(0, 0).fill_diagonal(2.0);
        assert!(solve_blocks(&a, &Vector6::repeat(1.0)).is_none());
    }

    #[test]
    fn a_point_mass_still_takes_its_translational_drag() {
        // A point mass (no inertia) whose drag has no turning part: the
        // whole system is singular. Its translation takes the implicit
        // decay all the same, `v' = (m v + dt k u) / (m + dt k)` along each
        // axis (`u` the fluid's velocity), and it takes no torque.
        let (m, dt) = (2.0, 0.1);
        let kd = Vector3::new(3.0, 5.0, 0.5);
        let u = Vector3::new(0.4, 0.0, -0.2);
        let mut k = Matrix6::zeros();
        for i in 0..3 {
            k[(i, i)] = kd[i];
        }
        let mut b = Vector6::zeros();
        b.fixed_rows_mut::<3>(0).copy_from(&kd.component_mul(&u));
        let sums = DragSums { k, b };
        let mass = MassProperties {
            mass: m,
            center_of_mass: Point3::origin(),
            inertia: Matrix3::zeros(),
        };
        let state = BodyState {
            linear_velocity: Vector3::new(1.5, -0.7, 0.3),
            angular_velocity: Vector3::new(0.2, 0.0, -1.0),
            ..BodyState::at_rest(Isometry3::identity())
        };
        let (applied, _) = implicit_drag(&sums, &state, &mass, None, dt);
        for i in 0..3 {
            let v = state.linear_velocity[i];
            let want = (m * v + dt * kd[i] * u[i]) / (m + dt * kd[i]);
            let got = v + applied.force[i] * dt / m;
            assert!((got - want).abs() < 1e-12, "axis {i}: {got} against {want}");
        }
        assert_eq!(applied.torque, Vector3::zeros());
    }
}
