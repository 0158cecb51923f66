//! The body and the fluid of a cell: a mesh baked once per scale, the water
//! sized to it, the water columns' volume and potential, and the height at
//! which the body floats.

use nalgebra::{Isometry3, Translation3, UnitQuaternion, Vector3};
use soak_bake::{Atlas, BakeOptions, builtin};
use soak_hydro::{
    Gerstner, GerstnerWave, HeightField, SeaSpectrum, SpectralSea, SpectralSurface, Water, WaterError,
};

use super::error::StressError;
use super::matrix::{Shape, WaterKind};

/// Density of the water, kg/m³ (soak's default fluid).
pub(crate) const RHO_W: f64 = 1000.0;
/// Gravity, m/s².
pub(crate) const G: f64 = 9.81;

/// A mesh baked at one scale, shared by its cells.
pub(crate) struct Fixture {
    /// The mesh, scaled (an open container's closed shape).
    pub(crate) mesh: soak_bake::Mesh,
    pub(crate) atlas: Atlas,
    /// Enclosed volume, m³.
    pub(crate) volume: f64,
    /// Nominal size `V^(1/3)`, m.
    pub(crate) size: f64,
    /// Bounding radius about the atlas origin, m.
    pub(crate) radius: f64,
}

impl Fixture {
    /// Bakes `mesh` scaled by `scale` into a `resolution`² atlas.
    pub(crate) fn new(mesh: Shape, scale: f64, resolution: u32) -> Result<Fixture, StressError> {
        let m = builtin::parse(mesh.source())
            .map_err(|source| StressError::Load {
                mesh: mesh.label(),
                scale,
                source,
            })?
            .map_positions(|p| p * scale);
        let m = if mesh.is_open() {
            soak_bake::cap_openings(&m).map_err(|e| StressError::Bake {
                mesh: mesh.label(),
                scale,
                source: e.into(),
            })?
        } else {
            m
        };
        let atlas = Atlas::bake(&m, BakeOptions::square(resolution)).map_err(|source| StressError::Bake {
            mesh: mesh.label(),
            scale,
            source,
        })?;
        let volume = atlas.volume();
        if !(volume.is_finite() && volume > 0.0) {
            return Err(StressError::Volume {
                mesh: mesh.label(),
                scale,
                volume,
            });
        }
        Ok(Fixture {
            mesh: m,
            size: volume.cbrt(),
            radius: atlas.bounding_radius(),
            volume,
            atlas,
        })
    }
}

/// The fluid of a cell, sized to the body (bounding radius `r`, m).
pub(crate) fn water(kind: WaterKind, r: f64) -> Result<Water, WaterError> {
    Ok(match kind {
        WaterKind::Plane => Water::calm(0.0),
        WaterKind::Sea => {
            let wave = |wavelength: f64, direction_deg: f64, phase: f64| GerstnerWave {
                amplitude: 0.07 * wavelength,
                wavelength,
                direction_deg,
                steepness: 0.9,
                phase,
            };
            Water::new(Gerstner::new(
                0.0,
                vec![wave(8.0 * r, 0.0, 0.0), wave(5.0 * r, 40.0, 1.0)],
                G,
            )?)
        }
        WaterKind::Ocean => {
            // JONSWAP whose peak wave is the sea's longer wave, 8 r, and
            // whose significant height is 0.6 r (a steep storm sea, Hs
            // over the peak wavelength 0.075), on a tile of four peak
            // wavelengths with 32 cells a side (waves down to r long).
            let spectrum = SeaSpectrum::jonswap(0.6 * r, wave_period(r));
            let tile = 32.0 * r;
            Water::new(SpectralSurface::new(SpectralSea::realize(
                &spectrum, 0.0, tile, 32, 1, G,
            )?))
        }
        WaterKind::Cliff => {
            // 0.3 r above the mean level for x < 0, 0.3 r below it for
            // x > 0, the step between two samples 0.1 r apart: a slope of 6.
            let n = 41;
            let spacing = 0.1 * r;
            let origin = -spacing * ((n - 1) / 2) as f64 - 0.5 * spacing;
            let heights = (0..n * n)
                .map(|i| {
                    let ix = i % n;
                    if ix < n / 2 { 0.3 * r } else { -0.3 * r }
                })
                .collect();
            Water::new(HeightField::new(
                [origin, origin],
                [spacing, spacing],
                n,
                n,
                heights,
            )?)
        }
    })
}

/// Submerged volume `Σ −A_y d` (m³) and the columns' potential
/// `Σ −A_y d²/2` (m⁴) of the atlas at `pose` in `water` at time `t`.
///
/// Once every texel is under water the potential is `∫_V d dV`, and the
/// columns reaching up to the surface from far below would sum it as
/// differences of numbers that grow with the depth (`Σ −A_y h_i y_i`, with
/// the surface's heights over the top and the bottom samples differing by
/// the sampling wherever the surface is not flat). It is then summed by
/// columns that stop at the height `Y` of the atlas origin, as
/// `∫_V h dV − Y V + ∫_V (Y − y) dV`, each term bounded by the body's size.
pub(crate) fn columns(atlas: &Atlas, pose: &Isometry3<f64>, water: &Water, t: f64) -> (f64, f64) {
    let mut volume = 0.0;
    let mut potential = 0.0;
    let top = (pose * atlas.origin()).y;
    let (mut under, mut local_potential) = (true, 0.0);
    let mut hint = [0.0; 2];
    for (i, a) in atlas.area_vectors().iter().enumerate() {
        let p = pose * atlas.position(i);
        let d = water.surface.probe(&p, t, false, &mut hint).0;
        let ay = (pose.rotation * Vector3::new(a[0] as f64, a[1] as f64, a[2] as f64)).y;
        if d > 0.0 {
            volume -= ay * d;
            potential -= ay * d * d / 2.0;
        } else {
            under = false;
        }
        // Column from the sample up to `top`: the surface's height
        // `h = d + y` relative to `top`, times the column, plus `∫ (top − y) dy`.
        let column = top - p.y;
        local_potential -= ay * ((d - column) * column + column * column / 2.0);
    }
    if under {
        return (volume, local_potential);
    }
    (volume, potential)
}

/// The height at which the body, turned by `rotation`, displaces
/// `fraction` of its volume in `water` at t = 0 (bisection).
pub(crate) fn equilibrium(f: &Fixture, rotation: &UnitQuaternion<f64>, fraction: f64, water: &Water) -> f64 {
    let pose = |y: f64| Isometry3::from_parts(Translation3::new(0.0, y, 0.0), *rotation);
    let (lowest, highest) = water.surface.height_bounds(0.0).unwrap_or((0.0, 0.0));
    let (mut lo, mut hi) = (lowest - 2.0 * f.radius, highest + 2.0 * f.radius);
    for _ in 0..60 {
        let mid = 0.5 * (lo + hi);
        let (v, _) = columns(&f.atlas, &pose(mid), water, 0.0);
        if v / f.volume > fraction {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    0.5 * (lo + hi)
}

/// Period of the longer wave of the sea, s.
pub(crate) fn wave_period(r: f64) -> f64 {
    let k = std::f64::consts::TAU / (8.0 * r);
    std::f64::consts::TAU / (G * k).sqrt()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Lowering a body wholly under water by `Δ` adds `V Δ` to the columns'
    /// potential `∫_V d dV`, whatever the surface over it: the measure the
    /// energy check uses must say so at any depth, where columns summed up
    /// to the surface (`Σ −A_y d²/2` as such) drift with the depth over the
    /// cliff's step.
    #[test]
    fn the_potential_of_a_submerged_body_grows_by_its_volume_times_the_depth() {
        let atlas = Atlas::bake(&builtin::cylinder(0.5, 1.0, 24), BakeOptions::square(32)).unwrap();
        let r = atlas.bounding_radius();
        let water = water(WaterKind::Cliff, r).unwrap();
        let turn = UnitQuaternion::from_euler_angles(0.05, 0.3, 0.09);
        let at = |depth: f64| {
            let pose = Isometry3::from_parts(Translation3::new(0.02, -depth, -0.01), turn);
            columns(&atlas, &pose, &water, 0.0)
        };
        let v = soak_hydro::volume_moments(&atlas).volume;
        let (_, u0) = at(2.0);
        for depth in [20.0, 2e3, 2e5] {
            let (_, u) = at(depth);
            // The atlas' own volume and the columns' agree to ~1e-8.
            let drift = (u - u0 - v * (depth - 2.0)).abs() / (v * (r + depth));
            assert!(
                drift < 1e-6,
                "at {depth} m the potential drifts by {drift:.2e} V (r + depth)"
            );
        }
    }
}
