//! Every bad input gets its typed error, naming the element.

use nalgebra::{Point2, Point3};
use soak_bake::{Atlas, BakeError, BakeOptions, Mesh, MeshProblem, builtin, validate};

/// A tetrahedron with a bijective UV layout (four separate triangles).
fn tetra() -> Mesh {
    let p = [
        Point3::new(0.0, 0.0, 0.0),
        Point3::new(1.0, 0.0, 0.0),
        Point3::new(0.0, 1.0, 0.0),
        Point3::new(0.0, 0.0, 1.0),
    ];
    // Outward faces.
    let faces = [[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]];
    let mut positions = Vec::new();
    let mut uvs = Vec::new();
    let mut triangles = Vec::new();
    for (k, f) in faces.iter().enumerate() {
        let (ox, oy) = ((k % 2) as f64 * 0.5, (k / 2) as f64 * 0.5);
        let corners = [(0.05, 0.05), (0.45, 0.05), (0.05, 0.45)];
        let base = positions.len() as u32;
        for (j, &v) in f.iter().enumerate() {
            positions.push(p[v]);
            uvs.push(Point2::new(ox + corners[j].0, oy + corners[j].1));
        }
        triangles.push([base, base + 1, base + 2]);
    }
    Mesh::new("tetra", positions, Some(uvs), triangles)
}

fn problem(mesh: &Mesh) -> MeshProblem {
    validate(mesh).expect_err("must be refused").problem
}

#[test]
fn the_fixture_is_valid() {
    validate(&tetra()).unwrap();
    Atlas::bake(&tetra(), BakeOptions::square(16)).unwrap();
}

#[test]
fn empty() {
    let m = Mesh::new("e", vec![], None, vec![]);
    assert_eq!(problem(&m), MeshProblem::Empty);
}

#[test]
fn index_out_of_range() {
    let mut m = tetra();
    m.triangles[2][1] = 99;
    assert!(matches!(
        problem(&m),
        MeshProblem::IndexOutOfRange {
            triangle: 2,
            index: 99,
            vertex_count: 12
        }
    ));
}

#[test]
fn nan_and_infinite_positions() {
    let mut m = tetra();
    m.positions[5].x = f64::NAN;
    assert!(matches!(
        problem(&m),
        MeshProblem::NonFinitePosition { vertex: 5, .. }
    ));
    let mut m = tetra();
    m.positions[3].z = f64::INFINITY;
    assert!(matches!(
        problem(&m),
        MeshProblem::NonFinitePosition { vertex: 3, .. }
    ));
}

#[test]
fn missing_and_mismatched_uvs() {
    assert_eq!(problem(&tetra().without_uvs()), MeshProblem::MissingUvs);
    let mut m = tetra();
    m.uvs.as_mut().unwrap().pop();
    assert!(matches!(
        problem(&m),
        MeshProblem::UvCountMismatch {
            uvs: 11,
            positions: 12
        }
    ));
}

#[test]
fn non_finite_and_out_of_range_uvs() {
    let mut m = tetra();
    m.uvs.as_mut().unwrap()[4].y = f64::NAN;
    assert!(matches!(problem(&m), MeshProblem::NonFiniteUv { vertex: 4, .. }));
    let mut m = tetra();
    m.uvs.as_mut().unwrap()[6].x = 1.5;
    assert!(matches!(problem(&m), MeshProblem::UvOutOfRange { vertex: 6, .. }));
}

#[test]
fn degenerate_triangle_in_3d() {
    // Collapse one face of the tetrahedron onto a line.
    let mut m = tetra();
    let t = m.triangles[3];
    let a = m.positions[t[0] as usize];
    let b = m.positions[t[1] as usize];
    m.positions[t[2] as usize] = Point3::from((a.coords + b.coords) / 2.0);
    assert!(matches!(
        problem(&m),
        MeshProblem::DegenerateTriangle { triangle: 3, .. }
    ));
}

#[test]
fn degenerate_triangle_in_uv() {
    let mut m = tetra();
    let uvs = m.uvs.as_mut().unwrap();
    uvs[2] = Point2::from((uvs[0].coords + uvs[1].coords) / 2.0);
    assert!(matches!(
        problem(&m),
        MeshProblem::DegenerateUvTriangle { triangle: 0, .. }
    ));
}

#[test]
fn open_edge() {
    let mut m = tetra();
    m.triangles.pop();
    assert!(matches!(problem(&m), MeshProblem::OpenEdge { .. }));
    let msg = validate(&m).unwrap_err().to_string();
    assert!(msg.starts_with("mesh `tetra` triangle"), "{msg}");
    assert!(msg.contains("open edge"), "{msg}");
}

#[test]
fn non_manifold_edge() {
    // Two tetrahedra sharing one edge (0-1) plus a fin: three faces on one edge.
    let mut m = tetra();
    let base = m.positions.len() as u32;
    m.positions.extend([
        Point3::new(0.0, 0.0, 0.0),
        Point3::new(1.0, 0.0, 0.0),
        Point3::new(0.5, -1.0, 0.3),
    ]);
    m.uvs.as_mut().unwrap().extend([
        Point2::new(0.9, 0.9),
        Point2::new(0.99, 0.9),
        Point2::new(0.9, 0.99),
    ]);
    m.triangles.push([base, base + 1, base + 2]);
    assert!(matches!(
        problem(&m),
        MeshProblem::NonManifoldEdge { count: 3, .. }
    ));
}

#[test]
fn inconsistent_winding() {
    let mut m = tetra();
    m.triangles[1].swap(1, 2);
    assert!(matches!(problem(&m), MeshProblem::InconsistentWinding { .. }));
}

#[test]
fn inside_out() {
    let m = tetra().flipped();
    match problem(&m) {
        MeshProblem::InsideOut { volume } => assert!((volume + 1.0 / 6.0).abs() < 1e-12),
        p => panic!("{p:?}"),
    }
}

#[test]
fn overlapping_uvs_then_unwrap_fixes_them() {
    // Every face of a box mapped onto the same square.
    let mut m = builtin::cuboid(1.0, 2.0, 3.0);
    let uvs = m.uvs.as_mut().unwrap();
    for (i, uv) in uvs.iter_mut().enumerate() {
        *uv = match i % 4 {
            0 => Point2::new(0.1, 0.1),
            1 => Point2::new(0.9, 0.1),
            2 => Point2::new(0.9, 0.9),
            _ => Point2::new(0.1, 0.9),
        };
    }
    let err = validate(&m).unwrap_err();
    assert!(
        matches!(err.problem, MeshProblem::OverlappingUvs { triangle: 0, .. }),
        "{err}"
    );
    assert!(err.to_string().contains("overlapping UVs with triangle"));
    let (fixed, report) = soak_bake::unwrap(&m, Default::default()).unwrap();
    assert_eq!(report.charts, 6);
    validate(&fixed).unwrap();
    let atlas = Atlas::bake(&fixed, BakeOptions::square(128)).unwrap();
    assert!((atlas.volume() - 6.0).abs() < 1e-5);
}

#[test]
fn resolution_zero_and_absurd() {
    let m = tetra();
    let bad = |w, h| {
        Atlas::bake(
            &m,
            BakeOptions {
                width: w,
                height: h,
                tile_size: 8,
                moment_matching: true,
            },
        )
        .unwrap_err()
    };
    assert_eq!(bad(0, 64), BakeError::ZeroResolution { width: 0, height: 64 });
    assert!(matches!(
        bad(64, 1 << 20),
        BakeError::ResolutionTooLarge { height: 1048576, .. }
    ));
    let e = Atlas::bake(
        &m,
        BakeOptions {
            width: 64,
            height: 64,
            tile_size: 0,
            moment_matching: true,
        },
    )
    .unwrap_err();
    assert_eq!(e, BakeError::TileSize(0));
}

#[test]
fn sliver_triangles_bake_with_exact_area() {
    // A long, thin box: faces 1000:1 slivers.
    let m = builtin::cuboid(100.0, 0.1, 0.1);
    for res in [8, 64, 512] {
        let atlas = Atlas::bake(&m, BakeOptions::square(res)).unwrap();
        let s = atlas.summary();
        assert!((s.area - m.area()).abs() / m.area() < 1e-6);
        assert!((s.volume - 1.0).abs() < 1e-5, "{res}: {}", s.volume);
        assert!(s.closure < 1e-6);
    }
}
