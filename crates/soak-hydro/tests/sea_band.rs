//! A band-limited read of a spectral sea ([`SeaBand`]): the band is the sea
//! without its shorter waves (against the sum over the kept modes, with no
//! transform and no interpolation), the band a body reads keeps every wave
//! the cut-off asks for, and a large body reading it stays near the whole
//! sea's answer with fewer nodes.

use nalgebra::{Isometry3, UnitQuaternion, Vector3};
use soak_bake::{Atlas, BakeOptions, builtin};
use soak_hydro::{
    BodyState, HydroError, HydroOptions, MassModel, SeaBand, SeaMode, SeaSpectrum, SpectralSea,
    SpectralSurface, Surface, SurfacePatch, Water, WaterError, evaluate, sampled_water,
};

const G: f64 = 9.80665;

/// A wind sea (Hs 1 m, Tp 5 s: peak wavelength 39 m) on its default tile
/// (312 m) at 128 cells: its shortest wave 4.9 m.
fn wind_sea() -> SpectralSea {
    let spectrum = SeaSpectrum::jonswap(1.0, 5.0);
    SpectralSea::realize(&spectrum, 0.0, spectrum.default_tile(G), 128, 5, G).unwrap()
}

/// The height of the sea whose modes are `modes` (on a tile `size` m
/// across) above rest position `(x0, z0)` at time `t`, by the sum over
/// the modes (choppiness 0: the particle stays above its rest position).
fn summed_height(modes: &[SeaMode], size: f64, x0: f64, z0: f64, t: f64) -> f64 {
    let dk = std::f64::consts::TAU / size;
    modes
        .iter()
        .map(|m| {
            let k = [m.n as f64 * dk, m.l as f64 * dk];
            let omega = (G * k[0].hypot(k[1])).sqrt();
            m.amplitude * (k[0] * x0 + k[1] * z0 - omega * t + m.phase).cos()
        })
        .sum()
}

#[test]
fn a_band_is_the_sea_without_its_shorter_waves() {
    let sea = wind_sea().with_choppiness(0.0).unwrap();
    let size = sea.size;
    for cells in [128, 64, 32, 8] {
        let band = sea.low_pass(cells).unwrap();
        assert_eq!(band.cells, cells);
        // Its modes: exactly the sea's longer than two of its cells.
        let cut = std::f64::consts::PI * cells as f64 / size;
        let dk = std::f64::consts::TAU / size;
        let kept: Vec<SeaMode> = sea
            .sea_modes()
            .into_iter()
            .filter(|m| (m.n as f64 * dk).hypot(m.l as f64 * dk) < cut)
            .collect();
        let mut band_modes = band.sea_modes();
        assert_eq!(band_modes.len(), kept.len(), "{cells} cells");
        band_modes.sort_by_key(|m| (m.n, m.l));
        let mut expected = kept.clone();
        expected.sort_by_key(|m| (m.n, m.l));
        for (a, b) in band_modes.iter().zip(&expected) {
            assert_eq!((a.n, a.l), (b.n, b.l));
            assert!((a.amplitude - b.amplitude).abs() < 1e-15 && (a.phase - b.phase).abs() < 1e-12);
        }
        // At its nodes (no interpolation) the band's surface is the sum over
        // the kept modes.
        let surface = SpectralSurface::new(band);
        let d = size / cells as f64;
        let t = 3.7;
        let mut worst: f64 = 0.0;
        for iz in 0..cells.min(16) {
            for ix in 0..cells.min(16) {
                let (x, z) = (ix as f64 * d, iz as f64 * d);
                worst = worst.max((surface.height(x, z, t) - summed_height(&kept, size, x, z, t)).abs());
            }
        }
        assert!(worst < 1e-12, "{cells} cells: {worst:e} m at the nodes");
        // Its shortest wave is two of its cells.
        assert!((surface.sampling_length(t).unwrap() - 2.0 * d).abs() < 1e-12);
    }
    // A finer grid than the sea's, or one off the powers of two, is a
    // typed error.
    for cells in [256, 48, 4] {
        assert!(matches!(
            sea.low_pass(cells),
            Err(WaterError::Parameter {
                name: "band cells",
                ..
            })
        ));
    }
}

#[test]
fn the_band_read_keeps_every_wave_asked_for() {
    let surface = SpectralSurface::new(wind_sea());
    let shortest = surface.sampling_length(0.0).unwrap();
    // Shorter than twice the tile's shortest wave: the whole sea.
    assert_eq!(surface.band_level(1.99 * shortest), 0);
    assert!(surface.band_limited(1.99 * shortest).is_none());
    assert!(surface.band_limited(f64::INFINITY).is_none());
    // Otherwise the coarsest band whose shortest wave is at most the one
    // asked for: it keeps every wave that long, and drops none shorter
    // than half of it.
    for (wavelength, level) in [
        (2.0, 1),
        (3.99, 1),
        (4.0, 2),
        (7.9, 2),
        (8.0, 3),
        (15.9, 3),
        (1e3, 4),
    ] {
        assert_eq!(surface.band_level(wavelength * shortest), level, "{wavelength}");
        let band = surface.band_limited(wavelength * shortest).unwrap();
        let band_shortest = band.sampling_length(0.0).unwrap();
        assert!(band_shortest <= wavelength * shortest);
        assert!((band_shortest - shortest * (1u32 << level) as f64).abs() < 1e-9);
    }
    // The band is built once and kept.
    let a = surface.band(2).unwrap() as *const SpectralSurface;
    let b = surface.band(2).unwrap() as *const SpectralSurface;
    assert_eq!(a, b);
    assert!(surface.band(0).is_none() && surface.band(5).is_none());
}

#[test]
fn a_large_body_reads_the_band_long_against_it() {
    // A 10 m barge on the wind sea: its bounding diameter 11.5 m, about
    // twice the sea's shortest wave.
    let mesh = builtin::cuboid(10.0, 3.0, 4.0);
    let atlas = Atlas::bake(&mesh, BakeOptions::square(128)).unwrap();
    let mass = MassModel::Solid { density: 500.0 }
        .mass_properties(&atlas)
        .unwrap();
    let diameter = 2.0 * atlas.bounding_radius();
    let water = Water::new(SpectralSurface::new(wind_sea()));
    let weight = water.density * water.gravity * mesh.volume();
    let whole = HydroOptions::default();
    let tile = SeaSpectrum::jonswap(1.0, 5.0).default_tile(G);
    let mut errors = Vec::new();
    for (ratio, level) in [(1.0, 1), (2.0, 2), (4.0, 3)] {
        let band = HydroOptions {
            sea_band: SeaBand::BodyLengths(ratio),
            ..HydroOptions::default()
        };
        let mut worst = [0.0f64; 3];
        for k in 0..6 {
            let k = k as f64;
            let pose = Isometry3::from_parts(
                Vector3::new(17.0 * k, -0.2 + 0.1 * k, -11.0 * k).into(),
                UnitQuaternion::from_euler_angles(0.05, 0.7 * k, -0.04),
            );
            let state = BodyState::at_rest(pose);
            let t = 2.3 * k;
            // The band's patch: nodes as far apart as its shortest wave asks.
            let sampled = sampled_water(&atlas, &water, &state, t, &band).unwrap().unwrap();
            let patch = sampled
                .surface
                .as_any()
                .and_then(|s| s.downcast_ref::<SurfacePatch>())
                .unwrap();
            let expected = 2.0 * tile / 128.0 * (1u32 << level) as f64 / 16.0;
            assert!(
                (patch.spacing() - expected).abs() < 1e-9,
                "ratio {ratio}: spacing {} for {expected}",
                patch.spacing()
            );
            let w = evaluate(&atlas, &water, &state, &mass, t, &whole).unwrap();
            let b = evaluate(&atlas, &water, &state, &mass, t, &band).unwrap();
            assert!(w.submerged_volume > 0.1 * mesh.volume());
            worst[0] = worst[0].max((w.submerged_volume - b.submerged_volume).abs() / mesh.volume());
            worst[1] = worst[1].max((w.buoyancy.force - b.buoyancy.force).norm() / weight);
            worst[2] = worst[2].max((w.buoyancy.torque - b.buoyancy.torque).norm() / (weight * diameter));
        }
        println!(
            "{ratio} body lengths (band {level}: waves under {:.2} body lengths dropped): volume {:.1e} of the barge's, force {:.1e} of its displacement's weight, torque {:.1e} of that times its diameter",
            2.0 * tile / 128.0 * (1u32 << level) as f64 / diameter,
            worst[0],
            worst[1],
            worst[2]
        );
        errors.push(worst);
    }
    // Waves shorter than the barge barely move it; the more of the waves
    // as long as it that are dropped, the further from the whole sea.
    assert!(errors[0].iter().all(|&e| e < 1e-2), "{errors:?}");
    assert!(
        (0..2).all(|i| errors[0][i] < errors[1][i] && errors[1][i] < errors[2][i]),
        "{errors:?}"
    );
    // A ratio that is not finite and positive is named.
    for ratio in [0.0, -1.0, f64::NAN] {
        let bad = HydroOptions {
            sea_band: SeaBand::BodyLengths(ratio),
            ..HydroOptions::default()
        };
        let state = BodyState::at_rest(Isometry3::identity());
        assert!(matches!(
            evaluate(&atlas, &water, &state, &mass, 0.0, &bad),
            Err(HydroError::Water(WaterError::Parameter {
                name: "sea band body lengths",
                ..
            }))
        ));
    }
}
