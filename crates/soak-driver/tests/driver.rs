//! The driver on its own engine ([`FreeBodies`]): bodies float at their
//! analytic draft, a body the engine lost is handled, a retired body costs
//! nothing and stays retired through a save, a body reading a band of a
//! sea's waves is taken as dry only above that band's crest, a body may
//! read a sea otherwise than the others, a step's phases are timed, bodies
//! sharing an atlas have their own mass model's mass.

use std::sync::Arc;

use nalgebra::Isometry3;
use soak_bake::{Atlas, BakeOptions, builtin};
use soak_driver::{BodyDesc, Driver, Effects, FreeBodies, FreeHandle, SoakError, StepParams};
use soak_hydro::{Drag, MassModel, SeaBand, SeaSampling, SeaSpectrum, SpectralSea, SpectralSurface, Water};

const STEP: StepParams = StepParams {
    dt: 1.0 / 60.0,
    substeps: 4,
};

fn crate_atlas() -> Arc<Atlas> {
    Arc::new(Atlas::bake(&builtin::cuboid(1.0, 0.6, 0.8), BakeOptions::square(64)).unwrap())
}

fn desc(name: &str, atlas: &Arc<Atlas>, density: f64) -> BodyDesc {
    BodyDesc {
        name: name.into(),
        atlas: atlas.clone(),
        mass_model: MassModel::Solid { density },
        effects: Effects::buoyancy().with_drag(Drag {
            coefficient: 1.0,
            linear: 200.0,
        }),
    }
}

/// Standard gravity, m/s².
const G: f64 = 9.80665;

/// A JONSWAP sea of significant height `hs` (m) and peak period `tp` (s) on
/// its default tile of `cells` a side, from `seed`.
fn jonswap(hs: f64, tp: f64, cells: usize, seed: u64) -> Water {
    let spectrum = SeaSpectrum::jonswap(hs, tp);
    let sea = SpectralSea::realize(&spectrum, 0.0, spectrum.default_tile(G), cells, seed, G).unwrap();
    Water::new(SpectralSurface::new(sea))
}

fn run(soak: &mut Driver<FreeHandle>, engine: &mut FreeBodies, steps: usize) {
    for _ in 0..steps {
        soak.before_step(engine, &STEP).unwrap();
        engine.step(&STEP);
        soak.after_step(STEP.dt);
    }
}

/// Crates of 250, 500 and 750 kg/m³ float with a quarter, half and three
/// quarters of their 0.6 m height under water.
#[test]
fn crates_float_at_their_analytic_drafts() {
    let atlas = crate_atlas();
    let mut engine = FreeBodies::new(9.81);
    let mut soak = Driver::new(Water::calm(0.0));
    let ids: Vec<_> = [250.0, 500.0, 750.0]
        .iter()
        .enumerate()
        .map(|(k, &rho)| {
            let h = engine.insert(Isometry3::translation(3.0 * k as f64, 0.4, 0.0));
            soak.register(&mut engine, h, desc("crate", &atlas, rho)).unwrap()
        })
        .collect();
    run(&mut soak, &mut engine, 1800);
    for (id, rho) in ids.into_iter().zip([250.0, 500.0, 750.0]) {
        let draft = soak.draft(id, &engine).unwrap();
        let want = 0.6 * rho / 1000.0;
        assert!(
            (draft - want).abs() < 1e-3,
            "{rho} kg/m³: draft {draft} m, want {want}"
        );
    }
}

/// Bodies sharing an atlas (one `Arc`) have their own mass model's mass
/// properties: each is what a body given its own copy of the atlas gets
/// (a 1 × 0.6 × 0.8 m crate: 120 kg at 250 kg/m³, 240 kg at 500), a shell
/// on the shared atlas its shell's, and a bad model is refused on a shared
/// atlas as on a new one.
#[test]
fn bodies_sharing_an_atlas_have_their_own_models_mass() {
    let atlas = crate_atlas();
    let copy = Arc::new(Atlas::clone(&atlas));
    let mut engine = FreeBodies::new(9.81);
    let mut soak = Driver::new(Water::calm(0.0));
    let mut add = |name: &str, atlas: &Arc<Atlas>, model: MassModel| {
        let h = engine.insert(Isometry3::translation(0.0, 0.3, 0.0));
        let mut d = desc(name, atlas, 500.0);
        d.mass_model = model;
        soak.register(&mut engine, h, d)
    };
    let solid = |density| MassModel::Solid { density };
    let shell = MassModel::Shell { areal_density: 20.0 };
    let ids = [
        add("a", &atlas, solid(500.0)).unwrap(),
        add("b", &atlas, solid(250.0)).unwrap(),
        add("c", &atlas, solid(500.0)).unwrap(),
        add("d", &atlas, shell.clone()).unwrap(),
        add("a copy", &copy, solid(500.0)).unwrap(),
        add("b copy", &copy, solid(250.0)).unwrap(),
        add("d copy", &copy, shell).unwrap(),
    ];
    let e = add("bad", &atlas, solid(-1.0)).unwrap_err();
    assert!(
        matches!(&e, SoakError::Hydro { name, .. } if name == "bad"),
        "{e}"
    );
    let mass = |k: usize| *soak.body(ids[k]).unwrap().mass_properties();
    for (k, copy) in [(0, 4), (1, 5), (2, 4), (3, 6)] {
        assert_eq!(mass(k), mass(copy), "body {k}");
    }
    for (k, want) in [(0, 240.0), (1, 120.0)] {
        let m = mass(k).mass;
        assert!((m - want).abs() < 1e-3 * want, "body {k}: {m} kg, want {want}");
    }
    // The shell: 20 kg/m² over the crate's 3.76 m².
    let m = mass(3).mass;
    assert!((m - 75.2).abs() < 1e-2 * 75.2, "shell {m} kg");
}

/// A body the engine no longer has: the step passes over it (no force is
/// handed to anything), its draft is unknown, a registration of a handle
/// the engine never had is refused by name.
#[test]
fn a_body_the_engine_lost_is_passed_over() {
    let atlas = crate_atlas();
    let mut engine = FreeBodies::new(9.81);
    let mut soak = Driver::new(Water::calm(0.0));
    let (a, b) = (
        engine.insert(Isometry3::translation(0.0, 0.3, 0.0)),
        engine.insert(Isometry3::translation(3.0, 0.3, 0.0)),
    );
    let ia = soak.register(&mut engine, a, desc("a", &atlas, 500.0)).unwrap();
    let ib = soak.register(&mut engine, b, desc("b", &atlas, 500.0)).unwrap();
    run(&mut soak, &mut engine, 60);
    engine.remove(a);
    run(&mut soak, &mut engine, 600);
    assert_eq!(soak.draft(ia, &engine), None);
    let draft = soak.draft(ib, &engine).unwrap();
    assert!((draft - 0.3).abs() < 2e-3, "draft {draft}");
    let e = soak
        .register(&mut engine, FreeHandle(99), desc("ghost", &atlas, 500.0))
        .unwrap_err();
    assert!(
        matches!(&e, SoakError::MissingBody { name } if name == "ghost"),
        "{e}"
    );
    assert!(soak.firewall().count() == 0);
}

/// A retired body: nothing is evaluated or handed to the engine for it,
/// its id stays taken, and a saved state restores it retired.
#[test]
fn a_retired_body_costs_nothing_and_stays_retired() {
    let atlas = crate_atlas();
    let mut engine = FreeBodies::new(9.81);
    let mut soak = Driver::new(Water::calm(0.0));
    let h = engine.insert(Isometry3::translation(0.0, 0.3, 0.0));
    let id = soak
        .register(&mut engine, h, desc("crate", &atlas, 500.0))
        .unwrap();
    run(&mut soak, &mut engine, 30);
    assert!(soak.body(id).unwrap().submerged_volume() > 0.0);
    soak.retire(id, &mut engine).unwrap();
    run(&mut soak, &mut engine, 30);
    let b = soak.body(id).unwrap();
    assert!(b.is_retired());
    assert_eq!(b.submerged_volume(), 0.0);
    assert!(!b.effects().needs_hydrostatics());
    // The engine was handed no force since: the body falls freely.
    assert_eq!(engine.wrench(h).unwrap().force, nalgebra::Vector3::zeros());
    // Saved and restored into a fresh driver with the same body, it is
    // retired there too.
    let state = soak.state();
    let mut again = Driver::new(Water::calm(0.0));
    let mut engine2 = FreeBodies::new(9.81);
    let h2 = engine2.insert(Isometry3::translation(0.0, 0.3, 0.0));
    let id2 = again
        .register(&mut engine2, h2, desc("crate", &atlas, 500.0))
        .unwrap();
    again.restore_state(&state).unwrap();
    assert!(again.body(id2).unwrap().is_retired());
    assert_eq!(again.state(), state);
    assert!(matches!(
        soak.retire(soak_driver::SoakId(7), &mut engine),
        Err(SoakError::UnknownId(7))
    ));
}

/// A body that reads a band of a spectral sea's waves (the waves under 20 m
/// dropped) is skipped as dry only above the band's highest crest, which
/// stands above the whole sea's here (its cells are four times as wide, and
/// the bound on its interpolant's overshoot with them): between the two
/// crests it is evaluated, above both it is skipped.
#[test]
fn a_body_reading_a_band_is_dry_only_above_the_bands_crest() {
    let atlas = crate_atlas();
    let g = G;
    let wind_sea = || jonswap(1.0, 5.0, 128, 0);
    let water = wind_sea();
    let radius = atlas.bounding_radius();
    let band = SeaBand::BodyLengths(20.0 / (2.0 * radius));
    let wavelength = band.wavelength(radius).unwrap().unwrap();
    let whole = water.surface.height_bounds(0.0).unwrap().1;
    let crest = water
        .surface
        .band_limited(wavelength)
        .expect("a band of the sea")
        .height_bounds(0.0)
        .unwrap()
        .1;
    assert!(
        crest > whole + 0.05,
        "the band's crest {crest} m, the sea's {whole} m"
    );
    for (lowest, dry) in [(0.5 * (whole + crest), false), (crest + 0.05, true)] {
        let mut engine = FreeBodies::new(g);
        let mut soak = Driver::new(wind_sea()).with_sea_band(band);
        let y = lowest + radius - atlas.origin().y;
        let h = engine.insert(Isometry3::translation(0.0, y, 0.0));
        let id = soak
            .register(&mut engine, h, desc("crate", &atlas, 500.0))
            .unwrap();
        soak.before_step(&mut engine, &STEP).unwrap();
        let skips = soak.body(id).unwrap().dry_skips();
        assert_eq!(
            skips,
            u64::from(dry),
            "lowest point {lowest} m: {skips} dry skips"
        );
    }
}

/// On a spectral sea, a crate reading it as the generator does (sampled
/// over its footprint) and one reading it as one plane
/// ([`Effects::with_sea_sampling`]) move, step by step and to the bit, as
/// each would alone in a generator reading every body its way; and the two
/// reads differ (the plane drops the surface's curvature over the hull).
#[test]
fn a_body_reads_the_sea_its_own_way() {
    let atlas = crate_atlas();
    let g = G;
    let sea = || jonswap(1.0, 4.0, 64, 3);
    let places = [
        Isometry3::translation(0.0, 0.05, 0.0),
        Isometry3::translation(4.0, 0.05, 1.0),
    ];
    // Each crate's pose over 90 steps, in a generator made by `make` with
    // the crates `which` (each with its own read or none).
    let poses = |make: &dyn Fn() -> Driver<FreeHandle>, which: &[(usize, Option<SeaSampling>)]| {
        let mut engine = FreeBodies::new(g);
        let mut soak = make();
        let handles: Vec<_> = which
            .iter()
            .map(|&(k, read)| {
                let h = engine.insert(places[k]);
                let mut d = desc("crate", &atlas, 500.0);
                if let Some(read) = read {
                    d.effects = d.effects.with_sea_sampling(read);
                }
                soak.register(&mut engine, h, d).unwrap();
                h
            })
            .collect();
        let mut out = vec![Vec::new(); which.len()];
        for _ in 0..90 {
            soak.before_step(&mut engine, &STEP).unwrap();
            engine.step(&STEP);
            soak.after_step(STEP.dt);
            for (o, h) in out.iter_mut().zip(&handles) {
                o.push(engine.get(*h).unwrap().pose);
            }
        }
        out
    };
    let mixed = poses(
        &|| Driver::new(sea()),
        &[(0, None), (1, Some(SeaSampling::Plane))],
    );
    let sampled = poses(&|| Driver::new(sea()), &[(0, None)]);
    let planes = poses(
        &|| Driver::new(sea()).with_sea_sampling(SeaSampling::Plane),
        &[(1, None)],
    );
    assert_eq!(mixed[0], sampled[0], "the sampled crate");
    assert_eq!(mixed[1], planes[0], "the crate read as planes");
    // The same crate at the second place, sampled: another path.
    let other = poses(&|| Driver::new(sea()), &[(1, None)]);
    let apart = mixed[1]
        .iter()
        .zip(&other[0])
        .map(|(a, b)| (a.translation.vector - b.translation.vector).norm())
        .fold(0.0, f64::max);
    assert!(apart > 1e-6, "the plane read and the sampled one {apart} m apart");
    // And the other way round: a crate sampled among bodies read as planes.
    let flipped = poses(
        &|| Driver::new(sea()).with_sea_sampling(SeaSampling::Plane),
        &[
            (
                0,
                Some(SeaSampling::PerWavelength(SeaSampling::DEFAULT_PER_WAVELENGTH)),
            ),
            (1, None),
        ],
    );
    assert_eq!(flipped[0], sampled[0]);
    assert_eq!(flipped[1], planes[0]);
}

/// A body's own read of a sea with no nodes per wavelength is refused at
/// registration, naming the body and the setting.
#[test]
fn a_bodys_sea_read_is_checked_when_it_is_registered() {
    let atlas = crate_atlas();
    let mut engine = FreeBodies::new(9.81);
    let mut soak = Driver::new(Water::calm(0.0));
    for per in [0.0, -1.0, f64::NAN, f64::INFINITY] {
        let h = engine.insert(Isometry3::identity());
        let mut d = desc("skiff", &atlas, 500.0);
        d.effects = d.effects.with_sea_sampling(SeaSampling::PerWavelength(per));
        let e = soak.register(&mut engine, h, d).unwrap_err();
        assert!(
            matches!(e, SoakError::Hydro { ref name, .. } if name == "skiff"),
            "{e:?}"
        );
        assert!(e.to_string().contains("sea samples per wavelength"), "{e}");
    }
    assert!(soak.bodies().is_empty());
    // The driver's own read, for a body that takes it: refused on that
    // body's registration, not left to fail at every step; a body reading
    // the sea its own way is not held to it.
    let mut soak = Driver::new(Water::calm(0.0)).with_sea_sampling(SeaSampling::PerWavelength(-4.0));
    let h = engine.insert(Isometry3::identity());
    let e = soak
        .register(&mut engine, h, desc("skiff", &atlas, 500.0))
        .unwrap_err();
    assert!(
        matches!(e, SoakError::Hydro { ref name, .. } if name == "skiff"),
        "{e:?}"
    );
    assert!(e.to_string().contains("sea samples per wavelength"), "{e}");
    let mut d = desc("raft", &atlas, 500.0);
    d.effects = d.effects.with_sea_sampling(SeaSampling::Plane);
    soak.register(&mut engine, h, d).unwrap();
    assert_eq!(soak.bodies().len(), 1);
}

/// The phases of a step are zero before the first and sum to the step's
/// `apply` after it: the bodies' evaluations take time, and `apply` takes
/// no less than its phases.
#[test]
fn a_steps_phases_are_timed() {
    let atlas = crate_atlas();
    let mut engine = FreeBodies::new(9.81);
    let mut soak = Driver::new(Water::calm(0.0));
    for k in 0..8 {
        let h = engine.insert(Isometry3::translation(3.0 * k as f64, 0.0, 0.0));
        soak.register(&mut engine, h, desc("crate", &atlas, 500.0))
            .unwrap();
    }
    assert_eq!(soak.last_step_phases(), soak_driver::StepPhases::default());
    let start = std::time::Instant::now();
    soak.apply(&mut engine, &STEP);
    let elapsed = start.elapsed();
    let p = soak.last_step_phases();
    assert!(p.evaluate > std::time::Duration::ZERO, "{p:?}");
    assert!(p.total() <= elapsed, "{p:?} against {elapsed:?}");
    assert_eq!(p.total(), p.predict + p.prepare + p.evaluate + p.hand + p.engine);
}
