//! The physics atlas generator makes any closed mesh bakeable.

use soak_bake::{Atlas, BakeOptions, UnwrapOptions, load_mesh, unwrap, validate};

#[test]
fn every_builtin_unwraps_to_a_bijective_atlas() {
    for name in [
        "builtin:sphere",
        "builtin:box:4x1x1",
        "builtin:cylinder",
        "builtin:capsule",
        "builtin:torus",
        "builtin:boat",
        "builtin:dumbbell",
    ] {
        let mesh = load_mesh(name).unwrap().without_uvs();
        let (out, report) = unwrap(&mesh, UnwrapOptions::default()).unwrap();
        // Same checks as an artist's map: bijective, inside the square, closed.
        validate(&out).unwrap_or_else(|e| panic!("{name}: {e}"));
        assert_eq!(out.triangles.len(), mesh.triangles.len());
        assert!(report.charts >= 1);
        assert!(
            report.density_min > 0.5 && report.density_max < 1.5,
            "{name}: {report:?}"
        );
        assert!(report.coverage > 0.3, "{name}: {report:?}");
        let atlas = Atlas::bake(&out, BakeOptions::square(256)).unwrap();
        assert!((atlas.volume() - mesh.volume()).abs() / mesh.volume() < 1e-6);
        // Triangle order is kept, so per-triangle data still applies.
        for t in (0..mesh.triangles.len()).step_by(13) {
            assert!((out.triangle_area_vector(t) - mesh.triangle_area_vector(t)).norm() < 1e-12);
        }
    }
}

#[test]
fn a_box_unwraps_into_its_six_faces_at_equal_density() {
    let mesh = load_mesh("builtin:box:4x1x1").unwrap().without_uvs();
    let (_, report) = unwrap(&mesh, UnwrapOptions::default()).unwrap();
    assert_eq!(report.charts, 6);
    assert!((report.density_max - report.density_min) < 1e-9);
}
