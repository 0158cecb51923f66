//! Typed errors of soak-wet.

use std::path::PathBuf;

use soak_hydro::WaterError;

/// A wetting operation was refused: the message names the offending value.
///
/// Nothing in soak-wet panics on bad input or lets a NaN into the liquid
/// texture; every check that fails ends here.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum WetError {
    /// A physical parameter is non-finite or out of its range.
    #[error("`{name}` = {value} is invalid: {expected}")]
    Parameter {
        /// Where the parameter lives, e.g. `material.permeability`.
        name: &'static str,
        /// Its value.
        value: f64,
        /// The range it must lie in.
        expected: &'static str,
    },
    /// The wetting state was made for another atlas.
    #[error("the wetting state holds {state} texels but the atlas has {atlas}")]
    AtlasMismatch {
        /// Texels of the state.
        state: usize,
        /// Texels of the atlas.
        atlas: usize,
    },
    /// A per-texel channel has the wrong length.
    #[error("{what} has {len} values for an atlas of {texels} texels")]
    ChannelLength {
        /// Which channel.
        what: &'static str,
        /// Values given.
        len: usize,
        /// Texels in the atlas.
        texels: usize,
    },
    /// A per-texel value is non-finite or out of range.
    #[error("{what} at texel {texel} is {value}, outside {expected}")]
    ChannelValue {
        /// Which channel.
        what: &'static str,
        /// The texel.
        texel: usize,
        /// Its value.
        value: f64,
        /// The range it must lie in.
        expected: &'static str,
    },
    /// The atlas has no texel.
    #[error("the atlas has no texel")]
    EmptyAtlas,
    /// A pose holds a NaN or an infinity.
    #[error("the pose of {what} is not finite")]
    NonFinitePose {
        /// Whose pose (`"the body"`, `"field member 3"`).
        what: String,
    },
    /// The time step is negative or not finite.
    #[error("time step {dt} s must be finite and non-negative")]
    TimeStep {
        /// The time step, s.
        dt: f64,
    },
    /// The simulation time is not finite.
    #[error("time {t} s is not finite")]
    Time {
        /// The time, s.
        t: f64,
    },
    /// The water is invalid.
    #[error(transparent)]
    Water(#[from] WaterError),
    /// A scene's mesh could not be baked.
    #[error(transparent)]
    Bake(#[from] soak_bake::BakeError),
    /// A voxel field would have too many voxels.
    #[error("a field of {dims:?} voxels ({voxels} in all) exceeds the limit of {limit}; use larger voxels")]
    FieldTooLarge {
        /// Voxels along x, y, z.
        dims: [u64; 3],
        /// Their product.
        voxels: u64,
        /// The largest field allowed.
        limit: u64,
    },
    /// A field's box is empty, inverted or not finite.
    #[error("field box from {min:?} to {max:?} m is empty or not finite")]
    FieldBox {
        /// Lower corner, m.
        min: [f64; 3],
        /// Upper corner, m.
        max: [f64; 3],
    },
    /// A shared field was asked to size its voxels from texels it has not seen.
    #[error(
        "a shared field built from a box needs an explicit resolution (VoxelSize or Cells), \
         not {resolution}; use SharedField::around to size voxels from the members' texels"
    )]
    Resolution {
        /// The resolution given.
        resolution: &'static str,
    },
    /// An image has the wrong size or could not be read or written.
    #[error("image {path:?}: {reason}")]
    Image {
        /// The file, if any.
        path: Option<PathBuf>,
        /// What went wrong.
        reason: String,
    },
}

impl WetError {
    pub(crate) fn parameter(name: &'static str, value: f64, expected: &'static str) -> Self {
        Self::Parameter {
            name,
            value,
            expected,
        }
    }
}

/// Checks `value` is finite and at least zero.
pub(crate) fn non_negative(name: &'static str, value: f64) -> Result<(), WetError> {
    if value.is_finite() && value >= 0.0 {
        Ok(())
    } else {
        Err(WetError::parameter(name, value, "finite and >= 0"))
    }
}

/// Checks `value` is finite and above zero.
pub(crate) fn positive(name: &'static str, value: f64) -> Result<(), WetError> {
    if value.is_finite() && value > 0.0 {
        Ok(())
    } else {
        Err(WetError::parameter(name, value, "finite and > 0"))
    }
}
