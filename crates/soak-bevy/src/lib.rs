#![doc = include_str!("../README.md")]

mod bodies;
mod error;
mod floating;
mod mesh;
mod systems;
mod water;

use bevy::app::{App, FixedUpdate, Plugin};
use bevy::ecs::intern::Interned;
use bevy::ecs::schedule::{IntoScheduleConfigs, ScheduleLabel};
use bevy_rapier3d::prelude::PhysicsSet;
use soak_hydro::Water;

pub use self::bodies::BodyKey;
pub use self::error::{FloatingError, FloatingErrorKind};
pub use self::floating::{FloatReport, Floating, FloatingMesh, SoakLink};
pub use self::systems::FloatingFailed;
pub use self::water::SoakWater;
/// The engine-neutral driver the plugin runs.
pub use soak_driver;

/// Makes bevy_rapier3d bodies with a [`Floating`] component float in the
/// [`SoakWater`] resource (calm water at `y = 0` unless inserted).
///
/// Its systems run in the schedule bevy_rapier steps in (by default
/// `FixedUpdate`: add bevy_rapier with
/// `RapierPhysicsPlugin::<NoUserData>::default().in_fixed_schedule()` and
/// `TimestepMode::Fixed`), before `PhysicsSet::SyncBackend`: each run
/// starts the bakes of new bodies on the async compute pool, registers
/// those whose atlas is ready, and hands every registered body the water's
/// force and torque for the step bevy_rapier is about to take, through its
/// `ExternalForce` (its mass through `AdditionalMassProperties`).
///
/// soak's CPU path runs here: Bevy 0.19 renders with wgpu 29 and soak's
/// GPU kernels use wgpu 30, so they cannot share Bevy's device (once both
/// use one wgpu, `Driver::with_gpu` takes Bevy's `RenderDevice` and
/// `RenderQueue` as they are).
#[derive(Debug, Clone)]
pub struct SoakPlugin {
    schedule: Interned<dyn ScheduleLabel>,
}

impl Default for SoakPlugin {
    fn default() -> Self {
        Self {
            schedule: FixedUpdate.intern(),
        }
    }
}

impl SoakPlugin {
    /// The plugin running in `schedule`: the one bevy_rapier steps in
    /// (`RapierPhysicsPlugin::in_schedule`), `PostUpdate` for its default.
    pub fn in_schedule(schedule: impl ScheduleLabel) -> Self {
        Self {
            schedule: schedule.intern(),
        }
    }
}

impl Plugin for SoakPlugin {
    fn build(&self, app: &mut App) {
        app.add_message::<FloatingError>();
        if !app.world().contains_resource::<SoakWater>() {
            app.insert_resource(SoakWater::new(Water::calm(0.0)));
        }
        app.add_systems(
            self.schedule,
            (
                systems::start_bakes,
                systems::finish_bakes,
                systems::register_bodies,
                systems::step_bodies,
            )
                .chain()
                .before(PhysicsSet::SyncBackend),
        );
    }
}

/// The types most users need.
pub mod prelude {
    pub use crate::{FloatReport, Floating, FloatingError, FloatingMesh, SoakPlugin, SoakWater};
    pub use soak_driver::{Effects, WaveCoupling};
    pub use soak_hydro::{Drag, MassModel, Water};
}
