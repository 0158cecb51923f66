//! What can go wrong on the GPU path, as values.

use crate::error::{HydroError, WaterError};

/// Handle of an atlas uploaded to a [`crate::gpu::GpuHydro`].
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct GpuAtlasId(pub(crate) u32);

/// A GPU hydrostatics operation failed.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum GpuError {
    /// No adapter on any enabled backend.
    #[error(
        "no GPU adapter found ({reason}); on Debian install mesa-vulkan-drivers and libvulkan1 \
         (lavapipe) or libegl1, libegl-mesa0 and libgl1-mesa-dri (llvmpipe), or pick a backend \
         with WGPU_BACKEND=vulkan|gl"
    )]
    NoAdapter {
        /// wgpu's reason.
        reason: String,
    },
    /// The adapter refused the device request.
    #[error("requesting a device from {adapter} failed: {reason}")]
    RequestDevice {
        /// The adapter's label.
        adapter: String,
        /// wgpu's reason.
        reason: String,
    },
    /// The device was lost (driver reset, destroyed device).
    #[error("the GPU device was lost while {what}: {reason}")]
    DeviceLost {
        /// The operation.
        what: &'static str,
        /// wgpu's reason.
        reason: String,
    },
    /// The device ran out of memory.
    #[error("out of GPU memory while {what} ({bytes} bytes requested)")]
    OutOfMemory {
        /// The operation.
        what: &'static str,
        /// Bytes that operation allocated.
        bytes: u64,
    },
    /// wgpu rejected an operation (a bug in soak, or a device below the
    /// WebGPU baseline).
    #[error("wgpu rejected {what}: {message}")]
    Validation {
        /// The operation.
        what: &'static str,
        /// wgpu's message.
        message: String,
    },
    /// A buffer that cannot be split would exceed the device's storage binding limit.
    #[error(
        "{what}: {needed} bytes needed in one storage binding, above the limit of {limit} bytes \
         (max_storage_buffer_binding_size); evaluate fewer bodies per batch"
    )]
    TooLarge {
        /// The buffer.
        what: &'static str,
        /// Bytes it needs.
        needed: u64,
        /// The limit in force.
        limit: u64,
    },
    /// The limit in force cannot hold even one work item.
    #[error("a storage binding limit of {limit} bytes is below the minimum of {minimum} bytes")]
    LimitTooSmall {
        /// The limit asked for.
        limit: u64,
        /// The smallest workable limit.
        minimum: u64,
    },
    /// The id names no atlas of this [`crate::gpu::GpuHydro`].
    #[error("atlas {0:?} was not uploaded to this GpuHydro")]
    UnknownAtlas(GpuAtlasId),
    /// The atlas has no texels.
    #[error("cannot upload an atlas without texels")]
    EmptyAtlas,
    /// A water surface the GPU cannot evaluate (a custom [`crate::Surface`]).
    #[error(
        "body {body}: the GPU evaluates Plane, Gerstner, HeightField and Unbounded surfaces \
         only; evaluate custom surfaces with soak_hydro::evaluate"
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
    /// Deformation was asked of an atlas uploaded without its triangles.
    #[error("atlas {0:?} was uploaded without triangles; use GpuHydro::upload_deformable")]
    NotDeformable(GpuAtlasId),
}
