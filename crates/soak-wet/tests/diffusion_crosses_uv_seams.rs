//! Diffusion runs in 3-D, so it crosses UV seams: a spot on the seam of a
//! cylinder's side chart (at φ = 0, where u jumps from 1 to 0) spreads as
//! symmetrically about its centre as a spot far from the seam (within 5 %).

use std::f64::consts::PI;

use nalgebra::Isometry3;
use soak_bake::{Atlas, BakeOptions, builtin};
use soak_hydro::Water;
use soak_wet::prelude::*;

const RADIUS: f64 = 0.5;

/// Liquid on either side of the arc position of `phi0` (m³) and its arc
/// variance about `phi0` on each side and over both (m²).
fn sides(atlas: &Atlas, h: &[f64], phi0: f64) -> ([f64; 2], [f64; 2], f64) {
    let (mut m, mut v) = ([0.0; 2], [0.0; 2]);
    for (i, &h) in h.iter().enumerate() {
        let p = atlas.position(i);
        let n = atlas.area_vectors().get(i);
        if n[1].abs() > 0.5 * atlas.areas()[i] {
            continue; // caps
        }
        let mut dphi = p.z.atan2(p.x) - phi0;
        dphi = (dphi + PI).rem_euclid(2.0 * PI) - PI;
        let s = RADIUS * dphi;
        let w = h * atlas.areas()[i] as f64;
        let k = usize::from(s > 0.0);
        m[k] += w;
        v[k] += w * s * s;
    }
    (m, [v[0] / m[0], v[1] / m[1]], (v[0] + v[1]) / (m[0] + m[1]))
}

/// Spreads a splash at angle `phi0` (rad) and returns the mass imbalance
/// `(M+ − M−) / (M+ + M−)`, the variance imbalance of the two sides, and
/// the arc variance about `phi0` over both.
fn spread(atlas: &Atlas, phi0: f64) -> (f64, f64, f64) {
    let mut wet = Wetting::new(atlas, Material::cotton(), Liquid::water())
        .unwrap()
        .with_diffusion(Diffusion::new(1e-3).with_resolution(FieldResolution::VoxelSize(0.02)));
    let pose = Isometry3::identity();
    let centre = [RADIUS * phi0.cos(), 0.0, RADIUS * phi0.sin()];
    let stuck = wet
        .splash(
            atlas,
            &pose,
            &Splash {
                center: centre,
                radius: 0.04,
                volume: 1e-7,
            },
        )
        .unwrap();
    assert!((stuck - 1e-7).abs() < 1e-12);
    let env = Environment {
        relative_humidity: 1.0,
        ..Environment::default()
    };
    let water = Water::calm(-10.0);
    for k in 0..60 {
        wet.step(atlas, &pose, &water, &env, k as f64 * 0.25, 0.25)
            .unwrap();
    }
    let (m, v, both) = sides(atlas, wet.liquid(), phi0);
    ((m[1] - m[0]) / (m[1] + m[0]), (v[1] - v[0]) / (v[1] + v[0]), both)
}

#[test]
fn a_spot_on_the_seam_spreads_symmetrically() {
    let atlas = Atlas::bake(&builtin::cylinder(RADIUS, 1.0, 96), BakeOptions::square(512)).unwrap();
    // The seam: the side chart's first and last columns meet at φ = 0.
    let (mass, var, spread_seam) = spread(&atlas, 0.0);
    let (mass_far, var_far, spread_far) = spread(&atlas, PI);
    eprintln!(
        "seam: mass imbalance {:+.2} %, variance imbalance {:+.2} %, arc variance {spread_seam:.4e} m²",
        100.0 * mass,
        100.0 * var
    );
    eprintln!(
        "far from the seam: mass imbalance {:+.2} %, variance imbalance {:+.2} %, arc variance {spread_far:.4e} m²",
        100.0 * mass_far,
        100.0 * var_far
    );
    assert!(mass.abs() < 0.05 && var.abs() < 0.05);
    assert!((spread_seam / spread_far - 1.0).abs() < 0.05);
    // It did spread: the variance grew well past the splash's.
    assert!(spread_seam > 10.0 * 0.04f64.powi(2) / 6.0);
}

#[test]
fn an_off_centre_spot_crosses_the_seam_as_it_would_anywhere() {
    let atlas = Atlas::bake(&builtin::cylinder(RADIUS, 1.0, 96), BakeOptions::square(512)).unwrap();
    // 6 cm off the seam, all of the splash on the φ > 0 side of the chart;
    // its mirror image in x = 0 (φ → π − φ) sees the same voxels, mirrored,
    // and no seam. Both are lopsided the same way (an oblique surface in a
    // Cartesian grid): the seam adds nothing to it.
    let phi0 = 0.06 / RADIUS;
    let (mass, var, spread_seam) = spread(&atlas, phi0);
    let (mass_m, var_m, spread_mirror) = spread(&atlas, PI - phi0);
    eprintln!(
        "6 cm off the seam: mass imbalance {:+.2} %, variance imbalance {:+.2} %; mirrored away from the seam: {:+.2} %, {:+.2} % (sides swap in the mirror); arc variance ratio {:.3}",
        100.0 * mass,
        100.0 * var,
        100.0 * mass_m,
        100.0 * var_m,
        spread_seam / spread_mirror
    );
    assert!((mass + mass_m).abs() < 0.05 && (var + var_m).abs() < 0.05);
    assert!((spread_seam / spread_mirror - 1.0).abs() < 0.05);
}
