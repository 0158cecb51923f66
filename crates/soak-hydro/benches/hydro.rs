//! Hydrostatics at 1024²: per texel in Archimedes mode (and with the body
//! all dry and all submerged) and in pressure mode, tiled, a plain
//! streaming read of the same atlas (the bandwidth floor), exact clipping
//! and the per-triangle baseline; and on a Gerstner sea, per texel, in
//! Archimedes mode (which also takes the surface's slope for its torque)
//! and in pressure mode, and on the two-wave swell of `buoy_on_waves.toml`
//! sampled (the default) and read exactly, and tiled; the sphere moving with drag,
//! per texel and tiled, and on the swell (sampled) with and without drag
//! (tiled, the fluid's velocity read once per tile and at every texel;
//! and with the drag over a 64² bake of the same mesh),
//! at 1024² and 128²; the scaling bench's box at 128² with and without
//! drag (and over a 32² drag bake); the boat at 1024², per texel and tiled; the sphere
//! at 2048², beyond the cache; a step of the interactive wave surface; a
//! spectral sea's tile evaluated at one time; the world bench's box and
//! sphere level at their draft and above the water, with and without drag.

use criterion::{Criterion, criterion_group, criterion_main};
use nalgebra::{Isometry3, UnitQuaternion, Vector3};
use soak_bake::{Atlas, BakeOptions, Mesh, builtin};
use soak_hydro::reference::{self, ClipPlane};
use soak_hydro::{
    BodyState, BuoyancyMode, Drag, DragTexels, Gerstner, GerstnerWave, HydroOptions, InteractiveWaves,
    MassModel, MassProperties, SeaSampling, SeaSpectrum, SeaVelocity, SpectralSea, TiledAtlas, Water,
    WaveRegion, evaluate, sampled_water, streaming_read,
};

/// `mesh` baked at `n`², and the mass properties of a solid of half the
/// water's density.
fn baked(mesh: &Mesh, n: u32) -> (Atlas, MassProperties) {
    let atlas = Atlas::bake(mesh, BakeOptions::square(n)).unwrap();
    let mass = MassModel::Solid { density: 500.0 }
        .mass_properties(&atlas)
        .unwrap();
    (atlas, mass)
}

/// The drag of the world bench's drag columns (`soak bench`).
fn bench_drag() -> HydroOptions {
    HydroOptions {
        drag: Some(Drag {
            coefficient: 0.8,
            linear: 20.0,
        }),
        ..HydroOptions::default()
    }
}

/// The two-wave swell of `buoy_on_waves.toml`.
fn swell() -> Water {
    Water::new(Gerstner::new(0.0, GerstnerWave::SWELL.to_vec(), 9.80665).unwrap())
}

fn hydro(c: &mut Criterion) {
    let mesh = builtin::sphere(0.5, 64, 32);
    let (atlas, mass) = baked(&mesh, 1024);
    let tiled = TiledAtlas::new(&atlas);
    let pose = Isometry3::from_parts(
        Vector3::new(0.0, 0.1, 0.0).into(),
        UnitQuaternion::from_euler_angles(0.3, 0.2, 0.1),
    );
    let state = BodyState::at_rest(pose);
    let water = Water::calm(0.0);
    let opts = HydroOptions::default();
    let mut g = c.benchmark_group("sphere_1024");
    g.bench_function("streaming_read", |b| b.iter(|| streaming_read(&atlas)));
    g.bench_function("per_texel", |b| {
        b.iter(|| evaluate(&atlas, &water, &state, &mass, 0.0, &opts).unwrap())
    });
    // Pressure mode sums the pressure force and its moment as well.
    let pressure = HydroOptions {
        buoyancy: BuoyancyMode::Pressure,
        ..opts
    };
    g.bench_function("per_texel_pressure", |b| {
        b.iter(|| evaluate(&atlas, &water, &state, &mass, 0.0, &pressure).unwrap())
    });
    // The same pass with the body wholly above and wholly under the water:
    // what a dry and a submerged texel each cost.
    for (name, y) in [("per_texel_all_dry", 5.0), ("per_texel_all_wet", -5.0)] {
        let st = BodyState::at_rest(Isometry3::from_parts(
            Vector3::new(0.0, y, 0.0).into(),
            pose.rotation,
        ));
        g.bench_function(name, |b| {
            b.iter(|| evaluate(&atlas, &water, &st, &mass, 0.0, &opts).unwrap())
        });
    }
    g.bench_function("tiled", |b| {
        b.iter(|| tiled.evaluate(&atlas, &water, &state, &mass, 0.0, &opts).unwrap())
    });
    drag_rows(
        &mut g,
        &atlas,
        &tiled,
        &DragTexels::bake(&mesh, 64).unwrap(),
        &mass,
        &state,
    );
    g.bench_function("exact_clipping", |b| {
        b.iter(|| reference::submerged_part(&mesh, &pose, &ClipPlane::horizontal(0.0)))
    });
    g.bench_function("per_triangle_baseline", |b| {
        b.iter(|| reference::per_triangle_buoyancy(&mesh, &pose, &ClipPlane::horizontal(0.0), 1000.0, 9.81))
    });
    let sea = Water::new(
        Gerstner::new(
            0.0,
            vec![GerstnerWave {
                amplitude: 0.3,
                wavelength: 5.0,
                direction_deg: 20.0,
                steepness: 0.6,
                phase: 0.3,
            }],
            9.81,
        )
        .unwrap(),
    );
    for (name, mode) in [
        ("gerstner_archimedes", BuoyancyMode::Archimedes),
        ("gerstner_pressure", BuoyancyMode::Pressure),
    ] {
        let o = HydroOptions {
            buoyancy: mode,
            ..opts
        };
        g.bench_function(name, |b| {
            b.iter(|| evaluate(&atlas, &sea, &state, &mass, 0.0, &o).unwrap())
        });
    }
    // The two-wave swell of `buoy_on_waves.toml`, sampled once per
    // evaluation (16 nodes per shortest wave, sampling included) and read exactly at
    // every texel: against `per_texel` on the plane, what a sea costs.
    let swell = swell();
    for (name, sea) in [
        (
            "swell_sampled",
            SeaSampling::PerWavelength(SeaSampling::DEFAULT_PER_WAVELENGTH),
        ),
        ("swell_exact", SeaSampling::Exact),
    ] {
        let o = HydroOptions { sea, ..opts };
        g.bench_function(name, |b| {
            b.iter(|| evaluate(&atlas, &swell, &state, &mass, 0.0, &o).unwrap())
        });
    }
    // Tiled: tiles under the waves in closed form (sampling included).
    g.bench_function("swell_tiled", |b| {
        b.iter(|| tiled.evaluate(&atlas, &swell, &state, &mass, 0.0, &opts).unwrap())
    });
    g.finish();
}

/// The same body moving (and spinning) through the water with quadratic
/// drag and skin friction, per texel and tiled: against the rows without
/// drag, what drag costs.
fn drag_rows(
    g: &mut criterion::BenchmarkGroup<'_, criterion::measurement::WallTime>,
    atlas: &Atlas,
    tiled: &TiledAtlas,
    coarse: &DragTexels,
    mass: &MassProperties,
    state: &BodyState,
) {
    let water = Water::calm(0.0);
    let moving = BodyState {
        linear_velocity: Vector3::new(0.7, -0.3, 0.2),
        angular_velocity: Vector3::new(0.2, 0.5, -0.1),
        ..*state
    };
    let opts = HydroOptions {
        drag: Some(Drag {
            coefficient: 0.8,
            linear: 20.0,
        }),
        ..HydroOptions::default()
    };
    g.bench_function("per_texel_drag", |b| {
        b.iter(|| evaluate(atlas, &water, &moving, mass, 0.0, &opts).unwrap())
    });
    g.bench_function("tiled_drag", |b| {
        b.iter(|| tiled.evaluate(atlas, &water, &moving, mass, 0.0, &opts).unwrap())
    });
    // The drag over a 64² bake of the same mesh, the buoyancy over the
    // body's own texels: against `tiled_drag`, what the coarse drag saves.
    g.bench_function("tiled_drag_texels_64", |b| {
        b.iter(|| {
            tiled
                .evaluate_with_drag(atlas, coarse, &water, &moving, mass, 0.0, &opts)
                .unwrap()
        })
    });
    // On the swell, sampled (the default), with and without drag.
    let swell = swell();
    let still = HydroOptions { drag: None, ..opts };
    g.bench_function("swell_moving", |b| {
        b.iter(|| evaluate(atlas, &swell, &moving, mass, 0.0, &still).unwrap())
    });
    g.bench_function("swell_drag", |b| {
        b.iter(|| evaluate(atlas, &swell, &moving, mass, 0.0, &opts).unwrap())
    });
    // Tiled on the swell: buoyancy in closed form under the waves, drag per
    // texel without the sea kernel's read of the tiles in closed form.
    g.bench_function("swell_moving_tiled", |b| {
        b.iter(|| tiled.evaluate(atlas, &swell, &moving, mass, 0.0, &still).unwrap())
    });
    g.bench_function("swell_drag_tiled", |b| {
        b.iter(|| tiled.evaluate(atlas, &swell, &moving, mass, 0.0, &opts).unwrap())
    });
    g.bench_function("swell_drag_tiled_texels_64", |b| {
        b.iter(|| {
            tiled
                .evaluate_with_drag(atlas, coarse, &swell, &moving, mass, 0.0, &opts)
                .unwrap()
        })
    });
    // The same with the fluid's velocity read at every texel rather than
    // once per tile (the default): what reading it per tile saves.
    let per_texel = HydroOptions {
        sea_velocity: SeaVelocity::PerTexel,
        ..opts
    };
    g.bench_function("swell_drag_tiled_per_texel", |b| {
        b.iter(|| {
            tiled
                .evaluate(atlas, &swell, &moving, mass, 0.0, &per_texel)
                .unwrap()
        })
    });
}

/// The sphere of [`hydro`] at 128² (8,000 texels, the resolution of the
/// Rapier worlds' bodies), with and without drag.
fn small(c: &mut Criterion) {
    let mesh = builtin::sphere(0.5, 64, 32);
    let (atlas, mass) = baked(&mesh, 128);
    let tiled = TiledAtlas::new(&atlas);
    let pose = Isometry3::from_parts(
        Vector3::new(0.0, 0.1, 0.0).into(),
        UnitQuaternion::from_euler_angles(0.3, 0.2, 0.1),
    );
    let state = BodyState::at_rest(pose);
    let water = Water::calm(0.0);
    let opts = HydroOptions::default();
    let mut g = c.benchmark_group("sphere_128");
    g.bench_function("per_texel", |b| {
        b.iter(|| evaluate(&atlas, &water, &state, &mass, 0.0, &opts).unwrap())
    });
    g.bench_function("tiled", |b| {
        b.iter(|| tiled.evaluate(&atlas, &water, &state, &mass, 0.0, &opts).unwrap())
    });
    drag_rows(
        &mut g,
        &atlas,
        &tiled,
        &DragTexels::bake(&mesh, 64).unwrap(),
        &mass,
        &state,
    );
    g.finish();
}

/// The scaling bench's box (1.0 × 0.6 × 0.8 m, 128², solid at half the
/// water's density) at its floating draft, slightly turned and moving
/// slowly on calm water, as the bench's bodies float: without drag, with
/// drag over its own texels, over a 32² bake of its mesh and over its
/// atlas coarsened by 4 (where a world of such bodies spends its drag).
fn bench_box(c: &mut Criterion) {
    let mesh = builtin::cuboid(1.0, 0.6, 0.8);
    let (atlas, mass) = baked(&mesh, 128);
    let tiled = TiledAtlas::new(&atlas);
    let coarse = DragTexels::bake(&mesh, 32).unwrap();
    let state = BodyState {
        linear_velocity: Vector3::new(0.01, 0.02, -0.005),
        angular_velocity: Vector3::new(0.01, -0.02, 0.03),
        ..BodyState::at_rest(Isometry3::from_parts(
            Vector3::zeros().into(),
            UnitQuaternion::from_euler_angles(0.05, 0.1, 0.02),
        ))
    };
    let water = Water::calm(0.0);
    let still = HydroOptions::default();
    let drag = bench_drag();
    let mut g = c.benchmark_group("box_128");
    g.bench_function("tiled", |b| {
        b.iter(|| {
            tiled
                .evaluate(&atlas, &water, &state, &mass, 0.0, &still)
                .unwrap()
        })
    });
    g.bench_function("tiled_drag", |b| {
        b.iter(|| tiled.evaluate(&atlas, &water, &state, &mass, 0.0, &drag).unwrap())
    });
    g.bench_function("tiled_drag_texels_32", |b| {
        b.iter(|| {
            tiled
                .evaluate_with_drag(&atlas, &coarse, &water, &state, &mass, 0.0, &drag)
                .unwrap()
        })
    });
    let merged = DragTexels::coarsened(atlas.clone().into(), DragTexels::COARSENING).unwrap();
    g.bench_function("tiled_drag_coarsened_4", |b| {
        b.iter(|| {
            tiled
                .evaluate_with_drag(&atlas, &merged, &water, &state, &mass, 0.0, &drag)
                .unwrap()
        })
    });
    // The same box afloat on the world bench's JONSWAP sea (H_s 2 m, T_p
    // 8 s), its patch sampled in each evaluation (the tile's fields at
    // that time evaluated once, before the timing).
    let sea = Water::spectral(&SeaSpectrum::jonswap(2.0, 8.0), 0).unwrap();
    let t = 30.0;
    let afloat = BodyState {
        pose: Isometry3::from_parts(
            Vector3::new(0.0, sea.surface.height(0.0, 0.0, t), 0.0).into(),
            state.pose.rotation,
        ),
        ..state
    };
    g.bench_function("jonswap_tiled", |b| {
        b.iter(|| tiled.evaluate(&atlas, &sea, &afloat, &mass, t, &still).unwrap())
    });
    // Its two parts: sampling the patch (9 nodes over the box's bounding
    // disc, each the choppy map inverted and its twist taken), and the
    // evaluation on the sampled patch.
    g.bench_function("jonswap_patch", |b| {
        b.iter(|| sampled_water(&atlas, &sea, &afloat, t, &still).unwrap())
    });
    // The sea read as one plane over the box instead (six reads of the sea
    // and its section at the sea's height, from its tiles' moments).
    let plane = HydroOptions {
        sea: SeaSampling::Plane,
        ..still
    };
    g.bench_function("jonswap_plane", |b| {
        b.iter(|| sampled_water(&atlas, &sea, &afloat, t, &plane).unwrap())
    });
    let patch = sampled_water(&atlas, &sea, &afloat, t, &still).unwrap().unwrap();
    g.bench_function("jonswap_on_patch", |b| {
        b.iter(|| tiled.evaluate(&atlas, &patch, &afloat, &mass, t, &still).unwrap())
    });
    g.bench_function("jonswap_drag_coarsened_4", |b| {
        b.iter(|| {
            tiled
                .evaluate_with_drag(&atlas, &merged, &sea, &afloat, &mass, t, &drag)
                .unwrap()
        })
    });
    g.finish();
}

/// The per-texel pass against the streaming read at 2048², where the atlas
/// (about 90 MB) no longer fits a processor's cache and the floor is the
/// memory's bandwidth; at 1024² (about 22 MB) it is the last-level cache's.
fn beyond_the_cache(c: &mut Criterion) {
    let (atlas, mass) = baked(&builtin::sphere(0.5, 64, 32), 2048);
    let rotation = UnitQuaternion::from_euler_angles(0.3, 0.2, 0.1);
    let water = Water::calm(0.0);
    let opts = HydroOptions::default();
    let mut g = c.benchmark_group("sphere_2048");
    g.bench_function("streaming_read", |b| b.iter(|| streaming_read(&atlas)));
    for (name, y) in [
        ("per_texel", 0.1),
        ("per_texel_all_dry", 5.0),
        ("per_texel_all_wet", -5.0),
    ] {
        let st = BodyState::at_rest(Isometry3::from_parts(Vector3::new(0.0, y, 0.0).into(), rotation));
        g.bench_function(name, |b| {
            b.iter(|| evaluate(&atlas, &water, &st, &mass, 0.0, &opts).unwrap())
        });
    }
    g.finish();
}

/// The boat at 1024², heeled 15° and trimmed 4° with the water at half its
/// height (the pose of `soak accuracy`): its waterline is long for its
/// surface, so the tiled path has the most cut tiles of the builtins.
fn boat(c: &mut Criterion) {
    let mesh = builtin::boat(4.0, 1.2, 0.6);
    let (atlas, mass) = baked(&mesh, 1024);
    let tiled = TiledAtlas::new(&atlas);
    let rotation = UnitQuaternion::from_axis_angle(&Vector3::z_axis(), 4f64.to_radians())
        * UnitQuaternion::from_axis_angle(&Vector3::x_axis(), 15f64.to_radians());
    let ys = mesh.positions.iter().map(|p| (rotation * p).y);
    let (lo, hi) = ys.fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), y| {
        (l.min(y), h.max(y))
    });
    let water = Water::calm(0.5 * (lo + hi));
    let state = BodyState::at_rest(Isometry3::from_parts(Vector3::zeros().into(), rotation));
    let opts = HydroOptions::default();
    let mut g = c.benchmark_group("boat_1024");
    g.bench_function("streaming_read", |b| b.iter(|| streaming_read(&atlas)));
    g.bench_function("per_texel", |b| {
        b.iter(|| evaluate(&atlas, &water, &state, &mass, 0.0, &opts).unwrap())
    });
    g.bench_function("tiled", |b| {
        b.iter(|| tiled.evaluate(&atlas, &water, &state, &mass, 0.0, &opts).unwrap())
    });
    g.finish();
}

/// One step of the interactive wave surface ([`InteractiveWaves`]): a
/// 64 m square at 0.25 m cells (256²) and at 0.5 m (128²), with a sponge,
/// under a towed pressure patch.
fn waves(c: &mut Criterion) {
    let mut g = c.benchmark_group("interactive_waves");
    for (cells, name) in [(256, "step_64m_256"), (128, "step_64m_128")] {
        let region = WaveRegion {
            centre: [0.0, 0.0],
            size: 64.0,
            cells,
        };
        let mut waves = InteractiveWaves::new(region, 9.81, 1000.0, cells / 16).unwrap();
        waves.add_gaussian(0.0, 0.0, 0.5, 0.05);
        g.bench_function(name, |b| b.iter(|| waves.step(1.0 / 60.0).unwrap()));
    }
    g.finish();
}

/// A spectral sea's whole tile at one time (`SpectralSea::fields`: seven
/// inverse FFTs, fourteen real fields), the `soak bench` JONSWAP sea (Hs
/// 2 m, Tp 8 s, its default 800 m tile) at 128² and 256² cells: the fixed
/// cost of a step on it, whatever the number of bodies.
fn spectral(c: &mut Criterion) {
    let g = soak_hydro::STANDARD_GRAVITY;
    let spectrum = SeaSpectrum::jonswap(2.0, 8.0);
    let mut group = c.benchmark_group("spectral_tile");
    for cells in [128, 256] {
        let sea = SpectralSea::realize(&spectrum, 0.0, spectrum.default_tile(g), cells, 0, g).unwrap();
        let mut t = 0.0;
        group.bench_function(format!("fields_{cells}"), |b| {
            b.iter(|| {
                t += 1.0 / 60.0;
                sea.fields(t)
            })
        });
    }
    group.finish();
}

criterion_group!(
    benches,
    hydro,
    small,
    bench_box,
    boat,
    beyond_the_cache,
    waves,
    spectral,
    level
);
criterion_main!(benches);

/// The world bench's two bodies (`soak bench`: the box and the sphere at
/// 128², solid at half the water's density) level at their floating draft
/// on calm water, heaving at 1 mm/s and drifting and turning a tenth of
/// that, as the bench's bodies float: each without drag and with its drag
/// over its atlas coarsened by 4 (`{body}`, `{body}_drag`); heaving down
/// (`{body}_down_drag`); and 3 m above the water (`{body}_dry`,
/// `{body}_dry_drag`), where a body's sums are nothing but an evaluation's
/// fixed costs.
fn level(c: &mut Criterion) {
    let mut g = c.benchmark_group("level");
    for (name, mesh) in [
        ("box", builtin::cuboid(1.0, 0.6, 0.8)),
        ("sphere", builtin::sphere(0.5, 64, 32)),
    ] {
        let (atlas, mass) = baked(&mesh, 128);
        let tiled = TiledAtlas::new(&atlas);
        let state = BodyState {
            linear_velocity: Vector3::new(1e-4, 1e-3, -1e-4),
            angular_velocity: Vector3::new(1e-4, -1e-4, 1e-4),
            ..BodyState::at_rest(Isometry3::identity())
        };
        let water = Water::calm(0.0);
        let still = HydroOptions::default();
        let drag = bench_drag();
        let merged = DragTexels::coarsened(atlas.clone().into(), DragTexels::COARSENING).unwrap();
        g.bench_function(name.to_string(), |b| {
            b.iter(|| {
                tiled
                    .evaluate(&atlas, &water, &state, &mass, 0.0, &still)
                    .unwrap()
            })
        });
        g.bench_function(format!("{name}_drag"), |b| {
            b.iter(|| {
                tiled
                    .evaluate_with_drag(&atlas, &merged, &water, &state, &mass, 0.0, &drag)
                    .unwrap()
            })
        });
        let high = BodyState {
            pose: Isometry3::translation(0.0, 3.0, 0.0),
            ..state
        };
        g.bench_function(format!("{name}_dry"), |b| {
            b.iter(|| tiled.evaluate(&atlas, &water, &high, &mass, 0.0, &still).unwrap())
        });
        g.bench_function(format!("{name}_dry_drag"), |b| {
            b.iter(|| {
                tiled
                    .evaluate_with_drag(&atlas, &merged, &water, &high, &mass, 0.0, &drag)
                    .unwrap()
            })
        });
        let down = BodyState {
            linear_velocity: Vector3::new(1e-4, -1e-3, -1e-4),
            ..state
        };
        g.bench_function(format!("{name}_down_drag"), |b| {
            b.iter(|| {
                tiled
                    .evaluate_with_drag(&atlas, &merged, &water, &down, &mass, 0.0, &drag)
                    .unwrap()
            })
        });
    }
    g.finish();
}
