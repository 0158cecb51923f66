//! In the conservative mode total liquid changes only by what absorption
//! added and evaporation removed, to 1e-6 relative after 10,000 steps; the
//! thesis scheme's drift on the same run is measured and printed.

use nalgebra::{Isometry3, UnitQuaternion, Vector3};
use soak_bake::{Atlas, BakeOptions, builtin};
use soak_hydro::Water;
use soak_wet::prelude::*;

struct Outcome {
    total: f64,
    ledger: soak_wet::Ledger,
    absorbed: f64,
    evaporated: f64,
}

/// A cube bobbing and rolling through the water line for 10,000 steps of
/// 0.05 s: absorption below, evaporation above, diffusion everywhere.
fn run(mode: DiffusionMode) -> Outcome {
    let atlas = Atlas::bake(&builtin::cuboid(1.0, 1.0, 1.0), BakeOptions::square(128)).unwrap();
    let liquid = Liquid {
        evaporation_rate: 1e7,
        ..Liquid::water()
    };
    let mut wet = Wetting::new(&atlas, Material::sand(), liquid)
        .unwrap()
        .with_diffusion(
            Diffusion::new(5e-3)
                .with_mode(mode)
                .with_resolution(FieldResolution::Cells(16)),
        );
    let water = Water::calm(0.0);
    let env = Environment::default();
    let dt = 0.05;
    for k in 0..10_000 {
        let t = k as f64 * dt;
        let pose = Isometry3::from_parts(
            Vector3::new(0.0, 0.45 * (0.13 * t).sin(), 0.0).into(),
            UnitQuaternion::from_euler_angles(0.4 * (0.07 * t).sin(), 0.02 * t, 0.0),
        );
        wet.step(&atlas, &pose, &water, &env, t, dt).unwrap();
        if k % 1000 == 0 {
            let sat = wet.material().saturation;
            assert!(wet.liquid().iter().all(|&h| (0.0..=sat).contains(&h)));
        }
    }
    let l = *wet.ledger();
    Outcome {
        total: wet.total_liquid(&atlas),
        ledger: l,
        absorbed: l.absorbed,
        evaporated: l.evaporated,
    }
}

#[test]
fn conservative_mode_conserves_liquid_over_ten_thousand_steps() {
    let c = run(DiffusionMode::Conservative);
    let error = (c.total - c.ledger.net()).abs() / c.total;
    eprintln!(
        "conservative: total {:.6e} m³, absorbed {:.6e}, evaporated {:.6e}, |total − (absorbed − evaporated)| / total = {error:.2e}",
        c.total, c.absorbed, c.evaporated
    );
    assert!(
        c.absorbed > 10.0 * c.total,
        "the run exchanges much more liquid than it keeps"
    );
    assert!(c.evaporated > 0.5 * c.absorbed);
    assert_eq!(c.ledger.drift, 0.0);
    assert!(error < 1e-6, "{error}");

    let t = run(DiffusionMode::Thesis);
    let balance = t.absorbed - t.evaporated;
    eprintln!(
        "thesis: total {:.6e} m³, absorbed − evaporated {:.6e}, drift {:+.6e} m³ = {:+.2} % of the total ({:+.2} % of the absorbed volume)",
        t.total,
        balance,
        t.ledger.drift,
        100.0 * t.ledger.drift / t.total,
        100.0 * t.ledger.drift / t.absorbed
    );
    // The ledger books the thesis scheme's error as drift: it still adds up.
    assert!((t.total - t.ledger.net()).abs() / t.total < 1e-6);
}
