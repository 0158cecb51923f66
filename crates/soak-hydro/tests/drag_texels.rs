//! Drag summed over a coarser bake of the same mesh ([`DragTexels`]):
//! the buoyancy stays the body's own to the bit, the drag stays within a
//! stated distance of the drag over the body's own texels, on calm water
//! and on the sampled swell, and drag texels of another mesh are refused.

use nalgebra::{Isometry3, UnitQuaternion, Vector3};
use soak_bake::{Atlas, BakeOptions, Mesh, builtin};
use soak_hydro::{
    BodyState, BuoyancyMode, Drag, DragTexels, Gerstner, GerstnerWave, HydroError, HydroForces, HydroOptions,
    MassModel, MassProperties, TiledAtlas, Water, evaluate_with_drag,
};

fn swell() -> Water {
    Water::new(Gerstner::new(0.0, GerstnerWave::SWELL.to_vec(), 9.80665).unwrap())
}

const DRAG: Drag = Drag {
    coefficient: 0.8,
    linear: 20.0,
};

/// `|ΔF| + |Δτ| / r` against `|F| + |τ| / r` of `want`'s drag at the
/// current velocity.
fn drag_difference(got: &HydroForces, want: &HydroForces, radius: f64) -> f64 {
    let (g, w) = (&got.drag_explicit, &want.drag_explicit);
    ((g.force - w.force).norm() + (g.torque - w.torque).norm() / radius)
        / (w.force.norm() + w.torque.norm() / radius)
}

/// Moving states of a body half under water, at several attitudes.
fn states(mesh_height: f64) -> Vec<BodyState> {
    let attitudes = [
        (0.0, 0.0, 0.0),
        (0.3, 0.2, 0.1),
        (-0.5, 1.1, 0.4),
        (1.4, -0.2, 2.0),
    ];
    attitudes
        .iter()
        .enumerate()
        .map(|(k, &(r, p, y))| BodyState {
            linear_velocity: Vector3::new(0.7, -0.3 + 0.2 * k as f64, 0.2),
            angular_velocity: Vector3::new(0.2, 0.5, -0.1 * k as f64),
            ..BodyState::at_rest(Isometry3::from_parts(
                Vector3::new(0.1, 0.1 * mesh_height, -0.2).into(),
                UnitQuaternion::from_euler_angles(r, p, y),
            ))
        })
        .collect()
}

struct Body {
    atlas: Atlas,
    tiled: TiledAtlas,
    mass: MassProperties,
}

fn body(mesh: &Mesh, n: u32) -> Body {
    let atlas = Atlas::bake(mesh, BakeOptions::square(n)).unwrap();
    let mass = MassModel::Solid { density: 500.0 }
        .mass_properties(&atlas)
        .unwrap();
    Body {
        tiled: TiledAtlas::new(&atlas),
        atlas,
        mass,
    }
}

/// Over `states` on `water`: the largest drag difference between drag
/// texels and the body's own texels, after checking that the
/// buoyancy is the same to the bit.
fn worst(b: &Body, drag: &DragTexels, water: &Water, t: f64, states: &[BodyState]) -> f64 {
    let options = HydroOptions {
        drag: Some(DRAG),
        ..HydroOptions::default()
    };
    let radius = b.atlas.bounding_radius();
    let mut worst = 0.0f64;
    for state in states {
        let own = b
            .tiled
            .evaluate(&b.atlas, water, state, &b.mass, t, &options)
            .unwrap();
        let got = b
            .tiled
            .evaluate_with_drag(&b.atlas, drag, water, state, &b.mass, t, &options)
            .unwrap();
        assert_eq!(got.buoyancy, own.buoyancy);
        assert_eq!(got.submerged_volume, own.submerged_volume);
        assert_eq!(got.center_of_buoyancy, own.center_of_buoyancy);
        assert!(got.drag.is_finite() && got.drag_explicit.is_finite());
        worst = worst.max(drag_difference(&got, &own, radius));
    }
    worst
}

/// `drag`'s worst difference from `b`'s own drag on calm water and on the
/// swell, printed; a message when it reaches `tolerance`.
fn compare(name: &str, b: &Body, drag: &DragTexels, height: f64, tolerance: f64) -> Option<String> {
    let states = states(height);
    let calm = worst(b, drag, &Water::calm(0.0), 0.0, &states);
    let sea = worst(b, drag, &swell(), 2.3, &states);
    println!("{name}: calm {calm:.2e}, swell {sea:.2e}");
    (calm.max(sea) >= tolerance)
        .then(|| format!("{name}: calm {calm:.2e}, swell {sea:.2e} (tolerance {tolerance:.0e})"))
}

/// The drag over coarse drag texels against the drag over the body's own
/// 512² texels, on calm water and on the swell, with the buoyancy
/// unchanged: within 2 % for the sphere and 1 % for the box at 64² (about
/// 4,000 and 2,400 texels), and 2 % for the boat at 128² (at 64² its
/// 3,000 texels, 7 cm wide on its long sides, are 7 % off when it heels).
#[test]
fn coarse_drag_texels_stay_close_to_the_bodys_own() {
    let cases: [(&str, Mesh, f64, u32, f64); 3] = [
        ("sphere", builtin::sphere(0.5, 64, 32), 1.0, 64, 2e-2),
        ("box", builtin::cuboid(1.0, 0.6, 0.8), 0.6, 64, 1e-2),
        ("boat", builtin::boat(4.0, 1.2, 0.6), 0.6, 128, 2e-2),
    ];
    let mut failed = Vec::new();
    for (name, mesh, height, coarse, tolerance) in cases {
        let b = body(&mesh, 512);
        let drag = DragTexels::bake(&mesh, coarse).unwrap();
        assert!(drag.atlas().len() < b.atlas.len() / 10, "{name}");
        failed.extend(compare(name, &b, &drag, height, tolerance));
    }
    assert!(failed.is_empty(), "{failed:?}");
}

/// Without drag the drag texels change nothing: the evaluation is the
/// body's own, bit for bit.
#[test]
fn without_drag_the_evaluation_is_the_bodys_own() {
    let mesh = builtin::sphere(0.5, 32, 16);
    let b = body(&mesh, 128);
    let drag = DragTexels::bake(&mesh, 32).unwrap();
    for mode in [BuoyancyMode::Archimedes, BuoyancyMode::Pressure] {
        let options = HydroOptions {
            buoyancy: mode,
            ..HydroOptions::default()
        };
        for (water, t) in [(Water::calm(0.0), 0.0), (swell(), 1.7)] {
            for state in states(1.0) {
                let own = b
                    .tiled
                    .evaluate(&b.atlas, &water, &state, &b.mass, t, &options)
                    .unwrap();
                let got = b
                    .tiled
                    .evaluate_with_drag(&b.atlas, &drag, &water, &state, &b.mass, t, &options)
                    .unwrap();
                assert_eq!(got, own);
            }
        }
    }
}

/// Drag texels baked from another mesh (another bounding-box centre) are
/// refused with both origins named; the same mesh at any resolution is
/// accepted.
#[test]
fn drag_texels_of_another_mesh_are_refused() {
    let mesh = builtin::sphere(0.5, 32, 16);
    let b = body(&mesh, 64);
    let other = builtin::sphere(0.5, 32, 16).map_positions(|p| p + Vector3::new(0.0, 0.25, 0.0));
    let wrong = DragTexels::bake(&other, 32).unwrap();
    let options = HydroOptions {
        drag: Some(DRAG),
        ..HydroOptions::default()
    };
    let state = states(1.0)[1];
    let e = b
        .tiled
        .evaluate_with_drag(
            &b.atlas,
            &wrong,
            &Water::calm(0.0),
            &state,
            &b.mass,
            0.0,
            &options,
        )
        .unwrap_err();
    assert!(matches!(e, HydroError::DragTexels { .. }), "{e}");
    assert!(e.to_string().contains("same mesh"), "{e}");
    for n in [16, 48, 200] {
        assert!(DragTexels::bake(&mesh, n).unwrap().check(&b.atlas).is_ok());
    }
}

/// The tiled evaluation with drag texels against its per-texel reference
/// (every texel of the body for the buoyancy, every drag texel for the
/// drag): the same drag but for rounding on calm water, and within the
/// tiled sea's own tolerance on the swell.
#[test]
fn tiled_drag_texels_match_the_per_texel_reference() {
    let mesh = builtin::cuboid(1.0, 0.6, 0.8);
    let b = body(&mesh, 256);
    let drag = DragTexels::bake(&mesh, 64).unwrap();
    let options = HydroOptions {
        drag: Some(DRAG),
        ..HydroOptions::default()
    };
    for (water, t, tolerance) in [(Water::calm(0.0), 0.0, 1e-9), (swell(), 2.3, 5e-3)] {
        for state in states(0.6) {
            let tiled = b
                .tiled
                .evaluate_with_drag(&b.atlas, &drag, &water, &state, &b.mass, t, &options)
                .unwrap();
            let texels = evaluate_with_drag(&b.atlas, &drag, &water, &state, &b.mass, t, &options).unwrap();
            let d = drag_difference(&tiled, &texels, b.atlas.bounding_radius());
            assert!(d < tolerance, "{d:.2e} (tolerance {tolerance:.0e})");
        }
    }
}

/// Drag texels coarsened from the body's own atlas (`DragTexels::
/// coarsened`) against the drag over the atlas' every texel, on calm
/// water and on the swell, with the buoyancy unchanged. At 512² by 8 (a
/// 64² grid) the box and the boat by 4 are as close as bakes of their
/// side, the sphere 3 % off (its 4,096 triangles keep 4,000 texels in a
/// 64² bake, 2,500 here); at 128² by 4 (a 32² grid, the scaling bench's
/// bodies) 3–4 %. (By 8 at 128², 192 texels, the box is 12 % off.)
#[test]
fn coarsened_drag_texels_stay_close_to_the_bodys_own() {
    // (mesh, height, resolution, factor, tolerance)
    let cases: [(&str, Mesh, f64, u32, u32, f64); 5] = [
        ("sphere", builtin::sphere(0.5, 64, 32), 1.0, 512, 8, 3e-2),
        ("box", builtin::cuboid(1.0, 0.6, 0.8), 0.6, 512, 8, 1e-2),
        ("boat", builtin::boat(4.0, 1.2, 0.6), 0.6, 512, 4, 2e-2),
        ("sphere", builtin::sphere(0.5, 64, 32), 1.0, 128, 4, 4e-2),
        ("box", builtin::cuboid(1.0, 0.6, 0.8), 0.6, 128, 4, 3e-2),
    ];
    let mut failed = Vec::new();
    for (name, mesh, height, n, k, tolerance) in cases {
        let b = body(&mesh, n);
        let drag = DragTexels::coarsened(b.atlas.clone().into(), k).unwrap();
        assert!(
            drag.atlas().len() * (k * k / 2) as usize <= b.atlas.len(),
            "{name}"
        );
        let name = format!(
            "{name} {n}² by {k} ({} texels of {})",
            drag.atlas().len(),
            b.atlas.len()
        );
        failed.extend(compare(&name, &b, &drag, height, tolerance));
    }
    assert!(failed.is_empty(), "{failed:?}");
}

/// Coarsened drag texels follow a deforming mesh: refreshed, they are
/// the coarsening of the refreshed atlas, bit for bit.
#[test]
fn coarsened_drag_texels_follow_a_deforming_mesh() {
    let mesh = builtin::cuboid(1.0, 0.6, 0.8);
    let atlas = std::sync::Arc::new(Atlas::bake(&mesh, BakeOptions::square(64)).unwrap());
    let mut drag = DragTexels::coarsened(atlas.clone(), 4).unwrap();
    let squashed: Vec<_> = mesh
        .positions
        .iter()
        .map(|p| nalgebra::Point3::new(1.5 * p.x, 0.5 * p.y, p.z))
        .collect();
    drag.refresh(&squashed).unwrap();
    let mut refreshed = Atlas::clone(&atlas);
    refreshed.refresh(&squashed).unwrap();
    let want = refreshed.coarsened(4, DragTexels::TILE_SIZE).unwrap();
    assert_eq!(drag.atlas().local_positions(), want.local_positions());
    assert_eq!(drag.atlas().area_vectors(), want.area_vectors());
    assert!((drag.atlas().area() - 2.0 * (1.5 * 0.3 + 1.5 * 0.8 + 0.3 * 0.8)).abs() < 1e-4);
}
