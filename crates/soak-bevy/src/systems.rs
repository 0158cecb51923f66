//! The plugin's systems, in the order they run each physics step, before
//! bevy_rapier's: [`start_bakes`], [`finish_bakes`], [`register_bodies`],
//! [`step_bodies`].

use std::sync::Arc;

use bevy::prelude::*;
use bevy::tasks::{AsyncComputeTaskPool, Task, futures::check_ready};
use bevy_rapier3d::prelude::{
    AdditionalMassProperties, Collider, ColliderMassProperties, DefaultRapierContext, ExternalForce,
    GravityScale, RapierConfiguration, RapierContextSimulation, RapierRigidBodySet, ReadMassProperties,
    RigidBody, TimestepMode, Velocity,
};
use soak_bake::Atlas;
use soak_driver::{BodyDesc, StepParams};

use crate::bodies::{BodyKey, ReadItem, Registering, to_vec3};
use crate::error::{FloatingError, FloatingErrorKind};
use crate::floating::{FloatReport, Floating, FloatingMesh, SoakLink};
use crate::mesh;
use crate::water::SoakWater;

/// An atlas being baked on another thread, and the mesh asset it is
/// cached under (if any).
#[derive(Component)]
pub(crate) struct Baking {
    task: Task<Result<Arc<Atlas>, FloatingErrorKind>>,
    asset: Option<(AssetId<Mesh>, u32)>,
}

/// The atlas is ready: the body registers at the next run.
#[derive(Component)]
pub(crate) struct Baked(Arc<Atlas>);

/// The body could not float (a [`FloatingError`] said why); the plugin
/// leaves the entity alone. Remove it (and fix the cause) to try again.
#[derive(Component, Clone, Copy, Debug, Default)]
pub struct FloatingFailed;

fn fail(
    commands: &mut Commands,
    errors: &mut MessageWriter<FloatingError>,
    entity: Entity,
    kind: FloatingErrorKind,
) {
    log::error!("soak: {kind}");
    errors.write(FloatingError { entity, kind });
    commands.entity(entity).insert(FloatingFailed);
}

/// Entities with [`Floating`] that have not started: checks they are
/// dynamic rigid bodies and starts the bake of their atlas on the async
/// compute pool (or takes one baked already).
#[allow(clippy::type_complexity)]
pub(crate) fn start_bakes(
    mut commands: Commands,
    pending: Query<
        (Entity, &Floating, Option<&RigidBody>),
        (
            Without<Baking>,
            Without<Baked>,
            Without<SoakLink>,
            Without<FloatingFailed>,
        ),
    >,
    meshes: Option<Res<Assets<Mesh>>>,
    water: Res<SoakWater>,
    mut errors: MessageWriter<FloatingError>,
) {
    // Assets being baked in this run, so that bodies of one asset wait for
    // the first one's bake instead of baking it again.
    let mut started: Vec<(AssetId<Mesh>, u32)> = Vec::new();
    for (entity, floating, rigid_body) in &pending {
        let name = floating.name.clone();
        match rigid_body {
            None => {
                fail(
                    &mut commands,
                    &mut errors,
                    entity,
                    FloatingErrorKind::NoRigidBody { name },
                );
                continue;
            }
            Some(RigidBody::Dynamic) => {}
            Some(other) => {
                let kind = match other {
                    RigidBody::Fixed => "Fixed",
                    RigidBody::KinematicPositionBased => "KinematicPositionBased",
                    _ => "KinematicVelocityBased",
                };
                fail(
                    &mut commands,
                    &mut errors,
                    entity,
                    FloatingErrorKind::NotDynamic { name, kind },
                );
                continue;
            }
        }
        let resolution = floating.resolution;
        let pool = AsyncComputeTaskPool::get();
        match &floating.mesh {
            FloatingMesh::Atlas(atlas) => {
                commands.entity(entity).insert(Baked(atlas.clone()));
            }
            FloatingMesh::Mesh(m) => {
                let m = m.clone();
                let task = pool.spawn(async move { mesh::bake(&name, &m, resolution) });
                commands.entity(entity).insert(Baking { task, asset: None });
            }
            FloatingMesh::Asset(handle) => {
                let key = (handle.id(), resolution);
                if let Some(atlas) = water.atlases.get(&key) {
                    commands.entity(entity).insert(Baked(atlas.clone()));
                    continue;
                }
                if started.contains(&key) || water_baking(&water, &key) {
                    continue;
                }
                // Not loaded yet: try again at the next run.
                let Some(asset) = meshes.as_ref().and_then(|m| m.get(handle)) else {
                    continue;
                };
                let m = match mesh::soak_mesh(&name, asset) {
                    Ok(m) => m,
                    Err(kind) => {
                        fail(&mut commands, &mut errors, entity, kind);
                        continue;
                    }
                };
                started.push(key);
                let task = pool.spawn(async move { mesh::bake(&name, &m, resolution) });
                commands.entity(entity).insert(Baking {
                    task,
                    asset: Some(key),
                });
            }
        }
    }
}

/// Whether an asset's atlas is being baked (a body waits for it).
fn water_baking(water: &SoakWater, key: &(AssetId<Mesh>, u32)) -> bool {
    water.baking.contains(key)
}

/// Collects the bakes that finished: a ready atlas is cached (for mesh
/// assets) and put on the entity; a failed one is a [`FloatingError`].
pub(crate) fn finish_bakes(
    mut commands: Commands,
    mut baking: Query<(Entity, &mut Baking)>,
    mut water: ResMut<SoakWater>,
    mut errors: MessageWriter<FloatingError>,
) {
    water.baking.clear();
    for (entity, mut b) in &mut baking {
        let Some(result) = check_ready(&mut b.task) else {
            if let Some(key) = b.asset {
                water.baking.push(key);
            }
            continue;
        };
        commands.entity(entity).remove::<Baking>();
        match result {
            Ok(atlas) => {
                if let Some(key) = b.asset {
                    water.atlases.insert(key, atlas.clone());
                }
                commands.entity(entity).insert(Baked(atlas));
            }
            Err(kind) => fail(&mut commands, &mut errors, entity, kind),
        }
    }
}

/// Registers the bodies whose atlas is ready: checks their colliders add
/// no mass (giving density 0 to those that set none), registers them with
/// the driver at their pose, and puts on them the mass it gives them, an
/// `ExternalForce`, a `Velocity` if they had none, and a [`FloatReport`].
#[allow(clippy::type_complexity)]
pub(crate) fn register_bodies(
    mut commands: Commands,
    ready: Query<(
        Entity,
        &Floating,
        &Baked,
        &Transform,
        Option<&Velocity>,
        Option<&GravityScale>,
        Option<&Children>,
    )>,
    colliders: Query<Option<&ColliderMassProperties>, With<Collider>>,
    mut water: ResMut<SoakWater>,
    mut errors: MessageWriter<FloatingError>,
) {
    for (entity, floating, baked, transform, velocity, gravity, children) in &ready {
        commands.entity(entity).remove::<Baked>();
        let name = floating.name.clone();
        // The body's own collider and those of its children.
        let mut massless = Vec::new();
        let mut refused = None;
        for c in std::iter::once(entity).chain(children.into_iter().flatten().copied()) {
            match colliders.get(c) {
                Ok(None) => massless.push(c),
                Ok(Some(ColliderMassProperties::Density(d))) if *d == 0.0 => {}
                Ok(Some(ColliderMassProperties::Mass(m))) if *m == 0.0 => {}
                Ok(Some(other)) => refused = Some((c, format!("{other:?}"))),
                Err(_) => {}
            }
        }
        if let Some((collider, what)) = refused {
            let kind = FloatingErrorKind::ColliderHasMass { name, collider, what };
            fail(&mut commands, &mut errors, entity, kind);
            continue;
        }
        let effects = match &floating.atlas_effects {
            None => floating.effects.clone(),
            Some(make) => match make(&baked.0, floating.effects.clone()) {
                Ok(effects) => effects,
                Err(reason) => {
                    fail(
                        &mut commands,
                        &mut errors,
                        entity,
                        FloatingErrorKind::Effects { name, reason },
                    );
                    continue;
                }
            },
        };
        // The driver names it by its entity and the slot it is about to
        // take: its id.
        let key = BodyKey {
            entity,
            slot: water.driver.bodies().len() as u32,
        };
        let mut engine = Registering::new(key, transform, velocity, gravity);
        let desc = BodyDesc {
            name,
            atlas: baked.0.clone(),
            mass_model: floating.mass_model.clone(),
            effects,
        };
        let id = match water.driver.register(&mut engine, key, desc) {
            Ok(id) => id,
            Err(e) => {
                fail(&mut commands, &mut errors, entity, e.into());
                continue;
            }
        };
        water.entities.insert(entity, id);
        let Some((props, engine_mass)) = engine.mass else {
            continue;
        };
        for c in massless {
            commands.entity(c).insert(ColliderMassProperties::Density(0.0));
        }
        commands
            .entity(entity)
            .insert((
                SoakLink { id, engine_mass },
                ExternalForce::default(),
                AdditionalMassProperties::MassProperties(props),
                FloatReport::default(),
            ))
            .insert_if_new((Velocity::zero(), ReadMassProperties::default()));
    }
}

/// What the plugin writes of a registered body each step.
type WriteItem = (
    &'static mut SoakLink,
    &'static mut ExternalForce,
    &'static mut AdditionalMassProperties,
    &'static mut FloatReport,
);

/// One physics step's work: forgets bodies whose entity went, reads the
/// step bevy_rapier is about to take, reads every registered body in one
/// pass, runs the driver (the liquid inside hulls, the water's forces,
/// wet surfaces, the waves), advances its clock, and writes every body's
/// `ExternalForce` (where it changed), mass and [`FloatReport`] in
/// another pass.
#[allow(clippy::too_many_arguments)]
pub(crate) fn step_bodies(
    mut water: ResMut<SoakWater>,
    mode: Res<TimestepMode>,
    time: Res<Time>,
    context: Query<
        (
            &RapierConfiguration,
            &RapierContextSimulation,
            &RapierRigidBodySet,
        ),
        With<DefaultRapierContext>,
    >,
    mut bodies: ParamSet<(Query<ReadItem>, Query<WriteItem>)>,
    mut removed: RemovedComponents<SoakLink>,
    mut unfloated: RemovedComponents<Floating>,
    mut commands: Commands,
    mut errors: MessageWriter<FloatingError>,
) {
    let water = &mut *water;
    // A body whose entity went, or that no longer floats: its id is not
    // reused, its state is dropped; one that lives on is handed no force
    // from then on.
    for entity in unfloated.read() {
        if water.entities.contains_key(&entity) {
            commands
                .entity(entity)
                .try_insert(ExternalForce::default())
                .try_remove::<(SoakLink, FloatReport)>();
        }
    }
    for entity in removed.read() {
        if let Some(id) = water.entities.remove(&entity) {
            let _ = water.driver.retire(id, &mut water.gathered);
        }
    }
    let Ok((config, simulation, set)) = context.single() else {
        return;
    };
    if !config.physics_pipeline_active {
        return;
    }
    // The step bevy_rapier takes in this run: `substeps` steps of
    // `dt/substeps`, each of Rapier's solver substeps, with the force held
    // throughout (one step of `dt` with all those substeps).
    let (dt, substeps) = match *mode {
        TimestepMode::Fixed { dt, substeps } => (dt, substeps),
        TimestepMode::Variable {
            max_dt,
            time_scale,
            substeps,
        } => ((time.delta_secs() * time_scale).min(max_dt), substeps),
        TimestepMode::Interpolated { .. } => {
            if !water.schedule_refused {
                water.schedule_refused = true;
                let kind = FloatingErrorKind::Schedule(
                    "soak: TimestepMode::Interpolated steps Rapier a varying number of times per run, with the \
                     force held over all of them: use TimestepMode::Fixed (with RapierPhysicsPlugin::in_fixed_schedule) \
                     or Variable; the water's forces are not applied"
                        .into(),
                );
                log::error!("{kind}");
                errors.write(FloatingError {
                    entity: Entity::PLACEHOLDER,
                    kind,
                });
            }
            return;
        }
    };
    if dt.is_nan() || dt <= 0.0 || water.entities.is_empty() {
        return;
    }
    let start = std::time::Instant::now();
    let solver = simulation.integration_parameters.num_solver_iterations.max(1);
    let params = StepParams::new(dt as f64, solver * substeps.max(1));
    water
        .driver
        .set_gravity(super::bodies::vector(config.gravity).norm());
    let slots = water.driver.bodies().len();
    water.gathered.gather(&bodies.p0(), &set.bodies, slots);
    let result = water.driver.before_step(&mut water.gathered, &params);
    if let Err(e) = result {
        let kind = FloatingErrorKind::Driver(e);
        log::error!("soak: {kind}");
        errors.write(FloatingError {
            entity: Entity::PLACEHOLDER,
            kind,
        });
        return;
    }
    water.driver.after_step(params.dt);
    let t = water.driver.time();
    let gathered = &water.gathered;
    for (mut link, mut force, mut additional, mut report) in &mut bodies.p1() {
        let slot = link.id.0;
        let Some(b) = water.driver.body(link.id) else {
            continue;
        };
        if let Some(w) = gathered.wrenches.get(slot).copied().flatten() {
            // bevy_rapier hands a changed force to Rapier (replacing the
            // last); an unchanged one goes on acting as it is.
            force.set_if_neq(ExternalForce {
                force: to_vec3(&w.force),
                torque: to_vec3(&w.torque),
            });
        }
        if let Some((props, engine_mass)) = gathered.masses.get(slot).copied().flatten() {
            *additional = AdditionalMassProperties::MassProperties(props);
            link.engine_mass = engine_mass;
        }
        let forces = b.forces();
        let (surface_liquid, saturation) = match b.wetting() {
            Some(w) => (
                w.total_liquid(b.atlas()),
                w.material().saturation * b.atlas().area(),
            ),
            None => (0.0, 0.0),
        };
        *report = FloatReport {
            time: t,
            submerged_volume: b.submerged_volume(),
            submerged_fraction: b.submerged_fraction(),
            center_of_buoyancy: to_vec3(&forces.center_of_buoyancy.coords),
            buoyancy: to_vec3(&forces.buoyancy.force),
            drag: to_vec3(&forces.drag.force),
            force: to_vec3(&b.applied().force),
            torque: to_vec3(&b.applied().torque),
            mass: b.mass_properties().mass,
            liquid_inside: b.flooding().map_or(0.0, |f| f.inside()),
            surface_liquid,
            wetness: if saturation > 0.0 {
                (surface_liquid / saturation).clamp(0.0, 1.0)
            } else {
                0.0
            },
        };
    }
    water.last_step = start.elapsed();
}
