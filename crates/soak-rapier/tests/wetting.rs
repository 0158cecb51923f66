//! Wetting in the force generator and in scene files.
//!
//! - a floating body soaks up water only through texels that were under
//!   water (or, with diffusion, on texels the diffusion reached from them),
//!   never below 0 nor above saturation;
//! - in the conservative mode the liquid changes exactly by what was
//!   absorbed minus what evaporated;
//! - a body without wetting holds no wetting state at all;
//! - the wet crate scene loads, runs, saves its liquid, writes PNGs, and
//!   its liquid totals after fixed step counts are snapshotted;
//! - bad wetting and environment values name the file and the key.
//!
//! One file on purpose: the generator and scene cases share the fixtures
//! and the liquid checks defined here.

use std::path::{Path, PathBuf};

use rapier3d::prelude::*;
use soak_bake::{Atlas, BakeOptions, builtin};
use soak_hydro::{Drag, Gerstner, GerstnerWave, MassModel, Water};
use soak_rapier::soak_wet::{Diffusion, DiffusionMode, Environment, Liquid, Material, Wetting};
use soak_rapier::{BodyDesc, Effects, ForceGenerator, LoadedScene, SceneError, Simulation, SoakId};

fn data(name: &str) -> PathBuf {
    [env!("CARGO_MANIFEST_DIR"), "..", "..", "data", name]
        .iter()
        .collect()
}

/// A time-lapse liquid: water that evaporates 1000× faster (as the
/// beach example's), so drying shows within seconds.
fn time_lapse() -> Liquid {
    Liquid {
        evaporation_rate: 1e7,
        ..Liquid::water()
    }
}

/// Weathered wood, ten times as permeable as fresh-sawn.
fn weathered_wood() -> Material {
    Material {
        permeability: 1e-12,
        ..Material::wood()
    }
}

fn swell() -> Water {
    Water::new(
        Gerstner::new(
            0.0,
            vec![GerstnerWave {
                amplitude: 0.12,
                wavelength: 4.0,
                direction_deg: 0.0,
                steepness: 0.5,
                phase: 0.0,
            }],
            9.81,
        )
        .unwrap(),
    )
}

/// A 1 m box of density 500 floating in `water`, its wetting set by `wet`.
fn floating_box(
    water: Water,
    wet: impl FnOnce(&Atlas) -> Option<Wetting>,
) -> (PhysicsWorld, ForceGenerator, SoakId) {
    let mut world = PhysicsWorld::new();
    world.integration_parameters.dt = 1.0 / 60.0;
    let handle = world.bodies.insert(
        RigidBodyBuilder::dynamic()
            .translation(Vector::new(0.0, 0.05, 0.0))
            .rotation(Vector::new(0.15, 0.0, 0.1)),
    );
    let atlas = Atlas::bake(&builtin::cuboid(1.0, 1.0, 1.0), BakeOptions::square(64)).unwrap();
    let wetting = wet(&atlas);
    let mut soak = ForceGenerator::new(water);
    let id = soak
        .register(
            &mut world.bodies,
            &world.colliders,
            handle,
            BodyDesc {
                name: "box".into(),
                atlas: atlas.into(),
                mass_model: MassModel::Solid { density: 500.0 },
                effects: Effects {
                    wetting: wetting.map(Box::new),
                    ..Effects::buoyancy().with_drag(Drag::default())
                },
            },
        )
        .unwrap();
    soak.set_environment(Environment {
        temperature: 301.15,
        relative_humidity: 0.4,
        wind_speed: 5.0,
        ..Environment::default()
    })
    .unwrap();
    (world, soak, id)
}

/// Depth under the water of every texel at the body's current pose (what
/// the coming step's absorption sees), m; negative above the surface.
fn depths(world: &PhysicsWorld, soak: &ForceGenerator, id: SoakId) -> Vec<f64> {
    let b = soak.body(id).unwrap();
    let pose = soak_rapier::convert::pose(world.bodies[b.handle()].position());
    let atlas = b.atlas();
    (0..atlas.len())
        .map(|i| {
            soak.water()
                .surface
                .depth(&(pose * atlas.position(i)), soak.time())
        })
        .collect()
}

#[test]
fn a_floating_body_soaks_only_where_it_was_submerged_and_stays_in_bounds() {
    let (mut world, mut soak, id) = floating_box(swell(), |atlas| {
        Some(Wetting::new(atlas, weathered_wood(), time_lapse()).unwrap())
    });
    let n = soak.body(id).unwrap().atlas().len();
    let hmax = weathered_wood().saturation;
    let mut deepest = vec![f64::NEG_INFINITY; n];
    let mut peak = vec![0.0f64; n];
    let mut dried = 0usize;
    for _ in 0..600 {
        for (d, x) in deepest.iter_mut().zip(depths(&world, &soak, id)) {
            *d = d.max(x);
        }
        soak.step(&mut world).unwrap();
        let h = soak.liquid_texture(id).unwrap();
        assert!(
            h.iter().all(|&v| (0.0..=hmax).contains(&v)),
            "liquid out of [0, h_max]"
        );
        for (p, &v) in peak.iter_mut().zip(h) {
            *p = p.max(v);
        }
    }
    let h = soak.liquid_texture(id).unwrap();
    let mut wet_never_under = 0;
    for i in 0..n {
        // Without diffusion, liquid only enters through submerged texels
        // (1e-6 m of slack for the f32 texel positions at the waterline).
        if peak[i] > 0.0 && deepest[i] < -1e-6 {
            wet_never_under += 1;
        }
        if h[i] < peak[i] - 0.1 * hmax {
            dried += 1;
        }
    }
    assert_eq!(
        wet_never_under, 0,
        "texels got wet without ever being under water"
    );
    // Half as dense as water, the cube is unstable upright and rolls over
    // to float on an edge: much of it went under at some point, not all.
    let under = deepest.iter().filter(|&&d| d > 0.01).count();
    let never = deepest.iter().filter(|&&d| d < -0.05).count();
    let soaked = peak.iter().filter(|&&p| p > 0.0).count();
    assert!(
        under > n / 4 && never > n / 20,
        "{under} of {n} texels went under, {never} never"
    );
    assert!(soaked >= under, "{soaked} soaked, {under} went 1 cm under");
    // The box rolls in the swell: some texels soaked, rose out and lost at
    // least a tenth of saturation to the air.
    assert!(dried > 0, "no texel dried after rising out of the water");
    let report = soak.body(id).unwrap().wet_report().unwrap();
    assert!(report.submerged_texels > 0 && report.diffusion.is_none());
}

#[test]
fn diffusion_carries_liquid_past_the_waterline_but_not_far() {
    // Real water (slow drying), so the diffusion shows above the waterline.
    let (mut world, mut soak, id) = floating_box(Water::calm(0.0), |atlas| {
        Some(
            Wetting::new(atlas, weathered_wood(), Liquid::water())
                .unwrap()
                .with_diffusion(
                    Diffusion::new(2e-4)
                        .with_resolution(soak_rapier::soak_wet::FieldResolution::VoxelSize(0.05)),
                ),
        )
    });
    let n = soak.body(id).unwrap().atlas().len();
    let hmax = weathered_wood().saturation;
    let mut deepest = vec![f64::NEG_INFINITY; n];
    for _ in 0..600 {
        for (d, x) in deepest.iter_mut().zip(depths(&world, &soak, id)) {
            *d = d.max(x);
        }
        soak.step(&mut world).unwrap();
        let h = soak.liquid_texture(id).unwrap();
        assert!(h.iter().all(|&v| (0.0..=hmax).contains(&v)));
    }
    let h = soak.liquid_texture(id).unwrap();
    // Above the highest waterline: some wet by diffusion near it, nothing
    // (to 1e-9 of saturation) 25 cm or more above it.
    let mut near = 0.0f64;
    let mut far = 0.0f64;
    for i in 0..n {
        if deepest[i] < -0.01 && deepest[i] > -0.1 {
            near = near.max(h[i]);
        }
        if deepest[i] < -0.25 {
            far = far.max(h[i]);
        }
    }
    assert!(
        near > 1e-3 * hmax,
        "diffusion did not cross the waterline: {near}"
    );
    assert!(far < 1e-9 * hmax, "liquid 25 cm above the water: {far}");
    let report = soak.body(id).unwrap().wet_report().unwrap();
    assert!(report.diffusion.is_some_and(|d| d.plan.substeps >= 1));
}

#[test]
fn conservative_mode_changes_the_total_only_by_absorption_minus_evaporation() {
    for mode in [DiffusionMode::Conservative, DiffusionMode::Thesis] {
        let (mut world, mut soak, id) = floating_box(swell(), |atlas| {
            let mut w = Wetting::new(atlas, weathered_wood(), time_lapse())
                .unwrap()
                .with_diffusion(Diffusion::new(5e-4).with_mode(mode));
            w.fill(atlas, 0.2).unwrap();
            Some(w)
        });
        let atlas = soak.body(id).unwrap().atlas().clone();
        let start = soak.wetting(id).unwrap().total_liquid(&atlas);
        let (mut absorbed, mut evaporated) = (0.0, 0.0);
        for _ in 0..900 {
            soak.step(&mut world).unwrap();
            let r = soak.body(id).unwrap().wet_report().unwrap();
            absorbed += r.absorbed;
            evaporated += r.evaporated;
        }
        let w = soak.wetting(id).unwrap();
        let change = w.total_liquid(&atlas) - start;
        let ledger = w.ledger();
        assert!(absorbed > 0.0 && evaporated > 0.0);
        assert!((ledger.absorbed - absorbed).abs() <= 1e-12 * absorbed);
        let drift = change - (absorbed - evaporated);
        match mode {
            DiffusionMode::Conservative => {
                assert!(
                    drift.abs() <= 1e-9 * (absorbed + evaporated),
                    "conservative drift {drift:e} m³ of {absorbed:e} absorbed"
                );
                assert_eq!(ledger.drift, 0.0);
            }
            DiffusionMode::Thesis => {
                // The thesis' scheme is not conservative; its ledger says by how much.
                assert!((drift - ledger.drift).abs() <= 1e-9 * (absorbed + evaporated));
            }
        }
    }
}

#[test]
fn without_wetting_there_is_no_wetting_state_at_all() {
    let (mut world, mut soak, id) = floating_box(swell(), |_| None);
    for _ in 0..60 {
        soak.step(&mut world).unwrap();
    }
    let b = soak.body(id).unwrap();
    assert!(b.wetting().is_none() && b.liquid().is_none() && b.wet_report().is_none());
    assert!(soak.liquid_texture(id).is_none());
    assert!(soak.state().bodies[0].wetting.is_none());
    assert!(soak.state().bodies[0].wet_report.is_none());
    // Nor any flooding state.
    assert!(b.flooding().is_none() && b.flood_report().is_none() && b.ballast().is_none());
    assert!(soak.state().bodies[0].flooding.is_none());

    // Turned on, then off again: the state goes away.
    let atlas = b.atlas().clone();
    soak.set_wetting(
        id,
        Some(Wetting::new(&atlas, Material::wood(), Liquid::water()).unwrap()),
    )
    .unwrap();
    soak.step(&mut world).unwrap();
    assert!(soak.wetting(id).is_some());
    soak.set_wetting(id, None).unwrap();
    assert!(soak.wetting(id).is_none());

    // A state for another atlas is refused.
    let other = Atlas::bake(&builtin::cuboid(1.0, 1.0, 1.0), BakeOptions::square(32)).unwrap();
    let e = soak
        .set_wetting(
            id,
            Some(Wetting::new(&other, Material::wood(), Liquid::water()).unwrap()),
        )
        .unwrap_err();
    assert!(e.to_string().contains("box"), "{e}");

    // A scene without `wetting` keys: none of its bodies hold any.
    let scene = LoadedScene::from_file(&data("scenes/three_boxes.toml")).unwrap();
    let mut sim = Simulation::from_scene(&scene).unwrap();
    sim.step().unwrap();
    assert!(sim.soak.bodies().iter().all(|b| b.wetting().is_none()));
    assert!(sim.report().iter().all(|r| r.surface_liquid.is_none()));
    let dir = std::env::temp_dir().join(format!("soak-wet-none-{}", std::process::id()));
    assert!(sim.write_liquid_pngs(&dir).unwrap().is_empty());
    assert!(!dir.exists());
}

fn wet_crate() -> LoadedScene {
    LoadedScene::from_file(&data("scenes/wet_crate.toml")).unwrap()
}

/// Area-weighted summary of the crate's liquid, rounded for a snapshot.
#[derive(serde::Serialize)]
struct Snapshot {
    step: u64,
    /// Litres.
    total_l: f64,
    /// m².
    wet_area_m2: f64,
    mean_fill: f64,
    /// Fraction of the area per tenth of saturation.
    histogram: Vec<f64>,
    /// Litres, cumulative.
    absorbed_l: f64,
    /// Litres, cumulative.
    evaporated_l: f64,
}

#[test]
fn the_wet_crate_scene_soaks_dries_and_snapshots() {
    let scene = wet_crate();
    let mut sim = Simulation::from_scene(&scene).unwrap();
    let id = sim.bodies[0].id.unwrap();
    assert_eq!(sim.soak.environment().temperature, 301.15);
    let mut snaps = Vec::new();
    let mut peak: Vec<f64> = vec![0.0; sim.soak.body(id).unwrap().atlas().len()];
    let round = |x: f64| soak_rapier::soak_wet::round_significant(x, 3);
    for target in [0u64, 300, 600, 1200, 2400, 3600] {
        while sim.steps_taken() < target {
            sim.step().unwrap();
            for (p, &h) in peak.iter_mut().zip(sim.soak.liquid_texture(id).unwrap()) {
                *p = p.max(h);
            }
        }
        let b = sim.soak.body(id).unwrap();
        let w = b.wetting().unwrap();
        let s = w.stats(b.atlas()).unwrap();
        snaps.push(Snapshot {
            step: target,
            total_l: round(1e3 * s.total),
            wet_area_m2: round(s.wet_area),
            mean_fill: round(s.mean_fill),
            histogram: s.histogram.iter().map(|&x| round(x)).collect(),
            absorbed_l: round(1e3 * w.ledger().absorbed),
            evaporated_l: round(1e3 * w.ledger().evaporated),
        });
    }
    let b = sim.soak.body(id).unwrap();
    let w = b.wetting().unwrap();
    let (atlas, h, hmax) = (b.atlas(), w.liquid(), w.material().saturation);
    // The crate (3.4 m² of planks, 3.4 L at saturation) floats 20 cm deep
    // of its 50: its bottom and lower sides are wet, the middle of its top dry.
    let area = atlas.area();
    assert!((area - 3.4).abs() < 0.01, "{area}");
    let last = snaps.last().unwrap();
    assert!(last.total_l > 0.5 && last.total_l < 3.0, "{} L", last.total_l);
    assert!(
        last.wet_area_m2 > 1.0 && last.wet_area_m2 < 3.0,
        "{} m²",
        last.wet_area_m2
    );
    let top: Vec<usize> = (0..atlas.len())
        .filter(|&i| {
            let p = atlas.position(i);
            atlas.area_vectors().get(i)[1] > 0.9 * atlas.areas()[i] && p.x.abs() < 0.25 && p.z.abs() < 0.15
        })
        .collect();
    assert!(!top.is_empty());
    assert!(top.iter().all(|&i| h[i] < 1e-3 * hmax), "the top got wet");
    // Where the plunge and the rolling wet the sides high, the planks dried
    // again once out of the water: texels that lost a quarter of saturation
    // or more since their wettest, and a third of what soaked in is gone.
    let dried = (0..atlas.len()).filter(|&i| h[i] < peak[i] - 0.25 * hmax).count();
    assert!(dried > 50, "only {dried} texels dried after soaking");
    assert!(w.ledger().evaporated > 0.2 * w.ledger().absorbed);
    // Conservative mode: the total is what came in minus what went out.
    let ledger = w.ledger();
    assert!((w.total_liquid(atlas) - ledger.net()).abs() < 1e-9 * ledger.absorbed);
    assert!(!sim.report()[0].non_finite);
    assert_eq!(sim.report()[0].surface_liquid, Some(w.total_liquid(atlas)));
    insta::assert_yaml_snapshot!("wet_crate_liquid", snaps);

    // The liquid texture as a pseudo-colour PNG, one per wet body.
    let dir = std::env::temp_dir().join(format!("soak-wet-crate-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    let files = sim.write_liquid_pngs(&dir).unwrap();
    assert_eq!(files.len(), 1);
    assert!(files[0].ends_with("crate_liquid_003600.png"), "{files:?}");
    let bytes = std::fs::read(&files[0]).unwrap();
    assert_eq!(&bytes[1..4], b"PNG");
    let _ = std::fs::remove_dir_all(&dir);
}

fn scene_error(text: &str) -> SceneError {
    let path = Path::new("wet_inline.toml");
    LoadedScene::from_str(text, path)
        .and_then(|s| Simulation::from_scene(&s).map(|_| ()))
        .unwrap_err()
}

#[test]
fn a_bad_wetting_file_names_the_file_the_key_and_the_line() {
    let path = data("bad/scene_bad_wetting.toml");
    let e = LoadedScene::from_file(&path).unwrap_err();
    let msg = e.to_string();
    assert!(msg.contains("scene_bad_wetting.toml"), "{msg}");
    match e {
        SceneError::Invalid {
            path: p, line, key, ..
        } => {
            assert_eq!(p, path);
            assert_eq!(key, "bodies[0].wetting.diffusion");
            assert_eq!(line, 15, "{msg}");
        }
        e => panic!("{e:?}"),
    }
}

#[test]
fn bad_wetting_and_environment_values_name_their_keys() {
    let head = "[water]\nkind = \"plane\"\n\n[[bodies]]\nname = \"b\"\nmesh = \"builtin:box\"\n\
                mass = { model = \"solid\", density = 500.0 }\n";
    let cases = [
        (
            "wetting = { material = \"balsa\" }\n",
            "bodies[0].wetting.material",
        ),
        (
            "wetting = { material = \"wood\", liquid = \"mercury\" }\n",
            "bodies[0].wetting.liquid",
        ),
        (
            "wetting = { material = \"wood\", mode = \"thesis\" }\n",
            "bodies[0].wetting.mode",
        ),
        (
            "wetting = { material = \"wood\", diffusion = 1e-4, voxel_size = 0.0 }\n",
            "bodies[0].wetting.voxel_size",
        ),
        (
            "wetting = { material = \"wood\", initial = 1.5 }\n",
            "bodies[0].wetting.initial",
        ),
        (
            "wetting = { material = { permeability = 1e-12, thickness = -0.005, saturation = 0.001 } }\n",
            "bodies[0].wetting.material.thickness",
        ),
        (
            "wetting = { material = \"wood\", liquid = { viscosity = 0.0, evaporation_rate = 1e4 } }\n",
            "bodies[0].wetting.liquid.viscosity",
        ),
        (
            "wetting = { material = \"wood\", initial = \"no_such_image.png\" }\n",
            "bodies[0].wetting.initial",
        ),
        (
            "fixed = true\nwetting = { material = \"wood\" }\n",
            "bodies[0].wetting",
        ),
        (
            "\n[environment]\nrelative_humidity = 65.0\n",
            "environment.relative_humidity",
        ),
        (
            "\n[environment]\ntemperature_c = -300.0\n",
            "environment.temperature_c",
        ),
        ("\n[environment]\nwind_speed = -1.0\n", "environment.wind_speed"),
        ("\n[output]\nliquid_png_every = 0\n", "output.liquid_png_every"),
    ];
    for (tail, key) in cases {
        let text = format!("{head}{tail}");
        match scene_error(&text) {
            SceneError::Invalid {
                path, key: k, line, ..
            } => {
                assert_eq!(path, Path::new("wet_inline.toml"));
                assert_eq!(k, key, "{tail}");
                assert!(line >= 7, "{key}: line {line}");
            }
            e => panic!("{tail}: {e:?}"),
        }
    }
    // An unknown key inside `wetting` is a parse error naming it.
    let e = scene_error(&format!(
        "{head}wetting = {{ material = \"wood\", difusion = 1e-4 }}\n"
    ));
    assert!(matches!(e, SceneError::Parse { .. }), "{e:?}");
    assert!(e.to_string().contains("wet_inline.toml"), "{e}");
}

#[test]
fn a_painted_initial_liquid_image_is_loaded() {
    let dir = std::env::temp_dir().join(format!("soak-wet-paint-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    // Left half saturated, right half dry.
    let img = image::GrayImage::from_fn(16, 16, |x, _| image::Luma([if x < 8 { 255 } else { 0 }]));
    img.save(dir.join("paint.png")).unwrap();
    let text = "[water]\nkind = \"plane\"\nlevel = -5.0\n\n[[bodies]]\nname = \"b\"\nmesh = \"builtin:box\"\n\
                resolution = 32\nmass = { model = \"solid\", density = 500.0 }\nfixed = false\n\
                wetting = { material = \"wood\", initial = \"paint.png\" }\n";
    let scene = LoadedScene::from_str(text, &dir.join("painted.toml")).unwrap();
    let sim = Simulation::from_scene(&scene).unwrap();
    let b = &sim.soak.bodies()[0];
    let h = b.liquid().unwrap();
    let hmax = Material::wood().saturation;
    let full = h.iter().filter(|&&v| v == hmax).count();
    let dry = h.iter().filter(|&&v| v == 0.0).count();
    assert!(
        full > h.len() / 8 && dry > h.len() / 8,
        "{full} full, {dry} dry of {}",
        h.len()
    );
    assert_eq!(full + dry, h.len());
    let _ = std::fs::remove_dir_all(&dir);
}

/// A dry crate held still in the air (no gravity, water far below) under
/// weather that changes by keys, and a splash landing on it at 0.5 s.
const WEATHER_AND_SPLASH: &str = r#"
dt = 0.1
duration = 3.0
gravity = [0.0, 0.0, 0.0]

[water]
kind = "plane"
level = -10.0

[[bodies]]
name = "crate"
mesh = "builtin:box:1x1x1"
resolution = 32
mass = { model = "solid", density = 500.0 }
wetting = { material = "wood" }

[environment]
temperature_c = 10.0
relative_humidity = 0.9
keys = [{ at = 1.0, temperature_c = 30.0 }, { at = 2.0, relative_humidity = 0.1 }]

[[splash]]
at = 0.5
center = [0.0, 0.6, 0.0]
radius = 0.4
volume = 1e-4
"#;

#[test]
fn scene_weather_follows_its_keys_and_a_splash_lands_once() {
    let scene = LoadedScene::from_str(WEATHER_AND_SPLASH, Path::new("weather.toml")).unwrap();
    let mut sim = Simulation::from_scene(&scene).unwrap();
    let id = sim.bodies[0].id.unwrap();
    let splashed = |sim: &Simulation| sim.soak.wetting(id).unwrap().ledger().splashed;
    let mut seen = Vec::new();
    while sim.steps_taken() < 30 {
        // The environment set for a step is the track's at the step's start.
        let t = sim.soak.time();
        sim.step().unwrap();
        let env = *sim.soak.environment();
        seen.push((t, env.temperature - 273.15, env.relative_humidity));
        if t < 0.5 - 1e-9 {
            assert_eq!(splashed(&sim), 0.0, "nothing before the splash (t = {t})");
        }
    }
    let close = |a: f64, b: f64| (a - b).abs() < 1e-9;
    for &(t, temperature, humidity) in &seen {
        // 10 °C → 30 °C over the first second, then held; humidity held at
        // 0.9 until 1 s (the first key keeps it), then down to 0.1 at 2 s.
        let want_t = 10.0 + 20.0 * t.min(1.0);
        let want_h = 0.9 - 0.8 * (t - 1.0).clamp(0.0, 1.0);
        assert!(
            close(temperature, want_t),
            "t = {t}: {temperature} °C, want {want_t}"
        );
        assert!(
            close(humidity, want_h),
            "t = {t}: humidity {humidity}, want {want_h}"
        );
    }
    // The splash landed once: up to its volume stuck, no more after.
    let s = splashed(&sim);
    assert!(s > 0.5e-4 && s <= 1e-4 * (1.0 + 1e-12), "{s} m³ stuck");
    let total = sim
        .soak
        .wetting(id)
        .unwrap()
        .total_liquid(sim.soak.body(id).unwrap().atlas());
    let ledger = *sim.soak.wetting(id).unwrap().ledger();
    assert!(
        (total - ledger.net()).abs() <= 1e-12 + 1e-9 * s,
        "held {total}, ledger {ledger:?}"
    );
    assert!(ledger.evaporated > 0.0, "the splash dries in the warm air");
}

#[test]
fn a_saved_run_remembers_its_splash() {
    let scene = LoadedScene::from_str(WEATHER_AND_SPLASH, Path::new("weather.toml")).unwrap();
    let mut straight = Simulation::from_scene(&scene).unwrap();
    let mut first = Simulation::from_scene(&scene).unwrap();
    for _ in 0..8 {
        straight.step().unwrap();
        first.step().unwrap();
    }
    let bytes = first.save(&scene).unwrap().to_bytes().unwrap();
    let saved = soak_rapier::SavedSimulation::from_bytes(&bytes).unwrap();
    let mut resumed = Simulation::resume(&saved).unwrap();
    for _ in 8..30 {
        straight.step().unwrap();
        resumed.step().unwrap();
    }
    let id = straight.bodies[0].id.unwrap();
    let a = straight.soak.liquid_texture(id).unwrap();
    let b = resumed.soak.liquid_texture(id).unwrap();
    assert!(a.iter().zip(b).all(|(x, y)| x.to_bits() == y.to_bits()));
    assert_eq!(
        straight.soak.wetting(id).unwrap().ledger().splashed,
        resumed.soak.wetting(id).unwrap().ledger().splashed
    );
}

#[test]
fn bad_weather_keys_and_splashes_are_named() {
    for (text, key) in [
        (
            WEATHER_AND_SPLASH.replace("{ at = 2.0, relative", "{ at = 0.5, relative"),
            "environment.keys[1].at",
        ),
        (
            WEATHER_AND_SPLASH.replace("relative_humidity = 0.1 }", "relative_humidity = 1.5 }"),
            "environment.keys[1].relative_humidity",
        ),
        (
            WEATHER_AND_SPLASH.replace("radius = 0.4", "radius = 0.0"),
            "splash[0].radius",
        ),
        (
            WEATHER_AND_SPLASH.replace("volume = 1e-4", "volume = -1.0"),
            "splash[0].volume",
        ),
        (
            WEATHER_AND_SPLASH.replace("at = 0.5\n", "at = -1.0\n"),
            "splash[0].at",
        ),
    ] {
        match LoadedScene::from_str(&text, Path::new("weather.toml")) {
            Err(SceneError::Invalid { key: k, line, .. }) => {
                assert_eq!(k, key);
                assert!(line > 1, "{key}: line {line}");
            }
            other => panic!("{key}: {other:?}"),
        }
    }
}
