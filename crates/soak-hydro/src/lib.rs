#![doc = include_str!("../README.md")]

// The files are private: what users reach is re-exported below, so the
// layout can change without changing the API.
mod added_mass;
mod error;
mod fft2;
mod hydrostatics;
mod mass;
mod parallel;
mod resolution;
mod scratch;
mod tiled;
mod water;
mod water_plane;
mod waves;

// Public on purpose: the wgpu compute kernels are a namespace behind a
// feature, with an API of their own (device helpers, batches of bodies, and
// in `gpu::wgsl` the WGSL other crates' kernels build on), whose names would
// crowd the crate root.
#[cfg(feature = "gpu")]
pub mod gpu;

// Public on purpose: the exact reference implementations (mesh clipping,
// polyhedral mass properties, closed forms for spheres, boxes and
// cylinders) read best as a namespace of their own, apart from the texel
// methods they check: `reference::submerged_part` beside `evaluate`, and
// `reference::solid_mass_properties` beside `MassModel::mass_properties`.
pub mod reference;

pub use self::added_mass::{AddedMass, EquivalentEllipsoid, lamb_coefficients};
pub use self::error::{HydroError, WaterError};
pub use self::hydrostatics::body_state::BodyState;
pub use self::hydrostatics::evaluation::{evaluate, sampled_water, streaming_read};
pub use self::hydrostatics::forces::{HydroForces, Wrench};
pub use self::hydrostatics::options::{BuoyancyMode, Drag, HydroOptions, SeaBand, SeaSampling, SeaVelocity};
pub use self::mass::{
    MassModel, MassProperties, PrincipalInertia, VolumeMoments, inertia_from_second_moment, parallel_axis,
    shell, volume_moments,
};
pub use self::resolution::{AUTO_RESOLUTIONS, ResolutionChoice, ResolutionError, bake_to_tolerance};
pub use self::tiled::{
    DragTexels, SEA_TILE_TOLERANCE, TileCounts, TileMoments, TiledAtlas, evaluate_with_drag,
};
pub use self::water::{
    AIR_DENSITY, DEFAULT_SEA_CELLS, FlowPlane, Gerstner, GerstnerWave, HeightField, MAX_PATCH_NODES,
    ParticleJet, Plane, SEA_CELLS, STANDARD_GRAVITY, SeaFields, SeaMode, SeaSpectrum, SpectralSea,
    SpectralSurface, SpectrumShape, Surface, SurfaceKind, SurfaceNode, SurfacePatch, Unbounded,
    WATER_DENSITY, Water,
};
pub use self::water_plane::{WaterPlane, water_plane};
pub use self::waves::{InteractiveWaves, MAX_WAVE_CELLS, WaveHeights, WaveRegion, WavesState};

/// The types most users need.
pub mod prelude {
    pub use crate::{
        BodyState, BuoyancyMode, Drag, Gerstner, GerstnerWave, HeightField, HydroForces, HydroOptions,
        MassModel, MassProperties, Plane, TiledAtlas, Water, evaluate,
    };
}
