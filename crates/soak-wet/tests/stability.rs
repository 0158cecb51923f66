//! Any diffusion coefficient and time step keep the liquid non-negative,
//! bounded by saturation and (conservative mode) conserved: substepping at
//! 100× the explicit limit, and random coefficients, steps and textures.

use nalgebra::Isometry3;
use proptest::prelude::*;
use soak_bake::{Atlas, BakeOptions, builtin};
use soak_hydro::Water;
use soak_wet::prelude::*;

fn humid() -> Environment {
    Environment {
        relative_humidity: 1.0,
        ..Environment::default()
    }
}

fn atlas() -> Atlas {
    Atlas::bake(&builtin::sphere(0.5, 24, 12), BakeOptions::square(64)).unwrap()
}

/// A checkerboard of saturated and dry texels: the hardest input for an
/// explicit kernel.
fn checker(atlas: &Atlas, sat: f64) -> Vec<f64> {
    atlas
        .texels()
        .iter()
        .map(|t| if (t[0] / 3 + t[1] / 3) % 2 == 0 { sat } else { 0.0 })
        .collect()
}

#[test]
fn substeps_hold_the_kernel_stable_at_100x_the_explicit_limit() {
    let atlas = atlas();
    for mode in [DiffusionMode::Conservative, DiffusionMode::Thesis] {
        let voxel = 0.1;
        let mut wet = Wetting::new(&atlas, Material::cotton(), Liquid::water())
            .unwrap()
            .with_diffusion(
                Diffusion::new(1.0)
                    .with_mode(mode)
                    .with_resolution(FieldResolution::VoxelSize(voxel)),
            );
        let sat = wet.material().saturation;
        wet.set_liquid(&atlas, checker(&atlas, sat)).unwrap();
        let before = wet.total_liquid(&atlas);
        // Probe Count_max with a tiny step, then take a step 100× the limit:
        // W · Count_max = 100, W = D dt / (3 Δx²).
        let r = wet
            .step(
                &atlas,
                &Isometry3::identity(),
                &Water::calm(-10.0),
                &humid(),
                0.0,
                1e-9,
            )
            .unwrap();
        let count = r.diffusion.unwrap().count_max as f64;
        let dt = 100.0 * 3.0 * voxel * voxel / count;
        let r = wet
            .step(
                &atlas,
                &Isometry3::identity(),
                &Water::calm(-10.0),
                &humid(),
                0.0,
                dt,
            )
            .unwrap();
        let plan = r.diffusion.unwrap().plan;
        assert_eq!(plan.substeps, 100, "{mode:?}");
        assert!(plan.weight * count <= 1.0 + 1e-12);
        assert!(!plan.limited);
        assert!(wet.liquid().iter().all(|&h| (0.0..=sat).contains(&h)), "{mode:?}");
        let after = wet.total_liquid(&atlas);
        if mode == DiffusionMode::Conservative {
            assert!(
                (after - before).abs() / before < 1e-12,
                "{}",
                (after - before) / before
            );
        }
        eprintln!(
            "{mode:?}: 100 substeps at w·Count = {:.3}, total {before:.6e} → {after:.6e} m³",
            plan.weight * count
        );
    }
}

#[test]
fn beyond_the_substep_budget_the_rate_is_capped_not_the_stability() {
    let atlas = atlas();
    let mut wet = Wetting::new(&atlas, Material::cotton(), Liquid::water())
        .unwrap()
        .with_diffusion(Diffusion::new(1e9).with_resolution(FieldResolution::VoxelSize(0.1)));
    let sat = wet.material().saturation;
    wet.set_liquid(&atlas, checker(&atlas, sat)).unwrap();
    let before = wet.total_liquid(&atlas);
    let r = wet
        .step(
            &atlas,
            &Isometry3::identity(),
            &Water::calm(-10.0),
            &humid(),
            0.0,
            1e6,
        )
        .unwrap();
    let plan = r.diffusion.unwrap().plan;
    assert!(plan.limited);
    assert_eq!(plan.substeps, 1024);
    assert!(wet.liquid().iter().all(|&h| (0.0..=sat).contains(&h)));
    assert!((wet.total_liquid(&atlas) - before).abs() / before < 1e-12);
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(24))]

    #[test]
    fn liquid_stays_in_bounds_for_any_coefficient_and_step(
        log_d in -8.0f64..4.0,
        log_dt in -3.0f64..3.0,
        thesis in any::<bool>(),
        level in -0.6f64..0.6,
        seed in 0u64..1000,
        rain in 0.0f64..1e-3,
    ) {
        let atlas = atlas();
        let mode = if thesis { DiffusionMode::Thesis } else { DiffusionMode::Conservative };
        let mut wet = Wetting::new(&atlas, Material::sand(), Liquid::water())
            .unwrap()
            .with_diffusion(Diffusion::new(10f64.powf(log_d)).with_mode(mode).with_resolution(FieldResolution::Cells(12)));
        let sat = wet.material().saturation;
        let h: Vec<f64> = (0..atlas.len())
            .map(|i| {
                let x = (i as u64).wrapping_mul(6364136223846793005).wrapping_add(seed.wrapping_mul(1442695040888963407));
                sat * ((x >> 33) % 1000) as f64 / 999.0
            })
            .collect();
        wet.set_liquid(&atlas, h).unwrap();
        let env = Environment { rain: Rain { rate: rain, region: Region::Everywhere }, ..Environment::default() };
        let dt = 10f64.powf(log_dt);
        for k in 0..3 {
            wet.step(&atlas, &Isometry3::identity(), &Water::calm(level), &env, k as f64 * dt, dt).unwrap();
            prop_assert!(wet.liquid().iter().all(|&h| h.is_finite() && (0.0..=sat).contains(&h)));
        }
        let total = wet.total_liquid(&atlas);
        prop_assert!((total - wet.ledger().net()).abs() <= 1e-9 * (1.0 + wet.ledger().absorbed + total));
    }
}
