//! Diffusion behaves like diffusion: on a flat plate a spot's variance grows
//! linearly in time at the rate `D_eff = 3 w Δx² / Δt` predicts (within
//! 10 %), and with diffusion off nothing spreads.

use nalgebra::{Isometry3, Point3, Vector3};
use soak_bake::{Atlas, BakeOptions, Mesh, builtin};
use soak_hydro::Water;
use soak_wet::prelude::*;

/// No evaporation (saturated air), no water contact.
fn still() -> (Environment, Water) {
    let env = Environment {
        relative_humidity: 1.0,
        ..Environment::default()
    };
    (env, Water::calm(-100.0))
}

/// Spot of saturated liquid of radius `r` at the plate centre, top face.
fn spot(atlas: &Atlas, wet: &mut Wetting, r: f64, up: Vector3<f64>) {
    let sat = wet.material().saturation;
    let h: Vec<f64> = (0..atlas.len())
        .map(|i| {
            let p = atlas.position(i);
            let a = atlas.area_vectors().get(i);
            let n = Vector3::new(a[0] as f64, a[1] as f64, a[2] as f64);
            if p.coords.norm() < r && n.dot(&up) > 0.0 {
                sat
            } else {
                0.0
            }
        })
        .collect();
    wet.set_liquid(atlas, h).unwrap();
}

/// In-plane variance (m²) of the liquid, about its mean, with in-plane axes `e1`, `e2`.
fn variance(atlas: &Atlas, h: &[f64], e1: Vector3<f64>, e2: Vector3<f64>) -> f64 {
    let (mut m, mut s1, mut s2, mut q) = (0.0, 0.0, 0.0, 0.0);
    for (i, &h) in h.iter().enumerate() {
        let w = h * atlas.areas()[i] as f64;
        let p = atlas.position(i).coords;
        let (u, v) = (p.dot(&e1), p.dot(&e2));
        m += w;
        s1 += w * u;
        s2 += w * v;
        q += w * (u * u + v * v);
    }
    q / m - (s1 / m).powi(2) - (s2 / m).powi(2)
}

/// Least-squares slope of `y` over `x`.
fn slope(x: &[f64], y: &[f64]) -> f64 {
    let n = x.len() as f64;
    let (mx, my) = (x.iter().sum::<f64>() / n, y.iter().sum::<f64>() / n);
    let sxy: f64 = x.iter().zip(y).map(|(a, b)| (a - mx) * (b - my)).sum();
    let sxx: f64 = x.iter().map(|a| (a - mx).powi(2)).sum();
    sxy / sxx
}

/// Runs a spreading spot on `mesh` and returns (fitted variance rate in
/// m²/s, the rate 4 D predicts, linearity: worst relative residual).
fn spread(
    mesh: &Mesh,
    up: Vector3<f64>,
    e1: Vector3<f64>,
    e2: Vector3<f64>,
    mode: DiffusionMode,
) -> (f64, f64, f64) {
    let atlas = Atlas::bake(mesh, BakeOptions::square(512)).unwrap();
    let d = 1e-3;
    let dt = 0.25;
    let diffusion = Diffusion::new(d)
        .with_mode(mode)
        .with_resolution(FieldResolution::VoxelSize(0.04));
    let mut wet = Wetting::new(&atlas, Material::cotton(), Liquid::water())
        .unwrap()
        .with_diffusion(diffusion);
    spot(&atlas, &mut wet, 0.03, up);
    let (env, water) = still();
    let pose = Isometry3::identity();
    let (mut t, mut v) = (Vec::new(), Vec::new());
    for k in 1..=100 {
        wet.step(&atlas, &pose, &water, &env, k as f64 * dt, dt).unwrap();
        if k >= 20 && k % 5 == 0 {
            t.push(k as f64 * dt);
            v.push(variance(&atlas, wet.liquid(), e1, e2));
        }
    }
    let rate = slope(&t, &v);
    let (mt, mv) = (
        t.iter().sum::<f64>() / t.len() as f64,
        v.iter().sum::<f64>() / v.len() as f64,
    );
    let worst = t
        .iter()
        .zip(&v)
        .map(|(ti, vi)| ((mv + rate * (ti - mt)) - vi).abs() / vi)
        .fold(0.0, f64::max);
    (rate, 4.0 * d, worst)
}

#[test]
fn a_spot_on_a_flat_plate_spreads_at_the_predicted_rate() {
    let plate = builtin::cuboid(2.0, 0.002, 2.0);
    let (rate, predicted, worst) = spread(
        &plate,
        Vector3::y(),
        Vector3::x(),
        Vector3::z(),
        DiffusionMode::Conservative,
    );
    eprintln!(
        "flat plate, conservative: variance rate {rate:.4e} m²/s, predicted 4D = {predicted:.4e} ({:+.2} %), linear within {:.2} %",
        100.0 * (rate / predicted - 1.0),
        100.0 * worst
    );
    assert!((rate / predicted - 1.0).abs() < 0.10);
    assert!(worst < 0.02, "variance is not linear in time: {worst}");
}

#[test]
fn the_thesis_scheme_and_a_tilted_plate_are_measured() {
    let plate = builtin::cuboid(2.0, 0.002, 2.0);
    let (rate, predicted, _) = spread(
        &plate,
        Vector3::y(),
        Vector3::x(),
        Vector3::z(),
        DiffusionMode::Thesis,
    );
    eprintln!(
        "flat plate, thesis scheme: variance rate {rate:.4e} m²/s = {:.2} × 4D",
        rate / predicted
    );
    let tilt = nalgebra::Rotation3::from_axis_angle(&Vector3::z_axis(), 30f64.to_radians());
    let tilted = builtin::cuboid(2.0, 0.002, 2.0).map_positions(|p| Point3::from(tilt * p.coords));
    let (rate, predicted, worst) = spread(
        &tilted,
        tilt * Vector3::y(),
        tilt * Vector3::x(),
        Vector3::z(),
        DiffusionMode::Conservative,
    );
    eprintln!(
        "plate tilted 30°, conservative: variance rate {rate:.4e} m²/s = {:.2} × 4D (linear within {:.1} %)",
        rate / predicted,
        100.0 * worst
    );
    // Oblique surfaces cross voxel layers: faster, but the same order.
    assert!(rate / predicted > 0.8 && rate / predicted < 3.0);
}

#[test]
fn with_diffusion_off_nothing_spreads() {
    let atlas = Atlas::bake(&builtin::cuboid(2.0, 0.002, 2.0), BakeOptions::square(128)).unwrap();
    let (env, water) = still();
    for diffusion in [None, Some(Diffusion::new(0.0))] {
        let mut wet = Wetting::new(&atlas, Material::cotton(), Liquid::water()).unwrap();
        wet.set_diffusion(diffusion).unwrap();
        spot(&atlas, &mut wet, 0.2, Vector3::y());
        let before = wet.liquid().to_vec();
        for k in 0..200 {
            let r = wet
                .step(&atlas, &Isometry3::identity(), &water, &env, k as f64, 1.0)
                .unwrap();
            assert!(r.diffusion.is_none());
        }
        assert_eq!(wet.liquid(), &before[..]);
        assert_eq!(wet.field_bytes(), 0);
    }
}
