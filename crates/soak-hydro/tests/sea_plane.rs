//! A sea read as one plane over each body ([`SeaSampling::Plane`]): on a
//! surface that is a plane it is that plane (current and all, on every
//! path), and on a sine wave its error against the exact read falls with
//! the wave's curvature over the body.

use std::sync::Arc;

use nalgebra::{Isometry3, Point3, UnitQuaternion, Vector3};
use soak_bake::{Atlas, BakeOptions, Mesh, builtin};
use soak_hydro::{
    BodyState, BuoyancyMode, Drag, DragTexels, Gerstner, GerstnerWave, HeightField, HydroForces,
    HydroOptions, MassModel, MassProperties, Plane, SeaSampling, TiledAtlas, Water, evaluate, sampled_water,
};

fn baked(mesh: &Mesh, n: u32) -> (Atlas, MassProperties) {
    let atlas = Atlas::bake(mesh, BakeOptions::square(n)).unwrap();
    let mass = MassModel::Solid { density: 500.0 }
        .mass_properties(&atlas)
        .unwrap();
    (atlas, mass)
}

/// A body moving and turning, tilted, its centre near `y`.
fn moving(x: f64, y: f64, z: f64) -> BodyState {
    let pose = Isometry3::from_parts(
        Vector3::new(x, y, z).into(),
        UnitQuaternion::from_euler_angles(0.3, 0.5, -0.2),
    );
    BodyState {
        linear_velocity: Vector3::new(0.7, -0.3, 0.2),
        angular_velocity: Vector3::new(0.2, 0.5, -0.1),
        ..BodyState::at_rest(pose)
    }
}

/// The worst difference between two evaluations' buoyancy, explicit drag
/// and implicit drag, force over `scale` and torque over `scale` times
/// `length`.
fn difference(a: &HydroForces, b: &HydroForces, scale: f64, length: f64) -> f64 {
    [
        (&a.buoyancy, &b.buoyancy),
        (&a.drag_explicit, &b.drag_explicit),
        (&a.drag, &b.drag),
    ]
    .iter()
    .map(|(x, y)| ((x.force - y.force).norm() / scale).max((x.torque - y.torque).norm() / (scale * length)))
    .fold(0.0, f64::max)
}

/// A height field sampling the plane `y = 0.1 + 0.08 x − 0.05 z` (which its
/// bilinear read reproduces) with a current is read as that plane, with
/// that current, by the per-texel path, the tiled path, the tiled path with
/// coarse drag texels and the sampled water the driver hands them, in both
/// buoyancy modes.
#[test]
fn a_plane_read_as_a_plane_is_that_plane() {
    let mesh = builtin::cuboid(1.0, 0.6, 0.4);
    let (atlas, mass) = baked(&mesh, 64);
    let atlas = Arc::new(atlas);
    let tiled = TiledAtlas::new(&atlas);
    let coarse = DragTexels::coarsened(atlas.clone(), 4).unwrap();
    let (n, spacing, origin) = (41, 0.5, -10.0);
    let height = |x: f64, z: f64| 0.1 + 0.08 * x - 0.05 * z;
    let heights = (0..n * n)
        .map(|k| {
            height(
                origin + (k % n) as f64 * spacing,
                origin + (k / n) as f64 * spacing,
            )
        })
        .collect();
    let current = [0.3, 0.0, -0.2];
    let field = HeightField {
        current,
        ..HeightField::new([origin; 2], [spacing; 2], n, n, heights).unwrap()
    };
    let sea = Water::new(field);
    let plane = Water::new(
        Plane::tilted(Point3::new(0.0, 0.1, 0.0), Vector3::new(-0.08, 1.0, 0.05))
            .unwrap()
            .with_current(current.into()),
    );
    let weight = mass.mass * 9.80665;
    let length = 2.0 * atlas.bounding_radius();
    for buoyancy in [BuoyancyMode::Archimedes, BuoyancyMode::Pressure] {
        let options = HydroOptions {
            buoyancy,
            drag: Some(Drag {
                coefficient: 0.8,
                linear: 20.0,
            }),
            sea: SeaSampling::Plane,
            ..HydroOptions::default()
        };
        for state in [
            moving(0.4, 0.05, -0.3),
            moving(-2.0, -0.15, 1.5),
            moving(3.0, -0.6, 2.0),
        ] {
            let want = evaluate(&atlas, &plane, &state, &mass, 0.0, &options).unwrap();
            assert!(
                want.buoyancy.force.norm() > 0.1 * weight,
                "{buoyancy:?}: the body floats: {want:?}, weight {weight}"
            );
            assert!(
                want.drag_explicit.force.norm() > 1e-3 * weight,
                "{buoyancy:?}: drag acts"
            );
            let read = sampled_water(&atlas, &sea, &state, 0.0, &options)
                .unwrap()
                .unwrap();
            let got = [
                evaluate(&atlas, &sea, &state, &mass, 0.0, &options).unwrap(),
                tiled
                    .evaluate(&atlas, &sea, &state, &mass, 0.0, &options)
                    .unwrap(),
                evaluate(&atlas, &read, &state, &mass, 0.0, &options).unwrap(),
            ];
            for (k, g) in got.iter().enumerate() {
                let e = difference(g, &want, weight, length);
                assert!(e < 1e-9, "{buoyancy:?}, path {k}: {e:e} of the weight");
            }
            // The coarse drag texels against the same texels under the plane.
            let want = tiled
                .evaluate_with_drag(&atlas, &coarse, &plane, &state, &mass, 0.0, &options)
                .unwrap();
            let got = tiled
                .evaluate_with_drag(&atlas, &coarse, &sea, &state, &mass, 0.0, &options)
                .unwrap();
            let e = difference(&got, &want, weight, length);
            assert!(e < 1e-9, "{buoyancy:?}, coarse drag: {e:e} of the weight");
        }
    }
}

/// The worst difference of the plane read from the exact read of a sine
/// wave of amplitude `a` and wavelength `lambda` (m) along +x, over the
/// body at eight places along the wave: buoyancy force over the weight of
/// the water the body would displace whole, and torque over that times
/// the bounding diameter.
fn sine_error(mesh: &Mesh, a: f64, lambda: f64) -> (f64, f64) {
    let (atlas, mass) = baked(mesh, 64);
    let wave = GerstnerWave {
        amplitude: a,
        wavelength: lambda,
        direction_deg: 0.0,
        steepness: 0.0,
        phase: 0.0,
    };
    let water = Water::new(Gerstner::new(0.0, vec![wave], 9.80665).unwrap());
    let weight = 1000.0 * 9.80665 * mesh.volume();
    let length = 2.0 * atlas.bounding_radius();
    let exact = HydroOptions {
        sea: SeaSampling::Exact,
        ..HydroOptions::default()
    };
    let plane = HydroOptions {
        sea: SeaSampling::Plane,
        ..HydroOptions::default()
    };
    let worst = (0..8)
        .map(|k| {
            let x = lambda * k as f64 / 8.0;
            let y = a * (std::f64::consts::TAU * x / lambda).cos();
            let state = BodyState::at_rest(Isometry3::from_parts(
                Vector3::new(x, y, 0.3).into(),
                UnitQuaternion::from_euler_angles(0.2, 0.3, 0.1),
            ));
            let e = evaluate(&atlas, &water, &state, &mass, 0.0, &exact).unwrap();
            let p = evaluate(&atlas, &water, &state, &mass, 0.0, &plane).unwrap();
            ((e.buoyancy.force - p.buoyancy.force).norm() / weight)
                .max((e.buoyancy.torque - p.buoyancy.torque).norm() / (weight * length))
        })
        .fold(0.0, f64::max);
    (worst, atlas.bounding_radius())
}

/// On a sine wave the plane drops the surface's curvature over the body:
/// the error is within `a k² r² / 8` (the mean over the disc of the
/// bounding radius `r` of the height a curvature of `a k²` puts between
/// the surface and its tangent plane), and doubling the wavelength at the
/// same amplitude takes at least two thirds of it away (a quarter of it is
/// left of a curvature term; less where the five heights' mean takes it
/// out: the sphere's waterplane is the disc the mean is made for).
#[test]
fn a_sine_wave_read_as_a_plane_errs_by_its_curvature_over_the_body() {
    for (name, mesh) in [
        ("box", builtin::cuboid(1.0, 0.6, 0.4)),
        ("sphere", builtin::sphere(0.5, 48, 24)),
    ] {
        let a = 0.3;
        let lengths = [8.0, 16.0, 32.0];
        let mut errors = Vec::new();
        for l in lengths {
            let (e, r) = sine_error(&mesh, a, l);
            let k = std::f64::consts::TAU / l;
            let bound = a * k * k * r * r / 8.0;
            assert!(e > 0.0 && e < bound, "{name}: {e:e} at {l} m, over {bound:e}");
            errors.push(e);
        }
        for w in errors.windows(2) {
            assert!(w[1] < w[0] / 3.0, "{name}: {errors:?}");
        }
    }
}

/// `Surface::heights_at`, which the plane read takes its heights from,
/// gives each point's `Surface::height` on the Gerstner sea (the default,
/// point by point) and on a spectral sea (its tile looked up once), the
/// hint carried from point to point: within Newton's tolerance of it.
#[test]
fn heights_at_are_the_surfaces_heights() {
    let gerstner = Water::new(Gerstner::new(0.0, GerstnerWave::SWELL.to_vec(), 9.80665).unwrap());
    let spectral = Water::spectral(&soak_hydro::SeaSpectrum::jonswap(2.0, 8.0), 3).unwrap();
    let points: Vec<[f64; 2]> = (0..9)
        .map(|k| [0.4 * k as f64 - 1.3, 2.1 - 0.7 * k as f64])
        .collect();
    for (name, water) in [("Gerstner", &gerstner), ("spectral", &spectral)] {
        let t = 2.7;
        let mut out = vec![f64::NAN; points.len()];
        water.surface.heights_at(&points, t, &mut [0.0; 2], &mut out);
        for (&[x, z], h) in points.iter().zip(&out) {
            let want = water.surface.height(x, z, t);
            assert!(
                (h - want).abs() < 1e-9,
                "{name} at ({x}, {z}): {h} against {want}"
            );
        }
    }
}

/// `Surface::heights_near`, the plane read's heights about a body's centre:
/// on a spectral sea each point's particle is read once, from a guess
/// made at the centre, and its height carried to the point along its
/// slope (read again a Newton step on where it missed by more than a
/// centimetre). Against the sea's own heights, over 200 centres across
/// the tile: within 1e-6 m for the bench's bodies (a reach of 0.55 m) and
/// for a reach of 2 m on the bench's sea (JONSWAP, Hs 2 m, Tp 8 s), and
/// within 5e-5 m for a reach of 2 m on a steep short sea (Hs 2 m, Tp 4 s),
/// where the plane read itself is off by centimetres. The default (the
/// Gerstner sea) is `heights_at` itself.
#[test]
fn heights_near_a_centre_are_the_surfaces_heights() {
    let bench = Water::spectral(&soak_hydro::SeaSpectrum::jonswap(2.0, 8.0), 3).unwrap();
    let steep = Water::spectral(&soak_hydro::SeaSpectrum::jonswap(2.0, 4.0), 5).unwrap();
    let gerstner = Water::new(Gerstner::new(0.0, GerstnerWave::SWELL.to_vec(), 9.80665).unwrap());
    let t = 4.3;
    for (name, water, reach, within) in [
        ("bench sea", &bench, 0.55, 1e-6),
        ("bench sea, 2 m", &bench, 2.0, 1e-6),
        ("steep sea, 2 m", &steep, 2.0, 5e-5),
        ("Gerstner", &gerstner, 2.0, 1e-9),
    ] {
        let mut worst = 0.0_f64;
        for i in 0..200 {
            let c = [i as f64 * 3.7 - 300.0, (i as f64 * 1.3).sin() * 200.0];
            let mut hint = [0.0; 2];
            water
                .surface
                .probe(&nalgebra::Point3::new(c[0], 0.0, c[1]), t, false, &mut hint);
            let points = [
                [c[0] + reach, c[1]],
                [c[0] - reach, c[1]],
                [c[0], c[1] + reach],
                [c[0], c[1] - reach],
            ];
            let mut out = [f64::NAN; 4];
            water.surface.heights_near(c, &points, t, &mut hint, &mut out);
            for (&[x, z], h) in points.iter().zip(out) {
                worst = worst.max((h - water.surface.height(x, z, t)).abs());
            }
        }
        println!("{name}, reach {reach} m: heights within {worst:.2e} m");
        assert!(worst < within, "{name}: {worst} m");
    }
}

/// A quadratic surface `y = h₀ + ½ (a Δx² + 2 b Δx Δz + c Δz²)` about a
/// point, `Δ` the horizontal offset from it: the surface the plane read's
/// mean is made for.
struct Bowl {
    at: [f64; 2],
    h0: f64,
    hessian: [f64; 3],
}

impl soak_hydro::Surface for Bowl {
    fn height(&self, x: f64, z: f64, _t: f64) -> f64 {
        let (dx, dz) = (x - self.at[0], z - self.at[1]);
        let [a, b, c] = self.hessian;
        self.h0 + 0.5 * (a * dx * dx + 2.0 * b * dx * dz + c * dz * dz)
    }
}

/// On a quadratic surface an upright wall-sided hull turned about the
/// vertical (a box yawed, and a long barge yawed the other way) displaces
/// under the plane read what it displaces under the surface itself: the
/// plane goes through the mean of the surface over the hull's section (its
/// own rectangle, not the disc of its bounding radius), so its volume is
/// the exact read's to rounding. Its centre of buoyancy is not quite: the
/// height holds the surface's variance over the section, which no plane
/// has, and the horizontal place the texels' third moments about the
/// centroid (zero over the rectangle, not quite over its texels). The disc
/// alone misses the box's volume by parts in a thousand here.
#[test]
fn a_quadratic_surface_read_as_a_plane_keeps_a_wall_sided_hulls_volume() {
    for (name, mesh, yaw, hessian) in [
        ("box", builtin::cuboid(1.0, 0.6, 0.8), 0.5, [0.09, 0.03, -0.05]),
        ("barge", builtin::cuboid(4.0, 0.5, 1.0), -0.3, [0.02, -0.01, 0.04]),
    ] {
        let (atlas, mass) = baked(&mesh, 64);
        let bowl = Bowl {
            at: [0.2, -0.1],
            h0: 0.05,
            hessian,
        };
        let water = Water::new(bowl);
        let state = BodyState::at_rest(Isometry3::from_parts(
            Vector3::new(0.3, -0.05, -0.2).into(),
            UnitQuaternion::from_euler_angles(0.0, yaw, 0.0),
        ));
        let read = |sea| HydroOptions {
            sea,
            ..HydroOptions::default()
        };
        let exact = evaluate(&atlas, &water, &state, &mass, 0.0, &read(SeaSampling::Exact)).unwrap();
        let tiled = TiledAtlas::new(&atlas);
        for (path, plane) in [
            (
                "per texel",
                evaluate(&atlas, &water, &state, &mass, 0.0, &read(SeaSampling::Plane)).unwrap(),
            ),
            (
                "tiled",
                tiled
                    .evaluate(&atlas, &water, &state, &mass, 0.0, &read(SeaSampling::Plane))
                    .unwrap(),
            ),
        ] {
            let volume = (plane.submerged_volume - exact.submerged_volume).abs() / exact.submerged_volume;
            let off = (plane.center_of_buoyancy - exact.center_of_buoyancy) / atlas.bounding_radius();
            let across = off.x.hypot(off.z);
            assert!(
                volume < 1e-9 && across < 1e-4 && off.y.abs() < 1e-3,
                "{name}, {path}: volume {volume:e}, centre across {across:e}, up {:e}",
                off.y
            );
        }
        // The disc of the bounding radius, which the read took before it
        // took the section, would have put the plane at the surface's
        // mean over the disc: off the section's by ½ tr(H (Σ − r²/4 I)).
        let r2 = atlas.bounding_radius().powi(2) / 4.0;
        let [a, _, c] = hessian;
        let (sx, sz) = (mesh_extent(&mesh, 0), mesh_extent(&mesh, 2));
        let (cy, sy) = (yaw.cos(), yaw.sin());
        // The rectangle's second moments in world axes.
        let (m0, m2) = (sx * sx / 12.0, sz * sz / 12.0);
        let (xx, zz) = (cy * cy * m0 + sy * sy * m2, sy * sy * m0 + cy * cy * m2);
        let off = 0.5 * (a * (xx - r2) + c * (zz - r2));
        let footprint =
            exact.submerged_volume / (exact.center_of_buoyancy.y - (-0.05 - 0.5 * mesh_extent(&mesh, 1)));
        assert!(
            off.abs() * footprint / exact.submerged_volume > 1e-3,
            "{name}: the disc's miss {off:e} m"
        );
    }
}

/// The mesh's extent along axis `k`, m.
fn mesh_extent(mesh: &Mesh, k: usize) -> f64 {
    let (lo, hi) = mesh
        .positions
        .iter()
        .fold((f64::MAX, f64::MIN), |(lo, hi), p| (lo.min(p[k]), hi.max(p[k])));
    hi - lo
}

/// The default read ([`SeaSampling::Auto`]) takes each body as it is
/// against the waves: on the bench's JONSWAP sea (its shortest wave 12.5
/// m) the 1 m box is read as one plane, the 4 m boat is sampled at 16
/// nodes per shortest wave, each the same to the bit as that read asked
/// for, on the per-texel and the tiled paths; a body exactly an eighth
/// of the shortest wave across is still a plane, one a hair wider is
/// sampled; a surface with no shortest wave (a height field) is read
/// exactly.
#[test]
fn the_default_read_takes_each_body_as_it_is_against_the_waves() {
    assert_eq!(SeaSampling::default(), SeaSampling::Auto);
    let sea = Water::spectral(&soak_hydro::SeaSpectrum::jonswap(2.0, 8.0), 0).unwrap();
    let t = 30.0;
    let shortest = sea.surface.sampling_length(t).unwrap();
    assert!((shortest - 12.5).abs() < 0.05, "{shortest}");
    let sampled = SeaSampling::PerWavelength(SeaSampling::DEFAULT_PER_WAVELENGTH);
    let edge = SeaSampling::PLANE_BELOW * shortest / 2.0;
    let auto = SeaSampling::Auto;
    assert_eq!(auto.for_body(edge, &*sea.surface, t), SeaSampling::Plane);
    assert_eq!(auto.for_body(edge * (1.0 + 1e-12), &*sea.surface, t), sampled);
    assert_eq!(
        SeaSampling::Exact.for_body(0.1, &*sea.surface, t),
        SeaSampling::Exact
    );
    let drag = Some(Drag {
        coefficient: 0.8,
        linear: 20.0,
    });
    for (mesh, expected) in [
        (builtin::cuboid(1.0, 0.6, 0.8), SeaSampling::Plane),
        (builtin::boat(4.0, 1.2, 0.6), sampled),
    ] {
        let (atlas, mass) = baked(&mesh, 64);
        let tiled = TiledAtlas::new(&atlas);
        let y = sea.surface.height(3.0, -2.0, t);
        let state = moving(3.0, y - 0.1, -2.0);
        let options = |sea| HydroOptions {
            drag,
            sea,
            ..HydroOptions::default()
        };
        assert_eq!(auto.for_body(atlas.bounding_radius(), &*sea.surface, t), expected);
        let a = evaluate(&atlas, &sea, &state, &mass, t, &options(auto)).unwrap();
        let b = evaluate(&atlas, &sea, &state, &mass, t, &options(expected)).unwrap();
        assert_eq!(a, b, "per texel, {expected:?}");
        let a = tiled
            .evaluate(&atlas, &sea, &state, &mass, t, &options(auto))
            .unwrap();
        let b = tiled
            .evaluate(&atlas, &sea, &state, &mass, t, &options(expected))
            .unwrap();
        assert_eq!(a, b, "tiled, {expected:?}");
        assert!(a.submerged_volume > 0.0);
    }
    // A height field has no shortest wave: read exactly, as the sampled
    // read reads it.
    let field = Water::new(
        HeightField::new(
            [-5.0, -5.0],
            [0.5, 0.5],
            21,
            21,
            (0..21 * 21)
                .map(|k| 0.05 * ((k % 21) as f64 * 0.4).sin())
                .collect(),
        )
        .unwrap(),
    );
    let (atlas, mass) = baked(&builtin::cuboid(1.0, 0.6, 0.8), 32);
    let state = moving(0.3, 0.0, 0.2);
    let options = |sea| HydroOptions {
        sea,
        ..HydroOptions::default()
    };
    let a = evaluate(&atlas, &field, &state, &mass, 0.0, &options(auto)).unwrap();
    let b = evaluate(&atlas, &field, &state, &mass, 0.0, &options(SeaSampling::Exact)).unwrap();
    assert_eq!(a, b, "a height field");
}

/// With drag, a body more than an eighth of the shortest wave across reads
/// the sea as a plane whose current changes linearly over it (the
/// velocity's gradient at its centre): its drag summed tile by tile agrees
/// with the per-texel sum under the same plane, and against the exact read
/// it is several times closer than the plane's current held uniform over
/// the body. A body within an eighth, or one without drag, reads a plane
/// with one current.
#[test]
fn a_large_body_reads_the_currents_gradient_with_its_plane() {
    let sea = Water::new(Gerstner::new(0.0, GerstnerWave::SWELL.to_vec(), 9.80665).unwrap());
    let drag = HydroOptions {
        drag: Some(Drag {
            coefficient: 0.8,
            linear: 20.0,
        }),
        sea: SeaSampling::Plane,
        ..HydroOptions::default()
    };
    let kind = |atlas: &Atlas, options: &HydroOptions, state: &BodyState, t: f64| {
        let read = sampled_water(atlas, &sea, state, t, options).unwrap().unwrap();
        let any = read.surface.as_any().unwrap();
        (any.is::<soak_hydro::FlowPlane>(), any.is::<Plane>())
    };
    // The swell's shortest wave is 4 m: a 0.4 m ball is within an eighth.
    let (ball, _) = baked(&builtin::sphere(0.2, 24, 12), 32);
    let state = moving(1.0, -0.05, 0.5);
    assert_eq!(kind(&ball, &drag, &state, 0.7), (false, true));

    let (atlas, mass) = baked(&builtin::cuboid(1.0, 0.6, 0.8), 64);
    let tiled = TiledAtlas::new(&atlas);
    let still = HydroOptions { drag: None, ..drag };
    let (mut worst_flow, mut worst_uniform, mut worst_tiled) = (0.0f64, 0.0f64, 0.0f64);
    for k in 0..6 {
        let k = k as f64;
        let (x, z, t) = (7.3 * k - 2.0, 0.6 - 5.1 * k, 1.3 * k);
        let y = sea.surface.height(x, z, t) - 0.1;
        let state = BodyState {
            linear_velocity: Vector3::new(0.6, -0.3, 0.2),
            angular_velocity: Vector3::new(0.2, 0.4, -0.1),
            ..BodyState::at_rest(Isometry3::from_parts(
                Vector3::new(x, y, z).into(),
                UnitQuaternion::from_euler_angles(0.3, 0.5 * k, 0.1),
            ))
        };
        assert_eq!(kind(&atlas, &still, &state, t), (false, true));
        assert_eq!(kind(&atlas, &drag, &state, t), (true, false));
        let read = sampled_water(&atlas, &sea, &state, t, &drag).unwrap().unwrap();
        let flow = *read
            .surface
            .as_any()
            .and_then(|s| s.downcast_ref::<soak_hydro::FlowPlane>())
            .unwrap();
        let uniform = read.under(flow.plane);
        let force = |water: &Water| {
            tiled
                .evaluate(&atlas, water, &state, &mass, t, &drag)
                .unwrap()
                .drag_explicit
        };
        let exact = evaluate(
            &atlas,
            &sea,
            &state,
            &mass,
            t,
            &HydroOptions {
                sea: SeaSampling::Exact,
                ..drag
            },
        )
        .unwrap()
        .drag_explicit;
        let per_texel = evaluate(&atlas, &read, &state, &mass, t, &drag)
            .unwrap()
            .drag_explicit;
        let (got, held) = (force(&read), force(&uniform));
        let r = atlas.bounding_radius();
        worst_tiled = worst_tiled.max(
            ((got.force - per_texel.force).norm() + (got.torque - per_texel.torque).norm() / r)
                / (per_texel.force.norm() + per_texel.torque.norm() / r),
        );
        let f = exact.force.norm();
        worst_flow = worst_flow.max((got.force - exact.force).norm() / f);
        worst_uniform = worst_uniform.max((held.force - exact.force).norm() / f);
    }
    eprintln!(
        "drag of a 1 m box on the swell read as a plane, worst of six poses: tiled against per-texel \
         {worst_tiled:.1e}; against the exact read {worst_flow:.3} (one current: {worst_uniform:.3})"
    );
    assert!(worst_tiled < 1e-2, "tiled against per-texel: {worst_tiled:e}");
    assert!(
        worst_flow < 0.3 && worst_flow < worst_uniform / 3.0,
        "linear current {worst_flow}, uniform {worst_uniform}"
    );
}
