//! Vertex data built on the CPU: meshes with crease-aware normals, the
//! water grid, and arrow solids.

use std::f64::consts::TAU;

use nalgebra::{Matrix4, Point3, Vector3};
use soak_bake::Mesh;

use super::gpu_types::{ArrowVertex, MeshVertex, WaterVertex};

/// Why a mesh cannot be drawn.
pub(crate) fn check_mesh(mesh: &Mesh) -> Result<(), String> {
    let n = mesh.positions.len();
    if let Some(uvs) = &mesh.uvs {
        if uvs.len() != n {
            return Err(format!("{} UVs for {} vertices", uvs.len(), n));
        }
        if let Some(i) = uvs.iter().position(|u| !(u.x.is_finite() && u.y.is_finite())) {
            return Err(format!("UV {i} is not finite"));
        }
    }
    if let Some(i) = mesh
        .positions
        .iter()
        .position(|p| !p.iter().all(|c| c.is_finite()))
    {
        return Err(format!("vertex {i} is not finite"));
    }
    for (t, tri) in mesh.triangles.iter().enumerate() {
        if let Some(&v) = tri.iter().find(|&&v| v as usize >= n) {
            return Err(format!("triangle {t} uses vertex {v} of {n}"));
        }
    }
    Ok(())
}

/// One vertex per triangle corner (so faces can carry ids and creases can
/// be hard), object space. Each corner's normal is the angle-weighted mean
/// of the normals of the faces around its position (welded across UV
/// seams) that lie within `crease_degrees` of its own face.
#[cfg(test)]
pub(crate) fn mesh_vertices(mesh: &Mesh, segments: Option<&[u32]>, crease_degrees: f64) -> Vec<MeshVertex> {
    mesh_layout(mesh, segments, crease_degrees).0
}

/// How [`mesh_layout`] lays an object's vertices out: the walls facing out
/// (`front` vertices), then for an open mesh the same walls facing in
/// (`back`: its inside is seen over the rim), then its caps (`caps`,
/// drawn only into the depth buffer, so the sea does not show inside a
/// container floating on it).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub(crate) struct MeshLayout {
    pub front: u32,
    pub back: u32,
    pub caps: u32,
}

/// [`mesh_vertices`] of every part of an object, in the order and counts
/// of [`MeshLayout`].
pub(crate) fn mesh_layout(
    mesh: &Mesh,
    segments: Option<&[u32]>,
    crease_degrees: f64,
) -> (Vec<MeshVertex>, MeshLayout) {
    let walls = mesh
        .first_opening_triangle()
        .map_or(mesh.triangles.len(), |f| f as usize);
    let remap = weld(&mesh.positions);
    let unit: Vec<Option<Vector3<f64>>> = (0..mesh.triangles.len())
        .map(|t| mesh.triangle_area_vector(t).try_normalize(1e-300))
        .collect();
    // Corner angles.
    let angles: Vec<[f64; 3]> = (0..mesh.triangles.len())
        .map(|t| {
            let p = mesh.triangle_points(t);
            std::array::from_fn(|k| {
                let (a, b) = (p[(k + 1) % 3] - p[k], p[(k + 2) % 3] - p[k]);
                a.angle(&b)
            })
        })
        .collect();
    // Corners (triangle, corner) around each welded position.
    let mut start = vec![0u32; mesh.positions.len() + 1];
    for tri in &mesh.triangles {
        for &v in tri {
            start[remap[v as usize] as usize + 1] += 1;
        }
    }
    for i in 1..start.len() {
        start[i] += start[i - 1];
    }
    let mut fill = start.clone();
    let mut around = vec![(0u32, 0u8); start[start.len() - 1] as usize];
    for (t, tri) in mesh.triangles.iter().enumerate() {
        for (k, &v) in tri.iter().enumerate() {
            let w = remap[v as usize] as usize;
            around[fill[w] as usize] = (t as u32, k as u8);
            fill[w] += 1;
        }
    }
    let cos_crease = crease_degrees.clamp(0.0, 180.0).to_radians().cos();
    let mut out = Vec::with_capacity(mesh.triangles.len() * 3);
    for (t, tri) in mesh.triangles.iter().enumerate() {
        let own = unit[t].unwrap_or_else(Vector3::zeros);
        let id = segments.map_or(t as u32, |s| s[t]);
        for &v in tri {
            let w = remap[v as usize] as usize;
            let mut n = Vector3::zeros();
            for &(f, k) in &around[start[w] as usize..start[w + 1] as usize] {
                let cap = (f as usize >= walls) != (t >= walls);
                if let Some(u) = unit[f as usize].filter(|_| !cap) {
                    if u.dot(&own) >= cos_crease - 1e-9 {
                        n += u * angles[f as usize][k as usize];
                    }
                }
            }
            let n = n.try_normalize(1e-300).unwrap_or(own);
            let p = mesh.positions[v as usize];
            let uv = mesh.uvs.as_ref().map_or([0.0, 0.0], |u| {
                let u = u[v as usize];
                [u.x as f32, u.y as f32]
            });
            out.push(MeshVertex {
                position: [p.x as f32, p.y as f32, p.z as f32],
                normal: [n.x as f32, n.y as f32, n.z as f32],
                uv,
                face: id,
            });
        }
    }
    let front = 3 * walls;
    let caps = out.split_off(front);
    if walls < mesh.triangles.len() {
        // The walls seen from inside: reversed winding, normals turned.
        let back: Vec<MeshVertex> = out
            .chunks(3)
            .flat_map(|t| {
                [t[0], t[2], t[1]].map(|mut v| {
                    v.normal = v.normal.map(|c| -c);
                    v
                })
            })
            .collect();
        out.extend(back);
    }
    let layout = MeshLayout {
        front: front as u32,
        back: (out.len() - front) as u32,
        caps: caps.len() as u32,
    };
    out.extend(caps);
    (out, layout)
}

/// The free surface of the liquid inside an open container at world
/// height `level` (m): the walls of `mesh` at `pose` cut by the plane
/// `y = level`, each closed loop of the cut triangulated, facing up. Empty
/// when the plane misses the walls or a loop cannot be triangulated.
pub(crate) fn inner_water(
    mesh: &Mesh,
    pose: &nalgebra::Isometry3<f64>,
    level: f64,
) -> (Vec<WaterVertex>, Vec<u32>) {
    let walls = mesh
        .first_opening_triangle()
        .map_or(mesh.triangles.len(), |f| f as usize);
    let remap = weld(&mesh.positions);
    let world: Vec<Point3<f64>> = mesh.positions.iter().map(|p| pose * p).collect();
    // The cut of each triangle: a segment between two edge crossings, an
    // edge keyed by its welded ends so neighbours share the point.
    let mut segments: Vec<((u32, u32), (u32, u32))> = Vec::new();
    let mut points: std::collections::HashMap<(u32, u32), Point3<f64>> = std::collections::HashMap::new();
    for tri in &mesh.triangles[..walls] {
        let mut cut = Vec::with_capacity(2);
        for k in 0..3 {
            let (a, b) = (tri[k] as usize, tri[(k + 1) % 3] as usize);
            let (ya, yb) = (world[a].y - level, world[b].y - level);
            if (ya < 0.0) != (yb < 0.0) {
                let key = (remap[a].min(remap[b]), remap[a].max(remap[b]));
                let s = ya / (ya - yb);
                points
                    .entry(key)
                    .or_insert_with(|| world[a] + (world[b] - world[a]) * s);
                cut.push(key);
            }
        }
        if let [p, q] = cut[..] {
            segments.push((p, q));
        }
    }
    // Chain the segments into loops.
    let mut next: std::collections::HashMap<(u32, u32), Vec<(u32, u32)>> = std::collections::HashMap::new();
    for &(p, q) in &segments {
        next.entry(p).or_default().push(q);
        next.entry(q).or_default().push(p);
    }
    let mut used = std::collections::HashSet::new();
    let (mut vertices, mut indices) = (Vec::new(), Vec::new());
    let mut keys: Vec<(u32, u32)> = next.keys().copied().collect();
    keys.sort_unstable();
    for start in keys {
        if used.contains(&start) {
            continue;
        }
        let mut ring = vec![start];
        used.insert(start);
        let mut at = start;
        while let Some(&n) = next[&at].iter().find(|n| !used.contains(*n)) {
            used.insert(n);
            ring.push(n);
            at = n;
        }
        if ring.len() < 3 || !next[&at].contains(&start) {
            continue;
        }
        let mut flat: Vec<nalgebra::Point2<f64>> = ring
            .iter()
            .map(|k| nalgebra::Point2::new(points[k].x, -points[k].z))
            .collect();
        // Counter-clockwise seen from above (x right, −z up the page).
        let area: f64 = (0..flat.len())
            .map(|i| {
                let (a, b) = (flat[i], flat[(i + 1) % flat.len()]);
                a.x * b.y - b.x * a.y
            })
            .sum();
        if area < 0.0 {
            ring.reverse();
            flat.reverse();
        }
        let Some(ears) = soak_bake::triangulate(&flat) else {
            continue;
        };
        let base = vertices.len() as u32;
        for k in &ring {
            let p = points[k];
            vertices.push(WaterVertex {
                position: [p.x as f32, level as f32, p.z as f32],
                normal: [0.0, 1.0, 0.0],
            });
        }
        for e in ears {
            indices.extend(e.map(|i| base + i as u32));
        }
    }
    (vertices, indices)
}

/// Index of the first vertex at the same position, for each vertex (exact
/// f64 equality, which is what seam-split vertices of soak's meshes have).
fn weld(positions: &[Point3<f64>]) -> Vec<u32> {
    let mut first = std::collections::HashMap::with_capacity(positions.len());
    positions
        .iter()
        .enumerate()
        .map(|(i, p)| {
            let key = [p.x.to_bits(), p.y.to_bits(), p.z.to_bits()];
            *first.entry(key).or_insert(i as u32)
        })
        .collect()
}

/// Surface area (m²) and UV area of a mesh: their ratio is the mean world
/// area of a unit of UV area.
pub(crate) fn areas(mesh: &Mesh) -> (f64, f64) {
    let mut world = 0.0;
    let mut uv = 0.0;
    for t in 0..mesh
        .first_opening_triangle()
        .map_or(mesh.triangles.len(), |f| f as usize)
    {
        world += mesh.triangle_area_vector(t).norm();
        if let Some([a, b, c]) = mesh.triangle_uvs(t) {
            uv += 0.5 * ((b - a).perp(&(c - a))).abs();
        }
    }
    (world, uv)
}

/// A water grid of `n`×`n` vertices over the square of half side `extent`
/// around `(cx, cz)`, spaced finer near the centre, displaced by `surface`
/// (rest position → world position). Normals from the displaced grid.
/// Returns vertices and triangle indices.
pub(crate) fn water_grid(
    cx: f64,
    cz: f64,
    extent: f64,
    n: u32,
    surface: impl Fn(f64, f64) -> Point3<f64>,
) -> (Vec<WaterVertex>, Vec<u32>) {
    let n = n.clamp(2, 1024) as usize;
    // s ∈ [−1, 1] ↦ extent·s·(a + (1 − a)s²): spacing grows outwards.
    let a = 0.15;
    let coord = |i: usize| {
        let s = -1.0 + 2.0 * i as f64 / (n - 1) as f64;
        extent * s * (a + (1.0 - a) * s * s)
    };
    let mut p = Vec::with_capacity(n * n);
    for j in 0..n {
        for i in 0..n {
            p.push(surface(cx + coord(i), cz + coord(j)));
        }
    }
    let at = |i: usize, j: usize| p[j * n + i];
    let mut vertices = Vec::with_capacity(n * n);
    for j in 0..n {
        for i in 0..n {
            let dx = at((i + 1).min(n - 1), j) - at(i.saturating_sub(1), j);
            let dz = at(i, (j + 1).min(n - 1)) - at(i, j.saturating_sub(1));
            let normal = dz.cross(&dx).try_normalize(1e-300).unwrap_or_else(Vector3::y);
            let q = at(i, j);
            vertices.push(WaterVertex {
                position: [q.x as f32, q.y as f32, q.z as f32],
                normal: [normal.x as f32, normal.y as f32, normal.z as f32],
            });
        }
    }
    let mut indices = Vec::with_capacity((n - 1) * (n - 1) * 6);
    for j in 0..n - 1 {
        for i in 0..n - 1 {
            let v = |i: usize, j: usize| (j * n + i) as u32;
            // Counter-clockwise seen from above (+y).
            indices.extend([v(i, j), v(i, j + 1), v(i + 1, j)]);
            indices.extend([v(i + 1, j), v(i, j + 1), v(i + 1, j + 1)]);
        }
    }
    (vertices, indices)
}

/// The triangles of `indices` not entirely outside one plane of the view
/// frustum of `view_proj` (wgpu clip space): the water grid reaches far
/// beyond the view, and a software rasteriser pays for every triangle.
pub(crate) fn cull_to_view(vertices: &[WaterVertex], indices: &[u32], view_proj: &Matrix4<f64>) -> Vec<u32> {
    let outcodes: Vec<u8> = vertices
        .iter()
        .map(|v| {
            let p = Point3::from(v.position.map(f64::from));
            let c = view_proj * p.to_homogeneous();
            u8::from(c.x < -c.w)
                | u8::from(c.x > c.w) << 1
                | u8::from(c.y < -c.w) << 2
                | u8::from(c.y > c.w) << 3
                | u8::from(c.z < 0.0) << 4
                | u8::from(c.z > c.w) << 5
        })
        .collect();
    indices
        .chunks_exact(3)
        .filter(|t| outcodes[t[0] as usize] & outcodes[t[1] as usize] & outcodes[t[2] as usize] == 0)
        .flatten()
        .copied()
        .collect()
}

/// Triangles of a shaft (cylinder) and head (cone) from `origin` along
/// `vector`, world space, 20 sides, outward normals. Empty for a zero or
/// non-finite vector.
pub(crate) fn arrow_vertices(
    origin: Point3<f64>,
    vector: Vector3<f64>,
    radius: f64,
    colour: [f64; 3],
    out: &mut Vec<ArrowVertex>,
) {
    let len = vector.norm();
    if !(len > 1e-9 && len.is_finite() && radius > 0.0 && radius.is_finite()) {
        return;
    }
    let d = vector / len;
    let helper = if d.x.abs() < 0.9 {
        Vector3::x()
    } else {
        Vector3::y()
    };
    let e1 = d.cross(&helper).normalize();
    let e2 = d.cross(&e1);
    let head_radius = 2.2 * radius;
    let head_len = (4.0 * head_radius).min(0.45 * len);
    let shaft_len = len - head_len;
    let colour = colour.map(|c| c as f32);
    let sides = 20;
    let ring = |k: usize| {
        let a = TAU * k as f64 / sides as f64;
        e1 * a.cos() + e2 * a.sin()
    };
    let mut push = |p: Point3<f64>, n: Vector3<f64>| {
        out.push(ArrowVertex {
            position: [p.x as f32, p.y as f32, p.z as f32],
            normal: [n.x as f32, n.y as f32, n.z as f32],
            colour,
        })
    };
    let base = origin;
    let neck = origin + d * shaft_len;
    let tip = origin + vector;
    // Cone slope for the head's normals.
    let slant = Vector3::new(head_len, head_radius, 0.0).normalize();
    for k in 0..sides {
        let (r0, r1) = (ring(k), ring(k + 1));
        // Shaft side.
        let (a, b) = (base + r0 * radius, base + r1 * radius);
        let (c, e) = (neck + r0 * radius, neck + r1 * radius);
        push(a, r0);
        push(b, r1);
        push(e, r1);
        push(a, r0);
        push(e, r1);
        push(c, r0);
        // Tail cap.
        push(base, -d);
        push(b, -d);
        push(a, -d);
        // Head underside.
        let (ha, hb) = (neck + r0 * head_radius, neck + r1 * head_radius);
        push(neck, -d);
        push(hb, -d);
        push(ha, -d);
        // Head cone.
        let n0 = r0 * slant.x + d * slant.y;
        let n1 = r1 * slant.x + d * slant.y;
        let nm = (n0 + n1).normalize();
        push(ha, n0);
        push(hb, n1);
        push(tip, nm);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use soak_bake::builtin;

    #[test]
    fn cube_faces_stay_flat_and_sphere_is_smooth() {
        let cube = builtin::cuboid(1.0, 1.0, 1.0);
        for v in mesh_vertices(&cube, None, 50.0).chunks(3) {
            // Every corner of a face has the face's normal.
            let n = Vector3::from(v[0].normal.map(f64::from));
            for c in v {
                let m = Vector3::from(c.normal.map(f64::from));
                assert!((n - m).norm() < 1e-6);
            }
        }
        let sphere = builtin::sphere(1.0, 32, 16);
        for v in mesh_vertices(&sphere, None, 50.0) {
            // Smooth normals of a unit sphere point along the position.
            let p = Vector3::from(v.position.map(f64::from));
            let n = Vector3::from(v.normal.map(f64::from));
            assert!((p.normalize() - n).norm() < 0.02, "{p:?} {n:?}");
        }
    }

    #[test]
    fn normals_point_outwards() {
        let boat = builtin::boat(4.0, 1.2, 0.6);
        let centre = Vector3::new(0.0, 0.3, 0.0);
        let verts = mesh_vertices(&boat, None, 50.0);
        let outward = verts
            .iter()
            .filter(|v| {
                let p = Vector3::from(v.position.map(f64::from));
                let n = Vector3::from(v.normal.map(f64::from));
                (p - centre).dot(&n) > 0.0
            })
            .count();
        assert!(outward as f64 > 0.95 * verts.len() as f64);
    }

    #[test]
    fn water_grid_faces_up() {
        let (v, i) = water_grid(0.0, 0.0, 10.0, 8, |x, z| Point3::new(x, 0.0, z));
        assert_eq!(v.len(), 64);
        for t in i.chunks(3) {
            let p: Vec<Vector3<f64>> = t
                .iter()
                .map(|&k| Vector3::from(v[k as usize].position.map(f64::from)))
                .collect();
            assert!((p[1] - p[0]).cross(&(p[2] - p[0])).y > 0.0);
        }
        assert!(v.iter().all(|w| w.normal == [0.0, 1.0, 0.0]));
    }
}
