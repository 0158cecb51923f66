//! A saved wetting state restores exactly: stepping the restored state and
//! the original gives bit-identical liquid (the field's binning, skipped by
//! serde, is rebuilt from the atlas); the same holds for a shared field.

use nalgebra::Isometry3;
use soak_bake::{Atlas, BakeOptions, builtin};
use soak_hydro::{Gerstner, GerstnerWave, Water};
use soak_wet::prelude::*;

#[test]
fn a_restored_state_continues_bit_for_bit() {
    let atlas = Atlas::bake(&builtin::sphere(0.5, 32, 16), BakeOptions::square(128)).unwrap();
    let sea = Gerstner::new(
        0.0,
        vec![GerstnerWave {
            amplitude: 0.1,
            wavelength: 3.0,
            direction_deg: 20.0,
            steepness: 0.5,
            phase: 0.0,
        }],
        9.81,
    )
    .unwrap();
    let water = Water::new(sea);
    let env = Environment {
        rain: Rain::mm_per_hour(50.0).over(Region::Disc {
            center: [0.2, 0.0],
            radius: 0.3,
        }),
        ..Environment::default()
    };
    for mode in [DiffusionMode::Conservative, DiffusionMode::Thesis] {
        let mut a = Wetting::new(&atlas, Material::sand(), Liquid::water())
            .unwrap()
            .with_diffusion(Diffusion::new(1e-3).with_mode(mode));
        let pose = |t: f64| Isometry3::translation(0.0, 0.2 * t.sin(), 0.0);
        for k in 0..30 {
            let t = 0.1 * k as f64;
            a.step(&atlas, &pose(t), &water, &env, t, 0.1).unwrap();
        }
        let saved = serde_json::to_string(&a).unwrap();
        let mut b: Wetting = serde_json::from_str(&saved).unwrap();
        assert_eq!(a.liquid(), b.liquid());
        assert_eq!(b.field_bytes(), 0, "the binning is not saved");
        for k in 30..60 {
            let t = 0.1 * k as f64;
            a.step(&atlas, &pose(t), &water, &env, t, 0.1).unwrap();
            b.step(&atlas, &pose(t), &water, &env, t, 0.1).unwrap();
        }
        assert!(a.total_liquid(&atlas) > 0.0);
        assert_eq!(a.liquid(), b.liquid(), "{mode:?}");
        assert_eq!(a.ledger(), b.ledger());
    }
}

#[test]
fn settings_round_trip_through_json() {
    let d = Diffusion::new(2e-3)
        .with_mode(DiffusionMode::Thesis)
        .with_resolution(FieldResolution::Cells(48));
    let back: Diffusion = serde_json::from_str(&serde_json::to_string(&d).unwrap()).unwrap();
    assert_eq!(back, d);
    let env = Environment {
        rain: Rain::mm_per_hour(2.0).over(Region::Box {
            min: [0.0; 3],
            max: [1.0; 3],
        }),
        ..Environment::default()
    };
    let back: Environment = serde_json::from_str(&serde_json::to_string(&env).unwrap()).unwrap();
    assert_eq!(back, env);
    let track = EnvironmentTrack::new(vec![(0.0, env), (10.0, Environment::default())]).unwrap();
    let back: EnvironmentTrack = serde_json::from_str(&serde_json::to_string(&track).unwrap()).unwrap();
    assert_eq!(back, track);
    // Defaults for omitted keys.
    let d: Diffusion = serde_json::from_str(r#"{"coefficient": 1e-3}"#).unwrap();
    assert_eq!(d, Diffusion::new(1e-3));
}
