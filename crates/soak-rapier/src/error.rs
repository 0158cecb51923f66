//! Typed errors of soak-rapier.

use std::path::PathBuf;

/// Registering or driving a body failed.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum SoakError {
    /// The rigid-body handle is not in the set.
    #[error("body `{name}`: its rigid-body handle is not in the set")]
    MissingBody {
        /// The soak body's name.
        name: String,
    },
    /// A collider attached to the body has mass.
    #[error(
        "body `{name}`: collider {collider} has density {density} kg/m³; soak sets the body's mass properties, \
         so give its colliders density 0"
    )]
    ColliderHasMass {
        /// The soak body's name.
        name: String,
        /// The collider index.
        collider: u32,
        /// Its density.
        density: f32,
    },
    /// The body's mass properties are invalid (zero mass, non-finite values).
    #[error("body `{name}`: {reason}")]
    MassProperties {
        /// The soak body's name.
        name: String,
        /// What is wrong.
        reason: String,
    },
    /// The soak id is not registered.
    #[error("no soak body with id {0}")]
    UnknownId(usize),
    /// Mass or hydrostatics failed.
    #[error("body `{name}`: {source}")]
    Hydro {
        /// The soak body's name.
        name: String,
        /// The underlying error.
        source: soak_hydro::HydroError,
    },
    /// A saved state does not fit.
    #[error("saved state: {0}")]
    State(String),
    /// The liquid inside a body failed to advance.
    #[error("liquid: {0}")]
    Liquid(String),
    /// The GPU backend failed (device, upload or evaluation).
    #[error("gpu: {0}")]
    Gpu(String),
    /// A body's wetting (or the environment) was refused or failed to advance.
    #[error("body `{name}`: wetting: {source}")]
    Wet {
        /// The soak body's name (`(environment)` for the environment).
        name: String,
        /// The underlying error.
        source: soak_wet::WetError,
    },
    /// Baking or refreshing the atlas failed.
    #[error("body `{name}`: {source}")]
    Bake {
        /// The soak body's name.
        name: String,
        /// The underlying error.
        source: soak_bake::BakeError,
    },
}

/// A scene file could not be read, parsed or built.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum SceneError {
    /// The file could not be read.
    #[error("cannot read scene `{path}`: {source}")]
    Io {
        /// The file.
        path: PathBuf,
        /// The I/O error.
        source: std::io::Error,
    },
    /// The TOML is malformed or has an unknown or mistyped key.
    #[error("scene `{path}`: {message}")]
    Parse {
        /// The file.
        path: PathBuf,
        /// The parser's message, with line and column.
        message: String,
    },
    /// A value is out of range.
    #[error("scene `{path}`, line {line}: `{key}` {message}")]
    Invalid {
        /// The file.
        path: PathBuf,
        /// 1-based line of the value.
        line: usize,
        /// The key, dotted (`bodies[2].mass.density`).
        key: String,
        /// What is wrong.
        message: String,
    },
    /// A body's mesh could not be loaded or baked.
    #[error("scene `{path}`, line {line}: body `{body}`: {message}")]
    Body {
        /// The file.
        path: PathBuf,
        /// 1-based line of the body's mesh key.
        line: usize,
        /// The body's name.
        body: String,
        /// What went wrong.
        message: String,
    },
}
