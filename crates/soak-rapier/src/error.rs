//! Typed errors of soak-rapier: [`SoakError`] (soak-driver's, for
//! registering and driving bodies) and [`SceneError`] (scene files).

pub use soak_driver::SoakError;

use std::path::PathBuf;

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
