//! Drag texels in a Rapier world: refused when baked from another mesh,
//! and following a deforming mesh like the body's own atlas (baked, or
//! coarsened from it).

use std::sync::Arc;

use nalgebra::{Point3, Vector3};
use rapier3d::prelude::*;
use soak_bake::{Atlas, BakeOptions, Mesh, builtin};
use soak_hydro::{Drag, DragTexels, MassModel, Water};
use soak_rapier::{BodyDesc, Effects, ForceGenerator, SoakError, SoakId};

const DRAG: Drag = Drag {
    coefficient: 1.0,
    linear: 5.0,
};

/// A world with one sphere half under calm water moving at 1 m/s, its drag
/// over `texels`.
fn world(mesh: &Mesh, texels: DragTexels) -> (PhysicsWorld, ForceGenerator, Result<SoakId, SoakError>) {
    let atlas = Atlas::bake(mesh, BakeOptions::square(128)).unwrap().into();
    world_of(
        atlas,
        Effects::buoyancy()
            .with_drag(DRAG)
            .with_drag_texels(texels.into()),
    )
}

/// A world with one body of `atlas` half under calm water moving at 1 m/s,
/// with `effects`.
fn world_of(
    atlas: Arc<Atlas>,
    effects: Effects,
) -> (PhysicsWorld, ForceGenerator, Result<SoakId, SoakError>) {
    let mut world = PhysicsWorld::new();
    world.integration_parameters.dt = 1.0 / 60.0;
    let handle = world
        .bodies
        .insert(RigidBodyBuilder::dynamic().linvel(Vector::new(1.0, 0.0, 0.0)));
    let mut soak = ForceGenerator::new(Water::calm(0.0));
    let id = soak.register(
        &mut world.bodies,
        &world.colliders,
        handle,
        BodyDesc {
            name: "buoy".into(),
            atlas,
            mass_model: MassModel::Solid { density: 500.0 },
            effects,
        },
    );
    (world, soak, id)
}

#[test]
fn drag_texels_of_another_mesh_are_refused_naming_the_body() {
    let mesh = builtin::sphere(0.5, 32, 16);
    let shifted = mesh.clone().map_positions(|p| p + Vector3::new(0.3, 0.0, 0.0));
    let (_, _, id) = world(&mesh, DragTexels::bake(&shifted, 32).unwrap());
    let e = id.unwrap_err();
    assert!(
        matches!(e, SoakError::Hydro { ref name, .. } if name == "buoy"),
        "{e}"
    );
    assert!(e.to_string().contains("same mesh"), "{e}");
}

/// A sphere deformed to 1.2 times its size: its drag texels follow, and
/// its drag is that of drag texels baked from the larger sphere.
#[test]
fn drag_texels_follow_a_deforming_mesh() {
    let mesh = builtin::sphere(0.5, 32, 16);
    let grown: Vec<Point3<f64>> = mesh.positions.iter().map(|p| p * 1.2).collect();
    let (mut w, mut soak, id) = world(&mesh, DragTexels::bake(&mesh, 32).unwrap());
    let id = id.unwrap();
    soak.deform(id, &grown, &mut w.bodies, &w.colliders).unwrap();
    soak.step(&mut w).unwrap();
    let deformed = soak.body(id).unwrap().forces().drag_explicit;

    let big = mesh.clone().map_positions(|p| p * 1.2);
    let (mut w, mut soak, fresh) = world(&mesh, DragTexels::bake(&big, 32).unwrap());
    // Baked from the larger mesh, its origin is the smaller one's (both
    // centred): the check accepts it; deform the body's own atlas too.
    let fresh = fresh.unwrap();
    soak.deform(fresh, &grown, &mut w.bodies, &w.colliders).unwrap();
    soak.step(&mut w).unwrap();
    let want = soak.body(fresh).unwrap().forces().drag_explicit;
    assert!(want.force.norm() > 1.0, "{want:?}");
    assert!(
        (deformed.force - want.force).norm() < 1e-4 * want.force.norm(),
        "{deformed:?} against {want:?}"
    );
}

/// A body's drag over its atlas coarsened by 4 (the drag texels made from
/// the very atlas it registers), its drag then within a few percent of
/// the drag over its own texels; deformed to 1.2 times its size, the
/// coarsened texels follow (coarsened again from the refreshed atlas):
/// its drag is that of a body baked from the larger sphere, coarsened.
#[test]
fn coarsened_drag_texels_follow_a_deforming_mesh() {
    let mesh = builtin::sphere(0.5, 32, 16);
    let body = |mesh: &Mesh, coarsen: bool| {
        let atlas = Arc::new(Atlas::bake(mesh, BakeOptions::square(128)).unwrap());
        let mut effects = Effects::buoyancy().with_drag(DRAG);
        if coarsen {
            effects = effects.with_drag_texels(DragTexels::coarsened(atlas.clone(), 4).unwrap().into());
        }
        let (world, soak, id) = world_of(atlas, effects);
        (world, soak, id.unwrap())
    };
    let drag = |(mut w, mut soak, id): (PhysicsWorld, ForceGenerator, SoakId)| {
        soak.step(&mut w).unwrap();
        soak.body(id).unwrap().forces().drag_explicit
    };
    let own = drag(body(&mesh, false));
    let coarse = drag(body(&mesh, true));
    assert!(own.force.norm() > 1.0, "{own:?}");
    assert!(
        (coarse.force - own.force).norm() < 3e-2 * own.force.norm(),
        "{coarse:?} against {own:?}"
    );

    let grown: Vec<Point3<f64>> = mesh.positions.iter().map(|p| p * 1.2).collect();
    let (mut w, mut soak, id) = body(&mesh, true);
    soak.deform(id, &grown, &mut w.bodies, &w.colliders).unwrap();
    let deformed = drag((w, soak, id));
    let want = drag(body(&mesh.clone().map_positions(|p| p * 1.2), true));
    assert!(
        (deformed.force - want.force).norm() < 1e-4 * want.force.norm(),
        "{deformed:?} against {want:?}"
    );
    assert!((deformed.force - coarse.force).norm() > 0.1 * coarse.force.norm());
}
