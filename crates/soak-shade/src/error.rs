//! Typed errors for invalid optical parameters.

/// An optical parameter outside its physical range.
///
/// The hot shading functions never panic and never return errors: they clamp
/// or propagate NaN as documented on each. Parameters are checked once, up
/// front, with the `validate` methods and the free `check_*` functions,
/// which name the offending parameter and its value.
///
/// Every variant names the parameter (e.g. `"liquid.refractive_index"`,
/// `"albedo.g"`) and carries the rejected value.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum ParameterError {
    /// The value is NaN or infinite.
    #[error("{parameter} is {value}, but must be a finite number")]
    NotFinite {
        /// Name of the parameter.
        parameter: &'static str,
        /// The rejected value.
        value: f64,
    },
    /// A refractive index relative to air that is not greater than 1.
    #[error("{parameter} is {value}, but a liquid's refractive index relative to air must be greater than 1")]
    IndexNotAboveOne {
        /// Name of the parameter.
        parameter: &'static str,
        /// The rejected value.
        value: f64,
    },
    /// A fraction (albedo, transmittance, saturation, porosity, roughness)
    /// outside `[0, 1]`.
    #[error("{parameter} is {value}, outside [0, 1]")]
    OutsideUnitInterval {
        /// Name of the parameter.
        parameter: &'static str,
        /// The rejected value.
        value: f64,
    },
    /// A value that must be strictly positive (a Γ shape parameter, a
    /// reference thickness).
    #[error("{parameter} is {value}, but must be greater than 0")]
    NotPositive {
        /// Name of the parameter.
        parameter: &'static str,
        /// The rejected value.
        value: f64,
    },
    /// A value that must not be negative (an absorption coefficient, a film
    /// thickness).
    #[error("{parameter} is {value}, but must not be negative")]
    Negative {
        /// Name of the parameter.
        parameter: &'static str,
        /// The rejected value.
        value: f64,
    },
}

/// A 1-D artist curve that cannot serve as a Γ blend.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum CurveError {
    /// Fewer than two samples.
    #[error("artist curve has {len} samples, but needs at least 2")]
    TooShort {
        /// Number of samples given.
        len: usize,
    },
    /// A sample is NaN or infinite.
    #[error("artist curve sample {index} is {value}, but must be a finite number")]
    NotFinite {
        /// Index of the sample.
        index: usize,
        /// The rejected value.
        value: f64,
    },
    /// A sample is lower than the one before it.
    #[error(
        "artist curve sample {index} is {value}, below sample {} ({previous}): Γ must be non-decreasing",
        index - 1
    )]
    Decreasing {
        /// Index of the offending sample (≥ 1).
        index: usize,
        /// Its value.
        value: f64,
        /// The value of sample `index − 1`.
        previous: f64,
    },
    /// The curve does not start at exactly 0 and end at exactly 1.
    #[error(
        "artist curve runs from {first} to {last}, but Γ must start at exactly 0 and end at exactly 1 (use ArtistCurve::normalized to rescale)"
    )]
    Ends {
        /// The first sample.
        first: f64,
        /// The last sample.
        last: f64,
    },
    /// The curve is flat, so it cannot be rescaled to run from 0 to 1.
    #[error("artist curve is flat at {value}: it cannot be rescaled to run from 0 to 1")]
    Flat {
        /// The constant value.
        value: f64,
    },
    /// The requested image row does not exist.
    #[error("image row {row} does not exist: the image is {height} pixels high")]
    RowOutOfBounds {
        /// The requested row.
        row: u32,
        /// The image height in pixels.
        height: u32,
    },
}

/// Checks that `value` is finite.
pub fn check_finite(parameter: &'static str, value: f64) -> Result<f64, ParameterError> {
    if value.is_finite() {
        Ok(value)
    } else {
        Err(ParameterError::NotFinite { parameter, value })
    }
}

/// Checks that `value` is a finite fraction in `[0, 1]`.
pub fn check_unit(parameter: &'static str, value: f64) -> Result<f64, ParameterError> {
    check_finite(parameter, value)?;
    if (0.0..=1.0).contains(&value) {
        Ok(value)
    } else {
        Err(ParameterError::OutsideUnitInterval { parameter, value })
    }
}

/// Checks that `value` is finite and strictly positive.
pub fn check_positive(parameter: &'static str, value: f64) -> Result<f64, ParameterError> {
    check_finite(parameter, value)?;
    if value > 0.0 {
        Ok(value)
    } else {
        Err(ParameterError::NotPositive { parameter, value })
    }
}

/// Checks that `value` is finite and not negative.
pub fn check_non_negative(parameter: &'static str, value: f64) -> Result<f64, ParameterError> {
    check_finite(parameter, value)?;
    if value >= 0.0 {
        Ok(value)
    } else {
        Err(ParameterError::Negative { parameter, value })
    }
}

/// Checks that `value` is a finite refractive index relative to air, `> 1`.
pub fn check_refractive_index(parameter: &'static str, value: f64) -> Result<f64, ParameterError> {
    check_finite(parameter, value)?;
    if value > 1.0 {
        Ok(value)
    } else {
        Err(ParameterError::IndexNotAboveOne { parameter, value })
    }
}

/// Checks every channel of an RGB fraction (albedo, transmittance) against
/// `[0, 1]`; `names` gives the parameter name of each channel, e.g.
/// `["albedo.r", "albedo.g", "albedo.b"]`.
pub fn check_unit_rgb(names: [&'static str; 3], rgb: [f64; 3]) -> Result<[f64; 3], ParameterError> {
    for (name, v) in names.into_iter().zip(rgb) {
        check_unit(name, v)?;
    }
    Ok(rgb)
}
