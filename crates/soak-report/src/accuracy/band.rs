//! The band rows: what reading only a band of a spectral sea's waves
//! ([`SeaBand::BodyLengths`]) costs in accuracy and saves in time, against
//! the same body reading every wave of the sea (both sampled at the
//! default nodes per wavelength).

use std::hint::black_box;

use serde::Serialize;
use soak_bake::{Mesh, builtin};
use soak_hydro::{
    HydroForces, HydroOptions, SeaBand, SpectralSurface, Surface, SurfacePatch, evaluate, sampled_water,
};

use super::AccuracyError;
use super::sea::{Baked, poses, short_sea};
use super::timing::per_call_ms;

/// One mesh at one cut-off.
#[derive(Clone, Debug, Serialize)]
pub struct BandRow {
    /// Mesh name.
    pub mesh: String,
    /// Texture side, texels.
    pub resolution: u32,
    /// The cut-off asked for, in body lengths (bounding diameters).
    pub body_lengths: f64,
    /// The band read: the sea's shortest wave times `2^level`.
    pub level: usize,
    /// The band's shortest wave in body lengths: every shorter wave is
    /// dropped.
    pub dropped_below: f64,
    /// Nodes of the body's patch (x × z), at the first pose.
    pub nodes: [usize; 2],
    /// Worst |V − V_whole| / V_body over the poses (the force's error
    /// against ρ g V_body is the same number).
    pub volume_error: f64,
    /// Worst |C_B − C_B,whole| / bounding diameter over the poses.
    pub cob_error: f64,
    /// Worst |τ − τ_whole| / (ρ g V_body × bounding diameter) over the
    /// poses.
    pub torque_error: f64,
    /// Tiled evaluation reading the band (sampling included), ms (median).
    pub band_ms: f64,
    /// Tiled evaluation reading every wave (sampling included), ms.
    pub whole_ms: f64,
}

/// The band rows on the short sea of [`short_sea`] (its shortest wave
/// 1.75 m): the boat and a 10 m barge, cut-offs of ½, 1, 2 and 4 body
/// lengths; `runs` timed samples per path.
pub(super) fn band_rows(resolution: u32, runs: usize) -> Result<Vec<BandRow>, AccuracyError> {
    let water = short_sea()?;
    let shortest = water
        .surface
        .as_any()
        .and_then(|s| s.downcast_ref::<SpectralSurface>())
        .and_then(|s| s.sampling_length(0.0))
        .unwrap_or(f64::NAN);
    let meshes: [(&str, Mesh); 2] = [
        ("boat 4×1.2×0.6", builtin::boat(4.0, 1.2, 0.6)),
        ("barge 10×3×4", builtin::cuboid(10.0, 3.0, 4.0)),
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
        let whole = HydroOptions::default();
        // The poses of the sea rows, the barge's scaled to its size.
        let scale = diameter / 4.2;
        let poses: Vec<_> = poses()
            .into_iter()
            .map(|(mut s, t)| {
                s.pose.translation.vector.x *= scale;
                s.pose.translation.vector.z *= scale;
                (s, t)
            })
            .collect();
        let reference = poses
            .iter()
            .map(|(s, t)| evaluate(&atlas, &water, s, &mass, *t, &whole))
            .collect::<Result<Vec<_>, _>>()?;
        for body_lengths in [0.5, 1.0, 2.0, 4.0] {
            let options = HydroOptions {
                sea_band: SeaBand::BodyLengths(body_lengths),
                ..whole
            };
            let mut errors = [0.0f64; 3];
            for ((state, t), e) in poses.iter().zip(&reference) {
                let b: HydroForces = evaluate(&atlas, &water, state, &mass, *t, &options)?;
                errors[0] = errors[0].max((b.submerged_volume - e.submerged_volume).abs() / volume);
                errors[1] = errors[1].max((b.center_of_buoyancy - e.center_of_buoyancy).norm() / diameter);
                errors[2] =
                    errors[2].max((b.buoyancy.torque - e.buoyancy.torque).norm() / (weight * diameter));
            }
            let (state, t) = poses[0];
            let patch = sampled_water(&atlas, &water, &state, t, &options)?;
            let patch = patch
                .as_ref()
                .and_then(|w| w.surface.as_any())
                .and_then(|s| s.downcast_ref::<SurfacePatch>());
            let (spacing, nodes) = patch.map_or((f64::NAN, [0, 0]), |p| (p.spacing(), p.nodes()));
            // The band's shortest wave: 16 nodes of the patch.
            let band_shortest = spacing * soak_hydro::SeaSampling::DEFAULT_PER_WAVELENGTH;
            let level = (band_shortest / shortest).log2().round() as usize;
            let [band_ms, whole_ms] = per_call_ms(
                runs,
                [
                    &mut || {
                        black_box(tiled.evaluate(&atlas, &water, &state, &mass, t, &options).ok());
                    },
                    &mut || {
                        black_box(tiled.evaluate(&atlas, &water, &state, &mass, t, &whole).ok());
                    },
                ],
            );
            rows.push(BandRow {
                mesh: name.to_string(),
                resolution,
                body_lengths,
                level,
                dropped_below: band_shortest / diameter,
                nodes,
                volume_error: errors[0],
                cob_error: errors[1],
                torque_error: errors[2],
                band_ms,
                whole_ms,
            });
        }
    }
    Ok(rows)
}

/// The band rows as lines of a table (header first).
pub(super) fn band_cells(rows: &[BandRow]) -> Vec<[String; 10]> {
    let mut all = vec![
        [
            "mesh",
            "atlas",
            "band (body lengths)",
            "waves dropped below",
            "nodes",
            "volume / force err",
            "CoB err",
            "torque err",
            "tiled, band",
            "tiled, every wave",
        ]
        .map(String::from),
    ];
    for r in rows {
        let dropped = if r.level == 0 {
            "none".to_string()
        } else {
            format!("{:.2} body lengths", r.dropped_below)
        };
        all.push([
            r.mesh.clone(),
            format!("{}²", r.resolution),
            format!("{}", r.body_lengths),
            dropped,
            format!("{}×{}", r.nodes[0], r.nodes[1]),
            format!("{:.1e}", r.volume_error),
            format!("{:.1e}", r.cob_error),
            format!("{:.1e}", r.torque_error),
            format!("{:.3} ms", r.band_ms),
            format!("{:.3} ms", r.whole_ms),
        ]);
    }
    all
}
