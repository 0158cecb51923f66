//! Face adjacency of a closed mesh: shared edges, their dihedral angles, and
//! the faces around each vertex.
//!
//! Vertices are welded by position ([`Mesh::welded_triangles`]) so UV seams
//! do not cut the adjacency. The mesh must have passed
//! [`soak_bake::validate_topology`]: every welded edge is shared by
//! exactly two triangles with opposite orientations.

use nalgebra::{Point3, Vector3};
use soak_bake::Mesh;

/// An edge shared by two faces.
#[derive(Clone, Copy, Debug)]
pub(crate) struct SharedEdge {
    /// The two faces on either side.
    pub faces: [u32; 2],
    /// Length of the edge, m.
    pub length: f64,
    /// Angle between the two face normals, degrees in [0, 180]: 0 where the
    /// surface is flat across the edge.
    pub normal_angle: f64,
    /// Whether the surface folds outwards across the edge (a valley).
    pub concave: bool,
}

/// Adjacency tables of a closed, validated mesh.
#[derive(Clone, Debug)]
pub(crate) struct Topology {
    /// Unit outward normal of each face.
    pub normals: Vec<Vector3<f64>>,
    /// Centroid of each face, m.
    pub centroids: Vec<Point3<f64>>,
    /// Area of each face, m².
    pub areas: Vec<f64>,
    /// Triangles with welded vertex indices.
    pub welded: Vec<[u32; 3]>,
    /// Every shared edge once, sorted by welded vertex pair.
    pub edges: Vec<SharedEdge>,
    /// The (up to three) shared-edge neighbours of each face, CSR offsets.
    neighbour_offsets: Vec<u32>,
    neighbours: Vec<u32>,
    /// The faces around each welded vertex, CSR offsets (indexed by welded id).
    vertex_face_offsets: Vec<u32>,
    vertex_faces: Vec<u32>,
}

impl Topology {
    /// Builds the tables. The mesh must be closed and manifold (validated).
    pub fn new(mesh: &Mesh) -> Self {
        let welded = mesh.welded_triangles();
        let n_faces = welded.len();
        let mut normals = Vec::with_capacity(n_faces);
        let mut centroids = Vec::with_capacity(n_faces);
        let mut areas = Vec::with_capacity(n_faces);
        for t in 0..n_faces {
            let av = mesh.triangle_area_vector(t);
            let area = av.norm();
            normals.push(if area > 0.0 { av / area } else { Vector3::zeros() });
            areas.push(area);
            let [a, b, c] = mesh.triangle_points(t);
            centroids.push(Point3::from((a.coords + b.coords + c.coords) / 3.0));
        }

        // (low, high, face) for every half-edge, grouped by vertex pair.
        let mut half: Vec<(u32, u32, u32)> = Vec::with_capacity(3 * n_faces);
        for (f, tri) in welded.iter().enumerate() {
            for k in 0..3 {
                let (a, b) = (tri[k], tri[(k + 1) % 3]);
                half.push((a.min(b), a.max(b), f as u32));
            }
        }
        half.sort_unstable();
        let mut edges = Vec::with_capacity(half.len() / 2);
        let mut i = 0;
        while i < half.len() {
            let mut j = i + 1;
            while j < half.len() && half[j].0 == half[i].0 && half[j].1 == half[i].1 {
                j += 1;
            }
            // A validated mesh has exactly two faces per edge; anything else
            // is skipped rather than trusted.
            if j - i == 2 {
                let (va, vb) = (half[i].0, half[i].1);
                let (f1, f2) = (half[i].2, half[i + 1].2);
                let pa = mesh.positions[va as usize];
                let pb = mesh.positions[vb as usize];
                let (n1, n2) = (normals[f1 as usize], normals[f2 as usize]);
                let cos = n1.dot(&n2).clamp(-1.0, 1.0);
                // The vertex of f1 not on the edge, tested against f2's plane.
                let opposite = welded[f1 as usize]
                    .into_iter()
                    .find(|&v| v != va && v != vb)
                    .unwrap_or(va);
                let po = mesh.positions[opposite as usize];
                let concave = (po - pa).dot(&n2) > 0.0;
                edges.push(SharedEdge {
                    faces: [f1, f2],
                    length: (pb - pa).norm(),
                    normal_angle: cos.acos().to_degrees(),
                    concave,
                });
            }
            i = j;
        }

        let mut degree = vec![0u32; n_faces + 1];
        for e in &edges {
            degree[e.faces[0] as usize + 1] += 1;
            degree[e.faces[1] as usize + 1] += 1;
        }
        for f in 0..n_faces {
            degree[f + 1] += degree[f];
        }
        let neighbour_offsets = degree;
        let mut fill = neighbour_offsets.clone();
        let mut neighbours = vec![0u32; *neighbour_offsets.last().unwrap_or(&0) as usize];
        for e in &edges {
            let [a, b] = e.faces;
            neighbours[fill[a as usize] as usize] = b;
            fill[a as usize] += 1;
            neighbours[fill[b as usize] as usize] = a;
            fill[b as usize] += 1;
        }

        let n_vertices = mesh.positions.len();
        let mut vdeg = vec![0u32; n_vertices + 1];
        for tri in &welded {
            for &v in tri {
                vdeg[v as usize + 1] += 1;
            }
        }
        for v in 0..n_vertices {
            vdeg[v + 1] += vdeg[v];
        }
        let vertex_face_offsets = vdeg;
        let mut vfill = vertex_face_offsets.clone();
        let mut vertex_faces = vec![0u32; 3 * n_faces];
        for (f, tri) in welded.iter().enumerate() {
            for &v in tri {
                vertex_faces[vfill[v as usize] as usize] = f as u32;
                vfill[v as usize] += 1;
            }
        }

        Self {
            normals,
            centroids,
            areas,
            welded,
            edges,
            neighbour_offsets,
            neighbours,
            vertex_face_offsets,
            vertex_faces,
        }
    }

    /// Number of faces.
    pub fn face_count(&self) -> usize {
        self.welded.len()
    }

    /// The faces sharing an edge with face `f`.
    pub fn neighbours(&self, f: usize) -> &[u32] {
        let (a, b) = (self.neighbour_offsets[f], self.neighbour_offsets[f + 1]);
        &self.neighbours[a as usize..b as usize]
    }

    /// The faces around welded vertex `v`.
    pub fn faces_around(&self, v: u32) -> &[u32] {
        let (a, b) = (
            self.vertex_face_offsets[v as usize],
            self.vertex_face_offsets[v as usize + 1],
        );
        &self.vertex_faces[a as usize..b as usize]
    }
}
