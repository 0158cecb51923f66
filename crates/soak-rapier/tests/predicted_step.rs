//! The driver predicts the engine's step (to keep stiff bodies stable and
//! check that no step creates energy): that prediction must be the step
//! Rapier takes, or the energy guard judges a step that never happens.

use nalgebra::{Isometry3, Matrix3, Point3, Translation3, UnitQuaternion, Vector3};
use rapier3d::prelude::{PhysicsWorld, RigidBodyBuilder};
use soak_driver::{Bodies, BodiesMut, engine_mass, predict_step};
use soak_hydro::{MassProperties, Wrench};
use soak_rapier::{RapierBodies, convert, step_params};

/// The prediction (substeps, the gyroscopic term, the turn through
/// `(1, h ω/2)` normalised, the cap on the angular speed) against Rapier's
/// own step, at an ordinary step and at one whose spin Rapier caps at π/4.
#[test]
fn the_predicted_step_is_the_one_rapier_takes() {
    for (spin, dt) in [(0.7, 1.0 / 60.0), (60.0, 1.0 / 10.0)] {
        let mut world = PhysicsWorld::new();
        world.integration_parameters.dt = dt as f32;
        let pose = Isometry3::from_parts(
            Translation3::new(0.3, -0.2, 0.1),
            UnitQuaternion::from_euler_angles(0.2, -0.1, 0.4),
        );
        let (v0, w0) = (Vector3::new(0.4, -1.1, 0.2), Vector3::new(0.3, -0.5, 1.0) * spin);
        let handle = world.bodies.insert(
            RigidBodyBuilder::dynamic()
                .pose(convert::to_pose(&pose))
                .linvel(convert::to_vector(&v0))
                .angvel(convert::to_vector(&w0)),
        );
        let mass = MassProperties {
            mass: 2.0,
            center_of_mass: Point3::new(0.05, -0.02, 0.01),
            inertia: Matrix3::new(0.3, 0.01, 0.0, 0.01, 0.5, 0.02, 0.0, 0.02, 0.7),
        };
        let wrench = Wrench {
            force: Vector3::new(1.0, 25.0, -2.0),
            torque: Vector3::new(0.2, -0.1, 0.3),
        };
        let mut engine = RapierBodies::new(&mut world.bodies, &world.colliders);
        assert!(engine.set_mass_properties(handle, &engine_mass("test", &mass).unwrap()));
        assert!(engine.set_wrench(handle, &wrench));
        let before = engine.body(handle).unwrap();
        let g = -world.gravity.y as f64;
        let predicted = predict_step(
            &before,
            &mass,
            &wrench,
            g,
            &step_params(&world.integration_parameters),
        )
        .unwrap();
        world.step();
        let rb = &world.bodies[handle];
        let close = |a: Vector3<f64>, b: Vector3<f64>, what: &str| {
            assert!(
                (a - b).norm() <= 1e-4 * (1.0 + b.norm()),
                "spin {spin}: {what} {a:?} != {b:?}"
            );
        };
        close(
            predicted.linear_velocity,
            convert::vector(rb.linvel()),
            "linear velocity",
        );
        close(
            predicted.angular_velocity,
            convert::vector(rb.angvel()),
            "angular velocity",
        );
        let after = convert::pose(rb.position());
        close(
            (predicted.pose * mass.center_of_mass).coords,
            (after * mass.center_of_mass).coords,
            "centre of mass",
        );
        assert!(
            predicted.pose.rotation.angle_to(&after.rotation) <= 1e-4,
            "spin {spin}: rotation off by {}",
            predicted.pose.rotation.angle_to(&after.rotation)
        );
        if spin > 10.0 {
            // The cap was reached: |ω| = π/(4 dt), dt as Rapier holds it.
            let dt = world.integration_parameters.dt as f64;
            assert!((predicted.angular_velocity.norm() - std::f64::consts::FRAC_PI_4 / dt).abs() < 1e-9);
        }
    }
}
