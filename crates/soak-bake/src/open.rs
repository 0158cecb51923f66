//! Open meshes: their rims found and capped, so an open container (a
//! bucket, a rowing boat, a single-sided hull) bakes as the closed shape
//! whose caps are where water gets in.
//!
//! A **rim** is a loop of edges that belong to one triangle only (the mesh's
//! boundary). [`cap_openings`] finds every rim, closes each with a
//! triangulated **cap** (ear clipping in the rim's best-fit plane, wound so
//! the cap faces out of the closed shape) and appends the caps' triangles
//! after the mesh's own: triangle `t < first cap` of the result is triangle
//! `t` of the input. The result is a closed mesh that bakes like any other;
//! its [`Mesh::openings`] name the caps, and the atlas keeps which texels
//! are caps ([`crate::Atlas::is_opening`]) so mass models can leave them
//! out and the liquid graph can let water through them.
//!
//! UVs: the input's UV square is kept as one chart, scaled with the caps'
//! charts (each cap projected onto its plane) to one texel density and
//! packed beside them; a mesh without UVs gets caps without UVs (unwrap the
//! result, [`crate::unwrap`], which keeps triangle order).

use nalgebra::{Point2, Point3, Vector3};

use crate::error::{MeshError, MeshProblem};
use crate::mesh::{Mesh, Opening, SourceNumbering};
use crate::pack::{DEFAULT_PADDING, pack_charts};
use crate::validate::{validate_geometry, validate_topology};

/// The boundary loops of `mesh` (vertices welded by position), each as the
/// vertex indices of the input in the direction its triangles run along it.
/// A closed mesh has none.
///
/// # Errors
/// Geometry errors ([`validate_geometry`]); [`MeshProblem::RimNotManifold`]
/// where two rims touch at a vertex (an edge is used once more than once
/// around it).
pub fn boundary_loops(mesh: &Mesh) -> Result<Vec<Vec<u32>>, MeshError> {
    validate_geometry(mesh)?;
    let remap = mesh.position_remap();
    let welded = mesh.welded_triangles();
    // Directed edges; an edge is a boundary edge when its reverse is absent and
    // it is used once.
    let mut directed: Vec<(u32, u32)> = Vec::with_capacity(welded.len() * 3);
    for t in &welded {
        for k in 0..3 {
            directed.push((t[k], t[(k + 1) % 3]));
        }
    }
    let mut undirected: Vec<(u32, u32)> = directed.iter().map(|&(a, b)| (a.min(b), a.max(b))).collect();
    undirected.sort_unstable();
    let count = |a: u32, b: u32| {
        let key = (a.min(b), a.max(b));
        let lo = undirected.partition_point(|e| *e < key);
        let hi = undirected.partition_point(|e| *e <= key);
        hi - lo
    };
    let mut next: std::collections::BTreeMap<u32, u32> = std::collections::BTreeMap::new();
    for &(a, b) in &directed {
        if count(a, b) == 1 && next.insert(a, b).is_some() {
            return Err(MeshError::new(mesh, MeshProblem::RimNotManifold { vertex: a }));
        }
    }
    let mut loops = Vec::new();
    let mut seen = std::collections::BTreeSet::new();
    let starts: Vec<u32> = next.keys().copied().collect();
    for start in starts {
        if seen.contains(&start) {
            continue;
        }
        let mut rim = vec![start];
        seen.insert(start);
        let mut v = start;
        loop {
            let Some(&w) = next.get(&v) else {
                return Err(MeshError::new(mesh, MeshProblem::RimNotManifold { vertex: v }));
            };
            if w == start {
                break;
            }
            if !seen.insert(w) {
                return Err(MeshError::new(mesh, MeshProblem::RimNotManifold { vertex: w }));
            }
            rim.push(w);
            v = w;
        }
        loops.push(rim);
    }
    // Welded ids are the first vertex of each position: indices of the input.
    debug_assert!(loops.iter().flatten().all(|&v| remap[v as usize] == v));
    Ok(loops)
}

/// Newell's normal of a polygon (area-weighted, not normalised: twice the
/// area vector).
fn newell(points: &[Point3<f64>]) -> Vector3<f64> {
    let mut n = Vector3::zeros();
    for (i, p) in points.iter().enumerate() {
        let q = points[(i + 1) % points.len()];
        n += p.coords.cross(&q.coords);
    }
    n
}

fn cross2(o: Point2<f64>, a: Point2<f64>, b: Point2<f64>) -> f64 {
    (a.x - o.x) * (b.y - o.y) - (a.y - o.y) * (b.x - o.x)
}

/// Whether segments `ab` and `cd` cross (proper intersection or touching at
/// a point that is not a shared endpoint).
fn segments_cross(a: Point2<f64>, b: Point2<f64>, c: Point2<f64>, d: Point2<f64>) -> bool {
    let (d1, d2) = (cross2(a, b, c), cross2(a, b, d));
    let (d3, d4) = (cross2(c, d, a), cross2(c, d, b));
    (d1 * d2 < 0.0) && (d3 * d4 < 0.0)
}

/// Triangulates a simple counter-clockwise polygon by ear clipping (the
/// ear with the best-shaped triangle first), as corner indices; `None` when
/// no ear can be found (the polygon is not simple, or degenerate).
///
/// # Example
/// ```
/// use nalgebra::Point2;
/// let square = [(0.0, 0.0), (1.0, 0.0), (1.0, 1.0), (0.0, 1.0)].map(|(x, y)| Point2::new(x, y));
/// assert_eq!(soak_bake::triangulate(&square).map(|t| t.len()), Some(2));
/// ```
pub fn triangulate(poly: &[Point2<f64>]) -> Option<Vec<[usize; 3]>> {
    ear_clip(poly)
}

fn ear_clip(poly: &[Point2<f64>]) -> Option<Vec<[usize; 3]>> {
    let mut idx: Vec<usize> = (0..poly.len()).collect();
    let mut out = Vec::with_capacity(poly.len().saturating_sub(2));
    let scale = poly
        .iter()
        .map(|p| p.coords.norm())
        .fold(0.0, f64::max)
        .max(f64::MIN_POSITIVE);
    let eps = 1e-12 * scale * scale;
    while idx.len() > 3 {
        let n = idx.len();
        let mut clipped = false;
        // The ear with the largest smallest angle keeps slivers out of caps;
        // a first convex ear is enough for correctness.
        let mut best: Option<(usize, f64)> = None;
        for i in 0..n {
            let (ia, ib, ic) = (idx[(i + n - 1) % n], idx[i], idx[(i + 1) % n]);
            let (a, b, c) = (poly[ia], poly[ib], poly[ic]);
            let area = cross2(a, b, c);
            if area <= eps {
                continue;
            }
            let blocked = idx.iter().any(|&j| {
                if j == ia || j == ib || j == ic {
                    return false;
                }
                let p = poly[j];
                cross2(a, b, p) >= 0.0 && cross2(b, c, p) >= 0.0 && cross2(c, a, p) >= 0.0
            });
            if blocked {
                continue;
            }
            let (ab, bc, ca) = ((b - a).norm(), (c - b).norm(), (a - c).norm());
            let quality = area / (ab * ab + bc * bc + ca * ca).max(f64::MIN_POSITIVE);
            if best.is_none_or(|(_, q)| quality > q) {
                best = Some((i, quality));
            }
        }
        if let Some((i, _)) = best {
            let (ia, ib, ic) = (idx[(i + n - 1) % n], idx[i], idx[(i + 1) % n]);
            out.push([ia, ib, ic]);
            idx.remove(i);
            clipped = true;
        }
        if !clipped {
            return None;
        }
    }
    if idx.len() == 3 {
        let (a, b, c) = (poly[idx[0]], poly[idx[1]], poly[idx[2]]);
        if cross2(a, b, c) <= eps {
            return None;
        }
        out.push([idx[0], idx[1], idx[2]]);
    }
    Some(out)
}

/// Closes every rim of an open mesh with a cap (module docs). A closed mesh
/// comes back unchanged, with no openings.
///
/// # Errors
/// Geometry errors; [`MeshProblem::RimNotManifold`] (two rims share a
/// vertex); [`MeshProblem::RimNotCappable`] naming the rim and why (it
/// crosses itself seen along its normal, it is degenerate); and, on the
/// capped mesh, the closed-mesh checks of [`validate_topology`] (a
/// non-manifold edge or inconsistent winding elsewhere in the mesh).
///
/// # Example
/// ```
/// use soak_bake::{Atlas, BakeOptions, builtin, cap_openings};
/// let open = builtin::open_box(1.0, 0.5, 1.0);
/// let closed = cap_openings(&open)?;
/// assert_eq!(closed.openings.len(), 1);
/// let atlas = Atlas::bake(&closed, BakeOptions::square(128))?;
/// assert!((atlas.volume() - 0.5).abs() < 1e-3); // the air in it displaces water
/// # Ok::<(), soak_bake::BakeError>(())
/// ```
pub fn cap_openings(mesh: &Mesh) -> Result<Mesh, MeshError> {
    let loops = boundary_loops(mesh)?;
    if loops.is_empty() {
        validate_topology(mesh)?;
        return Ok(mesh.clone());
    }
    let fail = |problem| MeshError::new(mesh, problem);
    let mut positions = mesh.positions.clone();
    let mut triangles = mesh.triangles.clone();
    let mut openings = Vec::with_capacity(loops.len());
    // Per cap vertex: its position in the cap's plane (m) and its cap.
    let mut cap_coords: Vec<Point2<f64>> = Vec::new();
    let mut cap_chart: Vec<u32> = Vec::new();
    for (r, rim) in loops.iter().enumerate() {
        if rim.len() < 3 {
            return Err(fail(MeshProblem::RimNotCappable {
                rim: r,
                reason: format!("has {} vertices", rim.len()),
            }));
        }
        // The cap runs the rim backwards so each rim edge a→b of the mesh is
        // b→a in the cap: the closed mesh stays consistently wound.
        let cap: Vec<u32> = rim.iter().rev().copied().collect();
        let pts: Vec<Point3<f64>> = cap.iter().map(|&v| mesh.positions[v as usize]).collect();
        let n2 = newell(&pts);
        let len = n2.norm();
        if !(len > 0.0 && len.is_finite()) {
            return Err(fail(MeshProblem::RimNotCappable {
                rim: r,
                reason: "encloses no area (all its vertices on one line)".into(),
            }));
        }
        let normal = n2 / len;
        let centre = Point3::from(pts.iter().map(|p| p.coords).sum::<Vector3<f64>>() / pts.len() as f64);
        let warp = pts
            .iter()
            .map(|p| (p - centre).dot(&normal).abs())
            .fold(0.0, f64::max);
        // A frame of the cap's plane, counter-clockwise about the normal.
        let helper = if normal.x.abs() < 0.9 {
            Vector3::x()
        } else {
            Vector3::y()
        };
        let e1 = normal.cross(&helper).normalize();
        let e2 = normal.cross(&e1);
        let flat: Vec<Point2<f64>> = pts
            .iter()
            .map(|p| Point2::new((p - centre).dot(&e1), (p - centre).dot(&e2)))
            .collect();
        let m = flat.len();
        for i in 0..m {
            for j in i + 1..m {
                if j == i + 1 || (i == 0 && j == m - 1) {
                    continue;
                }
                if segments_cross(flat[i], flat[(i + 1) % m], flat[j], flat[(j + 1) % m]) {
                    return Err(fail(MeshProblem::RimNotCappable {
                        rim: r,
                        reason: format!(
                            "crosses itself seen along its normal (edges from rim vertices {} and {})",
                            cap[i], cap[j]
                        ),
                    }));
                }
            }
        }
        let Some(ears) = ear_clip(&flat) else {
            return Err(fail(MeshProblem::RimNotCappable {
                rim: r,
                reason: "is not a simple polygon seen along its normal".into(),
            }));
        };
        let base = positions.len() as u32;
        for (k, p) in pts.iter().enumerate() {
            positions.push(*p);
            cap_coords.push(flat[k]);
            cap_chart.push(r as u32);
        }
        let first = triangles.len() as u32;
        let mut area = 0.0;
        let mut moment = Vector3::zeros();
        for e in &ears {
            triangles.push(e.map(|k| base + k as u32));
            let [a, b, c] = e.map(|k| pts[k]);
            let ar = 0.5 * (b - a).cross(&(c - a)).dot(&normal);
            area += ar;
            moment += ar * (a.coords + b.coords + c.coords) / 3.0;
        }
        let length = (0..m).map(|i| (pts[(i + 1) % m] - pts[i]).norm()).sum();
        let c = moment / area;
        openings.push(Opening {
            rim: rim.clone(),
            first_triangle: first,
            triangles: ears.len() as u32,
            area,
            centroid: [c.x, c.y, c.z],
            normal: [normal.x, normal.y, normal.z],
            length,
            warp,
        });
    }
    let uvs = mesh.uvs.as_ref().map(|uvs| {
        // The mesh's UV square as one chart at the mean texel density of its
        // surface, so caps and walls get texels per metre alike.
        let mut uv_area = 0.0;
        let mut area = 0.0;
        for (t, tri) in mesh.triangles.iter().enumerate() {
            let [a, b, c] = tri.map(|v| uvs[v as usize]);
            uv_area += 0.5 * cross2(a, b, c).abs();
            area += mesh.triangle_area_vector(t).norm();
        }
        let k = if uv_area > 0.0 {
            (area / uv_area).sqrt()
        } else {
            1.0
        };
        let mut coords: Vec<Point2<f64>> = uvs.iter().map(|p| Point2::from(p.coords * k)).collect();
        let mut chart_of = vec![0u32; uvs.len()];
        coords.extend(cap_coords.iter().copied());
        chart_of.extend(cap_chart.iter().map(|c| c + 1));
        pack_charts(&coords, &chart_of, loops.len() + 1, DEFAULT_PADDING).0
    });
    // The file's numbering carried over: a cap's vertex is a copy of its
    // rim's (the same position), its triangles are soak's own.
    let source = mesh.source.as_ref().map(|s| {
        let mut vertices = s.vertices.clone();
        vertices.extend(
            loops
                .iter()
                .flat_map(|rim| rim.iter().rev())
                .map(|&v| s.vertex(v).unwrap_or(0)),
        );
        let mut face_lines = s.face_lines.clone();
        face_lines.resize(triangles.len(), 0);
        SourceNumbering { vertices, face_lines }
    });
    let mut closed = Mesh::new(mesh.name.clone(), positions, uvs, triangles);
    closed.openings = openings;
    closed.source = source.filter(|s| s.vertices.len() == closed.positions.len());
    validate_topology(&closed)?;
    Ok(closed)
}

/// The cavities of a closed mesh modelled with thick walls (a bucket or a
/// crate whose outside, rim and inside are one closed surface), found and
/// capped: what [`cap_cavities`] returns.
#[derive(Clone, Debug, PartialEq)]
pub struct Cavities {
    /// The filled shape: the mesh without its cavities' inner walls, each
    /// cavity's mouth capped ([`Mesh::openings`]): what displaces water while
    /// the cavities are dry.
    pub filled: Mesh,
    /// The input's triangles that line the cavities (left out of
    /// `filled`), ascending.
    pub inner: Vec<u32>,
}

/// Finds the cavities of a closed mesh that open through a flat rim and
/// caps them (module docs for the caps).
///
/// A rim is flat where the mesh touches a plane that has the whole mesh
/// behind it (a face of its convex hull: the top of a bucket's rim): the
/// mesh's triangles in that plane form a region, and each hole in that
/// region — a loop of its edges that runs clockwise about the plane's
/// outward normal — is a cavity's mouth. The triangles reached from the
/// mouth without crossing it line the cavity; they are left out and the
/// mouth is capped, which leaves the filled shape closed. A mesh without
/// such a mouth (a closed hull, a cavity whose rim is rounded) comes back
/// with no cavities.
///
/// # Errors
/// The closed-mesh checks of [`validate_topology`]; a mouth that cannot be
/// capped ([`cap_openings`]'s errors).
///
/// # Example
/// ```
/// use soak_bake::{builtin, cap_cavities};
/// // 1 m × 0.5 m × 1 m outside, walls 5 cm thick, open at the top.
/// let crate_ = builtin::thick_open_box(1.0, 0.5, 1.0, 0.05);
/// let c = cap_cavities(&crate_)?;
/// assert_eq!(c.filled.openings.len(), 1);
/// assert!((c.filled.volume() - 0.5).abs() < 1e-12);
/// # Ok::<(), soak_bake::MeshError>(())
/// ```
pub fn cap_cavities(mesh: &Mesh) -> Result<Cavities, MeshError> {
    validate_topology(mesh)?;
    let welded = mesh.welded_triangles();
    let n_tri = welded.len();
    let (lo, hi) = mesh.bounds();
    let tol = 1e-9 * (hi - lo).norm().max(f64::MIN_POSITIVE);
    let normals: Vec<Option<Vector3<f64>>> = (0..n_tri)
        .map(|t| mesh.triangle_area_vector(t).try_normalize(f64::MIN_POSITIVE))
        .collect();
    // Support planes: triangles whose plane has every vertex behind it.
    // Triangles of one plane share (quantised) normal and offset.
    // Normals to 1e-6, offsets to a millionth of the mesh's diagonal.
    let key = |n: &Vector3<f64>, d: f64| -> [i64; 4] {
        let q = |x: f64| (x * 1e6).round() as i64;
        [q(n.x), q(n.y), q(n.z), (d / (1e3 * tol)).round() as i64]
    };
    let mut extreme: std::collections::HashMap<[i64; 3], f64> = std::collections::HashMap::new();
    let mut regions: std::collections::BTreeMap<[i64; 4], Vec<u32>> = std::collections::BTreeMap::new();
    for (t, n) in normals.iter().enumerate() {
        let Some(n) = n else { continue };
        let nk = [
            (n.x * 1e6).round() as i64,
            (n.y * 1e6).round() as i64,
            (n.z * 1e6).round() as i64,
        ];
        let top = *extreme.entry(nk).or_insert_with(|| {
            mesh.positions
                .iter()
                .map(|p| n.dot(&p.coords))
                .fold(f64::NEG_INFINITY, f64::max)
        });
        let pts = mesh.triangle_points(t);
        if pts.iter().all(|p| n.dot(&p.coords) >= top - tol) {
            regions.entry(key(n, top)).or_default().push(t as u32);
        }
    }
    // Edge → the triangles using it (welded, undirected).
    let mut edge_tris: std::collections::HashMap<(u32, u32), Vec<u32>> = std::collections::HashMap::new();
    for (t, tri) in welded.iter().enumerate() {
        for k in 0..3 {
            let (a, b) = (tri[k], tri[(k + 1) % 3]);
            edge_tris.entry((a.min(b), a.max(b))).or_default().push(t as u32);
        }
    }
    let mut inner = std::collections::BTreeSet::new();
    for tris in regions.values() {
        let in_region: std::collections::HashSet<u32> = tris.iter().copied().collect();
        let n = normals[tris[0] as usize].expect("support triangles have normals");
        // The region's boundary, each edge in its triangle's direction.
        let mut next: std::collections::BTreeMap<u32, u32> = std::collections::BTreeMap::new();
        for &t in tris {
            let tri = welded[t as usize];
            for k in 0..3 {
                let (a, b) = (tri[k], tri[(k + 1) % 3]);
                let shared = edge_tris[&(a.min(b), a.max(b))]
                    .iter()
                    .any(|o| *o != t && in_region.contains(o));
                if !shared {
                    next.insert(a, b);
                }
            }
        }
        let mut seen = std::collections::BTreeSet::new();
        let starts: Vec<u32> = next.keys().copied().collect();
        for start in starts {
            if seen.contains(&start) {
                continue;
            }
            let mut ring = vec![start];
            seen.insert(start);
            let mut v = start;
            while let Some(&w) = next.get(&v) {
                if w == start || !seen.insert(w) {
                    break;
                }
                ring.push(w);
                v = w;
            }
            let pts: Vec<Point3<f64>> = ring.iter().map(|&v| mesh.positions[v as usize]).collect();
            if ring.len() < 3 || newell(&pts).dot(&n) >= 0.0 {
                continue; // the region's outer boundary, not a mouth
            }
            // Flood the cavity's lining from across the mouth's edges.
            let mouth: std::collections::HashSet<(u32, u32)> = (0..ring.len())
                .map(|i| {
                    let (a, b) = (ring[i], ring[(i + 1) % ring.len()]);
                    (a.min(b), a.max(b))
                })
                .collect();
            let mut stack: Vec<u32> = mouth
                .iter()
                .flat_map(|e| edge_tris[e].iter().copied())
                .filter(|t| !in_region.contains(t))
                .collect();
            while let Some(t) = stack.pop() {
                if in_region.contains(&t) || !inner.insert(t) {
                    continue;
                }
                let tri = welded[t as usize];
                for k in 0..3 {
                    let (a, b) = (tri[k], tri[(k + 1) % 3]);
                    let e = (a.min(b), a.max(b));
                    if mouth.contains(&e) {
                        continue;
                    }
                    stack.extend(edge_tris[&e].iter().copied().filter(|o| !inner.contains(o)));
                }
            }
        }
    }
    if inner.is_empty() {
        return Ok(Cavities {
            filled: mesh.clone(),
            inner: Vec::new(),
        });
    }
    let mut kept = mesh.clone();
    kept.triangles = mesh
        .triangles
        .iter()
        .enumerate()
        .filter(|(t, _)| !inner.contains(&(*t as u32)))
        .map(|(_, tri)| *tri)
        .collect();
    Ok(Cavities {
        filled: cap_openings(&kept)?,
        inner: inner.into_iter().collect(),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ear_clip_of_a_concave_polygon_covers_its_area() {
        // An L shape, counter-clockwise.
        let poly = [
            (0.0, 0.0),
            (2.0, 0.0),
            (2.0, 1.0),
            (1.0, 1.0),
            (1.0, 2.0),
            (0.0, 2.0),
        ]
        .map(|(x, y)| Point2::new(x, y));
        let tris = ear_clip(&poly).expect("simple");
        assert_eq!(tris.len(), 4);
        let area: f64 = tris
            .iter()
            .map(|t| 0.5 * cross2(poly[t[0]], poly[t[1]], poly[t[2]]))
            .sum();
        assert!((area - 3.0).abs() < 1e-12);
        assert!(
            tris.iter()
                .all(|t| cross2(poly[t[0]], poly[t[1]], poly[t[2]]) > 0.0)
        );
    }

    #[test]
    fn a_bow_tie_is_not_simple() {
        let poly = [(0.0, 0.0), (1.0, 1.0), (1.0, 0.0), (0.0, 1.0)].map(|(x, y)| Point2::new(x, y));
        assert!(segments_cross(poly[0], poly[1], poly[2], poly[3]));
    }
}
