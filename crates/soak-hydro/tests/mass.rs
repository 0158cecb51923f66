//! Mass properties from texel sums against exact polyhedral and analytic values.

use nalgebra::{Matrix3, Point3, UnitQuaternion, Vector3};
use soak_bake::{Atlas, BakeOptions, builtin, load_mesh};
use soak_hydro::reference::{self, analytic};
use soak_hydro::{HydroError, MassModel, MassProperties};

fn bake(mesh: &soak_bake::Mesh, res: u32) -> Atlas {
    Atlas::bake(mesh, BakeOptions::square(res)).unwrap()
}

#[test]
fn solid_builtins_at_512_match_exact_polyhedral_values() {
    for name in [
        "builtin:box:4x1x1",
        "builtin:cylinder",
        "builtin:torus",
        "builtin:boat",
        "builtin:sphere",
    ] {
        let mesh = load_mesh(name).unwrap();
        let atlas = bake(&mesh, 512);
        let ours = MassModel::Solid { density: 700.0 }
            .mass_properties(&atlas)
            .unwrap();
        let exact = reference::solid_mass_properties(&mesh, 700.0);
        let diag = mesh.diagonal();
        let vol_err = (ours.mass - exact.mass).abs() / exact.mass;
        assert!(vol_err < 0.005, "{name}: mass error {vol_err}");
        let com_err = (ours.center_of_mass - exact.centroid).norm() / diag;
        assert!(com_err < 0.005, "{name}: centre error {com_err} of the diagonal");
        let trace = exact.inertia.trace();
        for (k, (a, b)) in ours.inertia.iter().zip(exact.inertia.iter()).enumerate() {
            let e = (a - b).abs() / trace;
            assert!(e < 0.005, "{name}: inertia[{k}] {a} vs {b} ({e} of the trace)");
        }
    }
}

#[test]
fn inertia_converges_with_resolution() {
    // Second moments vary over a face. Texel-centre sampling (the thesis')
    // has a first-order error from partly covered texels along triangle
    // edges; moment-matched samples (the default) remove it.
    let mesh = builtin::boat(4.0, 1.2, 0.6);
    let exact = reference::solid_mass_properties(&mesh, 1.0);
    let err = |res, matched| {
        let mut o = BakeOptions::square(res);
        o.moment_matching = matched;
        let m = MassModel::Solid { density: 1.0 }
            .mass_properties(&Atlas::bake(&mesh, o).unwrap())
            .unwrap();
        (m.inertia - exact.inertia).norm() / exact.inertia.norm()
    };
    let (centres64, centres2048) = (err(64, false), err(2048, false));
    assert!(centres2048 < centres64 / 10.0, "{centres64} {centres2048}");
    let (m256, m1024) = (err(256, true), err(1024, true));
    assert!(m256 < 1e-4 && m1024 < 1e-7, "{m256} {m1024}");
    assert!(m1024 < centres2048 / 100.0);
}

#[test]
fn sphere_shell_matches_the_analytic_thin_shell() {
    let r = 0.5;
    let mesh = builtin::sphere(r, 256, 128);
    let atlas = bake(&mesh, 1024);
    let ours = MassModel::Shell { areal_density: 2.0 }
        .mass_properties(&atlas)
        .unwrap();
    let analytic = analytic::sphere_shell_mass_properties(r, 2.0);
    assert!((ours.mass - analytic.mass).abs() / analytic.mass < 1e-3);
    let expected = 2.0 / 3.0 * ours.mass * r * r;
    for k in 0..3 {
        let e = (ours.inertia[(k, k)] - expected).abs() / expected;
        assert!(e < 2e-3, "axis {k}: {e}");
    }
    assert!(ours.center_of_mass.coords.norm() < 1e-4);
    // And against the exact shell of the same mesh, tighter.
    let exact = reference::shell_mass_properties(&mesh, 2.0);
    assert!((ours.inertia - exact.inertia).norm() / exact.inertia.norm() < 1e-3);
}

#[test]
fn shell_texture_follows_its_values() {
    let mesh = builtin::cuboid(2.0, 1.0, 1.0);
    let atlas = bake(&mesh, 128);
    let uniform = MassModel::Shell { areal_density: 3.0 }
        .mass_properties(&atlas)
        .unwrap();
    let tex = MassModel::ShellTexture {
        areal_density: vec![3.0; atlas.len()],
    }
    .mass_properties(&atlas)
    .unwrap();
    assert!((uniform.mass - tex.mass).abs() < 1e-9 * uniform.mass);
    assert!((uniform.mass - 3.0 * 10.0).abs() < 1e-4);
    // Weight the +x half heavier: the centre of mass moves to +x.
    let heavy: Vec<f32> = (0..atlas.len())
        .map(|i| if atlas.position(i).x > 0.0 { 9.0 } else { 1.0 })
        .collect();
    let m = MassModel::ShellTexture { areal_density: heavy }
        .mass_properties(&atlas)
        .unwrap();
    assert!(m.center_of_mass.x > 0.3, "{}", m.center_of_mass);
    // Wrong length and bad values are refused with the texel named.
    let short = MassModel::ShellTexture {
        areal_density: vec![1.0; 3],
    }
    .mass_properties(&atlas);
    assert!(matches!(short, Err(HydroError::ChannelLength { len: 3, .. })));
    let mut nan = vec![1.0f32; atlas.len()];
    nan[17] = f32::NAN;
    let bad = MassModel::ShellTexture { areal_density: nan }.mass_properties(&atlas);
    assert!(matches!(bad, Err(HydroError::ChannelValue { texel: 17, .. })));
    assert!(matches!(
        MassModel::Solid { density: -1.0 }.mass_properties(&atlas),
        Err(HydroError::Density { .. })
    ));
}

#[test]
fn principal_axes_of_a_rotated_box() {
    let (a, b, c) = (4.0, 1.0, 2.0);
    let q = UnitQuaternion::from_euler_angles(0.3, -0.7, 1.1);
    let mesh = builtin::cuboid(a, b, c).map_positions(|p| q * p);
    let m = MassModel::Solid { density: 1.0 }
        .mass_properties(&bake(&mesh, 1024))
        .unwrap();
    let mass = a * b * c;
    let mut want = [
        mass * (b * b + c * c) / 12.0,
        mass * (a * a + c * c) / 12.0,
        mass * (a * a + b * b) / 12.0,
    ];
    want.sort_by(f64::total_cmp);
    let p = m.principal();
    for k in 0..3 {
        assert!(
            (p.moments[k] - want[k]).abs() / want[2] < 1e-3,
            "{k}: {} vs {}",
            p.moments[k],
            want[k]
        );
    }
    // Rebuilding the tensor from the principal frame gives it back.
    let r = p.frame.to_rotation_matrix().into_inner();
    let back = r * Matrix3::from_diagonal(&p.moments) * r.transpose();
    assert!((back - m.inertia).norm() / m.inertia.norm() < 1e-9);
}

#[test]
fn combining_two_point_masses() {
    let a = MassProperties::point(1.0, Point3::new(-1.0, 0.0, 0.0));
    let b = MassProperties::point(3.0, Point3::new(1.0, 0.0, 0.0));
    let c = a.combine(&b);
    assert_eq!(c.mass, 4.0);
    assert!((c.center_of_mass - Point3::new(0.5, 0.0, 0.0)).norm() < 1e-15);
    // I_yy = Σ m d² = 1·1.5² + 3·0.5² = 3.
    assert!((c.inertia[(1, 1)] - 3.0).abs() < 1e-12);
    assert!(c.inertia[(0, 0)].abs() < 1e-12);
    assert_eq!(c.inertia_about(&Point3::new(0.5, 0.0, 0.0)), c.inertia);
    let _ = Vector3::<f64>::zeros();
}
