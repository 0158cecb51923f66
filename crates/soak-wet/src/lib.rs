#![doc = include_str!("../README.md")]

pub mod diffusion;
pub mod environment;
pub mod error;
mod exchange;
#[cfg(feature = "gpu")]
pub mod gpu;
pub mod grid;
mod layout;
pub mod liquid_image;
pub mod material;
mod reduce;
pub mod scenes;
pub mod shared_field;
pub mod source;
pub mod stats;
pub mod wetting;

pub use diffusion::{Diffusion, DiffusionMode, DiffusionReport, SHEPARD_MIN_DISTANCE, SubstepPlan};
pub use environment::{Environment, EnvironmentResponse, EnvironmentTrack};
pub use error::WetError;
pub use grid::{FieldResolution, VoxelGrid};
pub use liquid_image::{liquid_rgb, liquid_texture, pseudo_colour, write_liquid_png};
pub use material::{Liquid, Material};
pub use shared_field::{FieldMember, SharedField, SharedReport};
pub use source::{LiquidImage, Rain, Region, Splash};
pub use stats::LiquidStats;
pub use wetting::{Ledger, StepReport, Wetting};

/// The types most users need.
pub mod prelude {
    pub use crate::{
        Diffusion, DiffusionMode, Environment, EnvironmentTrack, FieldMember, FieldResolution, Liquid,
        Material, Rain, Region, SharedField, Splash, WetError, Wetting, write_liquid_png,
    };
}
