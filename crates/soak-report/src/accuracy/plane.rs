//! The plane rows: what reading a sea as one plane over each body
//! ([`SeaSampling::Plane`]) costs in accuracy and saves in time, against
//! the exact read of the same sea at every texel, beside the default
//! sampled read's errors against the same reference.

use std::hint::black_box;

use nalgebra::{Isometry3, UnitQuaternion, Vector3};
use serde::Serialize;
use soak_bake::{Mesh, builtin};
use soak_hydro::{BodyState, Drag, HydroForces, HydroOptions, SeaSampling, Water, evaluate};

use super::AccuracyError;
use super::sea::{Baked, short_sea, swell};
use super::timing::per_call_ms;

/// One mesh on one sea.
#[derive(Clone, Debug, Serialize)]
pub struct PlaneRow {
    /// The sea.
    pub sea: String,
    /// Mesh name.
    pub mesh: String,
    /// Texture side, texels.
    pub resolution: u32,
    /// Worst |V − V_exact| / V_body over the poses, the plane read (the
    /// force's error against ρ g V_body is the same number).
    pub volume_error: f64,
    /// Worst |C_B − C_B,exact| / bounding diameter, the plane read.
    pub cob_error: f64,
    /// Worst |τ − τ_exact| / (ρ g V_body × bounding diameter), the plane
    /// read.
    pub torque_error: f64,
    /// Worst |F − F_exact| / |F_exact| of the drag of the moving poses,
    /// the plane read.
    pub drag_error: f64,
    /// The same four of the sampled read (16 nodes per shortest wave),
    /// against the same reference.
    pub sampled_errors: [f64; 4],
    /// Tiled evaluation reading the plane (its five reads of the sea
    /// included), ms (median).
    pub plane_ms: f64,
    /// Tiled evaluation reading the sampled sea (sampling included), ms.
    pub sampled_ms: f64,
}

/// Six poses of a body on `water`, its centre `sink` (m) under the sea
/// there, tilted and turned, at times 1.3 s apart; with `moving`, each
/// moving at 0.7 m/s and turning at 0.46 rad/s.
fn poses_on(water: &Water, sink: f64, moving: bool) -> Vec<(BodyState, f64)> {
    (0..6)
        .map(|k| {
            let k = k as f64;
            let (x, z, t) = (7.3 * k - 2.0, 0.6 - 5.1 * k, 1.3 * k);
            let y = water.surface.height(x, z, t) - sink;
            let pose = Isometry3::from_parts(
                Vector3::new(x, y, z).into(),
                UnitQuaternion::from_euler_angles(0.3, 0.5 * k, 0.1),
            );
            let mut state = BodyState::at_rest(pose);
            if moving {
                state.linear_velocity = Vector3::new(0.6, -0.3, 0.2);
                state.angular_velocity = Vector3::new(0.2, 0.4, -0.1);
            }
            (state, t)
        })
        .collect()
}

/// The worst errors of `read` against `exact` over `poses` (volume, centre
/// of buoyancy, torque) and over `moving` (drag force), as [`PlaneRow`]
/// states them.
fn errors(
    baked: &Baked,
    water: &Water,
    poses: &[(BodyState, f64)],
    moving: &[(BodyState, f64)],
    read: &HydroOptions,
) -> Result<[f64; 4], AccuracyError> {
    let Baked {
        atlas,
        mass,
        volume,
        diameter,
        ..
    } = baked;
    let exact = HydroOptions {
        sea: SeaSampling::Exact,
        ..*read
    };
    let weight = water.density * water.gravity * volume;
    let mut worst = [0.0f64; 4];
    let still = HydroOptions { drag: None, ..*read };
    for (state, t) in poses {
        let e: HydroForces = evaluate(
            atlas,
            water,
            state,
            mass,
            *t,
            &HydroOptions { drag: None, ..exact },
        )?;
        let r = evaluate(atlas, water, state, mass, *t, &still)?;
        worst[0] = worst[0].max((r.submerged_volume - e.submerged_volume).abs() / volume);
        worst[1] = worst[1].max((r.center_of_buoyancy - e.center_of_buoyancy).norm() / diameter);
        worst[2] = worst[2].max((r.buoyancy.torque - e.buoyancy.torque).norm() / (weight * diameter));
    }
    for (state, t) in moving {
        let e = evaluate(atlas, water, state, mass, *t, &exact)?;
        let r = evaluate(atlas, water, state, mass, *t, read)?;
        let f = e.drag_explicit.force.norm();
        if f > 0.0 {
            worst[3] = worst[3].max((r.drag_explicit.force - e.drag_explicit.force).norm() / f);
        }
    }
    Ok(worst)
}

/// The plane rows: the bench's box and sphere and the boat, on the
/// bench's JONSWAP sea (Hs 2 m, Tp 8 s: [`crate::scaling::jonswap`]), on
/// the short sea of [`short_sea`] (its shortest wave 1.75 m, shorter
/// than the boat) and on the two-wave swell of [`swell`] (its shortest
/// wave 4 m; the box is the crate of `twenty_on_swell.toml`, which reads
/// it as one plane); `runs` timed samples per path.
pub(super) fn plane_rows(resolution: u32, runs: usize) -> Result<Vec<PlaneRow>, AccuracyError> {
    // The bench's sea, as `crate::scaling::jonswap` makes it.
    let bench = Water::spectral(&soak_hydro::SeaSpectrum::jonswap(2.0, 8.0), 0)
        .map_err(soak_hydro::HydroError::from)?;
    let seas = [
        ("JONSWAP Hs 2 m, Tp 8 s", bench),
        ("JONSWAP Hs 0.5 m, Tp 3 s", short_sea()?),
        ("two-wave swell", swell()?),
    ];
    let meshes: [(&str, Mesh); 3] = [
        ("box 1×0.6×0.8", builtin::cuboid(1.0, 0.6, 0.8)),
        ("sphere 64×32", builtin::sphere(0.5, 64, 32)),
        ("boat 4×1.2×0.6", builtin::boat(4.0, 1.2, 0.6)),
    ];
    let drag = Drag {
        coefficient: 0.8,
        linear: 20.0,
    };
    let mut rows = Vec::new();
    for (sea, water) in &seas {
        for (name, mesh) in &meshes {
            let baked = Baked::new(mesh, resolution)?;
            let poses = poses_on(water, 0.1, false);
            let moving = poses_on(water, 0.1, true);
            let plane = HydroOptions {
                drag: Some(drag),
                sea: SeaSampling::Plane,
                ..HydroOptions::default()
            };
            let sampled = HydroOptions {
                sea: SeaSampling::PerWavelength(SeaSampling::DEFAULT_PER_WAVELENGTH),
                ..plane
            };
            let e = errors(&baked, water, &poses, &moving, &plane)?;
            let sampled_errors = errors(&baked, water, &poses, &moving, &sampled)?;
            let (state, t) = moving[0];
            let Baked {
                atlas, tiled, mass, ..
            } = &baked;
            let [plane_ms, sampled_ms] = per_call_ms(
                runs,
                [
                    &mut || {
                        black_box(tiled.evaluate(atlas, water, &state, mass, t, &plane).ok());
                    },
                    &mut || {
                        black_box(tiled.evaluate(atlas, water, &state, mass, t, &sampled).ok());
                    },
                ],
            );
            rows.push(PlaneRow {
                sea: sea.to_string(),
                mesh: name.to_string(),
                resolution,
                volume_error: e[0],
                cob_error: e[1],
                torque_error: e[2],
                drag_error: e[3],
                sampled_errors,
                plane_ms,
                sampled_ms,
            });
        }
    }
    Ok(rows)
}

/// The plane rows as lines of a table (header first).
pub(super) fn plane_cells(rows: &[PlaneRow]) -> Vec<[String; 11]> {
    let mut all = vec![
        [
            "sea",
            "mesh",
            "atlas",
            "volume / force err",
            "CoB err",
            "torque err",
            "drag err",
            "sampled: volume, CoB, torque, drag err",
            "tiled, plane",
            "tiled, sampled",
            "speed-up",
        ]
        .map(String::from),
    ];
    for r in rows {
        let s = r.sampled_errors;
        all.push([
            r.sea.clone(),
            r.mesh.clone(),
            format!("{}²", r.resolution),
            format!("{:.1e}", r.volume_error),
            format!("{:.1e}", r.cob_error),
            format!("{:.1e}", r.torque_error),
            format!("{:.1e}", r.drag_error),
            format!("{:.1e}, {:.1e}, {:.1e}, {:.1e}", s[0], s[1], s[2], s[3]),
            format!("{:.4} ms", r.plane_ms),
            format!("{:.4} ms", r.sampled_ms),
            format!("{:.1}×", r.sampled_ms / r.plane_ms),
        ]);
    }
    all
}
