//! Scene files: good ones build and run, bad ones name the key and the line.

use std::path::PathBuf;

use soak_rapier::{LoadedScene, SavedSimulation, SceneError, Simulation};

fn data(name: &str) -> PathBuf {
    [env!("CARGO_MANIFEST_DIR"), "..", "..", "data", name]
        .iter()
        .collect()
}

fn error(name: &str) -> (SceneError, String) {
    let path = data(name);
    let e = LoadedScene::from_file(&path)
        .and_then(|s| Simulation::from_scene(&s).map(|_| ()))
        .unwrap_err();
    let msg = e.to_string();
    assert!(msg.contains(path.file_name().unwrap().to_str().unwrap()), "{msg}");
    (e, msg)
}

#[test]
fn unknown_key_names_it_and_its_line() {
    let (e, msg) = error("bad/scene_unknown_key.toml");
    assert!(matches!(e, SceneError::Parse { .. }), "{e:?}");
    assert!(msg.contains("positon") && msg.contains("line 10"), "{msg}");
}

#[test]
fn negative_density_names_the_key_and_line() {
    let (e, msg) = error("bad/scene_negative_density.toml");
    match e {
        SceneError::Invalid { line, key, .. } => {
            assert_eq!(key, "bodies[1].mass.density");
            assert_eq!(line, 15, "{msg}");
        }
        e => panic!("{e:?}"),
    }
}

#[test]
fn a_time_step_in_the_wrong_unit_is_refused() {
    let (e, msg) = error("bad/scene_wrong_unit.toml");
    assert!(matches!(e, SceneError::Invalid { line: 2, .. }), "{msg}");
    assert!(msg.contains("`dt`"), "{msg}");
}

#[test]
fn a_scene_can_run_forever_and_says_so() {
    let forever = "duration = \"forever\"\n[water]\nkind = \"plane\"\n";
    let scene = LoadedScene::from_str(forever, std::path::Path::new(".")).unwrap();
    assert!(scene.scene.duration.is_infinite());
    let mut sim = Simulation::from_scene(&scene).unwrap();
    assert_eq!(sim.total_steps(), u64::MAX);
    sim.step().unwrap();
    // Seconds as before, integers too.
    let ten = LoadedScene::from_str(
        "duration = 10\n[water]\nkind = \"plane\"\n",
        std::path::Path::new("."),
    )
    .unwrap();
    assert_eq!(ten.scene.duration, 10.0);
    // Any other word, or no time at all, is refused with its line.
    let e = LoadedScene::from_str(
        "dt = 0.01\nduration = \"never\"\n[water]\nkind = \"plane\"\n",
        std::path::Path::new("."),
    )
    .unwrap_err();
    assert!(e.to_string().contains("\"forever\""), "{e}");
    let e = LoadedScene::from_str(
        "dt = 0.01\nduration = -1.0\n[water]\nkind = \"plane\"\n",
        std::path::Path::new("."),
    )
    .unwrap_err();
    assert!(matches!(e, SceneError::Invalid { line: 2, .. }), "{e}");
}

/// The lowest and highest height of body `i` in the recorded samples after
/// `from` seconds, m.
fn heave_range(sim: &Simulation, i: usize, from: f64) -> (f64, f64) {
    sim.samples()
        .iter()
        .filter(|s| s.body == i && s.t > from)
        .map(|s| s.position[1])
        .fold((f64::MAX, f64::MIN), |(a, b), y| (a.min(y), b.max(y)))
}

#[test]
fn bodies_ride_a_spectral_sea() {
    // `data/scenes/spectral_sea.toml`: a buoy, a crate and a boat on a
    // JONSWAP sea of significant height 1 m, 30 s.
    let scene = LoadedScene::from_file(&data("scenes/spectral_sea.toml")).unwrap();
    let mut sim = Simulation::from_scene(&scene).unwrap();
    let water = sim.soak.water();
    let (lo, hi) = water.surface.height_bounds(0.0).unwrap();
    assert!(hi - lo > 1.0 && hi - lo < 4.0, "the sea's bounds {lo}..{hi}");
    sim.record(true);
    sim.run(|_| {}).unwrap();
    for (i, report) in sim.report().iter().enumerate() {
        let (lo, hi) = heave_range(&sim, i, 5.0);
        // Each heaves with the sea and stays afloat (no pump: each has drag).
        assert!(
            hi - lo > 0.2 && hi - lo < 2.5,
            "{}: heave range {lo}..{hi}",
            report.name
        );
        assert!(lo > -2.0, "{}: {lo}", report.name);
        assert!(!report.non_finite, "{}", report.name);
    }
}

/// `data/scenes/twenty_on_swell.toml`: ten crates and ten balls with
/// drag on the two-wave swell, the sea read as one plane over each body
/// (`[water] sampling = "plane"`). Each heaves with the swell and floats:
/// none sinks, none is thrown out of the water.
#[test]
fn twenty_pieces_of_flotsam_ride_the_swell_each_read_as_a_plane() {
    let mut scene = LoadedScene::from_file(&data("scenes/twenty_on_swell.toml")).unwrap();
    assert_eq!(scene.scene.water.sampling, Some(soak_hydro::SeaSampling::Plane));
    assert_eq!(scene.scene.bodies.len(), 20);
    scene.scene.duration = 4.0;
    let mut sim = Simulation::from_scene(&scene).unwrap();
    assert_eq!(sim.soak.sea_sampling(), soak_hydro::SeaSampling::Plane);
    sim.record(true);
    sim.run(|_| {}).unwrap();
    for (i, report) in sim.report().iter().enumerate() {
        let (lo, hi) = heave_range(&sim, i, 1.0);
        println!("{}: heave {lo:.3}..{hi:.3} m", report.name);
        assert!(
            hi - lo > 0.2 && hi - lo < 1.5,
            "{}: heave {lo}..{hi}",
            report.name
        );
        assert!(lo > -1.0 && hi < 1.0, "{}: heave {lo}..{hi}", report.name);
        assert!(
            report.submerged_fraction > 0.02 && report.submerged_fraction < 0.98,
            "{}: {} submerged",
            report.name,
            report.submerged_fraction
        );
        assert!(!report.non_finite, "{}", report.name);
    }
}

#[test]
fn on_a_spectral_sea_bodies_radiate_by_default_and_are_not_pumped() {
    // A crate and a ball with buoyancy alone (no drag) on a JONSWAP sea
    // of Hs 0.5 m, 60 s: radiation is on by default, and their heave stays
    // within the sea's own range. With `radiation = false` the crate was
    // thrown from −1.18 to +1.07 m (120 s, measured once).
    let text = r#"
dt = 0.0166667
duration = 60.0
[water]
kind = "spectrum"
significant_height = 0.5
peak_period = 4.0
seed = 3
[[bodies]]
name = "crate"
mesh = "builtin:box:1x0.5x0.5"
resolution = 64
mass = { model = "solid", density = 500.0 }
[[bodies]]
name = "ball"
mesh = "builtin:sphere:0.25"
resolution = 64
mass = { model = "solid", density = 500.0 }
position = [4.0, 0.0, 0.0]
"#;
    let scene = LoadedScene::from_str(text, std::path::Path::new("inline.toml")).unwrap();
    let mut sim = Simulation::from_scene(&scene).unwrap();
    for b in &sim.bodies {
        let body = sim.soak.body(b.id.unwrap()).unwrap();
        assert!(
            body.effects().radiation.is_some(),
            "{}: radiates by default",
            b.name
        );
    }
    sim.record(true);
    sim.run(|_| {}).unwrap();
    for (i, report) in sim.report().iter().enumerate() {
        let (lo, hi) = heave_range(&sim, i, 10.0);
        assert!(lo > -0.8 && hi < 0.8, "{}: heave {lo}..{hi}", report.name);
        assert!(!report.non_finite, "{}", report.name);
    }
}

#[test]
fn a_spectral_sea_is_checked_key_by_key() {
    let sea = "[water]\nkind = \"spectrum\"\n";
    let cases = [
        ("peak_period = 6.0\n", "a spectral sea needs `significant_height`"),
        ("significant_height = 1.0\n", "a spectral sea needs `peak_period`"),
        (
            "significant_height = -1.0\npeak_period = 6.0\n",
            "water.significant_height",
        ),
        (
            "significant_height = 1.0\npeak_period = 6.0\ncells = 100\n",
            "water.cells",
        ),
        (
            "significant_height = 1.0\npeak_period = 6.0\ngamma = 0.5\n",
            "water.gamma",
        ),
        (
            "significant_height = 1.0\npeak_period = 6.0\nspreading = -2.0\n",
            "water.spreading",
        ),
        (
            "significant_height = 1.0\npeak_period = 6.0\nchoppiness = -1.0\n",
            "water.choppiness",
        ),
        (
            "significant_height = 1.0\npeak_period = 6.0\ntile = 0.0\n",
            "water.tile",
        ),
        (
            "significant_height = 1.0\npeak_period = 6.0\nspectrum = \"pierson_moskowitz\"\ngamma = 2.0\n",
            "water.gamma",
        ),
    ];
    for (keys, expected) in cases {
        let e = LoadedScene::from_str(&format!("{sea}{keys}"), std::path::Path::new(".")).unwrap_err();
        assert!(e.to_string().contains(expected), "{keys}: {e}");
    }
    // The spectral keys mean nothing on a Gerstner sea.
    let gerstner = "[water]\nkind = \"gerstner\"\nwaves = [{ amplitude = 0.3, wavelength = 8.0, direction_deg = 0.0, steepness = 0.5 }]\nseed = 3\n";
    let e = LoadedScene::from_str(gerstner, std::path::Path::new(".")).unwrap_err();
    assert!(e.to_string().contains("water.seed"), "{e}");
    // The defaults: JONSWAP, eight peak wavelengths, 128 cells.
    let ok = format!("{sea}significant_height = 2.0\npeak_period = 8.0\n");
    let scene = LoadedScene::from_str(&ok, std::path::Path::new(".")).unwrap();
    let g = 9.81;
    let realised = scene.scene.water.spectral_sea(g).unwrap();
    assert_eq!(realised.cells, 128);
    assert!((realised.size - 8.0 * g * 64.0 / std::f64::consts::TAU).abs() < 1e-9);
}

#[test]
fn keys_that_do_not_apply_are_refused() {
    let (e, msg) = error("bad/scene_waves_on_a_plane.toml");
    assert!(matches!(e, SceneError::Invalid { line: 3, .. }), "{msg}");
    assert!(msg.contains("water.waves"), "{msg}");
}

#[test]
fn sea_sampling_is_checked_and_read() {
    let (e, msg) = error("bad/scene_sea_sampling_negative.toml");
    assert!(matches!(e, SceneError::Invalid { line: 4, .. }), "{msg}");
    assert!(msg.contains("water.sampling.per_wavelength"), "{msg}");
    let exact = "[water]\nkind = \"gerstner\"\nwaves = [{ amplitude = 0.3, wavelength = 8.0, direction_deg = 0.0, steepness = 0.5 }]\nsampling = \"exact\"\n";
    let scene = LoadedScene::from_str(exact, std::path::Path::new(".")).unwrap();
    assert_eq!(scene.scene.water.sampling, Some(soak_hydro::SeaSampling::Exact));
    let sim = Simulation::from_scene(&scene).unwrap();
    assert_eq!(sim.soak.sea_sampling(), soak_hydro::SeaSampling::Exact);
    // Sampling a plane means nothing: refused like waves on a plane.
    let plane = "[water]\nkind = \"plane\"\nsampling = \"exact\"\n";
    let e = LoadedScene::from_str(plane, std::path::Path::new(".")).unwrap_err();
    assert!(e.to_string().contains("water.sampling"), "{e}");
}

#[test]
fn a_bodys_own_sea_sampling_is_read_and_checked() {
    let sea = "[water]\nkind = \"gerstner\"\nwaves = [{ amplitude = 0.3, wavelength = 8.0, direction_deg = 0.0, steepness = 0.5 }]\n";
    let body = |name: &str, sampling: &str| {
        format!(
            "[[bodies]]\nname = \"{name}\"\nmesh = \"builtin:sphere:0.1\"\nresolution = 32\nmass = {{ model = \"solid\", density = 500.0 }}\n{sampling}"
        )
    };
    let text = format!(
        "{sea}{}{}",
        body("ship", ""),
        body("ball", "sampling = \"plane\"\n")
    );
    let scene = LoadedScene::from_str(&text, std::path::Path::new(".")).unwrap();
    assert_eq!(
        scene.scene.bodies[1].sampling,
        Some(soak_hydro::SeaSampling::Plane)
    );
    let sim = Simulation::from_scene(&scene).unwrap();
    let reads: Vec<_> = sim.soak.bodies().iter().map(|b| b.effects().sea).collect();
    assert_eq!(reads, [None, Some(soak_hydro::SeaSampling::Plane)]);
    // Nodes per wavelength that are not positive, named with their line.
    let bad = format!("{sea}{}", body("ball", "sampling = { per_wavelength = 0.0 }\n"));
    let e = LoadedScene::from_str(&bad, std::path::Path::new(".")).unwrap_err();
    assert!(matches!(e, SceneError::Invalid { line: 9, .. }), "{e}");
    assert!(e.to_string().contains("bodies[0].sampling.per_wavelength"), "{e}");
    // On calm water a body has no sea to read.
    let calm = format!(
        "[water]\nkind = \"plane\"\n{}",
        body("ball", "sampling = \"plane\"\n")
    );
    let e = LoadedScene::from_str(&calm, std::path::Path::new(".")).unwrap_err();
    assert!(e.to_string().contains("bodies[0].sampling"), "{e}");
}

#[test]
fn sea_velocity_is_read_and_refused_on_a_plane() {
    let sea = "[water]\nkind = \"gerstner\"\nwaves = [{ amplitude = 0.3, wavelength = 8.0, direction_deg = 0.0, steepness = 0.5 }]\n";
    let scene = LoadedScene::from_str(sea, std::path::Path::new(".")).unwrap();
    let sim = Simulation::from_scene(&scene).unwrap();
    assert_eq!(
        sim.soak.sea_velocity(),
        soak_hydro::SeaVelocity::PerTile,
        "the default"
    );
    let per_texel = format!("{sea}velocity = \"per_texel\"\n");
    let scene = LoadedScene::from_str(&per_texel, std::path::Path::new(".")).unwrap();
    assert_eq!(
        scene.scene.water.velocity,
        Some(soak_hydro::SeaVelocity::PerTexel)
    );
    let sim = Simulation::from_scene(&scene).unwrap();
    assert_eq!(sim.soak.sea_velocity(), soak_hydro::SeaVelocity::PerTexel);
    let plane = "[water]\nkind = \"plane\"\nvelocity = \"per_texel\"\n";
    let e = LoadedScene::from_str(plane, std::path::Path::new(".")).unwrap_err();
    assert!(e.to_string().contains("water.velocity"), "{e}");
    let unknown = format!("{sea}velocity = \"per_body\"\n");
    let e = LoadedScene::from_str(&unknown, std::path::Path::new(".")).unwrap_err();
    assert!(e.to_string().contains("per_tile"), "{e}");
}

#[test]
fn a_band_of_the_sea_is_read_and_checked() {
    let sea = "[water]\nkind = \"spectrum\"\nsignificant_height = 1.0\npeak_period = 5.0\n";
    let scene = LoadedScene::from_str(sea, std::path::Path::new(".")).unwrap();
    let sim = Simulation::from_scene(&scene).unwrap();
    assert_eq!(sim.soak.sea_band(), soak_hydro::SeaBand::Full, "the default");
    let band = format!("{sea}band = 0.5\n");
    let scene = LoadedScene::from_str(&band, std::path::Path::new(".")).unwrap();
    let sim = Simulation::from_scene(&scene).unwrap();
    assert_eq!(sim.soak.sea_band(), soak_hydro::SeaBand::BodyLengths(0.5));
    for bad in ["0.0", "-1.0", "nan"] {
        let text = format!("{sea}band = {bad}\n");
        let e = LoadedScene::from_str(&text, std::path::Path::new(".")).unwrap_err();
        assert!(matches!(e, SceneError::Invalid { line: 5, .. }), "{bad}: {e}");
        assert!(e.to_string().contains("water.band"), "{e}");
    }
    // A plane or a Gerstner sea has no band to drop: refused.
    for other in [
        "[water]\nkind = \"plane\"\nband = 0.5\n",
        "[water]\nkind = \"gerstner\"\nwaves = [{ amplitude = 0.3, wavelength = 8.0, direction_deg = 0.0, steepness = 0.5 }]\nband = 0.5\n",
    ] {
        let e = LoadedScene::from_str(other, std::path::Path::new(".")).unwrap_err();
        assert!(e.to_string().contains("water.band"), "{e}");
    }
}

#[test]
fn resolution_auto_picks_the_side_for_the_tolerance() {
    let scene = |body: &str| {
        format!(
            "[water]\nkind = \"plane\"\n[[bodies]]\nname = \"crate\"\nmesh = \"builtin:box:0.8\"\nmass = {{ model = \"solid\", density = 500.0 }}\n{body}"
        )
    };
    let loose = LoadedScene::from_str(
        &scene("resolution = \"auto\"\ntolerance = 1e-2\n"),
        std::path::Path::new("."),
    )
    .unwrap();
    let tight = LoadedScene::from_str(
        &scene("resolution = \"auto\"\ntolerance = 1e-4\n"),
        std::path::Path::new("."),
    )
    .unwrap();
    let (loose, tight) = (
        Simulation::from_scene(&loose).unwrap(),
        Simulation::from_scene(&tight).unwrap(),
    );
    assert!(loose.bodies[0].resolution >= 16);
    assert!(tight.bodies[0].resolution > loose.bodies[0].resolution);
    let fixed = LoadedScene::from_str(&scene("resolution = 48\n"), std::path::Path::new(".")).unwrap();
    assert_eq!(Simulation::from_scene(&fixed).unwrap().bodies[0].resolution, 48);
    // A tolerance without "auto", and a tolerance that is not positive, are refused.
    for (body, key) in [
        ("resolution = 64\ntolerance = 1e-3\n", "bodies[0].tolerance"),
        ("resolution = \"auto\"\ntolerance = -1.0\n", "bodies[0].tolerance"),
        ("resolution = \"fine\"\n", "resolution"),
    ] {
        let e = LoadedScene::from_str(&scene(body), std::path::Path::new(".")).unwrap_err();
        assert!(e.to_string().contains(key), "{body}: {e}");
    }
}

/// `drag_resolution` sums a body's drag over a second, coarser bake of its
/// mesh, `drag_coarsening` over its own atlas' blocks merged, each shared
/// by the bodies of one mesh: a sphere coasting across calm water slows
/// as it does with the drag over its own texels (within 1 % of its speed
/// after 2 s), and the keys are refused without `drag`, out of range or
/// together, named with their line.
#[test]
fn drag_resolution_sums_the_drag_over_a_coarser_bake() {
    let scene = |body: &str| {
        format!(
            "duration = 2.0\ndt = 0.016666666666666666\n[water]\nkind = \"plane\"\n\
             [[bodies]]\nname = \"a\"\nmesh = \"builtin:sphere:0.5\"\nresolution = 256\n\
             mass = {{ model = \"solid\", density = 500.0 }}\nlinear_velocity = [1.5, 0.0, 0.0]\n{body}\
             [[bodies]]\nname = \"b\"\nmesh = \"builtin:sphere:0.5\"\nresolution = 256\n\
             mass = {{ model = \"solid\", density = 500.0 }}\nposition = [0.0, 0.0, 3.0]\n\
             linear_velocity = [1.5, 0.0, 0.0]\n{body}"
        )
    };
    let drag = "drag = { coefficient = 1.0, linear = 5.0 }\n";
    let speeds = |body: &str| {
        let loaded = LoadedScene::from_str(&scene(body), std::path::Path::new(".")).unwrap();
        let mut sim = Simulation::from_scene(&loaded).unwrap();
        sim.run(|_| {}).unwrap();
        let report = sim.report();
        report.iter().map(|b| b.linear_velocity[0]).collect::<Vec<_>>()
    };
    let own = speeds(drag);
    let coarse = speeds(&format!("{drag}drag_resolution = 48\n"));
    assert!(own[0] < 1.0, "the drag slows the sphere: {own:?}");
    let merged = speeds(&format!("{drag}drag_coarsening = 4\n"));
    for (o, c) in own.iter().zip(&coarse) {
        assert!((o - c).abs() < 1e-2 * o, "own {own:?}, coarse {coarse:?}");
    }
    for (o, c) in own.iter().zip(&merged) {
        assert!((o - c).abs() < 1e-2 * o, "own {own:?}, coarsened {merged:?}");
    }
    // The two bodies of one mesh share one set of drag texels.
    for key in ["drag_resolution = 48", "drag_coarsening = 4"] {
        let loaded =
            LoadedScene::from_str(&scene(&format!("{drag}{key}\n")), std::path::Path::new(".")).unwrap();
        let sim = Simulation::from_scene(&loaded).unwrap();
        let texels: Vec<_> = sim
            .soak
            .bodies()
            .iter()
            .map(|b| b.effects().drag_texels.clone().unwrap())
            .collect();
        assert!(std::sync::Arc::ptr_eq(&texels[0], &texels[1]), "{key}");
    }
    for (body, named, message, at) in [
        (
            "drag_resolution = 64\n",
            "drag_resolution",
            "applies only to a body with `drag`",
            11,
        ),
        (
            &*format!("{drag}drag_resolution = 0\n"),
            "drag_resolution",
            "outside",
            12,
        ),
        (
            "drag_coarsening = 4\n",
            "drag_coarsening",
            "applies only to a body with `drag`",
            11,
        ),
        (
            &*format!("{drag}drag_coarsening = 0\n"),
            "drag_coarsening",
            "outside",
            12,
        ),
        (
            &*format!("{drag}drag_resolution = 64\ndrag_coarsening = 4\n"),
            "drag_coarsening",
            "not both",
            13,
        ),
    ] {
        let e = LoadedScene::from_str(&scene(body), std::path::Path::new(".")).unwrap_err();
        let msg = e.to_string();
        assert!(
            msg.contains(&format!("bodies[0].{named}")) && msg.contains(message),
            "{msg}"
        );
        assert!(
            matches!(e, SceneError::Invalid { line, .. } if line == at),
            "{msg}"
        );
    }
}

#[test]
fn a_missing_mesh_names_the_body_and_line() {
    let (e, msg) = error("bad/scene_missing_mesh.toml");
    assert!(matches!(e, SceneError::Body { line: 6, .. }), "{msg}");
    assert!(msg.contains("ghost") && msg.contains("no_such_mesh.obj"), "{msg}");
}

#[test]
fn the_three_boxes_settle_at_their_drafts() {
    let scene = LoadedScene::from_file(&data("scenes/three_boxes.toml")).unwrap();
    let mut sim = Simulation::from_scene(&scene).unwrap();
    sim.run(|_| {}).unwrap();
    for (r, s) in sim.report().iter().zip([0.25, 0.5, 0.75]) {
        let draft = 0.5 - r.position[1];
        assert!((draft - s).abs() < 0.01 * s, "{}: draft {draft}", r.name);
        assert!(
            (r.submerged_fraction - s).abs() < 0.01,
            "{}: {}",
            r.name,
            r.submerged_fraction
        );
        assert!(!r.non_finite);
    }
}

#[test]
fn the_buoy_rides_the_waves() {
    let scene = LoadedScene::from_file(&data("scenes/buoy_on_waves.toml")).unwrap();
    let mut sim = Simulation::from_scene(&scene).unwrap();
    sim.record(true);
    sim.run(|_| {}).unwrap();
    let ys: Vec<f64> = sim
        .samples()
        .iter()
        .filter(|s| s.t > 5.0)
        .map(|s| s.position[1])
        .collect();
    let (lo, hi) = ys
        .iter()
        .fold((f64::MAX, f64::MIN), |(a, b), &y| (a.min(y), b.max(y)));
    // It heaves with the sea (crest to trough about 0.7 m) and stays afloat.
    assert!(hi - lo > 0.2 && hi - lo < 1.5, "heave range {lo}..{hi}");
    assert!(lo > -1.0);
    assert!(!sim.report()[0].non_finite);
}

#[test]
fn the_holed_boat_floods_and_sinks_bow_first() {
    let scene = LoadedScene::from_file(&data("scenes/sinking_boat.toml")).unwrap();
    let mut sim = Simulation::from_scene(&scene).unwrap();
    sim.record(true);
    sim.run(|_| {}).unwrap();
    let r = &sim.report()[0];
    assert!(r.liquid_inside.unwrap() > 1.0, "{:?}", r.liquid_inside);
    assert!(r.position[1] < -2.0, "still afloat at {:?}", r.position);
    // Before it went under, the bow dipped: pitch (bow up > 0) negative.
    let min_pitch = sim
        .samples()
        .iter()
        .map(|s| {
            let q = nalgebra::UnitQuaternion::from_quaternion(nalgebra::Quaternion::new(
                s.rotation[3],
                s.rotation[0],
                s.rotation[1],
                s.rotation[2],
            ));
            (q * nalgebra::Vector3::x()).y.asin().to_degrees()
        })
        .fold(f64::MAX, f64::min);
    assert!(min_pitch < -20.0, "bow never dipped: {min_pitch}°");
    assert!(!r.non_finite);
}

/// Two boats dropped 1.5 m: the one with added mass and slamming is
/// stopped by the blow as it lands (it goes less deep than the one
/// without, which plunges on its buoyancy alone) and reports its peak.
#[test]
fn a_dropped_hull_with_slamming_lands_on_the_blow() {
    let scene = LoadedScene::from_file(&data("scenes/hull_drop.toml")).unwrap();
    let mut sim = Simulation::from_scene(&scene).unwrap();
    sim.record(true);
    sim.run(|_| {}).unwrap();
    let lowest = |body: usize| {
        sim.samples()
            .iter()
            .filter(|s| s.body == body)
            .map(|s| s.position[1])
            .fold(f64::MAX, f64::min)
    };
    let (slamming, plain) = (lowest(0), lowest(1));
    let report = sim.report();
    println!(
        "lowest: with slamming {slamming:.3} m, without {plain:.3} m; peak slamming force {:?} N",
        report[0].slamming_peak
    );
    assert!(slamming > plain + 0.05, "{slamming} vs {plain}");
    let peak = report[0].slamming_peak.unwrap();
    assert!(peak.is_finite() && peak > 0.0);
    assert_eq!(report[1].slamming_peak, None);
    assert!(!report[0].non_finite && !report[1].non_finite);
}

#[test]
fn permeability_without_a_graph_is_refused() {
    let text = "[water]\nkind = \"plane\"\n\n[[bodies]]\nname = \"b\"\nmesh = \"builtin:box\"\n\
                mass = { model = \"shell\", areal_density = 5.0 }\n\
                permeability = [{ centre = [0.0, 0.0, 0.0], radius = 0.1, kappa = 1e-6 }]\n";
    let e = LoadedScene::from_str(text, std::path::Path::new("inline.toml")).unwrap_err();
    assert!(
        e.to_string().contains("bodies[0].permeability") && e.to_string().contains("line 8"),
        "{e}"
    );
}

/// `data/scenes/passing_boat.toml`: the boat's wake reaches the buoy and
/// rocks it; the same scene without its `[waves]` table leaves the buoy
/// still. Saved with its waves half-way and resumed, the run equals the
/// straight one bit for bit.
#[test]
fn a_passing_boat_rocks_the_buoy_and_a_save_keeps_the_waves() {
    let path = data("scenes/passing_boat.toml");
    let scene = LoadedScene::from_file(&path).unwrap();
    let text = std::fs::read_to_string(&path).unwrap();
    let calm_text = text.replace("[waves]\nsize = 64.0\ncells = 256\n", "");
    assert_ne!(calm_text, text);
    let calm = LoadedScene::from_str(&calm_text, &path).unwrap();
    let tilt = |scene: &LoadedScene, steps: u64| {
        let mut sim = Simulation::from_scene(scene).unwrap();
        let mut most: f64 = 0.0;
        for _ in 0..steps {
            sim.step().unwrap();
            let up = soak_rapier::convert::rotation(*sim.world.bodies[sim.bodies[1].handle].rotation())
                * nalgebra::Vector3::y();
            most = most.max(up.y.clamp(-1.0, 1.0).acos().to_degrees());
        }
        (most, sim)
    };
    let (with, straight) = tilt(&scene, 720);
    let (without, _) = tilt(&calm, 720);
    println!("the buoy's largest tilt over 12 s: {with:.2}° with the waves, {without:.2}° without");
    assert!(with > 5.0, "{with}°");
    assert!(without < 1.0, "{without}°");

    let mut first = Simulation::from_scene(&scene).unwrap();
    for _ in 0..360 {
        first.step().unwrap();
    }
    let bytes = first.save(&scene).unwrap().to_bytes().unwrap();
    drop(first);
    let mut resumed = Simulation::resume(&SavedSimulation::from_bytes(&bytes).unwrap()).unwrap();
    for _ in 360..720 {
        resumed.step().unwrap();
    }
    assert_eq!(straight.soak.state(), resumed.soak.state());
    assert!(resumed.soak.state().waves.is_some());
}

/// The interactive waves ride on a spectral sea as on calm water: the
/// passing boat of `data/scenes/passing_boat.toml` on a JONSWAP sea (Hs
/// 0.3 m, Tp 3 s), with its `[waves]`. The buoy, rocked by the sea alone
/// in a run without the boat, moves as in that run until the boat's wake
/// reaches it, then it does not: the wake rides the sea to it. Saved half
/// way and resumed, the run equals the straight one bit for bit.
#[test]
fn on_a_spectral_sea_the_waves_bodies_make_ride_the_sea() {
    let path = data("scenes/passing_boat.toml");
    let text = std::fs::read_to_string(&path).unwrap();
    let sea = "kind = \"spectrum\"\nsignificant_height = 0.3\npeak_period = 3.0\nseed = 2\n";
    let with_boat = text.replace("kind = \"plane\"\nlevel = 0.0\n", sea);
    assert_ne!(with_boat, text);
    // The buoy alone: the boat's table (the first body) left out.
    let start = with_boat.find("[[bodies]]\nname = \"boat\"").unwrap();
    let end = with_boat.find("[[bodies]]\nname = \"buoy\"").unwrap();
    let alone = format!("{}{}", &with_boat[..start], &with_boat[end..]);
    let scene = LoadedScene::from_str(&with_boat, &path).unwrap();
    let buoy_alone = LoadedScene::from_str(&alone, &path).unwrap();
    let steps = 720;
    let ups = |scene: &LoadedScene, buoy: usize| {
        let mut sim = Simulation::from_scene(scene).unwrap();
        let mut ups = Vec::with_capacity(steps);
        for _ in 0..steps {
            sim.step().unwrap();
            ups.push(
                soak_rapier::convert::rotation(*sim.world.bodies[sim.bodies[buoy].handle].rotation())
                    * nalgebra::Vector3::y(),
            );
        }
        (ups, sim)
    };
    let (passed, straight) = ups(&scene, 1);
    let (rocked, _) = ups(&buoy_alone, 0);
    // The angle between the buoy's axes in the two runs, degrees.
    let apart: Vec<f64> = passed
        .iter()
        .zip(&rocked)
        .map(|(a, b)| a.dot(b).clamp(-1.0, 1.0).acos().to_degrees())
        .collect();
    let most = |range: std::ops::Range<usize>| apart[range].iter().fold(0.0f64, |m, &a| m.max(a));
    let (early, late) = (most(0..60), most(60..steps));
    let tilt = rocked
        .iter()
        .map(|u| u.y.clamp(-1.0, 1.0).acos().to_degrees())
        .fold(0.0f64, f64::max);
    println!(
        "the buoy's axis with the boat against without it: within {early:.4}° over the first second, \
         up to {late:.2}° after (the sea alone tilts it up to {tilt:.2}°)"
    );
    assert!(tilt > 1.0, "the sea does not rock the buoy: {tilt}°");
    assert!(early < 0.05, "{early}°");
    assert!(late > 3.0, "the wake never reached the buoy: {late}°");
    assert!(!straight.report().iter().any(|r| r.non_finite));

    let mut first = Simulation::from_scene(&scene).unwrap();
    for _ in 0..steps / 2 {
        first.step().unwrap();
    }
    let bytes = first.save(&scene).unwrap().to_bytes().unwrap();
    drop(first);
    let mut resumed = Simulation::resume(&SavedSimulation::from_bytes(&bytes).unwrap()).unwrap();
    for _ in steps / 2..steps {
        resumed.step().unwrap();
    }
    assert_eq!(straight.soak.state(), resumed.soak.state());
    assert!(resumed.soak.state().waves.is_some());
}

/// `data/scenes/flotsam.toml`: a boat reading the sea sampled over its
/// hull among crates and balls each reading it as one plane. Against the
/// same scene with every body sampled (16 nodes per shortest wave): the
/// boat, which reads the sea the same way in both, follows the same path to the bit (the flotsam's
/// reads do not reach it), and each piece of flotsam heaves with the sea
/// and stays within a few centimetres of its path on the sampled read.
#[test]
fn a_boat_among_flotsam_reads_the_sea_its_own_way() {
    let mut scene = LoadedScene::from_file(&data("scenes/flotsam.toml")).unwrap();
    let reads: Vec<_> = scene.scene.bodies.iter().map(|b| b.sampling).collect();
    assert_eq!(reads[0], None, "the boat reads the default");
    assert_eq!(reads.len(), 13);
    assert!(
        reads[1..]
            .iter()
            .all(|r| *r == Some(soak_hydro::SeaSampling::Plane))
    );
    scene.scene.duration = 5.0;
    let run = |scene: &LoadedScene| {
        let mut sim = Simulation::from_scene(scene).unwrap();
        sim.record(true);
        sim.run(|_| {}).unwrap();
        assert!(sim.report().iter().all(|r| !r.non_finite));
        sim
    };
    let mixed = run(&scene);
    for b in &mut scene.scene.bodies {
        b.sampling = Some(soak_hydro::SeaSampling::PerWavelength(
            soak_hydro::SeaSampling::DEFAULT_PER_WAVELENGTH,
        ));
    }
    let sampled = run(&scene);
    let path = |sim: &Simulation, i: usize| -> Vec<[f64; 3]> {
        sim.samples()
            .iter()
            .filter(|s| s.body == i)
            .map(|s| s.position)
            .collect()
    };
    assert_eq!(path(&mixed, 0), path(&sampled, 0), "the boat's path");
    for i in 1..13 {
        let (a, b) = (path(&mixed, i), path(&sampled, i));
        assert_eq!(a.len(), b.len());
        let apart = a
            .iter()
            .zip(&b)
            .map(|(p, q)| (0..3).map(|k| (p[k] - q[k]).abs()).fold(0.0, f64::max))
            .fold(0.0, f64::max);
        let (lo, hi) = heave_range(&mixed, i, 1.0);
        println!("body {i}: {apart:.2e} m apart at most, heave {:.3} m", hi - lo);
        assert!(hi - lo > 0.3, "body {i} heaves {lo}..{hi}");
        // 0.4–2.7 cm over the 5 s (heaves of 0.7–1.5 m), measured.
        assert!(apart < 0.05, "body {i}: {apart} m apart");
    }
}
