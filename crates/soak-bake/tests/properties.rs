//! Property tests of the atlas over random closed meshes: every builtin shape
//! with random parameters, stretched, turned and moved far from the origin,
//! at random resolutions. The texel sums must reproduce the mesh's own area,
//! its exact polyhedral volume, and close (Σ A = 0) — whatever the shape.

use nalgebra::{Isometry3, Point3, Translation3, UnitQuaternion, Vector3};
use proptest::prelude::*;
use soak_bake::{Atlas, BakeOptions, Mesh, builtin};

/// A builtin with random parameters.
fn shape() -> impl Strategy<Value = Mesh> {
    prop_oneof![
        (0.05..3.0f64, 8usize..48, 4usize..24).prop_map(|(r, s, k)| builtin::sphere(r, s, k)),
        (0.05..4.0f64, 0.05..4.0f64, 0.05..4.0f64).prop_map(|(x, y, z)| builtin::cuboid(x, y, z)),
        (0.05..2.0f64, 0.1..4.0f64, 6usize..48).prop_map(|(r, h, s)| builtin::cylinder(r, h, s)),
        (0.05..1.0f64, 0.1..3.0f64, 6usize..32).prop_map(|(r, h, s)| builtin::capsule(r, h, s)),
        (1.0..3.0f64, 0.1..0.9f64, 8usize..40, 6usize..20).prop_map(|(big, small, s, k)| builtin::torus(
            big,
            small * big,
            s,
            k
        )),
        (1.0..8.0f64, 0.3..0.6f64, 0.2..0.5f64).prop_map(|(l, b, d)| builtin::boat(l, b * l, d * l * 0.3)),
    ]
}

/// A closed mesh: a shape stretched along its axes (positive factors keep
/// it closed and outward-facing), then turned and moved.
fn closed_mesh() -> impl Strategy<Value = Mesh> {
    (
        shape(),
        prop::array::uniform3(0.3..3.0f64),
        prop::array::uniform3(-3.2..3.2f64),
        prop::array::uniform3(-1e3..1e3f64),
    )
        .prop_map(|(mut mesh, stretch, angles, offset)| {
            let pose = Isometry3::from_parts(
                Translation3::from(Vector3::from(offset)),
                UnitQuaternion::from_euler_angles(angles[0], angles[1], angles[2]),
            );
            for p in &mut mesh.positions {
                let q = Point3::new(p.x * stretch[0], p.y * stretch[1], p.z * stretch[2]);
                *p = pose * q;
            }
            mesh
        })
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(48))]

    #[test]
    fn atlas_sums_reproduce_area_volume_and_closure(
        mesh in closed_mesh(),
        resolution in prop::sample::select(vec![16u32, 48, 128, 256]),
    ) {
        let atlas = Atlas::bake(&mesh, BakeOptions::square(resolution))
            .map_err(|e| TestCaseError::fail(format!("bake: {e}")))?;
        let (area, volume) = (mesh.area(), mesh.volume());
        prop_assert!(area > 0.0 && volume > 0.0);
        // f32 samples relative to the bounding-box centre: relative errors
        // of a few 1e-7 are the storage's, not the method's.
        prop_assert!(
            (atlas.area() - area).abs() <= 1e-5 * area,
            "area {} vs mesh {}", atlas.area(), area
        );
        prop_assert!(
            (atlas.volume() - volume).abs() <= 1e-5 * volume,
            "volume {} vs mesh {}", atlas.volume(), volume
        );
        let closure = atlas.area_vector_sum().norm();
        prop_assert!(closure <= 1e-6 * area, "|Σ A| = {closure} for area {area}");
        // Every texel carries a finite, non-negative area.
        prop_assert!(atlas.areas().iter().all(|a| a.is_finite() && *a >= 0.0));
    }
}
