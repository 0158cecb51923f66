//! Validation of meshes before baking: geometry, topology and UVs.

use crate::error::{MeshError, MeshProblem};
use crate::mesh::Mesh;
use crate::uv_overlap;

/// Relative area (to the squared bounding diagonal) below which a triangle is degenerate.
pub const DEGENERATE_AREA: f64 = 1e-14;
/// UV area (in the unit square) below which a triangle is degenerate in UV space.
pub const DEGENERATE_UV_AREA: f64 = 1e-14;

fn fail(mesh: &Mesh, problem: MeshProblem) -> MeshError {
    MeshError::new(mesh, problem)
}

/// Non-empty, indices in range, finite positions, no zero-area triangles.
pub fn validate_geometry(mesh: &Mesh) -> Result<(), MeshError> {
    if mesh.triangles.is_empty() {
        return Err(fail(mesh, MeshProblem::Empty));
    }
    let n = mesh.positions.len();
    for (t, tri) in mesh.triangles.iter().enumerate() {
        for &index in tri {
            if index as usize >= n {
                return Err(fail(
                    mesh,
                    MeshProblem::IndexOutOfRange {
                        triangle: t,
                        index,
                        vertex_count: n,
                    },
                ));
            }
        }
    }
    for (vertex, p) in mesh.positions.iter().enumerate() {
        if !(p.x.is_finite() && p.y.is_finite() && p.z.is_finite()) {
            return Err(fail(
                mesh,
                MeshProblem::NonFinitePosition {
                    vertex,
                    position: [p.x, p.y, p.z],
                },
            ));
        }
    }
    let diag = mesh.diagonal();
    let min_area = DEGENERATE_AREA * diag * diag;
    for t in 0..mesh.triangles.len() {
        let area = mesh.triangle_area_vector(t).norm();
        if area <= min_area {
            return Err(fail(mesh, MeshProblem::DegenerateTriangle { triangle: t, area }));
        }
    }
    Ok(())
}

/// Geometry, then: closed (every edge shared by exactly two triangles),
/// manifold, consistently wound and outward facing. Vertices are welded by
/// position first, so seam-split vertices count as one.
pub fn validate_topology(mesh: &Mesh) -> Result<(), MeshError> {
    validate_geometry(mesh)?;
    let remap = mesh.position_remap();
    // (low, high, triangle, forward, original a, original b)
    let mut edges: Vec<(u32, u32, u32, bool, u32, u32)> = Vec::with_capacity(mesh.triangles.len() * 3);
    for (t, tri) in mesh.triangles.iter().enumerate() {
        for k in 0..3 {
            let (oa, ob) = (tri[k], tri[(k + 1) % 3]);
            let (a, b) = (remap[oa as usize], remap[ob as usize]);
            if a == b {
                let area = mesh.triangle_area_vector(t).norm();
                return Err(fail(mesh, MeshProblem::DegenerateTriangle { triangle: t, area }));
            }
            edges.push((a.min(b), a.max(b), t as u32, a < b, oa, ob));
        }
    }
    edges.sort_unstable_by_key(|e| (e.0, e.1, e.2));
    let mut first_error: Option<(u32, MeshProblem)> = None;
    let mut keep = |t: u32, p: MeshProblem| {
        if first_error.as_ref().is_none_or(|(ft, _)| t < *ft) {
            first_error = Some((t, p));
        }
    };
    let mut i = 0;
    while i < edges.len() {
        let mut j = i + 1;
        while j < edges.len() && edges[j].0 == edges[i].0 && edges[j].1 == edges[i].1 {
            j += 1;
        }
        let group = &edges[i..j];
        let e = group[0];
        match group.len() {
            1 => keep(
                e.2,
                MeshProblem::OpenEdge {
                    triangle: e.2 as usize,
                    a: e.4,
                    b: e.5,
                },
            ),
            2 => {
                if group[0].3 == group[1].3 {
                    keep(
                        group[0].2,
                        MeshProblem::InconsistentWinding {
                            triangle: group[0].2 as usize,
                            neighbour: group[1].2 as usize,
                        },
                    );
                }
            }
            count => keep(
                e.2,
                MeshProblem::NonManifoldEdge {
                    a: e.4,
                    b: e.5,
                    count,
                    triangle: e.2 as usize,
                },
            ),
        }
        i = j;
    }
    if let Some((_, problem)) = first_error {
        return Err(fail(mesh, problem));
    }
    let volume = mesh.volume();
    if volume < 0.0 {
        return Err(fail(mesh, MeshProblem::InsideOut { volume }));
    }
    Ok(())
}

/// UVs present, one per vertex, finite, inside [0, 1]², no triangle
/// degenerate in UV space, and no two triangles overlapping (a bijective map).
pub fn validate_uvs(mesh: &Mesh) -> Result<(), MeshError> {
    validate_geometry(mesh)?;
    let Some(uvs) = mesh.uvs.as_ref() else {
        return Err(fail(mesh, MeshProblem::MissingUvs));
    };
    if uvs.len() != mesh.positions.len() {
        return Err(fail(
            mesh,
            MeshProblem::UvCountMismatch {
                uvs: uvs.len(),
                positions: mesh.positions.len(),
            },
        ));
    }
    for (vertex, uv) in uvs.iter().enumerate() {
        if !(uv.x.is_finite() && uv.y.is_finite()) {
            return Err(fail(
                mesh,
                MeshProblem::NonFiniteUv {
                    vertex,
                    uv: [uv.x, uv.y],
                },
            ));
        }
        if !(0.0..=1.0).contains(&uv.x) || !(0.0..=1.0).contains(&uv.y) {
            return Err(fail(
                mesh,
                MeshProblem::UvOutOfRange {
                    vertex,
                    uv: [uv.x, uv.y],
                },
            ));
        }
    }
    let mut tris = Vec::with_capacity(mesh.triangles.len());
    for t in 0..mesh.triangles.len() {
        let [a, b, c] = mesh.triangle_uvs(t).expect("uvs checked above");
        let uv_area = 0.5 * (b - a).perp(&(c - a)).abs();
        if uv_area <= DEGENERATE_UV_AREA {
            return Err(fail(
                mesh,
                MeshProblem::DegenerateUvTriangle { triangle: t, uv_area },
            ));
        }
        tris.push([a, b, c]);
    }
    if let Some((triangle, other)) = uv_overlap::find_overlap(&tris) {
        return Err(fail(mesh, MeshProblem::OverlappingUvs { triangle, other }));
    }
    Ok(())
}

/// Everything baking needs: [`validate_topology`] and [`validate_uvs`].
///
/// Each check returns the first problem found as a [`MeshError`] naming the
/// offending vertex, edge or triangle.
pub fn validate(mesh: &Mesh) -> Result<(), MeshError> {
    validate_topology(mesh)?;
    validate_uvs(mesh)
}
