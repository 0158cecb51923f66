//! The sea rows: what the sampled read of a Gerstner sea
//! ([`SeaSampling::PerWavelength`]) costs in accuracy and saves in time,
//! against the exact inversion of the Gerstner map at every texel (the
//! reference), per knob setting; and the tiled path on the same sampled
//! sea ([`TiledAtlas`]: tiles under the waves in closed form); and the
//! drag of the body moving through the swell, the fluid's velocity read
//! from the sampled sea at every texel or once per tile
//! ([`SeaVelocity`]), against the exact inversion's.

use std::hint::black_box;

use nalgebra::{Isometry3, UnitQuaternion, Vector3};
use serde::Serialize;
use soak_bake::{Atlas, BakeOptions, Mesh, builtin};
use soak_hydro::{
    BodyState, Drag, Gerstner, GerstnerWave, HydroForces, HydroOptions, MassModel, SeaSampling, SeaVelocity,
    SurfacePatch, TiledAtlas, Water, evaluate, sampled_water,
};

use super::AccuracyError;
use super::cases::DENSITY;
use super::timing::per_call_ms;

/// One mesh at one atlas resolution and one sampling setting.
#[derive(Clone, Debug, Serialize)]
pub struct SeaRow {
    /// Mesh name.
    pub mesh: String,
    /// Texture side, texels.
    pub resolution: u32,
    /// Nodes per shortest wavelength.
    pub per_wavelength: f64,
    /// Node spacing, m.
    pub spacing: f64,
    /// Nodes of the body's patch (x × z), at the first pose.
    pub nodes: [usize; 2],
    /// Worst |V − V_exact| / V_body over the poses.
    pub volume_error: f64,
    /// Worst |C_B − C_B,exact| / bounding diameter over the poses.
    pub cob_error: f64,
    /// Worst |τ − τ_exact| / (ρ g V_body × bounding diameter) (Archimedes'
    /// torque, slope term included) over the poses.
    pub torque_error: f64,
    /// The tiled path on the sampled sea: the same three errors against
    /// the exact inversion (volume, centre of buoyancy, torque).
    pub tiled_errors: [f64; 3],
    /// Sampled evaluation (sampling included), ms (median).
    pub sampled_ms: f64,
    /// Tiled evaluation on the sampled sea (sampling included), ms (median).
    pub tiled_ms: f64,
    /// Exact inversion at every texel, ms (median).
    pub exact_ms: f64,
    /// The same body at the same pose on calm water (planar kernel), ms.
    pub plane_ms: f64,
    /// The body moving through the swell with drag: worst relative
    /// difference of the drag (force, and torque over the bounding
    /// radius) against the exact inversion's, the fluid's velocity read
    /// from the sampled sea at every texel and (tiled) once per tile; and
    /// between those two.
    pub drag_errors: [f64; 3],
    /// Tiled evaluation with drag, the fluid's velocity once per tile, ms.
    pub drag_tile_ms: f64,
    /// Tiled evaluation with drag, the fluid's velocity at every texel, ms.
    pub drag_texel_ms: f64,
}

/// The drag of the moving body in the sea rows.
const DRAG: Drag = Drag {
    coefficient: 0.8,
    linear: 20.0,
};

/// The poses of [`poses`], moving and turning through the water.
fn moving() -> Vec<(BodyState, f64)> {
    poses()
        .into_iter()
        .map(|(s, t)| {
            let state = BodyState {
                linear_velocity: Vector3::new(0.6, -0.2, 0.3),
                angular_velocity: Vector3::new(0.2, 0.4, -0.1),
                ..s
            };
            (state, t)
        })
        .collect()
}

/// `|ΔF| + |Δτ| / r` against `|F| + |τ| / r` of the reference's drag.
fn drag_difference(got: &HydroForces, want: &HydroForces, radius: f64) -> f64 {
    let (g, w) = (&got.drag_explicit, &want.drag_explicit);
    let off = (g.force - w.force).norm() + (g.torque - w.torque).norm() / radius;
    off / (w.force.norm() + w.torque.norm() / radius)
}

/// The two-wave swell of `data/scenes/buoy_on_waves.toml`.
pub fn swell() -> Result<Water, AccuracyError> {
    let waves = GerstnerWave::SWELL.to_vec();
    let sea =
        Gerstner::new(0.0, waves, soak_hydro::STANDARD_GRAVITY).map_err(soak_hydro::HydroError::from)?;
    Ok(Water::new(sea))
}

/// Six poses across the swell, at several places, heights, tilts and times.
pub(super) fn poses() -> Vec<(BodyState, f64)> {
    (0..6)
        .map(|k| {
            let k = k as f64;
            let pose = Isometry3::from_parts(
                Vector3::new(0.9 * k - 2.0, 0.03 * k - 0.2, 0.6 - 0.7 * k).into(),
                UnitQuaternion::from_euler_angles(0.3, 0.5 * k, 0.1),
            );
            (BodyState::at_rest(pose), 1.3 * k)
        })
        .collect()
}

/// A short, steep spectral sea for the spectral rows: JONSWAP of
/// significant height 0.5 m and peak period 3 s (its peak wave 14 m long),
/// `γ` 3.3, spreading 10, seed 1, on its default tile (112 m, 128 cells:
/// its shortest wave 1.75 m, shorter than the boat).
pub fn short_sea() -> Result<Water, AccuracyError> {
    Water::spectral(&soak_hydro::SeaSpectrum::jonswap(0.5, 3.0), 1)
        .map_err(|e| soak_hydro::HydroError::from(e).into())
}

/// The sea rows for the sphere, the box and the boat at `resolution`, at
/// 4, 8, 16 (the default) and 32 nodes per shortest wavelength; `runs`
/// timed samples per path.
pub(super) fn sea_rows(resolution: u32, runs: usize) -> Result<Vec<SeaRow>, AccuracyError> {
    rows_on(&swell()?, resolution, runs)
}

/// The same rows on the spectral sea of [`short_sea`]: the sampled read
/// against the exact inversion of its choppy map at every texel.
pub(super) fn spectral_rows(resolution: u32, runs: usize) -> Result<Vec<SeaRow>, AccuracyError> {
    rows_on(&short_sea()?, resolution, runs)
}

/// A mesh baked for the sea's rows: its atlas and tiles, its mass (solid,
/// [`DENSITY`]), its volume (m³) and its bounding diameter (m).
pub(super) struct Baked {
    pub atlas: Atlas,
    pub tiled: TiledAtlas,
    pub mass: soak_hydro::MassProperties,
    pub volume: f64,
    pub diameter: f64,
}

impl Baked {
    /// `mesh` baked at `resolution`².
    pub fn new(mesh: &Mesh, resolution: u32) -> Result<Self, AccuracyError> {
        let atlas = Atlas::bake(mesh, BakeOptions::square(resolution))?;
        let tiled = TiledAtlas::new(&atlas);
        let mass = MassModel::Solid { density: DENSITY }.mass_properties(&atlas)?;
        let diameter = 2.0 * atlas.bounding_radius();
        Ok(Self {
            atlas,
            tiled,
            mass,
            volume: mesh.volume(),
            diameter,
        })
    }
}

/// The sea rows on `water`.
fn rows_on(water: &Water, resolution: u32, runs: usize) -> Result<Vec<SeaRow>, AccuracyError> {
    let calm = Water::calm(0.0);
    let meshes: [(&str, Mesh); 3] = [
        ("sphere 64×32", builtin::sphere(0.5, 64, 32)),
        ("box 1×0.6×0.8", builtin::cuboid(1.0, 0.6, 0.8)),
        ("boat 4×1.2×0.6", builtin::boat(4.0, 1.2, 0.6)),
    ];
    let mut rows = Vec::new();
    for (name, mesh) in meshes {
        let Baked {
            atlas,
            tiled,
            mass,
            volume,
            diameter,
        } = Baked::new(&mesh, resolution)?;
        let weight = water.density * water.gravity * volume;
        let exact = HydroOptions {
            sea: SeaSampling::Exact,
            ..HydroOptions::default()
        };
        let reference = poses()
            .into_iter()
            .map(|(s, t)| evaluate(&atlas, water, &s, &mass, t, &exact))
            .collect::<Result<Vec<_>, _>>()?;
        let drag_exact = HydroOptions {
            drag: Some(DRAG),
            ..exact
        };
        let drag_reference = moving()
            .into_iter()
            .map(|(s, t)| evaluate(&atlas, water, &s, &mass, t, &drag_exact))
            .collect::<Result<Vec<_>, _>>()?;
        for per in [4.0, 8.0, 16.0, 32.0] {
            let options = HydroOptions {
                sea: SeaSampling::PerWavelength(per),
                ..HydroOptions::default()
            };
            let (mut errors, mut tiled_errors) = ([0.0f64; 3], [0.0f64; 3]);
            let worst = |errors: &mut [f64; 3], s: &HydroForces, e: &HydroForces| {
                errors[0] = errors[0].max((s.submerged_volume - e.submerged_volume).abs() / volume);
                errors[1] = errors[1].max((s.center_of_buoyancy - e.center_of_buoyancy).norm() / diameter);
                errors[2] =
                    errors[2].max((s.buoyancy.torque - e.buoyancy.torque).norm() / (weight * diameter));
            };
            for ((state, t), e) in poses().into_iter().zip(&reference) {
                worst(
                    &mut errors,
                    &evaluate(&atlas, water, &state, &mass, t, &options)?,
                    e,
                );
                let s = tiled.evaluate(&atlas, water, &state, &mass, t, &options)?;
                worst(&mut tiled_errors, &s, e);
            }
            let radius = 0.5 * diameter;
            let per_tile = HydroOptions {
                drag: Some(DRAG),
                ..options
            };
            let per_texel = HydroOptions {
                sea_velocity: SeaVelocity::PerTexel,
                ..per_tile
            };
            let mut drag_errors = [0.0f64; 3];
            for ((state, t), e) in moving().into_iter().zip(&drag_reference) {
                let texels = evaluate(&atlas, water, &state, &mass, t, &per_texel)?;
                let tiles = tiled.evaluate(&atlas, water, &state, &mass, t, &per_tile)?;
                drag_errors[0] = drag_errors[0].max(drag_difference(&texels, e, radius));
                drag_errors[1] = drag_errors[1].max(drag_difference(&tiles, e, radius));
                drag_errors[2] = drag_errors[2].max(drag_difference(&tiles, &texels, radius));
            }
            let (state, t) = poses()[0];
            let patch = sampled_water(&atlas, water, &state, t, &options)?;
            let patch = patch
                .as_ref()
                .and_then(|w| w.surface.as_any())
                .and_then(|s| s.downcast_ref::<SurfacePatch>());
            let (spacing, nodes) = patch.map_or((f64::NAN, [0, 0]), |p| (p.spacing(), p.nodes()));
            let (moving_state, _) = moving()[0];
            let [
                sampled_ms,
                tiled_ms,
                exact_ms,
                plane_ms,
                drag_tile_ms,
                drag_texel_ms,
            ] = per_call_ms(
                runs,
                [
                    &mut || {
                        black_box(evaluate(&atlas, water, &state, &mass, t, &options).ok());
                    },
                    &mut || {
                        black_box(tiled.evaluate(&atlas, water, &state, &mass, t, &options).ok());
                    },
                    &mut || {
                        black_box(evaluate(&atlas, water, &state, &mass, t, &exact).ok());
                    },
                    &mut || {
                        black_box(evaluate(&atlas, &calm, &state, &mass, t, &options).ok());
                    },
                    &mut || {
                        black_box(
                            tiled
                                .evaluate(&atlas, water, &moving_state, &mass, t, &per_tile)
                                .ok(),
                        );
                    },
                    &mut || {
                        black_box(
                            tiled
                                .evaluate(&atlas, water, &moving_state, &mass, t, &per_texel)
                                .ok(),
                        );
                    },
                ],
            );
            rows.push(SeaRow {
                mesh: name.to_string(),
                resolution,
                per_wavelength: per,
                spacing,
                nodes,
                volume_error: errors[0],
                cob_error: errors[1],
                torque_error: errors[2],
                tiled_errors,
                sampled_ms,
                tiled_ms,
                exact_ms,
                plane_ms,
                drag_errors,
                drag_tile_ms,
                drag_texel_ms,
            });
        }
    }
    Ok(rows)
}

/// The sea rows as lines of a table (header first), for text and markdown.
pub(super) fn sea_cells(rows: &[SeaRow]) -> Vec<[String; 15]> {
    let mut all = vec![
        [
            "mesh",
            "atlas",
            "nodes/λ",
            "spacing",
            "volume err",
            "CoB err",
            "torque err",
            "tiled: V / CoB / τ err",
            "sampled",
            "tiled",
            "exact",
            "plane",
            "drag err: texel / tile / tile−texel",
            "tiled + drag",
            "per texel",
        ]
        .map(String::from),
    ];
    for r in rows {
        all.push([
            r.mesh.clone(),
            format!("{}²", r.resolution),
            format!("{}", r.per_wavelength),
            format!("{:.3} m", r.spacing),
            format!("{:.1e}", r.volume_error),
            format!("{:.1e}", r.cob_error),
            format!("{:.1e}", r.torque_error),
            r.tiled_errors.map(|e| format!("{e:.1e}")).join(" / "),
            format!("{:.3} ms", r.sampled_ms),
            format!("{:.3} ms", r.tiled_ms),
            format!("{:.3} ms", r.exact_ms),
            format!("{:.3} ms", r.plane_ms),
            r.drag_errors.map(|e| format!("{e:.1e}")).join(" / "),
            format!("{:.3} ms", r.drag_tile_ms),
            format!("{:.3} ms", r.drag_texel_ms),
        ]);
    }
    all
}
