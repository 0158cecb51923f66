//! Helpers shared by the subcommands.

use std::time::Instant;

use anyhow::Context;
use nalgebra::{Isometry3, Matrix3, Point3, Translation3, UnitQuaternion, Vector3};
use soak_bake::{Atlas, BakeOptions, Mesh, UnwrapOptions, load_mesh, unwrap};

/// Loads a mesh (file or builtin), unwrapping it when asked.
pub fn mesh(source: &str, unwrap_uvs: bool) -> anyhow::Result<Mesh> {
    let mesh = load_mesh(source)?;
    if unwrap_uvs {
        let (m, _) = unwrap(&mesh, UnwrapOptions::default())?;
        return Ok(m);
    }
    Ok(mesh)
}

/// Bakes at `n`², returning the atlas and the time it took in ms.
pub fn bake(mesh: &Mesh, n: u32) -> anyhow::Result<(Atlas, f64)> {
    let start = Instant::now();
    let atlas = Atlas::bake(mesh, BakeOptions::square(n)).with_context(|| format!("baking {}", mesh.name))?;
    Ok((atlas, ms(start)))
}

/// Milliseconds since `start`.
pub fn ms(start: Instant) -> f64 {
    start.elapsed().as_secs_f64() * 1e3
}

/// Parses `A,B,C` into three numbers.
pub fn triple(s: &str) -> Result<[f64; 3], String> {
    let v: Vec<f64> = s
        .split(',')
        .map(|t| {
            t.trim()
                .parse::<f64>()
                .map_err(|_| format!("`{t}` is not a number"))
        })
        .collect::<Result<_, _>>()?;
    match v.as_slice() {
        [a, b, c] if v.iter().all(|x| x.is_finite()) => Ok([*a, *b, *c]),
        _ => Err(format!("`{s}` is not three finite numbers A,B,C")),
    }
}

/// A pose from a position (m) and XYZ Euler angles (degrees, applied x then y then z).
pub fn pose(position: [f64; 3], rotation_deg: [f64; 3]) -> Isometry3<f64> {
    let [rx, ry, rz] = rotation_deg.map(f64::to_radians);
    let q = UnitQuaternion::from_axis_angle(&Vector3::z_axis(), rz)
        * UnitQuaternion::from_axis_angle(&Vector3::y_axis(), ry)
        * UnitQuaternion::from_axis_angle(&Vector3::x_axis(), rx);
    Isometry3::from_parts(Translation3::from(Vector3::from(position)), q)
}

/// `[x, y, z]` of a point.
pub fn arr(p: &Point3<f64>) -> [f64; 3] {
    [p.x, p.y, p.z]
}

/// `[x, y, z]` of a vector.
pub fn vec3(v: &Vector3<f64>) -> [f64; 3] {
    [v.x, v.y, v.z]
}

/// Rows of a 3×3 matrix.
pub fn rows(m: &Matrix3<f64>) -> [[f64; 3]; 3] {
    [
        [m[(0, 0)], m[(0, 1)], m[(0, 2)]],
        [m[(1, 0)], m[(1, 1)], m[(1, 2)]],
        [m[(2, 0)], m[(2, 1)], m[(2, 2)]],
    ]
}

/// Median time of `runs` calls of `f`, ms.
pub fn time_ms<T>(runs: usize, mut f: impl FnMut() -> T) -> f64 {
    let mut t: Vec<f64> = (0..runs.max(1))
        .map(|_| {
            let s = Instant::now();
            std::hint::black_box(f());
            ms(s)
        })
        .collect();
    t.sort_by(f64::total_cmp);
    t[t.len() / 2]
}
