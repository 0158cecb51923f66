//! The meshes and poses swept through the water, and what a run covers.

use nalgebra::{Isometry3, Translation3, UnitQuaternion, Vector3};
use soak_bake::{Mesh, builtin, load_mesh};

use super::AccuracyError;

/// Density of the solid whose inertia is compared, kg/m³ (any value: errors are relative).
pub(super) const DENSITY: f64 = 500.0;
/// Sphere radius of the thesis' Fig. 7.10, m.
pub(super) const RADIUS: f64 = 0.5;
/// Centre-of-buoyancy errors count only where at least this fraction of the
/// body is under water: below, the centre of a sliver is ill-conditioned for
/// every method and says nothing about the rest of the sweep.
pub(super) const MIN_SUBMERGED: f64 = 0.01;

/// What the run covers.
pub(super) struct Plan {
    pub(super) resolutions: Vec<u32>,
    pub(super) levels: usize,
    pub(super) runs: usize,
}

impl Plan {
    pub(super) fn new(quick: bool) -> Self {
        if quick {
            Self {
                resolutions: vec![32, 64, 128, 256],
                levels: 11,
                runs: 3,
            }
        } else {
            Self {
                resolutions: vec![32, 64, 128, 256, 512, 1024, 2048],
                levels: 41,
                runs: 15,
            }
        }
    }
}

/// One mesh at one pose, swept through the water.
pub(super) struct Case {
    /// Short name in the table.
    pub(super) name: &'static str,
    pub(super) mesh: Mesh,
    /// XYZ Euler angles, degrees (as `soak hydro --rotation`).
    pub(super) rotation_deg: [f64; 3],
    /// In the table (the fine sphere only feeds the figures).
    pub(super) in_table: bool,
    /// A sphere of radius [`RADIUS`] centred at the origin: has an analytic curve.
    pub(super) sphere: bool,
}

pub(super) fn cases() -> Result<Vec<Case>, AccuracyError> {
    Ok(vec![
        Case {
            name: "sphere 64×32",
            mesh: builtin::sphere(RADIUS, 64, 32),
            rotation_deg: [0.0; 3],
            in_table: true,
            sphere: true,
        },
        Case {
            name: "sphere 256×128",
            mesh: builtin::sphere(RADIUS, 256, 128),
            rotation_deg: [0.0; 3],
            in_table: false,
            sphere: true,
        },
        Case {
            name: "box 4×1×1 at 17°,29°,43°",
            mesh: load_mesh("builtin:box:4x1x1")?,
            rotation_deg: [17.0, 29.0, 43.0],
            in_table: true,
            sphere: false,
        },
        Case {
            name: "boat, heel 15°, trim 4°",
            mesh: load_mesh("builtin:boat")?,
            rotation_deg: [15.0, 0.0, 4.0],
            in_table: true,
            sphere: false,
        },
        Case {
            name: "sphere 316×158 (100k)",
            mesh: builtin::sphere(RADIUS, 316, 158),
            rotation_deg: [0.0; 3],
            in_table: true,
            sphere: true,
        },
    ])
}

/// `n` evenly spaced values from `lo` to `hi`, both included.
pub(super) fn linspace(lo: f64, hi: f64, n: usize) -> Vec<f64> {
    let n = n.max(2);
    (0..n)
        .map(|i| lo + (hi - lo) * i as f64 / (n - 1) as f64)
        .collect()
}

/// A pose from a position (m) and XYZ Euler angles (degrees, applied x then y then z).
pub(super) fn pose(position: [f64; 3], rotation_deg: [f64; 3]) -> Isometry3<f64> {
    let [rx, ry, rz] = rotation_deg.map(f64::to_radians);
    let q = UnitQuaternion::from_axis_angle(&Vector3::z_axis(), rz)
        * UnitQuaternion::from_axis_angle(&Vector3::y_axis(), ry)
        * UnitQuaternion::from_axis_angle(&Vector3::x_axis(), rx);
    Isometry3::from_parts(Translation3::from(Vector3::from(position)), q)
}
