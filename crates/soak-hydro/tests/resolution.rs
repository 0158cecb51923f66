//! `bake_to_tolerance`: the coarsest atlas whose buoyancy meets a
//! tolerance against the exact clipping of the mesh.

use nalgebra::{Isometry3, UnitQuaternion, Vector3};
use soak_bake::{Atlas, BakeOptions, builtin};
use soak_hydro::reference::{ClipPlane, submerged_part};
use soak_hydro::{
    AUTO_RESOLUTIONS, BodyState, HydroOptions, MassModel, ResolutionError, Water, bake_to_tolerance, evaluate,
};

#[test]
fn the_chosen_atlas_meets_the_tolerance_and_the_coarser_one_does_not() {
    for (mesh, tolerance) in [
        (builtin::cuboid(1.0, 0.6, 0.8), 1e-3),
        (builtin::sphere(0.5, 64, 32), 1e-3),
        (builtin::sphere(0.5, 64, 32), 1e-4),
        (builtin::boat(4.0, 1.2, 0.6), 1e-3),
    ] {
        let (atlas, choice) = bake_to_tolerance(&mesh, tolerance, BakeOptions::default()).unwrap();
        assert_eq!(atlas.width(), choice.resolution);
        assert!(choice.error <= tolerance, "{}: {choice:?}", mesh.name);
        // Every coarser side tried missed it.
        let (last, earlier) = choice.tried.split_last().unwrap();
        assert_eq!(last.0, choice.resolution);
        assert!(
            earlier.iter().all(|&(_, e)| e > tolerance),
            "{}: {choice:?}",
            mesh.name
        );
        assert_eq!(choice.tried[0].0, AUTO_RESOLUTIONS[0]);
        // Independently of the search: the chosen atlas at a level and a
        // tilt it did not measure is within the tolerance too (with a
        // margin of two for a level between the measured ones).
        let pose = Isometry3::from_parts(
            Vector3::zeros().into(),
            UnitQuaternion::from_euler_angles(0.2, 0.9, -0.3),
        );
        let level = 0.037;
        let exact = submerged_part(&mesh, &pose, &ClipPlane::horizontal(level));
        let mass = MassModel::Solid { density: 1.0 }.mass_properties(&atlas).unwrap();
        let f = evaluate(
            &atlas,
            &Water::calm(level),
            &BodyState::at_rest(pose),
            &mass,
            0.0,
            &HydroOptions::default(),
        )
        .unwrap();
        let error = (f.submerged_volume - exact.volume).abs() / mesh.volume();
        assert!(
            error <= 2.0 * tolerance,
            "{}: {error} at an unmeasured pose",
            mesh.name
        );
    }
}

#[test]
fn a_tighter_tolerance_never_picks_a_coarser_atlas() {
    let mesh = builtin::sphere(0.5, 48, 24);
    let mut last = 0;
    for tolerance in [1e-2, 1e-3, 1e-4] {
        let (_, choice) = bake_to_tolerance(&mesh, tolerance, BakeOptions::default()).unwrap();
        assert!(choice.resolution >= last, "{tolerance}: {choice:?}");
        last = choice.resolution;
    }
}

#[test]
fn bad_or_unreachable_tolerances_are_typed_errors() {
    let mesh = builtin::cuboid(1.0, 1.0, 1.0);
    for bad in [0.0, -1e-3, f64::NAN, f64::INFINITY] {
        let e = bake_to_tolerance(&mesh, bad, BakeOptions::default()).unwrap_err();
        assert!(matches!(e, ResolutionError::Tolerance { .. }), "{bad}: {e:?}");
    }
    // The box's error is that of texel sampling: 1e-14 of its volume is
    // beyond any atlas.
    let e = bake_to_tolerance(&mesh, 1e-14, BakeOptions::default()).unwrap_err();
    match e {
        ResolutionError::Unreached {
            resolution, reached, ..
        } => {
            assert_eq!(resolution, *AUTO_RESOLUTIONS.last().unwrap());
            assert!(reached > 1e-14);
        }
        e => panic!("{e:?}"),
    }
    assert!(e_to_string_names_the_tolerance());
}

fn e_to_string_names_the_tolerance() -> bool {
    let e = bake_to_tolerance(&builtin::cuboid(1.0, 1.0, 1.0), -2.0, BakeOptions::default()).unwrap_err();
    e.to_string().contains("-2")
}

/// The atlas `bake_to_tolerance` returns is the one `Atlas::bake` makes at
/// that side.
#[test]
fn the_returned_atlas_is_the_plain_bake_at_that_side() {
    let mesh = builtin::capsule(0.3, 0.6, 32);
    let (atlas, choice) = bake_to_tolerance(&mesh, 1e-3, BakeOptions::default()).unwrap();
    let plain = Atlas::bake(&mesh, BakeOptions::square(choice.resolution)).unwrap();
    assert_eq!(atlas.len(), plain.len());
    assert_eq!(atlas.areas(), plain.areas());
}
