//! The sea sampled once per evaluation ([`SeaSampling::PerWavelength`])
//! against the exact inversion of the Gerstner map at every texel: the
//! sums agree to the stated tolerance, the error falls as the fourth power
//! of the node spacing, and the patch itself interpolates the surface.

use nalgebra::{Isometry3, Point3, UnitQuaternion, Vector3};
use soak_bake::{Atlas, BakeOptions, Mesh, builtin};
use soak_hydro::{
    BodyState, BuoyancyMode, Drag, Gerstner, GerstnerWave, HeightField, HydroError, HydroOptions, MassModel,
    MassProperties, SeaSampling, Surface, SurfacePatch, Water, WaterError, evaluate, sampled_water,
};

/// The two-wave swell of `data/scenes/buoy_on_waves.toml`.
fn swell() -> Water {
    let waves = GerstnerWave::SWELL.to_vec();
    Water::new(Gerstner::new(0.0, waves, 9.80665).unwrap())
}

fn baked(mesh: &Mesh, n: u32) -> (Atlas, MassProperties, f64) {
    let atlas = Atlas::bake(mesh, BakeOptions::square(n)).unwrap();
    let mass = MassModel::Solid { density: 500.0 }
        .mass_properties(&atlas)
        .unwrap();
    (atlas, mass, mesh.volume())
}

/// Poses across the swell: at several places, heights, tilts and times.
fn states() -> Vec<(BodyState, f64)> {
    (0..5)
        .map(|k| {
            let k = k as f64;
            let pose = Isometry3::from_parts(
                Vector3::new(0.9 * k - 1.0, 0.03 * k - 0.2, -0.7 * k).into(),
                UnitQuaternion::from_euler_angles(0.3, 0.4 * k, 0.1),
            );
            let mut state = BodyState::at_rest(pose);
            state.linear_velocity = Vector3::new(0.7, -0.3, 0.2);
            state.angular_velocity = Vector3::new(0.2, 0.5, -0.1);
            (state, 1.3 * k)
        })
        .collect()
}

/// Worst errors of the sampled read against the exact one over [`states`]:
/// submerged volume over the body's volume, centre of buoyancy over the
/// bounding diameter, and Archimedes' torque over `ρ g V` times that diameter.
fn errors(mesh: &Mesh, per_wavelength: f64) -> [f64; 3] {
    let water = swell();
    let (atlas, mass, volume) = baked(mesh, 128);
    let diameter = 2.0 * atlas.bounding_radius();
    let mut worst = [0.0f64; 3];
    for (state, t) in states() {
        let exact = HydroOptions {
            sea: SeaSampling::Exact,
            ..HydroOptions::default()
        };
        let sampled = HydroOptions {
            sea: SeaSampling::PerWavelength(per_wavelength),
            ..HydroOptions::default()
        };
        let e = evaluate(&atlas, &water, &state, &mass, t, &exact).unwrap();
        let s = evaluate(&atlas, &water, &state, &mass, t, &sampled).unwrap();
        assert!(e.submerged_volume > 0.0, "pose {state:?} is out of the water");
        let weight = water.density * water.gravity * volume;
        worst[0] = worst[0].max((e.submerged_volume - s.submerged_volume).abs() / volume);
        worst[1] = worst[1].max((e.center_of_buoyancy - s.center_of_buoyancy).norm() / diameter);
        worst[2] = worst[2].max((e.buoyancy.torque - s.buoyancy.torque).norm() / (weight * diameter));
    }
    worst
}

fn meshes() -> [(&'static str, Mesh); 3] {
    [
        ("sphere", builtin::sphere(0.5, 48, 24)),
        ("box", builtin::cuboid(1.0, 0.6, 0.8)),
        ("boat", builtin::boat(4.0, 1.2, 0.6)),
    ]
}

#[test]
fn the_default_sampling_is_within_1e_4_of_the_exact_read() {
    for (name, mesh) in meshes() {
        let e = errors(&mesh, SeaSampling::DEFAULT_PER_WAVELENGTH);
        assert!(e[0] < 1e-4 && e[1] < 1e-4 && e[2] < 1e-4, "{name}: {e:?}");
    }
}

#[test]
fn the_error_falls_as_the_fourth_power_of_the_spacing() {
    let mesh = builtin::sphere(0.5, 48, 24);
    let coarse = errors(&mesh, 8.0);
    let fine = errors(&mesh, 16.0);
    // Bicubic Hermite: halving the spacing divides the error by about 16.
    for k in 0..2 {
        let ratio = coarse[k] / fine[k];
        assert!(ratio > 8.0, "error {k}: {coarse:?} → {fine:?} ({ratio})");
    }
}

#[test]
fn pressure_mode_and_drag_follow_the_exact_read() {
    let water = swell();
    let (atlas, mass, volume) = baked(&builtin::cuboid(1.0, 0.6, 0.8), 128);
    let drag = Some(Drag {
        coefficient: 0.8,
        linear: 20.0,
    });
    for (state, t) in states() {
        let options = |sea| HydroOptions {
            buoyancy: BuoyancyMode::Pressure,
            drag,
            sea,
            ..HydroOptions::default()
        };
        let e = evaluate(&atlas, &water, &state, &mass, t, &options(SeaSampling::Exact)).unwrap();
        let s = evaluate(
            &atlas,
            &water,
            &state,
            &mass,
            t,
            &options(SeaSampling::PerWavelength(SeaSampling::DEFAULT_PER_WAVELENGTH)),
        )
        .unwrap();
        let weight = water.density * water.gravity * volume;
        let df = (e.buoyancy.force - s.buoyancy.force).norm() / weight;
        assert!(df < 1e-4, "pressure force off by {df} of ρgV");
        // The fluid velocity is trilinear between nodes, and the Gerstner
        // velocity has a kink at the mean level (constant above it, decaying
        // below): drag is within 12 % of the exact read's, less than the
        // uncertainty of its coefficient.
        let drag_error =
            (e.drag_explicit.force - s.drag_explicit.force).norm() / e.drag_explicit.force.norm();
        assert!(drag_error < 0.12, "drag off by {drag_error}");
    }
}

#[test]
fn sampled_water_is_sampled_once_and_read_as_it_is() {
    let water = swell();
    let (atlas, mass, _) = baked(&builtin::sphere(0.5, 48, 24), 64);
    let (state, t) = states()[2];
    let options = HydroOptions::default();
    let sampled = sampled_water(&atlas, &water, &state, t, &options)
        .unwrap()
        .expect("a sea is sampled by default");
    let patch = sampled
        .surface
        .as_any()
        .and_then(|s| s.downcast_ref::<SurfacePatch>())
        .unwrap();
    // 16 nodes per 4 m wave: 0.25 m apart over the body's footprint (its
    // bounding disc, 0.5 m in radius, and no margin: a Gerstner sea gives
    // each node's twist).
    assert!((patch.spacing() - 0.25).abs() < 1e-12);
    assert!(
        patch.nodes()[0] >= 5 && patch.nodes()[0] <= 6,
        "{:?}",
        patch.nodes()
    );
    let direct = evaluate(&atlas, &water, &state, &mass, t, &options).unwrap();
    let on_patch = evaluate(&atlas, &sampled, &state, &mass, t, &options).unwrap();
    assert_eq!(direct.submerged_volume, on_patch.submerged_volume);
    assert_eq!(direct.buoyancy, on_patch.buoyancy);
    // The exact read, and surfaces without a sampling length, sample nothing.
    let exact = HydroOptions {
        sea: SeaSampling::Exact,
        ..options
    };
    assert!(
        sampled_water(&atlas, &water, &state, t, &exact)
            .unwrap()
            .is_none()
    );
    let field = Water::new(HeightField::new([-5.0, -5.0], [1.0, 1.0], 11, 11, vec![0.1; 121]).unwrap());
    assert!(
        sampled_water(&atlas, &field, &state, t, &options)
            .unwrap()
            .is_none()
    );
    assert!(
        sampled_water(&atlas, &Water::calm(0.0), &state, t, &options)
            .unwrap()
            .is_none()
    );
}

/// The velocity's derivatives the patch reports are its interpolant's:
/// within a cell, central differences of the velocity (trilinear, so
/// differences across half a millimetre are exact to rounding); and the
/// value beside them is the velocity itself.
#[test]
fn the_patch_velocity_gradient_is_its_interpolants() {
    let water = swell();
    let patch = SurfacePatch::sample(
        &*water.surface,
        1.1,
        [-1.0, -2.0],
        [3.0, 1.0],
        0.25,
        Some((-1.0, 0.5)),
    )
    .unwrap();
    let h = 2.5e-4;
    for p in [
        Vector3::new(0.1, -0.3, -0.9),
        Vector3::new(2.33, -0.81, 0.4),
        Vector3::new(-0.61, 0.07, -1.7),
    ] {
        let (u, grad) = patch.velocity_gradient_at(&p);
        assert!((u - patch.velocity_at(&p)).norm() <= 1e-14, "{u} vs the velocity");
        for j in 0..3 {
            let e = Vector3::ith(j, h);
            let d = (patch.velocity_at(&(p + e)) - patch.velocity_at(&(p - e))) / (2.0 * h);
            let got: Vector3<f64> = grad.column(j).into();
            assert!(
                (got - d).norm() <= 1e-8 * (1.0 + d.norm()),
                "{p} along {j}: {got} vs {d}"
            );
        }
        assert!(grad.norm() > 0.1, "the swell's velocity varies: {grad}");
    }
}

#[test]
fn the_patch_passes_through_the_surface_at_its_nodes_and_near_it_between() {
    let water = swell();
    let t = 2.5;
    let patch = SurfacePatch::sample(
        &*water.surface,
        t,
        [-1.0, -2.0],
        [3.0, 1.0],
        0.25,
        Some((-1.0, 0.5)),
    )
    .unwrap();
    let mut hint = [0.0; 2];
    for j in 0..patch.nodes()[1] {
        for i in 0..patch.nodes()[0] {
            let (x, z) = (-1.0 + 0.25 * i as f64, -2.0 + 0.25 * j as f64);
            let exact = water.surface.height(x, z, t);
            let (h, slope) = patch.height_slope(x, z);
            assert!((h - exact).abs() < 1e-12, "node ({i}, {j}): {h} vs {exact}");
            let (_, _) = water.surface.probe(&Point3::new(x, 0.0, z), t, false, &mut hint);
            let s = water.surface.slope(x, z, t, &hint);
            assert!((slope[0] - s[0]).abs() < 1e-9 && (slope[1] - s[1]).abs() < 1e-9);
            // The velocity at the grid's nodes (below the surface) is the
            // surface's, and on the edge between two of them the mean of
            // theirs (trilinear).
            for l in 0..3 {
                let y = -1.0 + 0.25 * l as f64;
                let node = Point3::new(x, y, z);
                let v = patch.velocity(&node, t);
                let ve = water.surface.velocity(&node, t);
                assert!(
                    (v - ve).norm() < 1e-12 * ve.norm().max(1.0),
                    "node {node}: {v} vs {ve}"
                );
                let above = Point3::new(x, y + 0.25, z);
                let mid = patch.velocity(&Point3::new(x, y + 0.125, z), t);
                let mean = (v + patch.velocity(&above, t)) / 2.0;
                assert!(
                    (mid - mean).norm() < 1e-12 * mean.norm().max(1.0),
                    "{mid} vs {mean}"
                );
            }
        }
    }
    // Between nodes: within 1e-4 m of the 0.35 m-high swell (its sharper
    // crests are where the interpolant errs most); the bounds hold every
    // value.
    let (lo, hi) = patch.height_bounds(t).unwrap();
    for k in 0..400 {
        let (x, z) = (
            -1.0 + 4.0 * ((k * 37) % 400) as f64 / 400.0,
            -2.0 + 3.0 * ((k * 91) % 400) as f64 / 400.0,
        );
        let (h, _) = patch.height_slope(x, z);
        let exact = water.surface.height(x, z, t);
        assert!((h - exact).abs() < 1e-4, "({x}, {z}): {h} vs {exact}");
        assert!(lo <= h && h <= hi);
        let p = Point3::new(x, -0.4, z);
        let v = patch.velocity(&p, t);
        let ve = water.surface.velocity(&p, t);
        assert!(
            (v - ve).norm() < 0.02 * ve.norm().max(0.1),
            "velocity at {p}: {v} vs {ve}"
        );
    }
}

#[test]
fn bad_sampling_settings_are_typed_errors() {
    let water = swell();
    let (atlas, mass, _) = baked(&builtin::cuboid(1.0, 1.0, 1.0), 32);
    let (state, t) = states()[0];
    for bad in [0.0, -3.0, f64::NAN, f64::INFINITY] {
        let options = HydroOptions {
            sea: SeaSampling::PerWavelength(bad),
            ..HydroOptions::default()
        };
        let err = evaluate(&atlas, &water, &state, &mass, t, &options).unwrap_err();
        assert!(
            matches!(
                err,
                HydroError::Water(WaterError::Parameter {
                    name: "sea samples per wavelength",
                    ..
                })
            ),
            "{bad}: {err:?}"
        );
    }
    for bad in [0.0, -1.0, f64::NAN] {
        let err = SurfacePatch::sample(&*water.surface, 0.0, [0.0, 0.0], [1.0, 1.0], bad, None).unwrap_err();
        assert!(
            matches!(
                err,
                WaterError::Parameter {
                    name: "patch spacing",
                    ..
                }
            ),
            "{err:?}"
        );
    }
    let err = SurfacePatch::sample(&*water.surface, 0.0, [f64::NAN, 0.0], [1.0, 1.0], 0.1, None).unwrap_err();
    assert!(
        matches!(
            err,
            WaterError::Parameter {
                name: "patch min x",
                ..
            }
        ),
        "{err:?}"
    );
    // A huge region is sampled more coarsely, not with millions of nodes.
    let wide = SurfacePatch::sample(&*water.surface, 0.0, [-1e4, -1e4], [1e4, 1e4], 0.01, None).unwrap();
    assert!(wide.nodes()[0] <= soak_hydro::MAX_PATCH_NODES);
}
