//! soak's physics atlas generator: a bijective UV map with near-uniform texel
//! density for any mesh, missing or overlapping UVs notwithstanding.
//!
//! The method is described on [`unwrap`].

use std::collections::VecDeque;
use std::time::Instant;

use nalgebra::{Point2, Vector3};
use serde::{Deserialize, Serialize};

use crate::error::MeshError;
use crate::mesh::{Mesh, SourceNumbering};
use crate::pack::{DEFAULT_PADDING, pack_charts};
use crate::uv_overlap::find_overlap;
use crate::validate::validate_geometry;

/// Parameters of [`unwrap`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct UnwrapOptions {
    /// Largest angle between a face normal and its chart's mean normal, degrees.
    pub cone_degrees: f64,
    /// Padding between charts, as a fraction of the atlas side.
    pub padding: f64,
}

impl Default for UnwrapOptions {
    fn default() -> Self {
        Self {
            cone_degrees: 50.0,
            padding: DEFAULT_PADDING,
        }
    }
}

/// What [`unwrap`] produced.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct UnwrapReport {
    /// Number of charts.
    pub charts: usize,
    /// Smallest per-triangle texel density relative to the area-weighted mean.
    pub density_min: f64,
    /// Largest per-triangle texel density relative to the area-weighted mean.
    pub density_max: f64,
    /// Area-weighted coefficient of variation of the texel density.
    pub density_cv: f64,
    /// Fraction of the unit square covered by charts.
    pub coverage: f64,
    /// Wall time, ms.
    pub millis: f64,
}

/// Replaces the mesh's UVs with a generated physics atlas. Triangle order is
/// kept (triangle `t` of the result is triangle `t` of the input); vertices
/// are split along chart boundaries.
///
/// The atlas is bijective with near-uniform texel density for any mesh,
/// missing or overlapping UVs notwithstanding. Charts grow over face
/// adjacency while each face's normal stays within a cone about the chart's
/// mean normal; each chart is projected onto its plane (faces whose
/// projection would fold are left to other charts), checked for overlap (and
/// split until it has none), turned to its principal axes and packed with the
/// others at one common scale.
pub fn unwrap(mesh: &Mesh, options: UnwrapOptions) -> Result<(Mesh, UnwrapReport), MeshError> {
    let start = Instant::now();
    validate_geometry(mesh)?;
    let welded = mesh.welded_triangles();
    let n_tri = welded.len();
    let normals: Vec<Vector3<f64>> = (0..n_tri).map(|t| mesh.triangle_area_vector(t)).collect();
    let unit: Vec<Vector3<f64>> = normals.iter().map(|n| n / n.norm()).collect();
    let adjacency = face_adjacency(&welded);
    let cos_cone = options.cone_degrees.to_radians().cos();

    // Grow charts.
    let mut chart_of = vec![u32::MAX; n_tri];
    let mut charts: Vec<Vec<u32>> = Vec::new();
    let mut queue = VecDeque::new();
    let mut next_seed = 0;
    // Faces released by a chart (see below) are picked up by a later pass.
    while let Some(seed) = (next_seed..n_tri)
        .chain(0..next_seed)
        .find(|&f| chart_of[f] == u32::MAX)
    {
        next_seed = seed + 1;
        let id = charts.len() as u32;
        let mut faces = vec![seed as u32];
        chart_of[seed] = id;
        let mut sum = normals[seed];
        queue.clear();
        queue.push_back(seed);
        while let Some(f) = queue.pop_front() {
            for &g in &adjacency[f] {
                let g = g as usize;
                if chart_of[g] != u32::MAX {
                    continue;
                }
                let mean = sum.normalize();
                if unit[g].dot(&mean) >= cos_cone {
                    chart_of[g] = id;
                    sum += normals[g];
                    faces.push(g as u32);
                    queue.push_back(g);
                }
            }
        }
        // Release faces that drifted out of the cone of the final mean normal.
        let mean = sum.normalize();
        let (kept, released): (Vec<u32>, Vec<u32>) = faces
            .iter()
            .partition(|&&f| unit[f as usize].dot(&mean) >= cos_cone);
        let faces = if kept.is_empty() { vec![seed as u32] } else { kept };
        for f in released {
            if f as usize != seed || faces[0] as usize != seed {
                chart_of[f as usize] = u32::MAX;
            }
        }
        charts.push(faces);
    }

    // Project, drop folding faces, split overlapping charts.
    let mut final_charts: Vec<(Vec<u32>, Vector3<f64>)> = Vec::new();
    let mut pending: Vec<Vec<u32>> = charts;
    let mut orphans: Vec<u32> = Vec::new();
    while let Some(faces) = pending.pop() {
        let m: Vector3<f64> = faces.iter().map(|&f| normals[f as usize]).sum::<Vector3<f64>>();
        let m = if m.norm() > 0.0 {
            m.normalize()
        } else {
            unit[faces[0] as usize]
        };
        let (keep, drop): (Vec<u32>, Vec<u32>) =
            faces.iter().partition(|&&f| unit[f as usize].dot(&m) > 0.05);
        orphans.extend(drop);
        if keep.is_empty() {
            continue;
        }
        let (u, v) = plane_basis(&m);
        let tris: Vec<[Point2<f64>; 3]> = keep
            .iter()
            .map(|&f| {
                mesh.triangle_points(f as usize)
                    .map(|p| Point2::new(p.coords.dot(&u), p.coords.dot(&v)))
            })
            .collect();
        if keep.len() > 1 && find_overlap(&tris).is_some() {
            let half = keep.len() / 2;
            pending.push(keep[..half].to_vec());
            pending.push(keep[half..].to_vec());
        } else {
            final_charts.push((keep, m));
        }
    }
    // Faces that fold in every chart they reached become their own charts.
    for f in orphans {
        final_charts.push((vec![f], unit[f as usize]));
    }

    // Emit split vertices with chart coordinates.
    let mut positions = Vec::new();
    let mut coords = Vec::new();
    let mut chart_of_vertex = Vec::new();
    // Each new vertex's vertex in `mesh`, to carry the file's numbering.
    let mut origin: Vec<u32> = Vec::new();
    let mut triangles = vec![[0u32; 3]; n_tri];
    let mut local_index: Vec<u32> = vec![u32::MAX; mesh.positions.len()];
    let mut touched: Vec<usize> = Vec::new();
    for (c, (faces, m)) in final_charts.iter().enumerate() {
        let (u, v) = plane_basis(m);
        let first_vertex = positions.len();
        for &f in faces {
            let orig = mesh.triangles[f as usize];
            let weld = welded[f as usize];
            let mut tri = [0u32; 3];
            for k in 0..3 {
                let key = weld[k] as usize;
                if local_index[key] == u32::MAX {
                    let p = mesh.positions[orig[k] as usize];
                    origin.push(orig[k]);
                    local_index[key] = positions.len() as u32;
                    touched.push(key);
                    positions.push(p);
                    coords.push(Point2::new(p.coords.dot(&u), p.coords.dot(&v)));
                    chart_of_vertex.push(c as u32);
                }
                tri[k] = local_index[key];
            }
            triangles[f as usize] = tri;
        }
        align_principal(&mut coords[first_vertex..]);
        for k in touched.drain(..) {
            local_index[k] = u32::MAX;
        }
    }
    let (uvs, scale) = pack_charts(&coords, &chart_of_vertex, final_charts.len(), options.padding);
    let mut out = Mesh::new(mesh.name.clone(), positions, Some(uvs), triangles);
    out.openings = mesh.openings.clone();
    out.source = mesh.source.as_ref().map(|s| SourceNumbering {
        vertices: origin.iter().map(|&v| s.vertex(v).unwrap_or(0)).collect(),
        face_lines: s.face_lines.clone(),
    });

    // Texel density per triangle: UV area over surface area, relative to the mean.
    let mut total_area = 0.0;
    let mut total_uv = 0.0;
    let dens: Vec<(f64, f64)> = (0..n_tri)
        .map(|t| {
            let a = out.triangle_area_vector(t).norm();
            let [p, q, r] = out.triangle_uvs(t).expect("just set");
            let uv = 0.5 * (q - p).perp(&(r - p)).abs();
            total_area += a;
            total_uv += uv;
            (a, uv / a)
        })
        .collect();
    let mean = total_uv / total_area;
    let (mut lo, mut hi, mut var) = (f64::MAX, 0.0f64, 0.0);
    for &(a, d) in &dens {
        let r = d / mean;
        lo = lo.min(r);
        hi = hi.max(r);
        var += a * (r - 1.0).powi(2);
    }
    let _ = scale;
    let report = UnwrapReport {
        charts: final_charts.len(),
        density_min: lo,
        density_max: hi,
        density_cv: (var / total_area).sqrt(),
        coverage: total_uv,
        millis: start.elapsed().as_secs_f64() * 1e3,
    };
    Ok((out, report))
}

/// Neighbours across each edge shared by exactly two faces (welded indices).
fn face_adjacency(welded: &[[u32; 3]]) -> Vec<Vec<u32>> {
    let mut edges: Vec<(u32, u32, u32)> = Vec::with_capacity(welded.len() * 3);
    for (t, tri) in welded.iter().enumerate() {
        for k in 0..3 {
            let (a, b) = (tri[k], tri[(k + 1) % 3]);
            edges.push((a.min(b), a.max(b), t as u32));
        }
    }
    edges.sort_unstable();
    let mut adj = vec![Vec::with_capacity(3); welded.len()];
    let mut i = 0;
    while i < edges.len() {
        let mut j = i + 1;
        while j < edges.len() && edges[j].0 == edges[i].0 && edges[j].1 == edges[i].1 {
            j += 1;
        }
        if j - i == 2 {
            let (a, b) = (edges[i].2, edges[i + 1].2);
            adj[a as usize].push(b);
            adj[b as usize].push(a);
        }
        i = j;
    }
    adj
}

/// An orthonormal basis `(u, v)` of the plane normal to `m`, with `u × v = m`,
/// so faces facing along `m` keep their counter-clockwise orientation.
fn plane_basis(m: &Vector3<f64>) -> (Vector3<f64>, Vector3<f64>) {
    let helper = if m.x.abs() < 0.6 {
        Vector3::x()
    } else {
        Vector3::y()
    };
    let u = helper.cross(m).normalize();
    let v = m.cross(&u);
    (u, v)
}

/// Rotates 2-D points about their mean to their principal axes (a tighter box to pack).
fn align_principal(pts: &mut [Point2<f64>]) {
    if pts.len() < 3 {
        return;
    }
    let n = pts.len() as f64;
    let c = pts.iter().fold(nalgebra::Vector2::zeros(), |s, p| s + p.coords) / n;
    let (mut sxx, mut syy, mut sxy) = (0.0, 0.0, 0.0);
    for p in pts.iter() {
        let d = p.coords - c;
        sxx += d.x * d.x;
        syy += d.y * d.y;
        sxy += d.x * d.y;
    }
    let angle = 0.5 * (2.0 * sxy).atan2(sxx - syy);
    let (s, co) = (-angle).sin_cos();
    for p in pts.iter_mut() {
        let d = p.coords - c;
        *p = Point2::new(co * d.x - s * d.y, s * d.x + co * d.y);
    }
}
