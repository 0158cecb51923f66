//! Results do not depend on the thread count: every reduction runs in
//! fixed chunks added in a fixed order, so one and many threads give
//! bit-identical liquid. A plane whose current changes over space wets as
//! its plane does.

use nalgebra::{Isometry3, Translation3, UnitQuaternion};
use soak_bake::{Atlas, BakeOptions, builtin};
use soak_hydro::{Gerstner, GerstnerWave, Water};
use soak_wet::prelude::*;

fn run(mode: DiffusionMode) -> (Vec<f64>, f64) {
    let atlas = Atlas::bake(&builtin::cylinder(0.5, 1.0, 64), BakeOptions::square(256)).unwrap();
    let sea = Water::new(
        Gerstner::new(
            0.0,
            vec![GerstnerWave {
                amplitude: 0.1,
                wavelength: 2.0,
                direction_deg: 45.0,
                steepness: 0.7,
                phase: 0.0,
            }],
            9.81,
        )
        .unwrap(),
    );
    let mut wet = Wetting::new(&atlas, Material::sand(), Liquid::water())
        .unwrap()
        .with_diffusion(Diffusion::new(1e-3).with_mode(mode));
    let pose0 = Isometry3::identity();
    wet.splash(
        &atlas,
        &pose0,
        &Splash {
            center: [0.5, 0.3, 0.0],
            radius: 0.1,
            volume: 1e-5,
        },
    )
    .unwrap();
    for k in 0..40 {
        let t = 0.1 * k as f64;
        let pose = Isometry3::from_parts(
            Translation3::new(0.0, 0.2 * t.sin(), 0.0),
            UnitQuaternion::from_euler_angles(0.3 * t, 0.0, 0.1),
        );
        wet.step(&atlas, &pose, &sea, &Environment::default(), t, 0.1)
            .unwrap();
    }
    let total = wet.total_liquid(&atlas);
    (wet.liquid().to_vec(), total)
}

#[test]
fn one_thread_and_many_agree_bit_for_bit() {
    for mode in [DiffusionMode::Conservative, DiffusionMode::Thesis] {
        let many = run(mode);
        let again = run(mode);
        let one = rayon::ThreadPoolBuilder::new()
            .num_threads(1)
            .build()
            .unwrap()
            .install(|| run(mode));
        let three = rayon::ThreadPoolBuilder::new()
            .num_threads(3)
            .build()
            .unwrap()
            .install(|| run(mode));
        assert!(many.1 > 0.0);
        assert_eq!(many, again, "{mode:?}: repeatable");
        assert_eq!(many, one, "{mode:?}: one thread");
        assert_eq!(many, three, "{mode:?}: three threads");
    }
}

/// A plane whose current changes over space (what a sea read as one plane
/// hands a large body) has the plane's heights: a body moving through it
/// takes up and gives off the same liquid, to the bit, as under the plane
/// alone, and some of it did (the body dips in and out).
#[test]
fn a_flow_plane_wets_as_its_plane() {
    use nalgebra::{Matrix3, Point3, Vector3};
    use soak_hydro::Plane;
    let atlas = Atlas::bake(&builtin::cuboid(1.0, 0.6, 0.8), BakeOptions::square(128)).unwrap();
    let plane = Plane::tilted(Point3::new(0.0, 0.05, 0.0), Vector3::new(0.1, 1.0, -0.05))
        .unwrap()
        .with_current(Vector3::new(0.3, 0.0, 0.1));
    let gradient = Matrix3::new(0.0, 0.2, 0.0, -0.1, 0.0, 0.0, 0.0, 0.0, 0.3);
    let flow = plane.with_gradient(gradient, Point3::new(1.0, 0.0, 0.0)).unwrap();
    let run = |water: &Water| {
        let mut wet = Wetting::new(&atlas, Material::sand(), Liquid::water()).unwrap();
        for k in 0..40 {
            let t = 0.1 * k as f64;
            let pose = Isometry3::from_parts(
                Translation3::new(0.0, 0.25 * t.sin(), 0.0),
                UnitQuaternion::from_euler_angles(0.3 * t, 0.0, 0.1),
            );
            wet.step(&atlas, &pose, water, &Environment::default(), t, 0.1)
                .unwrap();
        }
        (
            wet.liquid().to_vec(),
            wet.ledger().absorbed,
            wet.ledger().evaporated,
        )
    };
    let (under_plane, under_flow) = (run(&Water::new(plane)), run(&Water::new(flow)));
    let (absorbed, evaporated) = (under_plane.1, under_plane.2);
    assert!(absorbed > 0.0 && evaporated > 0.0, "{absorbed} {evaporated}");
    assert_eq!(under_flow, under_plane);
}
