#![doc = include_str!("../README.md")]

pub mod atlas;
pub mod bake;
pub mod builtin;
pub mod columns;
pub mod error;
pub mod export;
pub mod load;
pub mod mesh;
pub mod pack;
pub mod unwrap;
pub mod uv_overlap;
pub mod validate;

pub use atlas::{Atlas, AtlasSummary, Tile};
pub use bake::{BakeOptions, DEFAULT_TILE_SIZE, MAX_RESOLUTION};
pub use columns::Columns;
pub use error::{BakeError, ExportError, LoadError, MeshError, MeshProblem};
pub use load::load_mesh;
pub use mesh::Mesh;
pub use unwrap::{UnwrapOptions, UnwrapReport, unwrap};

/// The types most users need.
pub mod prelude {
    pub use crate::{Atlas, BakeError, BakeOptions, LoadError, Mesh, MeshError, load_mesh, unwrap};
}
