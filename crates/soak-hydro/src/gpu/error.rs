//! What can go wrong on the GPU path, as values.

use crate::error::{HydroError, WaterError};

/// Handle of an atlas uploaded to a [`crate::gpu::GpuHydro`].
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct GpuAtlasId(pub(crate) u32);

/// A GPU hydrostatics, mass-properties or deformation operation failed.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum GpuHydroError {
    /// The device: no adapter, a lost device, out of memory, a command wgpu
    /// rejects, a buffer above the storage binding limit (soak-gpu's errors,
    /// shared by every GPU path of soak).
    #[error(transparent)]
    Gpu(#[from] soak_gpu::GpuError),
    /// The id names no atlas of this [`crate::gpu::GpuHydro`].
    #[error("atlas {0:?} was not uploaded to this GpuHydro")]
    UnknownAtlas(GpuAtlasId),
    /// The atlas has no texels.
    #[error("cannot upload an atlas without texels")]
    EmptyAtlas,
    /// A water surface the GPU cannot evaluate (a custom [`crate::Surface`]).
    #[error(
        "body {body}: the GPU evaluates Plane, FlowPlane, Gerstner, HeightField, SpectralSurface, SurfacePatch \
         and Unbounded surfaces only; evaluate custom surfaces with soak_hydro::evaluate"
    )]
    UnsupportedSurface {
        /// Index of the body in the batch.
        body: usize,
    },
    /// A body's state or mass properties hold a non-finite value.
    #[error("body {body}: `{field}` is not finite")]
    NonFiniteState {
        /// Index of the body in the batch.
        body: usize,
        /// The field.
        field: &'static str,
    },
    /// A body's water is invalid.
    #[error("body {body}: {source}")]
    Water {
        /// Index of the body in the batch.
        body: usize,
        /// What is wrong with it.
        source: WaterError,
    },
    /// The mass model is invalid.
    #[error(transparent)]
    Mass(#[from] HydroError),
    /// Interactive waves on the GPU: a region, step, state or pressure
    /// refused.
    #[error("waves: {0}")]
    Waves(WaterError),
    /// Deformation: the vertex count differs from the baked mesh's.
    #[error("{given} vertex positions for an atlas baked from {expected} vertices")]
    VertexCount {
        /// Positions given.
        given: usize,
        /// Vertices of the baked mesh.
        expected: usize,
    },
    /// Deformation: a vertex position is not finite.
    #[error("deformed vertex {vertex} is not finite")]
    NonFiniteVertex {
        /// The vertex.
        vertex: usize,
    },
    /// Deformation: the triangles do not match the baked mesh.
    #[error(
        "triangle {triangle} ({detail}) does not match the baked mesh of {triangles} triangles and {vertices} vertices"
    )]
    Triangles {
        /// The first offending triangle (or the count given).
        triangle: usize,
        /// What is wrong.
        detail: &'static str,
        /// Triangles of the baked mesh.
        triangles: usize,
        /// Vertices of the baked mesh.
        vertices: usize,
    },
    /// A deformable upload of a coarsened atlas ([`soak_bake::Atlas::coarsened`]),
    /// whose samples are not on single triangles: upload the baked atlas.
    #[error("a deformable atlas must be baked, not coarsened (by {factor})")]
    Coarsened {
        /// The atlas' coarsening factor.
        factor: u32,
    },
    /// Deformation was asked of an atlas uploaded without its triangles.
    #[error("atlas {0:?} was uploaded without triangles; use GpuHydro::upload_deformable")]
    NotDeformable(GpuAtlasId),
}
