//! The exact references of `soak_hydro::reference`, checked against answers
//! derived by hand (closed forms, quadrature, symmetry), never against the
//! code itself.
//!
//! One file on purpose: one test per reference function, each with the
//! closed form it is checked against beside it.

use std::f64::consts::{FRAC_PI_2, PI};

use nalgebra::{Isometry3, Matrix3, Point3, Translation3, Unit, UnitQuaternion, Vector3};
use soak_bake::{Mesh, builtin};
use soak_hydro::reference::{
    ClipPlane, SubmergedPart, analytic, per_triangle_buoyancy, shell_mass_properties, solid_mass_properties,
    submerged_part, wetted_area,
};

fn rel(a: f64, b: f64) -> f64 {
    (a - b).abs() / b.abs().max(f64::MIN_POSITIVE)
}

fn mat_rel(a: &Matrix3<f64>, b: &Matrix3<f64>) -> f64 {
    (a - b).norm() / b.norm().max(f64::MIN_POSITIVE)
}

fn sci(values: &[f64]) -> String {
    values
        .iter()
        .map(|v| format!("{v:.3e}"))
        .collect::<Vec<_>>()
        .join(", ")
}

fn diag(x: f64, y: f64, z: f64) -> Matrix3<f64> {
    Matrix3::from_diagonal(&Vector3::new(x, y, z))
}

fn rotations() -> Vec<UnitQuaternion<f64>> {
    vec![
        UnitQuaternion::identity(),
        UnitQuaternion::from_axis_angle(&Vector3::x_axis(), FRAC_PI_2),
        UnitQuaternion::from_axis_angle(&Unit::new_normalize(Vector3::new(1.0, 2.0, 3.0)), 0.7),
        UnitQuaternion::from_euler_angles(0.3, -1.1, 2.5),
    ]
}

fn translations() -> Vec<Vector3<f64>> {
    vec![
        Vector3::zeros(),
        Vector3::new(0.25, -0.5, 0.125),
        Vector3::new(10.5, -3.25, 7.0),
        Vector3::new(123.4, -56.7, 89.0),
    ]
}

fn identity() -> Isometry3<f64> {
    Isometry3::identity()
}

/// The unit right tetrahedron (0,0,0), (1,0,0), (0,1,0), (0,0,1), outward winding.
fn tetrahedron() -> Mesh {
    let positions = vec![
        Point3::new(0.0, 0.0, 0.0),
        Point3::new(1.0, 0.0, 0.0),
        Point3::new(0.0, 1.0, 0.0),
        Point3::new(0.0, 0.0, 1.0),
    ];
    Mesh::new(
        "tetrahedron",
        positions,
        None,
        vec![[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]],
    )
}

/// A prism with the square cross-section (±1, 0), (0, ±1) in xy, z ∈ [−½, ½]:
/// the unit cube under (x, y) ↦ (x − y, x + y). Two of its edges lie exactly at y = 0.
fn diamond_prism() -> Mesh {
    builtin::cuboid(1.0, 1.0, 1.0).map_positions(|p| Point3::new(p.x - p.y, p.x + p.y, p.z))
}

/// Second moment about the world origin, `∫ x xᵀ dV`.
fn origin_second_moment(part: &SubmergedPart) -> Matrix3<f64> {
    let c = part.centroid.coords;
    part.second_moment + c * c.transpose() * part.volume
}

#[test]
fn boxes_have_exact_mass_properties_under_rigid_motions() {
    let mut worst = 0.0f64;
    for (sx, sy, sz) in [(1.0, 1.0, 1.0), (4.0, 1.0, 1.0)] {
        let density = 850.0;
        let volume = sx * sy * sz;
        let mass = density * volume;
        let local = diag(sy * sy + sz * sz, sx * sx + sz * sz, sx * sx + sy * sy) * (mass / 12.0);
        for q in rotations() {
            for t in translations() {
                let pose = Isometry3::from_parts(Translation3::from(t), q);
                let mesh = builtin::cuboid(sx, sy, sz).map_positions(|p| pose * p);
                let props = solid_mass_properties(&mesh, density);
                let r = q.to_rotation_matrix();
                let expected = r.matrix() * local * r.matrix().transpose();
                assert!(
                    rel(props.volume, volume) < 1e-12,
                    "{sx}x{sy}x{sz} volume {}",
                    props.volume
                );
                assert!(rel(props.mass, mass) < 1e-12);
                let scale = t.norm() + (sx + sy + sz);
                assert!(
                    (props.centroid.coords - t).norm() < 1e-12 * scale,
                    "centroid {:?}",
                    props.centroid
                );
                let e = mat_rel(&props.inertia, &expected);
                assert!(e < 1e-12, "{sx}x{sy}x{sz} at {t:?}: inertia error {e:e}");
                worst = worst.max(e);
            }
        }
    }
    eprintln!("boxes under rigid motions: worst inertia rel. error {worst:.2e}");
    // The unit cube's shell: six plates of mass M/6, I = 5 M a² / 18 about every axis.
    for q in rotations() {
        let mesh = builtin::cuboid(1.0, 1.0, 1.0).map_positions(|p| q * p + Vector3::new(3.0, -2.0, 1.0));
        let shell = shell_mass_properties(&mesh, 2.0);
        assert!(rel(shell.area, 6.0) < 1e-12);
        assert!((shell.centroid - Point3::new(3.0, -2.0, 1.0)).norm() < 1e-12);
        assert!(mat_rel(&shell.inertia, &(Matrix3::identity() * (5.0 * 12.0 / 18.0))) < 1e-12);
    }
}

#[test]
fn uv_sphere_converges_to_the_analytic_sphere() {
    let r = 0.5;
    let solid = analytic::sphere_mass_properties(r, 1.0);
    let shell = analytic::sphere_shell_mass_properties(r, 1.0);
    assert!(rel(solid.volume, 4.0 / 3.0 * PI * 0.125) < 1e-15);
    let mut last = [f64::INFINITY; 4];
    for (segments, rings) in [(16, 8), (32, 16), (64, 32), (128, 64), (256, 128)] {
        let mesh = builtin::sphere(r, segments, rings);
        let p = solid_mass_properties(&mesh, 1.0);
        let s = shell_mass_properties(&mesh, 1.0);
        // Compare the mesh's inertia with 2/5 M r² and 2/3 M r² (analytic mass).
        let errors = [
            rel(p.volume, solid.volume),
            mat_rel(&p.inertia, &(Matrix3::identity() * (0.4 * solid.mass * r * r))),
            rel(s.area, shell.area),
            mat_rel(
                &s.inertia,
                &(Matrix3::identity() * (2.0 / 3.0 * shell.mass * r * r)),
            ),
        ];
        eprintln!(
            "sphere {segments}x{rings}: volume, inertia, area, shell inertia rel. errors {}",
            sci(&errors)
        );
        for (e, l) in errors.iter().zip(&last) {
            assert!(
                e < l,
                "error must shrink with tessellation: {errors:?} after {last:?}"
            );
        }
        assert!(p.centroid.coords.norm() < 1e-12 && s.centroid.coords.norm() < 1e-12);
        last = errors;
    }
    assert!(last.iter().all(|&e| e < 1e-3), "256x128 errors {last:?}");
}

#[test]
fn axis_aligned_box_submerged_is_exact_across_and_beyond_the_box() {
    let (sx, sy, sz): (f64, f64, f64) = (4.0, 1.0, 1.0);
    for t in [
        Vector3::zeros(),
        Vector3::new(2.0, 3.0, -1.0),
        Vector3::new(-0.3, 0.7, 0.1),
    ] {
        let pose = Isometry3::translation(t.x, t.y, t.z);
        for w in [-2.0, -0.5, -0.4999, -0.3, 0.0, 0.123, 0.25, 0.49, 0.5, 0.7, 3.0] {
            // The water height relative to the box centre, then by hand.
            let h = (w + sy / 2.0).clamp(0.0, sy);
            let volume = sx * h * sz;
            let (centroid, second) = if h > 0.0 {
                (
                    Point3::new(0.0, -sy / 2.0 + h / 2.0, 0.0),
                    diag(sx * sx, h * h, sz * sz) * (volume / 12.0),
                )
            } else {
                (Point3::new(0.0, w, 0.0), Matrix3::zeros())
            };
            let analytic = analytic::cuboid_submerged(sx, sy, sz, w);
            let exact = submerged_part(
                &builtin::cuboid(sx, sy, sz),
                &pose,
                &ClipPlane::horizontal(w + t.y),
            );
            for (name, part, offset) in [("analytic", analytic, Vector3::zeros()), ("exact", exact, t)] {
                assert!(
                    (part.volume - volume).abs() < 1e-12 * sx * sy * sz,
                    "{name} w={w}: {}",
                    part.volume
                );
                assert!(
                    (part.centroid - (centroid + offset)).norm() < 1e-12 * (1.0 + t.norm()),
                    "{name} w={w} t={t:?}: {:?}",
                    part.centroid
                );
                assert!(
                    (part.second_moment - second).norm() < 1e-12 * 16.0,
                    "{name} w={w}"
                );
            }
        }
    }
}

#[test]
fn rotated_box_submerged_plus_emerged_is_the_whole() {
    let mesh = builtin::cuboid(4.0, 1.0, 1.0);
    let volume = 4.0;
    let local = diag(16.0, 1.0, 1.0) * (volume / 12.0);
    let mut worst = 0.0f64;
    for q in rotations() {
        let t = Vector3::new(0.3, 0.1, -0.2);
        let pose = Isometry3::from_parts(Translation3::from(t), q);
        let r = q.to_rotation_matrix();
        let whole_second = r.matrix() * local * r.matrix().transpose() + t * t.transpose() * volume;
        for w in [-2.5, -1.0, -0.61, -0.2, 0.0, 0.15, 0.37, 0.9, 1.3, 2.5] {
            let plane = ClipPlane::horizontal(w);
            let wet = submerged_part(&mesh, &pose, &plane);
            let dry = submerged_part(&mesh, &pose, &plane.flipped());
            assert!(wet.volume >= 0.0 && dry.volume >= 0.0);
            assert!(rel(wet.volume + dry.volume, volume) < 1e-12, "w={w}");
            worst = worst.max(rel(wet.volume + dry.volume, volume));
            let first = wet.first_moment() + dry.first_moment();
            assert!(
                (first - t * volume).norm() < 1e-12 * volume * (1.0 + t.norm()),
                "w={w}: {first:?}"
            );
            let second = origin_second_moment(&wet) + origin_second_moment(&dry);
            assert!(mat_rel(&second, &whole_second) < 1e-12, "w={w}");
            // Water below the box's centroid leaves less than half of it wet.
            assert_eq!(wet.volume < dry.volume, w < t.y, "w={w}");
        }
    }
    eprintln!("rotated box, wet + dry volume: worst rel. error {worst:.2e}");
}

#[test]
fn waterline_through_tetrahedron_vertices() {
    let tet = tetrahedron();
    let at = |w: f64| submerged_part(&tet, &identity(), &ClipPlane::horizontal(w));

    // Through the three base vertices: the base face lies in the plane.
    let base = at(0.0);
    assert_eq!(base.volume, 0.0);
    assert_eq!(base.centroid, Point3::new(0.5, 0.0, 0.5)); // plane point nearest the box centre
    assert_eq!(base.second_moment, Matrix3::zeros());
    assert_eq!(wetted_area(&tet, &identity(), &ClipPlane::horizontal(0.0)), 0.0);
    // Just above it: a thin slab over the base triangle, centroid (1/3, 0, 1/3).
    let slab = at(1e-9);
    assert!((slab.volume - 0.5e-9).abs() < 1e-17);
    assert!((slab.centroid - Point3::new(1.0 / 3.0, 0.5e-9, 1.0 / 3.0)).norm() < 1e-8);

    // Halfway: V(w) = (1 − (1 − w)³)/6; by slices, ∫y dV = 11/384, ∫x dV = 15/384.
    let half = at(0.5);
    assert!((half.volume - 7.0 / 48.0).abs() < 1e-15);
    assert!((half.centroid - Point3::new(15.0 / 56.0, 11.0 / 56.0, 15.0 / 56.0)).norm() < 1e-14);

    // Through the apex vertex only: the whole tetrahedron, second moments
    // ∫x² = 1/60, ∫xy = 1/120 about the origin.
    let full = at(1.0);
    assert!((full.volume - 1.0 / 6.0).abs() < 1e-15);
    assert!((full.centroid - Point3::new(0.25, 0.25, 0.25)).norm() < 1e-15);
    let expected = Matrix3::from_fn(|i, j| if i == j { 1.0 / 160.0 } else { -1.0 / 480.0 });
    assert!((full.second_moment - expected).norm() < 1e-15);
    let area = wetted_area(&tet, &identity(), &ClipPlane::horizontal(1.0));
    assert!((area - (1.5 + 3f64.sqrt() / 2.0)).abs() < 1e-14);

    // Continuous through the special heights.
    for w in [0.0, 0.5, 1.0] {
        let v = at(w);
        for e in [-1e-9, 1e-9] {
            let p = at(w + e);
            assert!(p.volume.is_finite() && p.centroid.coords.iter().all(|x| x.is_finite()));
            assert!((p.volume - v.volume).abs() < 1e-9, "w={w}{e:+}");
            if v.volume > 0.0 {
                assert!((p.centroid - v.centroid).norm() < 1e-8, "w={w}{e:+}");
                assert!((p.second_moment - v.second_moment).norm() < 1e-8, "w={w}{e:+}");
            }
        }
    }
}

#[test]
fn waterline_along_diamond_edges_and_box_faces() {
    let prism = diamond_prism();
    let at = |w: f64| submerged_part(&prism, &identity(), &ClipPlane::horizontal(w));
    assert!((prism.volume() - 2.0).abs() < 1e-15);

    // y = 0 runs exactly along the two side edges: the lower half is a triangular
    // prism (base 2, height 1, length 1): V = 1, ȳ = −1/3, ∫(y−ȳ)² = b h³/36 = 1/18,
    // ∫x² = ∫₀¹ (2t)³/12 dt = 1/6, ∫z² = V/12.
    let half = at(0.0);
    assert!((half.volume - 1.0).abs() < 1e-15);
    assert!((half.centroid - Point3::new(0.0, -1.0 / 3.0, 0.0)).norm() < 1e-15);
    assert!((half.second_moment - diag(1.0 / 6.0, 1.0 / 18.0, 1.0 / 12.0)).norm() < 1e-15);
    let area = wetted_area(&prism, &identity(), &ClipPlane::horizontal(0.0));
    assert!(
        (area - (2.0 * 2f64.sqrt() + 2.0)).abs() < 1e-14,
        "two √2×1 faces and two unit end triangles: {area}"
    );

    // Along the bottom edge: dry. Along the top edge: all of it.
    let none = at(-1.0);
    assert_eq!((none.volume, none.centroid), (0.0, Point3::new(0.0, -1.0, 0.0)));
    let all = at(1.0);
    assert!((all.volume - 2.0).abs() < 1e-15 && all.centroid.coords.norm() < 1e-15);
    assert!((all.second_moment - diag(1.0 / 3.0, 1.0 / 3.0, 1.0 / 6.0)).norm() < 1e-15);

    for w in [-1.0, 0.0, 1.0] {
        let v = at(w);
        for e in [-1e-9, 1e-9] {
            let p = at(w + e);
            // dV/dw is the waterline width (0 or 2) times the length 1.
            assert!(
                (p.volume - v.volume).abs() <= 2.0 * 1e-9 + 1e-15,
                "w={w}{e:+}: {}",
                p.volume
            );
            if v.volume > 0.0 && p.volume > 0.0 {
                assert!((p.centroid - v.centroid).norm() < 1e-8, "w={w}{e:+}");
            }
        }
    }

    // A cube whose bottom or top face lies in the plane (translation exact in binary).
    let cube = builtin::cuboid(1.0, 1.0, 1.0);
    let pose = Isometry3::translation(0.0, 0.25, 0.0);
    let bottom = submerged_part(&cube, &pose, &ClipPlane::horizontal(-0.25));
    assert_eq!(
        (bottom.volume, bottom.centroid),
        (0.0, Point3::new(0.0, -0.25, 0.0))
    );
    let top = submerged_part(&cube, &pose, &ClipPlane::horizontal(0.75));
    assert!((top.volume - 1.0).abs() < 1e-15 && (top.centroid - Point3::new(0.0, 0.25, 0.0)).norm() < 1e-15);
    assert!((wetted_area(&cube, &pose, &ClipPlane::horizontal(0.75)) - 5.0).abs() < 1e-14);
    for (w, v) in [(-0.25, 0.0), (0.75, 1.0)] {
        for e in [-1e-9, 1e-9] {
            let p = submerged_part(&cube, &pose, &ClipPlane::horizontal(w + e));
            assert!((p.volume - (v + e).clamp(0.0, 1.0)).abs() < 1e-15, "w={w}{e:+}");
        }
    }
}

#[test]
fn sphere_mesh_submerged_converges_to_the_cap() {
    let r: f64 = 0.5;
    let whole = 4.0 / 3.0 * PI * r.powi(3);
    let heights: Vec<f64> = (0..=20).map(|i| -0.5 + 0.05 * i as f64).collect();
    let mut last = [f64::INFINITY; 4];
    for (segments, rings) in [(16, 8), (32, 16), (64, 32), (128, 64), (256, 128)] {
        let mesh = builtin::sphere(r, segments, rings);
        let mut errors = [0.0f64; 4];
        for &w in &heights {
            let exact = submerged_part(&mesh, &identity(), &ClipPlane::horizontal(w));
            let cap = analytic::sphere_submerged(r, w);
            let wet = wetted_area(&mesh, &identity(), &ClipPlane::horizontal(w));
            let cap_area = 2.0 * PI * r * (r + w).clamp(0.0, 2.0 * r);
            errors[0] = errors[0].max((exact.volume - cap.volume).abs() / whole);
            errors[1] = errors[1].max((exact.centroid - cap.centroid).norm() / r);
            errors[2] = errors[2].max((exact.second_moment - cap.second_moment).norm() / (whole * r * r));
            errors[3] = errors[3].max((wet - cap_area).abs() / (4.0 * PI * r * r));
        }
        eprintln!(
            "sphere {segments}x{rings} vs cap over w∈[−0.5,0.5]: max volume, centroid, second moment, wetted area errors {}",
            sci(&errors)
        );
        for (e, l) in errors.iter().zip(&last) {
            assert!(e < l, "error must shrink: {errors:?} after {last:?}");
        }
        last = errors;
    }
    assert!(last.iter().all(|&e| e < 1e-3), "{last:?}");
}

#[test]
fn analytic_sphere_cap_matches_closed_forms_in_water_height() {
    // Integrate the slices y ∈ [−r, w] directly: disks of radius² r² − y².
    let r = 0.7;
    for i in 0..=28 {
        let w = -r + i as f64 * 0.05;
        let v = PI * (r * r * w - w.powi(3) / 3.0 + 2.0 * r.powi(3) / 3.0);
        let my = -PI * (r * r - w * w).powi(2) / 4.0;
        let myy = PI * (r * r * w.powi(3) / 3.0 - w.powi(5) / 5.0 + 2.0 * r.powi(5) / 15.0);
        let mxx = PI / 4.0
            * (r.powi(4) * w - 2.0 * r * r * w.powi(3) / 3.0 + w.powi(5) / 5.0 + 8.0 * r.powi(5) / 15.0);
        let cap = analytic::sphere_submerged(r, w);
        assert!((cap.volume - v).abs() < 1e-14, "w={w}");
        if v > 1e-6 {
            let y = my / v;
            assert!((cap.centroid.y - y).abs() < 1e-12, "w={w}");
            let expected = diag(mxx, myy - v * y * y, mxx);
            assert!((cap.second_moment - expected).norm() < 1e-13, "w={w}");
        }
    }
    assert_eq!(
        analytic::sphere_submerged(r, -1.0).centroid,
        Point3::new(0.0, -1.0, 0.0)
    );
    assert!(
        rel(
            analytic::sphere_submerged(r, 5.0).volume,
            4.0 / 3.0 * PI * r.powi(3)
        ) < 1e-15
    );
}

#[test]
fn per_triangle_baseline_is_exact_below_the_equator_and_overestimates_above() {
    let (r, rho, g) = (0.5, 1000.0, 9.81);
    let (segments, rings) = (128, 64);
    let mesh = builtin::sphere(r, segments, rings);
    let whole = 4.0 / 3.0 * PI * r.powi(3);
    let base = |w: f64| per_triangle_buoyancy(&mesh, &identity(), &ClipPlane::horizontal(w), rho, g);
    let exact = |w: f64| submerged_part(&mesh, &identity(), &ClipPlane::horizontal(w));

    // Less than half submerged: every wet face points down and its column ends at
    // the waterline inside the (convex) body, so the columns tile the submerged part.
    for i in 0..=10 {
        let w = -0.5 + 0.05 * i as f64;
        let (b, e) = (base(w), exact(w));
        assert!(
            (b.volume - e.volume).abs() < 1e-12 * whole,
            "w={w}: {} vs {}",
            b.volume,
            e.volume
        );
        assert!((b.force - Vector3::new(0.0, rho * g * e.volume, 0.0)).norm() < 1e-9 * rho * g * whole);
        assert!(
            b.centre.x.abs() < 1e-9 && b.centre.z.abs() < 1e-9,
            "w={w}: {:?}",
            b.centre
        );
        assert!(
            (b.volume - analytic::sphere_column_volume(r, w)).abs() < 2e-3 * whole,
            "w={w}"
        );
    }

    // Past the equator the upward faces are ignored: the excess over the truth is
    // π w³/3 for a smooth sphere, growing until the sphere is under.
    let mut previous = 0.0;
    for i in 1..=10 {
        let w = 0.05 * i as f64;
        let excess = base(w).volume - exact(w).volume;
        assert!(excess > previous, "w={w}: excess {excess} after {previous}");
        assert!(
            (excess - PI * w.powi(3) / 3.0).abs() < 2e-3 * whole,
            "w={w}: excess {excess}"
        );
        assert!((base(w).volume - analytic::sphere_column_volume(r, w)).abs() < 2e-3 * whole);
        previous = excess;
    }

    // Fully submerged: the truth is constant, the baseline grows by the projected
    // area per metre, here the equator polygon's (n/2) r² sin(2π/n).
    let projected = segments as f64 / 2.0 * r * r * (2.0 * PI / segments as f64).sin();
    let top = base(0.5).volume;
    for w in [0.5, 0.75, 1.0, 2.0, 5.0] {
        let b = base(w).volume;
        assert!(rel(b, top + projected * (w - 0.5)) < 1e-12, "w={w}: {b}");
        assert!(rel(exact(w).volume, mesh.volume()) < 1e-12);
    }
    eprintln!(
        "baseline/exact on sphere {segments}x{rings}: w=0: {:.6}, w=0.25: {:.6}, w=0.5: {:.6}, w=1: {:.6}",
        base(0.0).volume / exact(0.0).volume,
        base(0.25).volume / exact(0.25).volume,
        base(0.5).volume / exact(0.5).volume,
        base(1.0).volume / exact(1.0).volume,
    );
}

#[test]
fn cylinders_match_their_closed_forms() {
    let (r, h) = (0.5, 1.2);
    let mesh = builtin::cylinder(r, h, 512);
    let solid = solid_mass_properties(&mesh, 1.0);
    let exact = analytic::cylinder_mass_properties(r, h, 1.0);
    // Hand: V = π r² H; I_yy = M r²/2; I_xx = M (3r² + H²)/12.
    let m = PI * r * r * h;
    assert!(rel(exact.volume, m) < 1e-15);
    assert!(
        mat_rel(
            &exact.inertia,
            &diag(m * (0.75 + 1.44) / 12.0, m * 0.125, m * (0.75 + 1.44) / 12.0)
        ) < 1e-15
    );
    assert!(rel(solid.volume, exact.volume) < 1e-4);
    assert!(mat_rel(&solid.inertia, &exact.inertia) < 1e-4);

    // Upright, cut at several heights: exact for the polygon up to its area ratio.
    let ratio = 512.0 / (2.0 * PI) * (2.0 * PI / 512.0).sin();
    for w in [-0.7, -0.6, -0.3, 0.0, 0.2, 0.6, 0.9] {
        let cut = submerged_part(&mesh, &identity(), &ClipPlane::horizontal(w));
        let smooth = analytic::cylinder_submerged(r, h, w);
        assert!((cut.volume - ratio * smooth.volume).abs() < 1e-12, "w={w}");
        assert!((cut.centroid - smooth.centroid).norm() < 1e-12, "w={w}");
        assert!(
            (cut.second_moment - smooth.second_moment).norm() < 1e-4 * m * r * r,
            "w={w}"
        );
    }

    // Lying on its side (axis along x).
    let side = Isometry3::rotation(Vector3::z() * FRAC_PI_2);
    let len = h;
    for i in 0..=24 {
        let w = -0.6 + 0.05 * i as f64;
        let cut = submerged_part(&mesh, &side, &ClipPlane::horizontal(w));
        let smooth = analytic::lying_cylinder_submerged(r, len, w);
        let q = segment_by_quadrature(r, w);
        assert!((smooth.volume - len * q[0]).abs() < 1e-12, "w={w}");
        if q[0] > 0.0 {
            let y = q[1] / q[0];
            assert!((smooth.centroid.y - y).abs() < 1e-10, "w={w}");
            let expected = diag(
                smooth.volume * len * len / 12.0,
                len * (q[2] - q[0] * y * y),
                len * q[3],
            );
            assert!((smooth.second_moment - expected).norm() < 1e-12, "w={w}");
        }
        assert!(
            (cut.volume - smooth.volume).abs() < 1e-4 * m,
            "w={w}: {} vs {}",
            cut.volume,
            smooth.volume
        );
        // (At w = −r the rotated mesh's bottom edge is level only to rounding: the
        // centroid of a vanishing sliver is ill-conditioned, so skip it.)
        if smooth.volume > 1e-6 * m {
            assert!((cut.centroid - smooth.centroid).norm() < 1e-4, "w={w}");
        }
    }
}

/// Area, ∫y, ∫y², ∫z² of the disk of radius `r` below `y = w`, by Simpson's rule
/// in the angle ψ (y = r sin ψ), where the integrands are smooth.
fn segment_by_quadrature(r: f64, w: f64) -> [f64; 4] {
    if w <= -r {
        return [0.0; 4];
    }
    let top = (w / r).clamp(-1.0, 1.0).asin();
    let n = 2000;
    let step = (top + FRAC_PI_2) / n as f64;
    let mut sum = [0.0; 4];
    for k in 0..=n {
        let psi = -FRAC_PI_2 + k as f64 * step;
        let weight = if k == 0 || k == n {
            1.0
        } else if k % 2 == 1 {
            4.0
        } else {
            2.0
        };
        let (y, half) = (r * psi.sin(), r * psi.cos());
        let dy = r * psi.cos();
        // A chord of length 2·half at height y.
        let f = [
            2.0 * half,
            2.0 * half * y,
            2.0 * half * y * y,
            2.0 * half.powi(3) / 3.0,
        ];
        for (s, v) in sum.iter_mut().zip(f) {
            *s += weight * v * dy;
        }
    }
    sum.map(|s| s * step / 3.0)
}

#[test]
fn tilted_water_equals_rotated_body() {
    // Rotating both the body and the plane normal by R changes nothing but the frame.
    let (sx, sy, sz) = (4.0, 1.0, 1.0);
    let mesh = builtin::cuboid(sx, sy, sz);
    for q in rotations() {
        let pose = Isometry3::from_parts(Translation3::identity(), q);
        let normal = Unit::new_normalize(q * Vector3::y());
        for w in [-0.7, -0.2, 0.0, 0.3, 0.8] {
            let part = submerged_part(&mesh, &pose, &ClipPlane::new(normal, w));
            let h = (w + sy / 2.0).clamp(0.0, sy);
            let centroid = if h > 0.0 {
                q * Point3::new(0.0, -sy / 2.0 + h / 2.0, 0.0)
            } else {
                q * Point3::new(0.0, w, 0.0)
            };
            assert!((part.volume - sx * h * sz).abs() < 1e-12 * 4.0, "w={w}");
            assert!(
                (part.centroid - centroid).norm() < 1e-12,
                "w={w}: {:?} vs {centroid:?}",
                part.centroid
            );
        }
    }
}

#[test]
fn pose_is_the_same_as_moving_the_mesh() {
    let pose = Isometry3::from_parts(
        Translation3::new(1.5, -0.2, 3.0),
        UnitQuaternion::from_euler_angles(0.4, 0.9, -0.3),
    );
    for mesh in [
        builtin::boat(4.0, 1.2, 0.6),
        builtin::torus(0.5, 0.15, 48, 24),
        builtin::capsule(0.25, 0.5, 32),
    ] {
        let moved = mesh.clone().map_positions(|p| pose * p);
        for w in [-0.5, -0.1, 0.0, 0.2] {
            let plane = ClipPlane::horizontal(w);
            let a = submerged_part(&mesh, &pose, &plane);
            let b = submerged_part(&moved, &identity(), &plane);
            let scale = mesh.volume();
            assert!((a.volume - b.volume).abs() < 1e-12 * scale, "{} w={w}", mesh.name);
            if a.volume > 0.0 {
                // (A dry body's fallback centroid depends on which bounding box is used.)
                assert!((a.centroid - b.centroid).norm() < 1e-11, "{} w={w}", mesh.name);
            }
            assert!(
                (a.second_moment - b.second_moment).norm() < 1e-12 * scale,
                "{} w={w}",
                mesh.name
            );
            let (x, y) = (
                per_triangle_buoyancy(&mesh, &pose, &plane, 1000.0, 9.81),
                per_triangle_buoyancy(&moved, &identity(), &plane, 1000.0, 9.81),
            );
            assert!((x.volume - y.volume).abs() < 1e-12 * scale, "{} w={w}", mesh.name);
            if x.volume > 0.0 {
                assert!((x.centre - y.centre).norm() < 1e-10, "{} w={w}", mesh.name);
            }
        }
    }
}

#[test]
fn non_convex_torus_splits_exactly() {
    let (big, small) = (0.5, 0.15);
    let mesh = builtin::torus(big, small, 256, 128);
    let whole = solid_mass_properties(&mesh, 1.0);
    // Pappus: V = 2π² R r².
    assert!(rel(whole.volume, 2.0 * PI * PI * big * small * small) < 1e-3);
    let pose = Isometry3::from_parts(
        Translation3::new(0.0, 0.05, 0.0),
        UnitQuaternion::from_euler_angles(1.2, 0.0, 0.4),
    );
    for w in [-0.4, -0.1, 0.0, 0.07, 0.3] {
        let plane = ClipPlane::horizontal(w);
        let (a, b) = (
            submerged_part(&mesh, &pose, &plane),
            submerged_part(&mesh, &pose, &plane.flipped()),
        );
        assert!(rel(a.volume + b.volume, whole.volume) < 1e-12, "w={w}");
        let first = a.first_moment() + b.first_moment();
        let expected = (pose * whole.centroid).coords * whole.volume;
        assert!((first - expected).norm() < 1e-12 * whole.volume, "w={w}");
    }
}

#[test]
fn dry_and_extreme_placements_stay_finite() {
    let boat = builtin::boat(4.0, 1.2, 0.6);
    let pose = Isometry3::translation(2.0, 10.0, -1.0);
    let part = submerged_part(&boat, &pose, &ClipPlane::horizontal(0.0));
    let (lo, hi) = boat.bounds();
    let centre = pose * nalgebra::center(&lo, &hi);
    assert_eq!(part.volume, 0.0);
    assert_eq!(part.second_moment, Matrix3::zeros());
    assert!((part.centroid - Point3::new(centre.x, 0.0, centre.z)).norm() < 1e-12);
    let b = per_triangle_buoyancy(&boat, &pose, &ClipPlane::horizontal(0.0), 1000.0, 9.81);
    assert_eq!((b.volume, b.force), (0.0, Vector3::zeros()));

    for name in [
        "builtin:sphere:0.5:24:12",
        "builtin:box",
        "builtin:cylinder",
        "builtin:capsule",
        "builtin:torus",
        "builtin:boat",
        "builtin:dumbbell",
    ] {
        let mesh = builtin::parse(name).unwrap();
        let volume = mesh.volume();
        for q in rotations() {
            for w in [-3.0, -0.25, 0.0, 0.1, 0.3, 3.0] {
                let pose = Isometry3::from_parts(Translation3::identity(), q);
                let p = submerged_part(&mesh, &pose, &ClipPlane::horizontal(w));
                let b = per_triangle_buoyancy(&mesh, &pose, &ClipPlane::horizontal(w), 1000.0, 9.81);
                let finite = p.volume.is_finite()
                    && p.centroid
                        .coords
                        .iter()
                        .chain(p.second_moment.iter())
                        .all(|x| x.is_finite())
                    && b.centre
                        .coords
                        .iter()
                        .chain(b.force.iter())
                        .all(|x| x.is_finite());
                assert!(finite, "{name} w={w}");
                assert!(
                    p.volume >= -1e-15 && p.volume <= volume * (1.0 + 1e-12),
                    "{name} w={w}: {}",
                    p.volume
                );
            }
        }
    }
}

#[test]
fn scale_invariance_from_millimetres_to_kilometres() {
    let unit = builtin::cuboid(4.0, 1.0, 1.0);
    let q = UnitQuaternion::from_euler_angles(0.3, -1.1, 2.5);
    let reference = submerged_part(
        &unit,
        &Isometry3::from_parts(Translation3::identity(), q),
        &ClipPlane::horizontal(0.2),
    );
    for s in [1e-3, 1e3] {
        let mesh = unit.clone().map_positions(|p| p * s);
        let props = solid_mass_properties(&mesh, 1.0);
        assert!(rel(props.volume, 4.0 * s.powi(3)) < 1e-10, "s={s}");
        assert!(
            rel(props.inertia[(0, 0)], 4.0 * 2.0 / 12.0 * s.powi(5)) < 1e-10,
            "s={s}"
        );
        let pose = Isometry3::from_parts(Translation3::new(0.0, 0.0, 0.0), q);
        let part = submerged_part(&mesh, &pose, &ClipPlane::horizontal(0.2 * s));
        assert!(rel(part.volume, reference.volume * s.powi(3)) < 1e-10, "s={s}");
        assert!(
            (part.centroid.coords / s - reference.centroid.coords).norm() < 1e-10,
            "s={s}"
        );
        assert!(
            mat_rel(&(part.second_moment / s.powi(5)), &reference.second_moment) < 1e-10,
            "s={s}"
        );
    }
}

#[test]
fn results_round_trip_through_serde() {
    let part = submerged_part(
        &builtin::cuboid(1.0, 2.0, 3.0),
        &identity(),
        &ClipPlane::horizontal(0.1),
    );
    // (serde_json parses floats to within an ulp, not always bit-exactly.)
    let back: SubmergedPart = serde_json::from_str(&serde_json::to_string(&part).unwrap()).unwrap();
    assert!(rel(back.volume, part.volume) < 1e-15 && (back.centroid - part.centroid).norm() < 1e-15);
    assert!((back.second_moment - part.second_moment).norm() < 1e-15);
    let plane = ClipPlane::through(
        &Point3::new(0.0, 2.0, 0.0),
        Unit::new_normalize(Vector3::new(0.0, 1.0, 1.0)),
    );
    let back: ClipPlane = serde_json::from_str(&serde_json::to_string(&plane).unwrap()).unwrap();
    assert!((back.normal.into_inner() - plane.normal.into_inner()).norm() < 1e-15);
    assert!(rel(back.offset, plane.offset) < 1e-15);
    assert!(plane.signed_distance(&Point3::new(0.0, 2.0, 0.0)).abs() < 1e-15);
}
