//! The tiled path on a sampled sea against the per-texel path on the same
//! patch (every texel reading the patch's bicubic): tiles under the waves
//! in closed form from the surface's second-order Taylor polynomial, within
//! the tolerance the tiles are held to.

use nalgebra::{Isometry3, UnitQuaternion, Vector3};
use soak_bake::{Atlas, BakeOptions, Mesh, builtin};
use soak_hydro::{
    BodyState, BuoyancyMode, Drag, Gerstner, GerstnerWave, HydroForces, HydroOptions, MassModel, SeaSampling,
    SeaVelocity, TiledAtlas, Water, evaluate, sampled_water,
};

fn swell() -> Water {
    Water::new(Gerstner::new(0.0, GerstnerWave::SWELL.to_vec(), 9.80665).unwrap())
}

/// The largest differences between two evaluations: of the submerged
/// volume (of `volume`), the centre of buoyancy (of `radius`), the force
/// (of the weight of the water `volume` displaces) and the torque (of that
/// times `radius`).
fn differences(a: &HydroForces, b: &HydroForces, volume: f64, radius: f64) -> [f64; 4] {
    let weight = 1000.0 * 9.80665 * volume;
    [
        (a.submerged_volume - b.submerged_volume).abs() / volume,
        (a.center_of_buoyancy - b.center_of_buoyancy).norm() / radius,
        (a.buoyancy.force - b.buoyancy.force).norm() / weight,
        (a.buoyancy.torque - b.buoyancy.torque).norm() / (weight * radius),
    ]
}

/// A place (its height from the surface's there) and Euler angles (rad).
type Place = (Vector3<f64>, (f64, f64, f64));

fn check(name: &str, mesh: &Mesh, n: u32, poses: &[Place]) {
    let atlas = Atlas::bake(mesh, BakeOptions::square(n)).unwrap();
    let tiled = TiledAtlas::new(&atlas);
    let mass = MassModel::Solid { density: 500.0 }
        .mass_properties(&atlas)
        .unwrap();
    let volume = atlas.volume();
    let radius = atlas.bounding_radius();
    let sea = swell();
    for &(offset, (r, p, y)) in poses {
        for (mode, t) in [(BuoyancyMode::Archimedes, 1.3), (BuoyancyMode::Pressure, 4.1)] {
            // `offset.y` from the surface's height over the body at `t`.
            let at = offset + Vector3::y() * sea.surface.height(offset.x, offset.z, t);
            let state = BodyState {
                linear_velocity: Vector3::new(0.3, -0.1, 0.2),
                angular_velocity: Vector3::new(0.1, 0.2, -0.3),
                ..BodyState::at_rest(Isometry3::from_parts(
                    at.into(),
                    UnitQuaternion::from_euler_angles(r, p, y),
                ))
            };
            let options = HydroOptions {
                buoyancy: mode,
                ..HydroOptions::default()
            };
            let water = sampled_water(&atlas, &sea, &state, t, &options).unwrap().unwrap();
            let want = evaluate(&atlas, &water, &state, &mass, t, &options).unwrap();
            let (got, counts) = tiled
                .evaluate_counted(&atlas, &water, &state, &mass, t, &options)
                .unwrap();
            let d = differences(&got, &want, volume, radius);
            println!(
                "{name} {n}² at {offset:?} {mode:?}: {} closed, {} per texel, {} dry; volume {:.1e}, \
                 centre {:.1e}, force {:.1e}, torque {:.1e}",
                counts.submerged, counts.cut, counts.dry, d[0], d[1], d[2], d[3]
            );
            // The closed forms were used, and agree with the texels far
            // below the patch's own error against the exact surface.
            assert!(counts.submerged >= 50, "{name} {at:?}: {counts:?}");
            // Archimedes' torque takes the depth at the tile's centre in its
            // second-order slope term, and the pressure's force the depth
            // at the centre in `Σ d² A`: theirs are the loosest.
            let bounds = [1e-6, 1e-6, 1e-5, 1e-5];
            for (what, (d, bound)) in ["volume", "centre", "force", "torque"]
                .iter()
                .zip(d.iter().zip(bounds))
            {
                assert!(*d < bound, "{name} {at:?} {mode:?}: {what} {d:.2e}");
            }
            let direct = tiled.evaluate(&atlas, &sea, &state, &mass, t, &options).unwrap();
            assert_eq!(
                direct.submerged_volume, got.submerged_volume,
                "{name}: sampled here or handed in"
            );

            // With drag, the fluid's velocity read at every texel: the same
            // texels' drag, each in the fluid's velocity where it is (summed
            // in another order).
            let options = HydroOptions {
                drag: Some(Drag {
                    coefficient: 0.8,
                    linear: 20.0,
                }),
                sea_velocity: SeaVelocity::PerTexel,
                ..options
            };
            let water = sampled_water(&atlas, &sea, &state, t, &options).unwrap().unwrap();
            let want = evaluate(&atlas, &water, &state, &mass, t, &options).unwrap();
            let got = tiled
                .evaluate(&atlas, &water, &state, &mass, t, &options)
                .unwrap();
            let scale = want.drag.force.norm() + want.drag.torque.norm() / radius;
            let off = |got: &HydroForces| {
                (got.drag.force - want.drag.force).norm()
                    + (got.drag.torque - want.drag.torque).norm() / radius
            };
            println!("  with drag: {:.1e} of {scale:.1e}", off(&got));
            assert!(
                scale > 1.0 && off(&got) < 1e-12 * scale,
                "{name} {at:?} {mode:?}: drag off by {:.2e} of {scale:.2e}",
                off(&got)
            );
            // Read once per tile to first order (the default): within a
            // few thousandths at these resolutions (the sphere's tiles span
            // 3 cm, the boat's 10 cm, of waves 4 and 9 m long).
            let per_tile = HydroOptions {
                sea_velocity: SeaVelocity::PerTile,
                ..options
            };
            let tiles = tiled
                .evaluate(&atlas, &water, &state, &mass, t, &per_tile)
                .unwrap();
            println!(
                "  with drag, velocity per tile: {:.1e} of {scale:.1e}",
                off(&tiles)
            );
            assert!(
                off(&tiles) < 5e-3 * scale,
                "{name} {at:?} {mode:?}: drag per tile off by {:.2e} of {scale:.2e}",
                off(&tiles)
            );
            assert_eq!(
                tiles.submerged_volume, got.submerged_volume,
                "{name}: drag leaves buoyancy alone"
            );
            let d = differences(&got, &want, volume, radius);
            assert!(
                d[0] < 1e-6 && d[1] < 1e-6,
                "{name} {at:?} {mode:?}: with drag {d:?}"
            );
        }
    }
}

#[test]
fn tiles_under_the_swell_take_the_per_texel_sums() {
    let sphere = builtin::sphere(0.5, 64, 32);
    let poses = [
        (Vector3::new(0.0, 0.1, 0.0), (0.3, 0.2, 0.1)),
        (Vector3::new(2.3, -0.2, -1.1), (-0.4, 1.0, 0.2)),
    ];
    check("sphere", &sphere, 384, &poses);
    let boat = builtin::boat(4.0, 1.2, 0.6);
    let poses = [
        (Vector3::new(0.5, -0.35, 0.3), (0.05, 0.4, -0.03)),
        (Vector3::new(-1.0, -0.3, 2.0), (-0.1, 2.0, 0.08)),
    ];
    check("boat", &boat, 256, &poses);
}

/// Wholly under the swell: within the depth scale of the surface, where
/// Archimedes' deep-volume weight needs every texel's depth, the tiled path
/// hands the body to the per-texel path (the same bits); deep down, where
/// that weight is one, the closed forms serve and agree.
#[test]
fn a_body_wholly_under_the_swell_takes_the_texels_near_the_surface_and_the_tiles_deep_down() {
    let atlas = Atlas::bake(&builtin::sphere(0.5, 48, 24), BakeOptions::square(256)).unwrap();
    let tiled = TiledAtlas::new(&atlas);
    let mass = MassModel::Solid { density: 500.0 }
        .mass_properties(&atlas)
        .unwrap();
    let sea = swell();
    let options = HydroOptions::default();
    let t = 2.0;
    for (below, closed) in [(0.7, false), (3.0, true)] {
        let at = Vector3::new(0.4, sea.surface.height(0.4, -0.2, t) - below, -0.2);
        let state = BodyState::at_rest(Isometry3::from_parts(
            at.into(),
            UnitQuaternion::from_euler_angles(0.2, 0.5, -0.1),
        ));
        let water = sampled_water(&atlas, &sea, &state, t, &options).unwrap().unwrap();
        let want = evaluate(&atlas, &water, &state, &mass, t, &options).unwrap();
        let (got, counts) = tiled
            .evaluate_counted(&atlas, &water, &state, &mass, t, &options)
            .unwrap();
        assert_eq!(got.submerged_texels, atlas.len(), "{below} m under");
        if closed {
            assert_eq!(counts.submerged + counts.cut, tiled.tiles().len(), "{counts:?}");
            assert!(counts.submerged > 0, "{counts:?}");
            assert_eq!(got.deep, 1.0);
            let d = differences(&got, &want, atlas.volume(), atlas.bounding_radius());
            let bounds = [1e-6, 1e-6, 1e-5, 1e-5];
            assert!(
                d.iter().zip(bounds).all(|(d, b)| *d < b),
                "{below} m under: {d:?}"
            );
        } else {
            assert_eq!(counts, soak_hydro::TileCounts::default(), "{below} m under");
            assert_eq!(got.buoyancy, want.buoyancy);
            assert_eq!(got.submerged_volume, want.submerged_volume);
            assert!(got.deep < 1.0, "{}", got.deep);
        }
    }
}

/// What the tiles' tolerance costs, against what it is set against: at
/// 128², where a body's tiles are a fifth of its size, the tiled read of a
/// patch departs from the per-texel read of the same patch by a small part
/// of that patch's own error against the exact surface (the largest of
/// each over a run of poses afloat on the swell, in both buoyancy modes).
#[test]
fn at_128_the_tiles_add_a_small_part_of_the_patchs_own_error() {
    for (name, mesh) in [
        ("box", builtin::cuboid(1.0, 0.6, 0.8)),
        ("ball", builtin::sphere(0.3, 32, 16)),
    ] {
        let atlas = Atlas::bake(&mesh, BakeOptions::square(128)).unwrap();
        let tiled = TiledAtlas::new(&atlas);
        let mass = MassModel::Solid { density: 500.0 }
            .mass_properties(&atlas)
            .unwrap();
        let (volume, radius) = (atlas.volume(), atlas.bounding_radius());
        let sea = swell();
        let (mut tiles, mut patch) = ([0.0f64; 4], [0.0f64; 4]);
        let mut closed = 0;
        for i in 0..6 {
            let f = i as f64;
            let t = 0.37 * f;
            let (x, z) = (8.0 * (0.7 * f).cos(), 8.0 * (0.7 * f).sin());
            let y = sea.surface.height(x, z, t) + 0.15 * radius * (1.3 * f).sin();
            let state = BodyState::at_rest(Isometry3::from_parts(
                Vector3::new(x, y, z).into(),
                UnitQuaternion::from_euler_angles(0.3 * f.sin(), 0.2 * (0.5 * f).cos(), 0.3 * f),
            ));
            for mode in [BuoyancyMode::Archimedes, BuoyancyMode::Pressure] {
                let options = HydroOptions {
                    buoyancy: mode,
                    sea: SeaSampling::PerWavelength(16.0),
                    ..HydroOptions::default()
                };
                let water = sampled_water(&atlas, &sea, &state, t, &options).unwrap().unwrap();
                let (got, counts) = tiled
                    .evaluate_counted(&atlas, &water, &state, &mass, t, &options)
                    .unwrap();
                closed += counts.submerged;
                let texels = evaluate(&atlas, &water, &state, &mass, t, &options).unwrap();
                let exact_read = HydroOptions {
                    sea: SeaSampling::Exact,
                    ..options
                };
                let exact = evaluate(&atlas, &sea, &state, &mass, t, &exact_read).unwrap();
                for (worst, d) in [
                    (&mut tiles, differences(&got, &texels, volume, radius)),
                    (&mut patch, differences(&texels, &exact, volume, radius)),
                ] {
                    for (w, d) in worst.iter_mut().zip(d) {
                        *w = w.max(d);
                    }
                }
            }
        }
        println!(
            "{name} 128²: tiles against texels {tiles:?}, patch against exact {patch:?}, {closed} tiles closed"
        );
        assert!(closed > 0, "{name}: no tile in closed form");
        // Volume and force: a tenth of the patch's own error; the centre of
        // buoyancy, half (on the box a fifth, on the ball a third: at a
        // tenth of this tolerance, a twentieth of it, with a fifth as many
        // tiles in closed form).
        for (k, part) in [(0, 0.1), (1, 0.5), (2, 0.1)] {
            assert!(
                tiles[k] < part * patch[k],
                "{name}: {k}: tiles {:.2e} against the patch's {:.2e}",
                tiles[k],
                patch[k]
            );
        }
        // The torque: within 2e-5 of the displaced weight times the radius
        // (the ball's own is all but zero by its symmetry).
        assert!(tiles[3] < 2e-5, "{name}: torque {:.2e}", tiles[3]);
    }
}
