//! Open meshes: rims found, capped, baked as the closed shape; the caps'
//! texels known; rims that cannot be capped refused with the rim and why.

use nalgebra::{Point2, Point3};
use soak_bake::{Atlas, BakeOptions, Mesh, MeshProblem, boundary_loops, builtin, cap_openings, validate};

fn bake(mesh: &Mesh, n: u32) -> Atlas {
    Atlas::bake(mesh, BakeOptions::square(n)).expect("capped meshes bake")
}

#[test]
fn an_open_box_caps_to_the_closed_box() {
    let open = builtin::open_box(1.2, 0.5, 0.8);
    assert!(matches!(
        validate(&open).unwrap_err().problem,
        MeshProblem::OpenEdge { .. }
    ));
    let loops = boundary_loops(&open).unwrap();
    assert_eq!(loops.len(), 1);
    assert_eq!(loops[0].len(), 4);
    let closed = cap_openings(&open).unwrap();
    let o = &closed.openings[0];
    assert!((o.area - 0.96).abs() < 1e-12, "cap area {}", o.area);
    assert!((o.length - 4.0).abs() < 1e-12);
    assert_eq!(o.normal, [0.0, 1.0, 0.0]);
    assert!((o.centroid[1] - 0.25).abs() < 1e-12 && o.warp < 1e-12);
    // Exact: the capped surface encloses the box.
    assert!((closed.volume() - 0.48).abs() < 1e-12);
    let atlas = bake(&closed, 128);
    assert!(
        (atlas.volume() - 0.48).abs() < 1e-6,
        "atlas volume {}",
        atlas.volume()
    );
    let cap: f64 = atlas
        .opening_samples()
        .iter()
        .map(|&i| atlas.areas()[i as usize] as f64)
        .sum();
    assert!((cap - 0.96).abs() < 1e-5, "cap texels carry {cap} m²");
    // Every cap sample lies on the rim's plane, facing up.
    for &i in &atlas.opening_samples() {
        let p = atlas.position(i as usize);
        assert!((p.y - 0.25).abs() < 1e-6);
        assert!(atlas.area_vectors().get(i as usize)[1] > 0.0);
    }
    assert!(!bake(&builtin::cuboid(1.0, 1.0, 1.0), 32).has_openings());
}

#[test]
fn a_bucket_and_an_open_boat_enclose_their_closed_shapes() {
    let bucket = cap_openings(&builtin::bucket(0.3, 0.6, 64)).unwrap();
    let cylinder = builtin::cylinder(0.3, 0.6, 64);
    assert_eq!(bucket.openings.len(), 1);
    assert!((bucket.volume() - cylinder.volume()).abs() < 1e-12 * cylinder.volume().max(1.0));
    let atlas = bake(&bucket, 256);
    assert!((atlas.volume() - cylinder.volume()).abs() / cylinder.volume() < 1e-4);

    let boat = cap_openings(&builtin::open_boat(4.0, 1.2, 0.6)).unwrap();
    let decked = builtin::boat(4.0, 1.2, 0.6);
    assert_eq!(boat.openings.len(), 1);
    assert!(
        (boat.volume() - decked.volume()).abs() < 1e-9,
        "{} vs {}",
        boat.volume(),
        decked.volume()
    );
    let rim = &boat.openings[0];
    assert!(rim.warp < 1e-12 && (rim.centroid[1] - 0.6).abs() < 1e-12);
    assert!((rim.area - decked_deck_area(&decked)).abs() < 1e-9);
    let atlas = bake(&boat, 256);
    assert!((atlas.volume() - decked.volume()).abs() / decked.volume() < 1e-3);
    // A closed mesh has no rims and comes back unchanged.
    assert_eq!(cap_openings(&decked).unwrap(), decked);
}

fn decked_deck_area(mesh: &Mesh) -> f64 {
    (0..mesh.triangles.len())
        .filter(|&t| mesh.triangle_points(t).iter().all(|p| (p.y - 0.6).abs() < 1e-12))
        .map(|t| mesh.triangle_area_vector(t).y)
        .sum()
}

/// A fan from an apex over a boundary polygon: the polygon is its one rim.
fn fan(name: &str, rim: &[(f64, f64)], apex: Point3<f64>) -> Mesh {
    let mut positions: Vec<Point3<f64>> = rim.iter().map(|&(x, z)| Point3::new(x, 0.0, z)).collect();
    positions.push(apex);
    let a = rim.len() as u32;
    let triangles = (0..a).map(|i| [a, i, (i + 1) % a]).collect();
    let uvs = positions
        .iter()
        .map(|p| Point2::new(0.5 + 0.1 * p.x, 0.5 + 0.1 * p.z))
        .collect();
    Mesh::new(name, positions, Some(uvs), triangles)
}

#[test]
fn rims_that_cannot_be_capped_are_named() {
    // Seen along its normal the rim crosses itself (an uneven bow tie).
    let bow = fan(
        "bow",
        &[(0.0, 0.0), (2.0, 2.0), (2.0, 0.0), (0.0, 1.0)],
        Point3::new(0.8, 1.0, 0.7),
    );
    let e = cap_openings(&bow).unwrap_err();
    assert_eq!(e.mesh, "bow");
    match e.problem {
        MeshProblem::RimNotCappable { rim: 0, ref reason } => {
            assert!(reason.contains("crosses itself"), "{reason}")
        }
        ref p => panic!("{p:?}"),
    }
    // Two open boxes touching at a corner: their rims meet at a vertex.
    let a = builtin::open_box(1.0, 1.0, 1.0);
    let b = a
        .clone()
        .map_positions(|p| p + nalgebra::Vector3::new(1.0, 0.0, 1.0));
    let n = a.positions.len() as u32;
    let both = Mesh::new(
        "two",
        a.positions.iter().chain(&b.positions).copied().collect(),
        None,
        a.triangles
            .iter()
            .copied()
            .chain(b.triangles.iter().map(|t| t.map(|v| v + n)))
            .collect(),
    );
    assert!(matches!(
        cap_openings(&both).unwrap_err().problem,
        MeshProblem::RimNotManifold { .. }
    ));
}

#[test]
fn a_concave_rim_is_capped_without_overlap() {
    // An L-shaped rim under a tent: the cap must cover exactly the L.
    let l = [
        (0.0, 0.0),
        (0.0, 2.0),
        (1.0, 2.0),
        (1.0, 1.0),
        (2.0, 1.0),
        (2.0, 0.0),
    ];
    let tent = fan("tent", &l, Point3::new(0.5, 1.0, 0.5));
    let closed = cap_openings(&tent).unwrap();
    let o = &closed.openings[0];
    assert!((o.area - 3.0).abs() < 1e-12);
    assert_eq!(o.normal, [0.0, -1.0, 0.0]);
    assert_eq!(o.triangles, 4);
}

#[test]
fn a_thick_walled_box_has_its_cavity_found_and_capped() {
    let walls = builtin::thick_open_box(1.0, 0.5, 1.0, 0.05);
    validate(&walls).expect("one closed surface");
    // Its solid is the walls: the box less the cavity 0.9 × 0.45 × 0.9.
    assert!((walls.volume() - (0.5 - 0.9 * 0.45 * 0.9)).abs() < 1e-12);
    let c = soak_bake::cap_cavities(&walls).unwrap();
    assert_eq!(
        c.inner.len(),
        10,
        "the cavity's four walls and floor, two triangles each"
    );
    assert_eq!(c.filled.openings.len(), 1);
    let mouth = &c.filled.openings[0];
    assert!((mouth.area - 0.81).abs() < 1e-12 && mouth.normal == [0.0, 1.0, 0.0]);
    assert!(
        (c.filled.volume() - 0.5).abs() < 1e-12,
        "filled: {}",
        c.filled.volume()
    );
    let atlas = bake(&c.filled, 128);
    assert!((atlas.volume() - 0.5).abs() < 1e-6);
    // A closed hull has no cavity; an open mesh is refused (not closed).
    assert!(
        soak_bake::cap_cavities(&builtin::boat(4.0, 1.2, 0.6))
            .unwrap()
            .inner
            .is_empty()
    );
    assert!(soak_bake::cap_cavities(&builtin::open_box(1.0, 0.5, 1.0)).is_err());
}
