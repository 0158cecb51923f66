#![doc = include_str!("../README.md")]

// The files are private: what users reach is re-exported below, so the
// layout can change without changing the API.
mod atlas;
mod bake;
mod coarsen;
mod columns;
mod error;
mod export;
mod load;
mod mesh;
mod open;
mod pack;
mod pieces;
mod unwrap;
mod uv_overlap;
mod validate;

// Public on purpose: the procedural meshes are a namespace users name
// (`builtin::cuboid`, `builtin::sphere`, `builtin::parse`, `builtin::NAMES`),
// the fixtures of every example and test, whose short names would be
// ambiguous at the crate root.
pub mod builtin;

pub use self::atlas::{Atlas, AtlasSummary, MomentSums, TexelMoments, Tile};
pub use self::bake::{BakeOptions, DEFAULT_TILE_SIZE, MAX_RESOLUTION};
pub use self::columns::Columns;
pub use self::error::{BakeError, ExportError, LoadError, MeshError, MeshProblem};
pub use self::export::AtlasImage;
pub use self::load::{load_gltf_bytes, load_mesh, load_obj_bytes};
pub use self::mesh::{Mesh, Opening, SourceNumbering};
pub use self::open::{Cavities, boundary_loops, cap_cavities, cap_openings, triangulate};
pub use self::pack::{DEFAULT_PADDING, pack_charts};
pub use self::unwrap::{UnwrapOptions, UnwrapReport, unwrap};
pub use self::uv_overlap::{find_overlap, triangles_overlap};
pub use self::validate::{
    DEGENERATE_AREA, DEGENERATE_UV_AREA, validate, validate_geometry, validate_topology, validate_uvs,
};

/// The types most users need.
pub mod prelude {
    pub use crate::{
        Atlas, BakeError, BakeOptions, LoadError, Mesh, MeshError, UnwrapOptions, builtin, load_mesh, unwrap,
    };
}
