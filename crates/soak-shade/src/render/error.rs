//! What can go wrong when rendering, as values.

use crate::error::ParameterError;

/// Rendering (or a GPU optics evaluation) failed.
///
/// GPU failures (no adapter, lost device, out of memory, a command wgpu
/// rejects) and invalid scenes are reported here; the renderer never
/// panics on them.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum RenderError {
    /// The device: no adapter, a lost device, out of memory, a command wgpu
    /// rejects (a bug in soak, or a device below what the renderer needs,
    /// e.g. no renderable `Rgba16Float`); soak-gpu's errors, shared by every
    /// GPU path of soak.
    #[error(transparent)]
    Gpu(#[from] soak_gpu::GpuError),
    /// An image size the renderer cannot make.
    #[error("{what} is {width}×{height} pixels; each side must be in 1..={max}")]
    ImageSize {
        /// Which image.
        what: &'static str,
        /// Requested width, px.
        width: u32,
        /// Requested height, px.
        height: u32,
        /// The device's largest 2-D texture side.
        max: u32,
    },
    /// An MSAA sample count the renderer does not support.
    #[error("sample count {0} is not supported; use 1 or 4")]
    SampleCount(u32),
    /// An object's material or albedo is out of range.
    #[error("object {object} ({name}): {source}")]
    Material {
        /// Index of the object in the scene.
        object: usize,
        /// The object's name.
        name: String,
        /// What is wrong.
        source: ParameterError,
    },
    /// An object's mesh is unusable.
    #[error("object {object} ({name}): {detail}")]
    Mesh {
        /// Index of the object in the scene.
        object: usize,
        /// The object's name.
        name: String,
        /// What is wrong, e.g. "triangle 12 uses vertex 90 of 88".
        detail: String,
    },
    /// An object has a texture (albedo or liquid) but its mesh has no UVs.
    #[error("object {object} ({name}) has a {texture} texture but its mesh has no UVs")]
    MissingUvs {
        /// Index of the object in the scene.
        object: usize,
        /// The object's name.
        name: String,
        /// `"albedo"`, `"liquid"` or `"subsurface"`.
        texture: &'static str,
    },
    /// An image with no pixels, or a liquid texture with a value that is
    /// not finite.
    #[error("object {object} ({name}): {detail}")]
    Texture {
        /// Index of the object in the scene.
        object: usize,
        /// The object's name.
        name: String,
        /// What is wrong.
        detail: String,
    },
    /// A per-face segment id list whose length is not the triangle count.
    #[error("object {object} ({name}): {given} segment ids for {triangles} triangles")]
    SegmentCount {
        /// Index of the object in the scene.
        object: usize,
        /// The object's name.
        name: String,
        /// Ids given.
        given: usize,
        /// Triangles of the mesh.
        triangles: usize,
    },
    /// A camera, light, water or arrow parameter that is not usable.
    #[error("{what}: {detail}")]
    Scene {
        /// The item, e.g. `"camera"`, `"arrow 2"`.
        what: String,
        /// What is wrong.
        detail: String,
    },
}
