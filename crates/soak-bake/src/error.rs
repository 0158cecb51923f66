//! Typed errors of mesh loading, validation and baking.

use std::path::PathBuf;

/// What is wrong with a mesh, naming the offending element.
///
/// Indices are zero-based and refer to the mesh as it was given (vertex and
/// triangle order of the file or generator).
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum MeshProblem {
    /// The mesh has no triangles.
    #[error("has no triangles")]
    Empty,
    /// A triangle refers to a vertex that does not exist.
    #[error("triangle {triangle} refers to vertex {index}, but there are only {vertex_count} vertices")]
    IndexOutOfRange {
        /// Triangle index.
        triangle: usize,
        /// The out-of-range vertex index.
        index: u32,
        /// Number of vertices in the mesh.
        vertex_count: usize,
    },
    /// A vertex position is NaN or infinite.
    #[error("vertex {vertex} has a non-finite position {position:?}")]
    NonFinitePosition {
        /// Vertex index.
        vertex: usize,
        /// The offending position.
        position: [f64; 3],
    },
    /// A texture coordinate is NaN or infinite.
    #[error("vertex {vertex} has a non-finite UV {uv:?}")]
    NonFiniteUv {
        /// Vertex index.
        vertex: usize,
        /// The offending UV.
        uv: [f64; 2],
    },
    /// Baking needs texture coordinates and the mesh has none.
    #[error("has no UVs (unwrap it to generate a physics atlas)")]
    MissingUvs,
    /// The UV array does not have one entry per vertex.
    #[error("has {uvs} UVs for {positions} vertices")]
    UvCountMismatch {
        /// Number of UVs.
        uvs: usize,
        /// Number of positions.
        positions: usize,
    },
    /// A texture coordinate lies outside the unit square, so the map is not
    /// a bijection into one texture.
    #[error("vertex {vertex} has UV {uv:?} outside [0, 1]² (unwrap it to generate a physics atlas)")]
    UvOutOfRange {
        /// Vertex index.
        vertex: usize,
        /// The offending UV.
        uv: [f64; 2],
    },
    /// A triangle has (numerically) zero area in 3-D.
    #[error("triangle {triangle} is degenerate: its area {area:.3e} m² is zero relative to the mesh size")]
    DegenerateTriangle {
        /// Triangle index.
        triangle: usize,
        /// Its area in m².
        area: f64,
    },
    /// A triangle has zero area in UV space.
    #[error("triangle {triangle} is degenerate in UV space (UV area {uv_area:.3e})")]
    DegenerateUvTriangle {
        /// Triangle index.
        triangle: usize,
        /// Its UV-space area.
        uv_area: f64,
    },
    /// An edge belongs to one triangle only: the mesh is not closed.
    #[error(
        "triangle {triangle} has an open edge between vertices {a} and {b} (the mesh is not closed; an open container is read with `--open`, or `open = true` on a scene body, which caps its rims)"
    )]
    OpenEdge {
        /// Triangle index.
        triangle: usize,
        /// First vertex of the edge.
        a: u32,
        /// Second vertex of the edge.
        b: u32,
    },
    /// Two rims (boundary loops) of an open mesh touch at a vertex, so the
    /// rim through it cannot be followed.
    #[error("two rims meet at vertex {vertex}: the open mesh's boundary is not manifold there")]
    RimNotManifold {
        /// The vertex where the rims meet.
        vertex: u32,
    },
    /// A rim of an open mesh cannot be capped.
    #[error("rim {rim} cannot be capped: it {reason}")]
    RimNotCappable {
        /// The rim, in the order [`crate::boundary_loops`] gives them.
        rim: usize,
        /// Why.
        reason: String,
    },
    /// An edge is shared by more than two triangles.
    #[error(
        "edge between vertices {a} and {b} is shared by {count} triangles (non-manifold), first triangle {triangle}"
    )]
    NonManifoldEdge {
        /// First vertex of the edge.
        a: u32,
        /// Second vertex of the edge.
        b: u32,
        /// How many triangles share it.
        count: usize,
        /// One of the triangles.
        triangle: usize,
    },
    /// Two triangles sharing an edge traverse it in the same direction.
    #[error("triangles {triangle} and {neighbour} have inconsistent winding across their shared edge")]
    InconsistentWinding {
        /// Triangle index.
        triangle: usize,
        /// The neighbour with the opposite orientation.
        neighbour: usize,
    },
    /// The mesh is consistently wound but its normals point inwards.
    #[error("is inside out: its signed volume is {volume:.3e} m³ (flip the winding)")]
    InsideOut {
        /// The signed volume in m³.
        volume: f64,
    },
    /// Two triangles overlap in UV space: the map is not bijective.
    #[error(
        "triangle {triangle} has overlapping UVs with triangle {other} (unwrap it to generate a physics atlas)"
    )]
    OverlappingUvs {
        /// Triangle index.
        triangle: usize,
        /// The triangle it overlaps.
        other: usize,
    },
}

/// A mesh failed validation. The message names the mesh and the element:
/// in the file's own terms (its lines and vertex numbers) when the mesh was
/// read from an OBJ file, in the mesh's indices otherwise.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("mesh `{mesh}` {}", in_file.as_deref().map_or_else(|| problem.to_string(), str::to_owned))]
pub struct MeshError {
    /// The mesh's name (file name or builtin name).
    pub mesh: String,
    /// What is wrong with it, in the mesh's (zero-based) indices.
    pub problem: MeshProblem,
    /// The same problem in the file's terms (`the face on line 13 has an
    /// open edge between vertices 5 and 6`), when the mesh carries its
    /// file's numbering ([`Mesh::source`](crate::Mesh::source)) and the
    /// problem names its elements.
    pub in_file: Option<String>,
}

impl MeshError {
    /// The error for `problem` found in `mesh`, told in the file's terms
    /// where the mesh carries its file's numbering.
    pub fn new(mesh: &crate::Mesh, problem: MeshProblem) -> Self {
        let in_file = mesh.source.as_ref().and_then(|s| in_file_terms(s, &problem));
        Self {
            mesh: mesh.name.clone(),
            problem,
            in_file,
        }
    }
}

const OPEN_HINT: &str =
    "an open container is read with `--open`, or `open = true` on a scene body, which caps its rims";

/// `problem` in the file's lines and vertex numbers; `None` where it names
/// nothing the file numbers (or something soak made, such as a cap).
fn in_file_terms(source: &crate::SourceNumbering, problem: &MeshProblem) -> Option<String> {
    let v = |i: u32| source.vertex(i);
    let line = |t: usize| source.face_line(t);
    Some(match *problem {
        MeshProblem::OpenEdge { triangle, a, b } => format!(
            "the face on line {} has an open edge between vertices {} and {} (the file's numbering): the mesh is not closed; {OPEN_HINT}",
            line(triangle)?,
            v(a)?,
            v(b)?
        ),
        MeshProblem::NonManifoldEdge {
            a,
            b,
            count,
            triangle,
        } => format!(
            "the edge between vertices {} and {} (the file's numbering) is shared by {count} triangles (non-manifold), the first from the face on line {}",
            v(a)?,
            v(b)?,
            line(triangle)?
        ),
        MeshProblem::InconsistentWinding { triangle, neighbour } => format!(
            "the faces on lines {} and {} have inconsistent winding across their shared edge",
            line(triangle)?,
            line(neighbour)?
        ),
        MeshProblem::DegenerateTriangle { triangle, area } => format!(
            "the face on line {} is degenerate: its area {area:.3e} m² is zero relative to the mesh size",
            line(triangle)?
        ),
        MeshProblem::OverlappingUvs { triangle, other } => format!(
            "the faces on lines {} and {} have overlapping UVs (unwrap it to generate a physics atlas)",
            line(triangle)?,
            line(other)?
        ),
        MeshProblem::RimNotManifold { vertex } => format!(
            "two rims meet at vertex {} (the file's numbering): the open mesh's boundary is not manifold there",
            v(vertex)?
        ),
        _ => return None,
    })
}

/// Loading a mesh from a file or a `builtin:` name failed.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum LoadError {
    /// The file could not be read.
    #[error("cannot read `{path}`: {source}")]
    Io {
        /// The file.
        path: PathBuf,
        /// The I/O error.
        source: std::io::Error,
    },
    /// The file extension names no format soak reads.
    #[error("`{path}`: unknown mesh format (expected .obj, .gltf or .glb, or a builtin: name)")]
    UnknownFormat {
        /// The file.
        path: PathBuf,
    },
    /// The OBJ parser rejected the file.
    #[error("`{path}`: invalid OBJ: {reason}")]
    Obj {
        /// The file.
        path: PathBuf,
        /// What the parser reported.
        reason: String,
    },
    /// The glTF importer rejected the file or one of its buffers.
    #[error("`{path}`: invalid glTF: {reason}")]
    Gltf {
        /// The file.
        path: PathBuf,
        /// What the importer reported.
        reason: String,
    },
    /// A glTF primitive lacks positions or uses a mode other than triangles.
    #[error("`{path}`: mesh {mesh} primitive {primitive}: {reason}")]
    GltfPrimitive {
        /// The file.
        path: PathBuf,
        /// glTF mesh index.
        mesh: usize,
        /// Primitive index within the mesh.
        primitive: usize,
        /// What is missing.
        reason: String,
    },
    /// The loaded mesh is not valid.
    #[error("`{path}`: {source}")]
    Mesh {
        /// The file.
        path: PathBuf,
        /// The validation error.
        source: Box<MeshError>,
    },
    /// A `builtin:` name could not be parsed.
    #[error("builtin mesh `{name}`: {reason}")]
    Builtin {
        /// The full name as given.
        name: String,
        /// What is wrong with it.
        reason: String,
    },
}

/// Baking an atlas failed.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum BakeError {
    /// Width or height is zero.
    #[error("resolution {width}x{height} has a zero side")]
    ZeroResolution {
        /// Requested width in texels.
        width: u32,
        /// Requested height in texels.
        height: u32,
    },
    /// Width or height exceeds [`crate::MAX_RESOLUTION`].
    #[error("resolution {width}x{height} exceeds the maximum of {max}x{max} texels")]
    ResolutionTooLarge {
        /// Requested width in texels.
        width: u32,
        /// Requested height in texels.
        height: u32,
        /// The maximum side.
        max: u32,
    },
    /// The tile size is zero or larger than 256.
    #[error("tile size {0} is outside 1..=256")]
    TileSize(u32),
    /// The mesh is not valid for baking.
    #[error(transparent)]
    Mesh(#[from] MeshError),
    /// A refresh was given a different number of vertices than the atlas was baked from.
    #[error("refresh with {given} vertices, but the atlas was baked from {expected}")]
    VertexCountMismatch {
        /// Vertices given.
        given: usize,
        /// Vertices the atlas was baked from.
        expected: usize,
    },
    /// A refresh was given a non-finite vertex position.
    #[error("refresh: vertex {vertex} has a non-finite position")]
    NonFiniteRefresh {
        /// The vertex.
        vertex: usize,
    },
    /// A coarsening factor of zero or more than 256 texels.
    #[error("coarsening factor {factor} is outside 1..=256")]
    Coarsening {
        /// The factor asked for.
        factor: u32,
    },
    /// A refresh of a coarsened atlas, whose samples are not on single
    /// triangles: refresh the baked atlas and coarsen it again.
    #[error("refresh of an atlas coarsened by {factor}: refresh the baked atlas and coarsen it again")]
    CoarsenedRefresh {
        /// The atlas' coarsening factor.
        factor: u32,
    },
}

/// Writing an atlas image failed.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum ExportError {
    /// The image encoder or the file system failed.
    #[error("cannot write `{path}`: {source}")]
    Image {
        /// The file.
        path: PathBuf,
        /// The encoder error.
        source: image::ImageError,
    },
    /// The file extension is neither .png nor .exr.
    #[error("`{path}`: unknown image format (expected .png or .exr)")]
    UnknownFormat {
        /// The file.
        path: PathBuf,
    },
}
