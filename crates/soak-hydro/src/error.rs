//! Typed errors of soak-hydro.

/// A water description is invalid.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum WaterError {
    /// A scalar parameter is non-finite or out of range.
    #[error("water parameter `{name}` = {value} is invalid")]
    Parameter {
        /// The parameter.
        name: &'static str,
        /// Its value.
        value: f64,
    },
    /// A plane normal is zero, non-finite or does not point up.
    #[error("plane normal {normal:?} must be finite and point up (y > 0)")]
    PlaneNormal {
        /// The normal as given.
        normal: [f64; 3],
    },
    /// A Gerstner wave has an invalid field.
    #[error("Gerstner wave {index}: `{field}` = {value} is invalid")]
    Wave {
        /// Wave index.
        index: usize,
        /// The field.
        field: &'static str,
        /// Its value.
        value: f64,
    },
    /// A spectral sea's mode, given to `SpectralSea::from_modes`, has an
    /// invalid field.
    #[error("spectral mode {index} (of those given): `{field}` = {value} is invalid")]
    Mode {
        /// The mode's index in the list given.
        index: usize,
        /// The field.
        field: &'static str,
        /// Its value.
        value: f64,
    },
    /// A height field's sample count does not match its grid.
    #[error("height field of {nx}x{nz} samples (at least 2x2) has {len} heights")]
    HeightFieldShape {
        /// Samples along x.
        nx: usize,
        /// Samples along z.
        nz: usize,
        /// Heights given.
        len: usize,
    },
    /// A height-field sample is not finite.
    #[error("height field sample {index} is {value}")]
    HeightFieldSample {
        /// Sample index.
        index: usize,
        /// Its value.
        value: f64,
    },
}

/// Mass properties or hydrostatics could not be computed.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum HydroError {
    /// A solid mass model for an open mesh's atlas: its walls are a single
    /// surface that encloses no volume.
    #[error(
        "a solid mass model needs a closed mesh: this atlas is of an open mesh whose walls enclose no volume \
         (use walls of a density and a thickness, or a shell)"
    )]
    OpenSolid,
    /// Given mass properties with a mass not > 0 or a value not finite.
    #[error("given mass properties {properties} need a mass > 0 and finite values")]
    GivenMass {
        /// The properties given, printed.
        properties: String,
    },
    /// A wall thickness is non-finite or not positive.
    #[error("wall thickness {value} m must be finite and positive")]
    Thickness {
        /// The thickness given, m.
        value: f64,
    },
    /// A density is non-finite or not positive.
    #[error("{what} density {value} must be finite and positive")]
    Density {
        /// Which density.
        what: &'static str,
        /// Its value.
        value: f64,
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
    /// A per-texel value is non-finite or negative.
    #[error("{what} at texel {texel} is {value}")]
    ChannelValue {
        /// Which channel.
        what: &'static str,
        /// The texel.
        texel: usize,
        /// Its value.
        value: f32,
    },
    /// A body's added mass cannot be computed.
    #[error("added mass: {reason}")]
    AddedMass {
        /// What is wrong.
        reason: String,
    },
    /// The mass model gives no mass.
    #[error("the mass model gives zero mass")]
    ZeroMass,
    /// The body state holds a non-finite value.
    #[error("body state `{field}` is not finite")]
    NonFiniteState {
        /// The field.
        field: &'static str,
    },
    /// The water is invalid.
    #[error(transparent)]
    Water(#[from] WaterError),
    /// The texels a body's drag is summed over are not of its mesh.
    #[error(
        "the drag texels' origin {drag:?} is not the body atlas' {body:?} (object frame, m): bake both from the same mesh"
    )]
    DragTexels {
        /// The body atlas' origin.
        body: [f64; 3],
        /// The drag texels' origin.
        drag: [f64; 3],
    },
}
