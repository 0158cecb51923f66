//! The drag-texel rows: what summing a body's drag over a coarser bake of
//! its mesh, or over its own atlas coarsened ([`DragTexels`]), costs in
//! accuracy and saves in time, against the drag over the body's own
//! texels (the reference), per drag resolution, for bodies moving on calm
//! water and through the swell.

use std::hint::black_box;

use nalgebra::{Isometry3, UnitQuaternion, Vector3};
use serde::Serialize;
use soak_bake::{Atlas, BakeOptions, Mesh, builtin};
use soak_hydro::{BodyState, Drag, DragTexels, HydroForces, HydroOptions, MassModel, TiledAtlas, Water};

use super::AccuracyError;
use super::cases::DENSITY;
use super::sea::swell;
use super::timing::per_call_ms;

/// One mesh at one atlas resolution with its drag over one coarser bake.
#[derive(Clone, Debug, Serialize)]
pub struct DragTexelRow {
    /// Mesh name.
    pub mesh: String,
    /// The body's atlas side (its buoyancy), texels.
    pub resolution: u32,
    /// The drag bake's side, texels (for a coarsened atlas, the atlas'
    /// side over the factor).
    pub drag_resolution: u32,
    /// The factor the body's own atlas was coarsened by for its drag
    /// ([`DragTexels::coarsened`]); `None` for a bake of the mesh.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub coarsening: Option<u32>,
    /// Drag texels (a bake's at least one per triangle; a coarsened
    /// atlas' one per block and piece of surface).
    pub drag_texels: usize,
    /// Worst relative difference of the drag (force, and torque over the
    /// bounding radius) from the drag over the body's own texels, over
    /// the moving poses on calm water.
    pub calm_error: f64,
    /// The same on the two-wave swell (sampled).
    pub sea_error: f64,
    /// Tiled evaluation on calm water without drag, ms (median).
    pub still_ms: f64,
    /// Tiled evaluation with the drag over the body's own texels, ms.
    pub own_ms: f64,
    /// Tiled evaluation with the drag over the drag bake, ms.
    pub coarse_ms: f64,
}

/// The drag of the moving bodies.
const DRAG: Drag = Drag {
    coefficient: 0.8,
    linear: 20.0,
};

/// Six moving poses at the surface (heights from the body's half-height
/// `h`), tilted and turning, at several times.
fn moving(h: f64) -> Vec<(BodyState, f64)> {
    (0..6)
        .map(|k| {
            let k = k as f64;
            let pose = Isometry3::from_parts(
                Vector3::new(0.9 * k - 2.0, h * (0.4 - 0.15 * k), 0.6 - 0.7 * k).into(),
                UnitQuaternion::from_euler_angles(0.3 * k, 0.5 * k, 0.1),
            );
            let state = BodyState {
                linear_velocity: Vector3::new(0.7, 0.1 * k - 0.3, 0.2),
                angular_velocity: Vector3::new(0.2, 0.5, -0.1 * k),
                ..BodyState::at_rest(pose)
            };
            (state, 1.3 * k)
        })
        .collect()
}

/// `|ΔF| + |Δτ| / r` against `|F| + |τ| / r` of the reference's drag.
fn drag_difference(got: &HydroForces, want: &HydroForces, radius: f64) -> f64 {
    let (g, w) = (&got.drag_explicit, &want.drag_explicit);
    let off = (g.force - w.force).norm() + (g.torque - w.torque).norm() / radius;
    off / (w.force.norm() + w.torque.norm() / radius)
}

/// The drag-texel rows for the sphere, the box and the boat at
/// `resolution`, their drag over bakes at 32², 64², 128² and 256², then
/// over their atlas coarsened to the same sides; `runs` timed samples per
/// path.
pub(super) fn drag_texel_rows(resolution: u32, runs: usize) -> Result<Vec<DragTexelRow>, AccuracyError> {
    let calm = Water::calm(0.0);
    let sea = swell()?;
    let meshes: [(&str, Mesh, f64); 3] = [
        ("sphere 64×32", builtin::sphere(0.5, 64, 32), 0.5),
        ("box 1×0.6×0.8", builtin::cuboid(1.0, 0.6, 0.8), 0.3),
        ("boat 4×1.2×0.6", builtin::boat(4.0, 1.2, 0.6), 0.3),
    ];
    let options = HydroOptions {
        drag: Some(DRAG),
        ..HydroOptions::default()
    };
    let still = HydroOptions {
        drag: None,
        ..options
    };
    let mut rows = Vec::new();
    for (name, mesh, h) in meshes {
        let atlas = std::sync::Arc::new(Atlas::bake(&mesh, BakeOptions::square(resolution))?);
        let tiled = TiledAtlas::new(&atlas);
        let mass = MassModel::Solid { density: DENSITY }.mass_properties(&atlas)?;
        let radius = atlas.bounding_radius();
        let poses = moving(h);
        let own = |water: &Water| {
            poses
                .iter()
                .map(|(s, t)| tiled.evaluate(&atlas, water, s, &mass, *t, &options))
                .collect::<Result<Vec<_>, _>>()
        };
        let (own_calm, own_sea) = (own(&calm)?, own(&sea)?);
        let sides = [32, 64, 128, 256].into_iter().filter(|&n| n < resolution);
        let bakes = sides.clone().map(|n| (n, None));
        let coarsened = sides.map(|n| (n, Some(resolution / n)));
        for (drag_resolution, coarsening) in bakes.chain(coarsened) {
            let coarse = match coarsening {
                None => DragTexels::bake(&mesh, drag_resolution)?,
                Some(k) => DragTexels::coarsened(atlas.clone(), k)?,
            };
            let worst = |water: &Water, reference: &[HydroForces]| -> Result<f64, AccuracyError> {
                let mut worst = 0.0f64;
                for ((s, t), want) in poses.iter().zip(reference) {
                    let got = tiled.evaluate_with_drag(&atlas, &coarse, water, s, &mass, *t, &options)?;
                    worst = worst.max(drag_difference(&got, want, radius));
                }
                Ok(worst)
            };
            let (calm_error, sea_error) = (worst(&calm, &own_calm)?, worst(&sea, &own_sea)?);
            let (state, t) = poses[0];
            let [still_ms, own_ms, coarse_ms] = per_call_ms(
                runs,
                [
                    &mut || {
                        black_box(tiled.evaluate(&atlas, &calm, &state, &mass, t, &still).ok());
                    },
                    &mut || {
                        black_box(tiled.evaluate(&atlas, &calm, &state, &mass, t, &options).ok());
                    },
                    &mut || {
                        black_box(
                            tiled
                                .evaluate_with_drag(&atlas, &coarse, &calm, &state, &mass, t, &options)
                                .ok(),
                        );
                    },
                ],
            );
            rows.push(DragTexelRow {
                mesh: name.to_string(),
                resolution,
                drag_resolution,
                coarsening,
                drag_texels: coarse.atlas().len(),
                calm_error,
                sea_error,
                still_ms,
                own_ms,
                coarse_ms,
            });
        }
    }
    Ok(rows)
}

/// The drag-texel rows as lines of a table (header first).
pub(super) fn drag_texel_cells(rows: &[DragTexelRow]) -> Vec<[String; 10]> {
    let mut all = vec![
        [
            "mesh",
            "atlas",
            "drag texels from",
            "drag texels",
            "drag err: calm",
            "swell",
            "no drag",
            "own drag",
            "drag bake",
            "ratio",
        ]
        .map(String::from),
    ];
    for r in rows {
        all.push([
            r.mesh.clone(),
            format!("{}²", r.resolution),
            match r.coarsening {
                None => format!("{}²", r.drag_resolution),
                Some(k) => format!("atlas by {k} ({}²)", r.drag_resolution),
            },
            format!("{}", r.drag_texels),
            format!("{:.1e}", r.calm_error),
            format!("{:.1e}", r.sea_error),
            format!("{:.4} ms", r.still_ms),
            format!("{:.4} ms", r.own_ms),
            format!("{:.4} ms", r.coarse_ms),
            format!("{:.2}×", r.coarse_ms / r.still_ms),
        ]);
    }
    all
}
