//! What went wrong with a floating body ([`FloatingError`]), sent as a
//! Bevy message: nothing in the plugin panics on bad input.

use bevy::prelude::{Entity, Message};

/// A body that could not float, or a step that failed, as a Bevy
/// [`Message`] (read it with `MessageReader<FloatingError>`). The plugin
/// also logs each one at error level.
#[derive(Debug, Message)]
pub struct FloatingError {
    /// The entity with the [`Floating`](crate::Floating) component
    /// (`Entity::PLACEHOLDER` for a step that failed as a whole).
    pub entity: Entity,
    /// What went wrong.
    pub kind: FloatingErrorKind,
}

/// What went wrong ([`FloatingError::kind`]).
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum FloatingErrorKind {
    /// The entity has no bevy_rapier `RigidBody`: soak floats rigid bodies.
    #[error(
        "body `{name}`: the entity has no bevy_rapier RigidBody; add RigidBody::Dynamic (and a Collider) to make it float"
    )]
    NoRigidBody {
        /// The body's name.
        name: String,
    },
    /// The rigid body is not dynamic (fixed or kinematic): forces move
    /// nothing.
    #[error("body `{name}`: its RigidBody is {kind}, not Dynamic: the water's forces would move nothing")]
    NotDynamic {
        /// The body's name.
        name: String,
        /// Which kind it is.
        kind: &'static str,
    },
    /// A collider of the body has mass of its own (soak owns the body's
    /// mass).
    #[error(
        "body `{name}`: its collider on entity {collider} has {what}; soak sets the body's mass, so give its \
         colliders ColliderMassProperties::Density(0.0) (or none: the plugin sets it)"
    )]
    ColliderHasMass {
        /// The body's name.
        name: String,
        /// The collider's entity.
        collider: Entity,
        /// Its mass properties, as set.
        what: String,
    },
    /// The Bevy mesh asset could not be read as a triangle mesh.
    #[error("body `{name}`: mesh asset: {reason}")]
    MeshAsset {
        /// The body's name.
        name: String,
        /// What is wrong.
        reason: String,
    },
    /// The mesh could not be unwrapped or baked into an atlas.
    #[error("body `{name}`: {source}")]
    Bake {
        /// The body's name.
        name: String,
        /// The underlying error.
        source: soak_bake::BakeError,
    },
    /// The mesh is invalid (open, non-manifold, NaN positions...).
    #[error("body `{name}`: {source}")]
    Mesh {
        /// The body's name.
        name: String,
        /// The underlying error.
        source: soak_bake::MeshError,
    },
    /// The effects made for the atlas could not be made
    /// ([`Floating::with_atlas_effects`](crate::Floating::with_atlas_effects)).
    #[error("body `{name}`: effects for its atlas: {reason}")]
    Effects {
        /// The body's name.
        name: String,
        /// What went wrong.
        reason: String,
    },
    /// The driver refused the body or failed in a step.
    #[error(transparent)]
    Driver(#[from] soak_driver::SoakError),
    /// bevy_rapier steps in a way the driver cannot follow.
    #[error("{0}")]
    Schedule(String),
}
