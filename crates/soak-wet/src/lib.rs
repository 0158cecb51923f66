#![doc = include_str!("../README.md")]

// The files are private: what users reach is re-exported below, so the
// layout can change without changing the API.
mod body_field;
mod diffusion;
mod environment;
mod error;
mod exchange;
mod grid;
mod layout;
mod ledger;
mod liquid_image;
mod material;
mod reduce;
mod shared_field;
mod source;
mod stats;
mod wetting;

// Public on purpose: wetting on wgpu compute kernels is a namespace behind a
// feature, with an API of its own (`GpuWetting`, `GpuWetBody`, device
// helpers, the kernel sources).
#[cfg(feature = "gpu")]
pub mod gpu;

// Public on purpose: the ready-made scenes (`scenes::Beach`,
// `scenes::terrain_slab`, `scenes::TidalSea`, ...) are a namespace of helpers
// for examples, tests and benches, apart from the library's own types.
pub mod scenes;

pub use self::diffusion::{Diffusion, DiffusionMode, DiffusionReport, SHEPARD_MIN_DISTANCE, SubstepPlan};
pub use self::environment::{Environment, EnvironmentResponse, EnvironmentTrack};
pub use self::error::WetError;
pub use self::grid::{AUTO_MAX_CELLS, AUTO_TEXEL_SPAN, FieldResolution, MAX_VOXELS, VoxelGrid};
pub use self::ledger::{Ledger, StepReport};
pub use self::liquid_image::{UNCOVERED, liquid_rgb, liquid_texture, pseudo_colour, write_liquid_png};
pub use self::material::{Liquid, Material};
pub use self::shared_field::{FieldMember, SharedField, SharedReport};
pub use self::source::{
    LiquidImage, MAX_EXR_BLOCK_BYTES, MAX_IMAGE_BYTES, MAX_IMAGE_SIDE, Rain, Region, Splash,
};
pub use self::stats::{HISTOGRAM_BINS, LiquidStats, WET_FILL, round_significant};
pub use self::wetting::Wetting;

/// The types most users need.
pub mod prelude {
    pub use crate::{
        Diffusion, DiffusionMode, Environment, EnvironmentTrack, FieldMember, FieldResolution, Liquid,
        Material, Rain, Region, SharedField, Splash, WetError, Wetting, write_liquid_png,
    };
}
