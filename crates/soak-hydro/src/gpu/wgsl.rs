//! The WGSL of soak-hydro's kernels that other crates' kernels build on, and
//! its Rust side: the buffer layouts (`Body`, `Wave`, `SURFACE_*`, the texels
//! as [`texel_vec4s`] packs them) and the
//! water surfaces (`surface_at`: depth under a plane, a Gerstner sea, a
//! height field, a sampled surface or an unbounded medium), with the
//! encoder that fills a
//! [`Body`]'s surface fields from a [`crate::Water`].
//!
//! soak-wet's absorption kernel composes `BINDINGS`, `WATER_SURFACE` and its
//! own WGSL, and encodes its bodies' water with [`encode_surface`], so the
//! depth a wetting texel sees is the one the hydrostatics sees.

/// Buffer layouts of the hydrostatics kernels (`Body`, `Wave`, `Item`,
/// `Dispatch`, the `SURFACE_*` kinds), mirrored by [`Body`] and [`Wave`].
pub const BINDINGS: &str = include_str!("../../shaders/bindings.wgsl");
/// Water surfaces: `surface_at(body, r)` and what it needs. Composed after
/// [`BINDINGS`]; the including module declares the bindings `waves`,
/// `heights` and `radii`.
pub const WATER_SURFACE: &str = include_str!("../../shaders/water_surface.wgsl");

pub use super::layout::{Body, Wave, texel_vec4s};
pub use super::surface::{HeightFields, encode_surface};
