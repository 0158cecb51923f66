#![doc = include_str!("../README.md")]

pub mod error;
#[cfg(feature = "gpu")]
pub mod gpu;
pub mod hydrostatics;
pub mod mass;
mod parallel;
pub mod reference;
pub mod tiled;
pub mod water;

pub use error::{HydroError, WaterError};
pub use hydrostatics::{
    BodyState, BuoyancyMode, Drag, HydroForces, HydroOptions, Wrench, evaluate, streaming_read,
};
pub use mass::{MassModel, MassProperties, PrincipalInertia, VolumeMoments, volume_moments};
pub use tiled::TiledAtlas;
pub use water::{Gerstner, GerstnerWave, HeightField, Plane, Surface, SurfaceKind, Unbounded, Water};

/// The types most users need.
pub mod prelude {
    pub use crate::{
        BodyState, BuoyancyMode, Drag, HydroForces, HydroOptions, MassModel, MassProperties, Plane,
        TiledAtlas, Water, evaluate,
    };
}
