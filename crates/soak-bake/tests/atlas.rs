//! The atlas' integral invariants against exact mesh quantities.

use std::f64::consts::PI;

use soak_bake::{Atlas, BakeOptions, builtin, load_mesh};

const BUILTINS: &[&str] = &[
    "builtin:sphere",
    "builtin:box:4x1x1",
    "builtin:cylinder",
    "builtin:capsule",
    "builtin:torus",
    "builtin:boat",
    "builtin:dumbbell",
];

#[test]
fn sphere_area_and_volume_at_512() {
    let r = 0.5;
    let mesh = builtin::sphere(r, 64, 32);
    let atlas = Atlas::bake(&mesh, BakeOptions::square(512)).unwrap();
    let analytic_area = 4.0 * PI * r * r;
    let area_err = (atlas.area() - analytic_area).abs() / analytic_area;
    assert!(area_err < 0.005, "area error {area_err}");
    let exact_volume = mesh.volume();
    let vol_err = (atlas.volume() - exact_volume).abs() / exact_volume;
    assert!(
        vol_err < 0.005,
        "volume error {vol_err} against the polyhedral volume"
    );
}

#[test]
fn sphere_converges_from_64_to_1024() {
    // Area and volume are integrals of quantities constant over each planar
    // face, so the texel sums equal the polyhedral values at every resolution
    // (up to f32 storage); against the analytic sphere the error is the
    // tessellation's and shrinks with it.
    let r = 0.5;
    let analytic = 4.0 / 3.0 * PI * r * r * r;
    let mut last_err = f64::MAX;
    for (segments, res) in [(16, 64), (32, 128), (64, 256), (128, 512), (256, 1024)] {
        let mesh = builtin::sphere(r, segments, segments / 2);
        let atlas = Atlas::bake(&mesh, BakeOptions::square(res)).unwrap();
        let poly = (atlas.volume() - mesh.volume()).abs() / mesh.volume();
        assert!(poly < 1e-6, "{res}²: texel volume vs polyhedral {poly}");
        let err = (atlas.volume() - analytic).abs() / analytic;
        assert!(
            err < last_err,
            "{res}²: error {err} did not shrink from {last_err}"
        );
        last_err = err;
    }
    assert!(last_err < 5e-4, "finest error {last_err}");
}

#[test]
fn every_builtin_is_closed_and_area_exact_at_every_resolution() {
    for name in BUILTINS {
        let mesh = load_mesh(name).unwrap();
        let exact_area = mesh.area();
        for res in [8, 32, 256, 1024] {
            let atlas = Atlas::bake(&mesh, BakeOptions::square(res)).unwrap();
            let s = atlas.summary();
            assert!(s.closure < 1e-6, "{name} {res}²: closure {}", s.closure);
            let rel = (s.area - exact_area).abs() / exact_area;
            assert!(
                rel < 1e-6,
                "{name} {res}²: area {} vs {exact_area} ({rel})",
                s.area
            );
            let vrel = (s.volume - mesh.volume()).abs() / mesh.volume();
            assert!(vrel < 1e-6, "{name} {res}²: volume rel error {vrel}");
            if res == 8 {
                assert!(s.centroid_samples > 0, "{name}: 8² must need centroid samples");
            }
            // Every triangle is represented.
            assert!(atlas.texels_per_triangle().iter().all(|&n| n >= 1));
        }
    }
}

#[test]
fn a_missing_triangle_shows_in_closure() {
    let mut mesh = builtin::sphere(0.5, 64, 32);
    let atlas = Atlas::bake(&mesh, BakeOptions::square(256)).unwrap();
    assert!(atlas.summary().closure < 1e-6);
    // Bake the full mesh, then drop one triangle's samples by hand: closure jumps.
    let drop = mesh.triangles.len() / 2;
    let sum = atlas
        .area_vectors()
        .iter()
        .zip(atlas.triangle_ids())
        .filter(|(_, t)| **t as usize != drop)
        .fold(nalgebra::Vector3::zeros(), |s, (a, _)| {
            s + nalgebra::Vector3::new(a[0] as f64, a[1] as f64, a[2] as f64)
        });
    assert!(sum.norm() / atlas.area() > 1e-4);
    // And an open mesh is refused outright.
    mesh.triangles.remove(drop);
    assert!(Atlas::bake(&mesh, BakeOptions::square(256)).is_err());
}

#[test]
fn each_texel_centre_is_claimed_once() {
    for name in BUILTINS {
        let mesh = load_mesh(name).unwrap();
        let atlas = Atlas::bake(&mesh, BakeOptions::square(300)).unwrap();
        let mut seen = std::collections::HashSet::new();
        let centroids: std::collections::HashSet<u32> = atlas.centroid_samples().iter().copied().collect();
        for (i, t) in atlas.texels().iter().enumerate() {
            if centroids.contains(&(i as u32)) {
                continue;
            }
            assert!(seen.insert(*t), "{name}: texel {t:?} claimed twice");
        }
    }
}

#[test]
fn samples_lie_on_their_triangles_and_are_in_tile_order() {
    let mesh = builtin::boat(4.0, 1.2, 0.6);
    let atlas = Atlas::bake(&mesh, BakeOptions::square(128)).unwrap();
    for i in 0..atlas.len() {
        let t = atlas.triangle_ids()[i] as usize;
        let [a, b, c] = mesh.triangle_points(t);
        let n = mesh.triangle_area_vector(t).normalize();
        let p = atlas.position(i);
        assert!((p - a).dot(&n).abs() < 1e-5, "sample {i} off its plane");
        let [l1, l2] = atlas.barycentrics()[i];
        // Moment matching nudges samples by a fraction of a texel, at most
        // slightly past an edge.
        assert!(l1 >= -0.05 && l2 >= -0.05 && l1 + l2 <= 1.05, "{l1} {l2}");
        let q = a + (b - a) * l1 as f64 + (c - a) * l2 as f64;
        assert!((q - p).norm() < 1e-5);
        let av = atlas.area_vectors().get(i);
        let av = nalgebra::Vector3::new(av[0] as f64, av[1] as f64, av[2] as f64);
        assert!((av.normalize() - n).norm() < 1e-5);
    }
    let ts = atlas.tile_size() as u16;
    let mut covered = 0;
    for tile in atlas.tiles() {
        let r = tile.range();
        covered += r.len();
        let [x0, y0] = atlas.texels()[r.start];
        for i in r {
            let [x, y] = atlas.texels()[i];
            assert_eq!((x / ts, y / ts), (x0 / ts, y0 / ts));
        }
    }
    assert_eq!(covered, atlas.len());
}

#[test]
fn refresh_follows_a_deformation_without_rebaking() {
    let mesh = builtin::sphere(0.5, 48, 24);
    let mut atlas = Atlas::bake(&mesh, BakeOptions::square(256)).unwrap();
    let (v0, a0) = (atlas.volume(), atlas.area());
    // Inflate by 2 and shift: area ×4, volume ×8, closure kept.
    let moved: Vec<_> = mesh
        .positions
        .iter()
        .map(|p| nalgebra::Point3::new(2.0 * p.x + 3.0, 2.0 * p.y, 2.0 * p.z))
        .collect();
    atlas.refresh(&moved).unwrap();
    assert!((atlas.area() / a0 - 4.0).abs() < 1e-6);
    assert!((atlas.volume() / v0 - 8.0).abs() < 1e-6);
    assert!(atlas.summary().closure < 1e-6);
    // Same samples as a fresh bake of the deformed mesh.
    let mut deformed = mesh.clone();
    deformed.positions = moved.clone();
    let fresh = Atlas::bake(&deformed, BakeOptions::square(256)).unwrap();
    assert_eq!(fresh.len(), atlas.len());
    for i in (0..atlas.len()).step_by(97) {
        assert!((fresh.position(i) - atlas.position(i)).norm() < 1e-5);
    }
    // Bad refreshes are refused and leave the atlas untouched.
    let before = atlas.volume();
    assert!(matches!(
        atlas.refresh(&moved[1..]),
        Err(soak_bake::BakeError::VertexCountMismatch { .. })
    ));
    let mut nan = moved.clone();
    nan[7].y = f64::NAN;
    assert!(matches!(
        atlas.refresh(&nan),
        Err(soak_bake::BakeError::NonFiniteRefresh { vertex: 7 })
    ));
    assert_eq!(atlas.volume(), before);
}

#[test]
fn tiny_and_huge_scales_keep_relative_precision() {
    for s in [1e-3, 1e3] {
        let mesh = builtin::cuboid(4.0 * s, s, s);
        let atlas = Atlas::bake(&mesh, BakeOptions::square(128)).unwrap();
        let v = 4.0 * s * s * s;
        assert!((atlas.volume() - v).abs() / v < 1e-6, "scale {s}");
        assert!(atlas.summary().closure < 1e-6);
        // Far from the origin too: positions are stored relative to the box centre.
        let far = mesh
            .clone()
            .map_positions(|p| p + nalgebra::Vector3::new(1e4 * s, 0.0, 0.0));
        let atlas = Atlas::bake(&far, BakeOptions::square(128)).unwrap();
        assert!((atlas.volume() - v).abs() / v < 1e-6, "scale {s}, far");
    }
}

#[test]
fn sample_image_reads_the_texel_under_each_sample() {
    let mesh = builtin::cuboid(1.0, 1.0, 1.0);
    let atlas = Atlas::bake(&mesh, BakeOptions::square(64)).unwrap();
    // A 2×1 image: left half 1, right half 2.
    let vals = atlas.sample_image(&[1.0, 2.0], 2, 1);
    for (i, t) in atlas.texels().iter().enumerate() {
        assert_eq!(vals[i], if t[0] < 32 { 1.0 } else { 2.0 });
    }
}

#[test]
fn moment_matching_makes_each_triangles_first_and_second_moments_exact() {
    let mesh = builtin::boat(4.0, 1.2, 0.6);
    for matched in [false, true] {
        let mut o = BakeOptions::square(256);
        o.moment_matching = matched;
        let atlas = Atlas::bake(&mesh, o).unwrap();
        let n = mesh.triangles.len();
        let mut first = vec![nalgebra::Vector3::zeros(); n];
        let mut second = vec![nalgebra::Matrix3::zeros(); n];
        let mut count = vec![0usize; n];
        for i in 0..atlas.len() {
            let t = atlas.triangle_ids()[i] as usize;
            let x = atlas.position(i).coords;
            first[t] += x;
            second[t] += x * x.transpose();
            count[t] += 1;
        }
        let (mut worst1, mut unmatched2, mut with_cov) = (0.0f64, 0usize, 0usize);
        for t in 0..n {
            if count[t] < 2 {
                continue;
            }
            let [a, b, c] = mesh.triangle_points(t).map(|p| p.coords);
            let k = count[t] as f64;
            let centroid = (a + b + c) / 3.0;
            // Exact second moment of a uniform triangle: (Σ v vᵀ + (Σ v)(Σ v)ᵀ)/12.
            let s = a + b + c;
            let exact2 =
                (a * a.transpose() + b * b.transpose() + c * c.transpose() + s * s.transpose()) / 12.0;
            let size = (b - a).norm().max((c - a).norm());
            worst1 = worst1.max((first[t] / k - centroid).norm() / size);
            if count[t] >= 16 {
                with_cov += 1;
                // What remains is f32 storage rounding relative to the triangle size.
                if (second[t] / k - exact2).norm() / (size * size) > 1e-4 {
                    unmatched2 += 1;
                }
            }
        }
        if matched {
            // Every triangle's mean is exact; the covariance of every triangle
            // with 16 samples or more, but for the few whose samples are too
            // unevenly spread to map without distorting them.
            assert!(worst1 < 1e-5, "{worst1}");
            assert!(unmatched2 * 20 < with_cov, "{unmatched2} of {with_cov}");
        } else {
            // Texel centres alone: a first-order error from the edges.
            assert!(worst1 > 1e-4, "{worst1}");
        }
    }
}
