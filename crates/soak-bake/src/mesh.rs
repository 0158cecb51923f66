//! The triangle mesh that goes into baking.

use nalgebra::{Point2, Point3, Vector3};
use serde::{Deserialize, Serialize};

/// A triangle mesh with optional per-vertex texture coordinates.
///
/// Positions are in object space, in metres; triangles wind counter-clockwise
/// seen from outside (outward normals). Vertices may be split along UV seams:
/// topology checks weld them by position.
#[derive(Clone, Debug, PartialEq)]
pub struct Mesh {
    /// A name for messages: a file name or a `builtin:` name.
    pub name: String,
    /// Vertex positions in object space, m.
    pub positions: Vec<Point3<f64>>,
    /// Texture coordinates in [0, 1]², one per vertex, if the mesh has them.
    pub uvs: Option<Vec<Point2<f64>>>,
    /// Triangles as triples of vertex indices.
    pub triangles: Vec<[u32; 3]>,
    /// The caps [`crate::cap_openings`] closed this mesh's rims with, in the
    /// order of their triangles (which come after the mesh's own); empty for
    /// a mesh that was closed to begin with.
    pub openings: Vec<Opening>,
    /// How the file this mesh was read from numbers its vertices and faces,
    /// so that errors name them as the file does; `None` for a mesh made in
    /// code (and for glTF, whose accessors have no lines).
    pub source: Option<SourceNumbering>,
}

/// The numbering of the file a mesh was read from (Wavefront OBJ).
///
/// The loader renumbers vertices (one per distinct `v/vt/vn` corner) and
/// unwrapping splits them again along seams; these tables take a vertex or
/// triangle of the mesh back to the file's own terms. A number of 0 marks a
/// vertex or triangle soak made (a cap's).
#[derive(Clone, Debug, PartialEq, Default)]
pub struct SourceNumbering {
    /// For each vertex: the file's number of the vertex at its position,
    /// 1-based as the file's faces count them (the first `v` line at that
    /// position, if several share it).
    pub vertices: Vec<u32>,
    /// For each triangle: the line of the face it came from, 1-based (a
    /// polygon of `n` corners gives `n − 2` triangles, all on its line).
    pub face_lines: Vec<u32>,
}

impl SourceNumbering {
    /// The file's number of vertex `v`, if it came from the file.
    pub fn vertex(&self, v: u32) -> Option<u32> {
        self.vertices.get(v as usize).copied().filter(|&n| n > 0)
    }

    /// The file's line of the face triangle `t` came from, if it did.
    pub fn face_line(&self, t: usize) -> Option<u32> {
        self.face_lines.get(t).copied().filter(|&n| n > 0)
    }
}

impl Mesh {
    /// A mesh from its parts.
    pub fn new(
        name: impl Into<String>,
        positions: Vec<Point3<f64>>,
        uvs: Option<Vec<Point2<f64>>>,
        triangles: Vec<[u32; 3]>,
    ) -> Self {
        Self {
            name: name.into(),
            positions,
            uvs,
            triangles,
            openings: Vec::new(),
            source: None,
        }
    }

    /// The first cap triangle (all triangles from it on close openings), if
    /// the mesh has openings.
    pub fn first_opening_triangle(&self) -> Option<u32> {
        self.openings.iter().map(|o| o.first_triangle).min()
    }

    /// The three corner positions of triangle `t`.
    ///
    /// # Panics
    /// If `t` or its vertex indices are out of range (validate first).
    #[inline]
    pub fn triangle_points(&self, t: usize) -> [Point3<f64>; 3] {
        let [a, b, c] = self.triangles[t];
        [
            self.positions[a as usize],
            self.positions[b as usize],
            self.positions[c as usize],
        ]
    }

    /// The three corner UVs of triangle `t`, if the mesh has UVs.
    #[inline]
    pub fn triangle_uvs(&self, t: usize) -> Option<[Point2<f64>; 3]> {
        let uvs = self.uvs.as_ref()?;
        let [a, b, c] = self.triangles[t];
        Some([uvs[a as usize], uvs[b as usize], uvs[c as usize]])
    }

    /// Area vector of triangle `t`: area (m²) times the unit face normal.
    #[inline]
    pub fn triangle_area_vector(&self, t: usize) -> Vector3<f64> {
        let [a, b, c] = self.triangle_points(t);
        0.5 * (b - a).cross(&(c - a))
    }

    /// Total surface area, m².
    pub fn area(&self) -> f64 {
        (0..self.triangles.len())
            .map(|t| self.triangle_area_vector(t).norm())
            .sum()
    }

    /// Axis-aligned bounding box `(min, max)` of the vertices, m.
    /// Both are the origin for a mesh without vertices.
    pub fn bounds(&self) -> (Point3<f64>, Point3<f64>) {
        let mut it = self.positions.iter();
        let Some(first) = it.next() else {
            return (Point3::origin(), Point3::origin());
        };
        let (mut lo, mut hi) = (*first, *first);
        for p in it {
            lo = lo.inf(p);
            hi = hi.sup(p);
        }
        (lo, hi)
    }

    /// Length of the bounding-box diagonal, m.
    pub fn diagonal(&self) -> f64 {
        let (lo, hi) = self.bounds();
        (hi - lo).norm()
    }

    /// Exact signed volume enclosed by the (closed, outward-wound) mesh, m³,
    /// by summing signed tetrahedra against the bounding-box centre.
    pub fn volume(&self) -> f64 {
        let (lo, hi) = self.bounds();
        let o = nalgebra::center(&lo, &hi);
        (0..self.triangles.len())
            .map(|t| {
                let [a, b, c] = self.triangle_points(t);
                (a - o).dot(&(b - o).cross(&(c - o)))
            })
            .sum::<f64>()
            / 6.0
    }

    /// Sum of the triangle area vectors, m²; zero for a closed mesh.
    pub fn area_vector_sum(&self) -> Vector3<f64> {
        (0..self.triangles.len())
            .map(|t| self.triangle_area_vector(t))
            .sum()
    }

    /// The same mesh with every triangle's winding reversed.
    pub fn flipped(mut self) -> Self {
        for t in &mut self.triangles {
            t.swap(1, 2);
        }
        self
    }

    /// The same mesh without texture coordinates.
    pub fn without_uvs(mut self) -> Self {
        self.uvs = None;
        self
    }

    /// The same mesh with every position mapped by `f` (UVs and topology kept).
    pub fn map_positions(mut self, f: impl Fn(Point3<f64>) -> Point3<f64>) -> Self {
        for p in &mut self.positions {
            *p = f(*p);
        }
        self
    }

    /// For every vertex, the index of the first vertex at the same position
    /// (f32 precision), so seam-split vertices are welded for topology checks.
    pub fn position_remap(&self) -> Vec<u32> {
        let ps: Vec<[f32; 3]> = self
            .positions
            .iter()
            .map(|p| [p.x as f32, p.y as f32, p.z as f32])
            .collect();
        meshopt::generate_position_remap_decoder(&ps)
    }

    /// The same shape in about `target` triangles (at least 4), for work
    /// whose cost grows with the triangle count faster than its accuracy
    /// does (a panel method): seams welded by position, then simplified by
    /// edge collapse (meshoptimizer's quadric simplifier) with a deviation of
    /// at most a twentieth of the mesh's extent. No UVs; the caps of an
    /// open mesh become ordinary triangles. A mesh already that small is
    /// returned as it is (welded).
    pub fn simplified(&self, target: usize) -> Mesh {
        self.simplified_within(target, 0.05)
    }

    /// [`Mesh::simplified`] with a deviation of at most `deviation` times
    /// the mesh's extent: the simplifier stops short of `target` rather
    /// than deviate further.
    pub fn simplified_within(&self, target: usize, deviation: f32) -> Mesh {
        let indices: Vec<u32> = self.welded_triangles().into_iter().flatten().collect();
        let ps: Vec<[f32; 3]> = self
            .positions
            .iter()
            .map(|p| [p.x as f32, p.y as f32, p.z as f32])
            .collect();
        let kept = match meshopt::VertexDataAdapter::new(meshopt::typed_to_bytes(&ps), 12, 0) {
            Ok(adapter) if self.triangles.len() > target => meshopt::simplify(
                &indices,
                &adapter,
                3 * target.max(4),
                deviation,
                meshopt::SimplifyOptions::None,
                None,
            ),
            _ => indices,
        };
        Mesh {
            name: self.name.clone(),
            positions: self.positions.clone(),
            uvs: None,
            triangles: kept.chunks_exact(3).map(|t| [t[0], t[1], t[2]]).collect(),
            openings: Vec::new(),
            source: None,
        }
    }

    /// Triangles with vertex indices welded by position (see [`Mesh::position_remap`]).
    pub fn welded_triangles(&self) -> Vec<[u32; 3]> {
        let remap = self.position_remap();
        self.triangles
            .iter()
            .map(|t| t.map(|v| remap[v as usize]))
            .collect()
    }
}

/// One capped rim of an open mesh.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Opening {
    /// The rim's vertices in order (indices of the input mesh), the loop the
    /// mesh's own boundary edges run along.
    pub rim: Vec<u32>,
    /// The cap's first triangle in the capped mesh.
    pub first_triangle: u32,
    /// Number of cap triangles.
    pub triangles: u32,
    /// The cap's area, m².
    pub area: f64,
    /// The cap's centroid, object space, m.
    pub centroid: [f64; 3],
    /// The cap's outward unit normal (out of the closed shape).
    pub normal: [f64; 3],
    /// The rim's length, m.
    pub length: f64,
    /// Largest distance of a rim vertex from the cap's plane, m (0 for a
    /// planar rim).
    pub warp: f64,
}
