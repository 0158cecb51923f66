//! Water: a surface `y = f(x, z, t)` in the world frame (y up), its velocity
//! field, and the fluid's density.
//!
//! One file for the trait and one per surface:
//!
//! - `surface`: [`Surface`](crate::Surface), [`SurfaceKind`](crate::SurfaceKind),
//!   [`Water`](crate::Water) and the constants.
//! - `plane`: [`Plane`](crate::Plane).
//! - `gerstner`: [`Gerstner`](crate::Gerstner) and
//!   [`GerstnerWave`](crate::GerstnerWave), with the inversion of the
//!   Gerstner map.
//! - `height_field`: [`HeightField`](crate::HeightField).
//! - `unbounded`: [`Unbounded`](crate::Unbounded).
//! - `spectrum`: [`SeaSpectrum`](crate::SeaSpectrum) (JONSWAP,
//!   Pierson–Moskowitz, cos-2s spreading) and
//!   [`SpectralSea`](crate::SpectralSea), a sea realised on a periodic
//!   FFT tile.
//! - `patch`: [`SurfacePatch`](crate::SurfacePatch), any surface sampled
//!   once over a region and interpolated.

mod gerstner;
mod height_field;
mod patch;
mod plane;
mod spectral_surface;
mod spectrum;
mod surface;
mod unbounded;

pub use self::gerstner::{Gerstner, GerstnerWave};
pub use self::height_field::HeightField;
pub(crate) use self::patch::PatchGrid;
#[cfg(feature = "gpu")]
pub(crate) use self::patch::PatchVelocityGrid;
pub use self::patch::{MAX_PATCH_NODES, SurfacePatch};
pub use self::plane::{FlowPlane, Plane};
pub use self::spectral_surface::SpectralSurface;
pub use self::spectrum::{
    DEFAULT_SEA_CELLS, ParticleJet, SEA_CELLS, SeaFields, SeaMode, SeaSpectrum, SpectralSea, SpectrumShape,
};
pub(crate) use self::surface::node_at;
pub use self::surface::{
    AIR_DENSITY, STANDARD_GRAVITY, Surface, SurfaceKind, SurfaceNode, WATER_DENSITY, Water,
};
pub use self::unbounded::Unbounded;
