//! The drag sums of every CPU path against the plain per-texel formula
//! `K += Jᵀ K_i J`, `b += Jᵀ K_i u` with generic 3×3 products: texel by
//! texel for random texels and velocities, and over whole bodies at many
//! poses, velocities and currents for the per-texel and tiled paths.

use nalgebra::{Isometry3, Matrix3, Matrix6, Point3, UnitQuaternion, Vector3, Vector6};
use proptest::prelude::*;
use soak_bake::{Atlas, BakeOptions, builtin};

use super::body_state::BodyState;
use super::drag_kernel::{Added, DragMoments, HBox, LocalDrag, add_drag_texels};
use super::evaluation::{drag_sums, evaluate, sampled_water};
use super::forces::Wrench;
use super::frame::{Frame, texel};
use super::implicit_drag::implicit_drag;
use super::options::{Drag, HydroOptions};
use super::sea_drag::{LinearFluid, SeaDragParams, SeaDragSums, sea_drag_texels};
use super::sums::{DragAcc, DragSums, TexelDrag};
use crate::mass::{MassModel, MassProperties};
use crate::tiled::TiledAtlas;
use crate::water::{Gerstner, GerstnerWave, Plane, Unbounded, Water};

/// The reference: a submerged texel's drag as `Jᵀ K_i J` and `Jᵀ K_i u`
/// with `K_i = k_q I + λ a (I − n nᵀ)` and `J = [I, −[r]×]`, in generic
/// 3×3 products.
fn reference_texel(
    s: &mut DragSums,
    drag: &Drag,
    rho: f64,
    rc: &Vector3<f64>,
    a: &Vector3<f64>,
    vrel: &Vector3<f64>,
    u: &Vector3<f64>,
) {
    let facing = a.dot(vrel);
    let kq = if facing > 0.0 {
        0.5 * rho * drag.coefficient * facing
    } else {
        0.0
    };
    let area = a.norm();
    let mut ki = Matrix3::identity() * kq;
    if drag.linear > 0.0 && area > 0.0 {
        let n = a / area;
        ki += (Matrix3::identity() - n * n.transpose()) * (drag.linear * area);
    }
    let sk = rc.cross_matrix();
    let mut j = Matrix3x6::zeros();
    j.fixed_view_mut::<3, 3>(0, 0).copy_from(&Matrix3::identity());
    j.fixed_view_mut::<3, 3>(0, 3).copy_from(&(-sk));
    s.k += j.transpose() * ki * j;
    s.b += j.transpose() * (ki * u);
}

type Matrix3x6 = nalgebra::SMatrix<f64, 3, 6>;

/// The reference over every submerged texel of a body (world axes about
/// the centre of mass).
fn reference_sums(
    atlas: &Atlas,
    water: &Water,
    state: &BodyState,
    mass: &MassProperties,
    drag: &Drag,
) -> DragSums {
    let frame = Frame::new(atlas, water, state, mass, 0.0, 0.0);
    let mut s = DragSums::default();
    for i in 0..atlas.len() {
        let (x, a) = texel(atlas, i);
        let p = frame.ow + frame.rot * x;
        if frame.depth(water, &p, 0.0) > 0.0 {
            let rc = p - frame.com;
            let u = water.surface.velocity(&Point3::from(p), 0.0);
            let v = state.linear_velocity + state.angular_velocity.cross(&rc) - u;
            reference_texel(&mut s, drag, water.density, &rc, &(frame.rot * a), &v, &u);
        }
    }
    s
}

/// Largest absolute entry.
fn max_abs<const R: usize, const C: usize>(m: &nalgebra::SMatrix<f64, R, C>) -> f64 {
    m.iter().fold(0.0, |x: f64, y| x.max(y.abs()))
}

/// Relative differences of `K` and `b` against the reference's: on `K`
/// against its largest entry, on `b` against its largest entry or, where
/// the fluid is still, zero (and then exactly).
fn differences(got: &DragSums, want: &DragSums) -> (f64, f64) {
    let rel = |d: f64, size: f64| if size > 0.0 { d / size } else { d };
    (
        rel(max_abs(&(got.k - want.k)), max_abs(&want.k)),
        rel(max_abs(&(got.b - want.b)), max_abs(&want.b)),
    )
}

/// Texels from proptest's numbers: position, area vector, velocity,
/// fluid velocity.
fn vec3() -> impl Strategy<Value = Vector3<f64>> {
    prop::array::uniform3(-2.0..2.0f64).prop_map(Vector3::from)
}

fn drag_coefficients() -> impl Strategy<Value = Drag> {
    (
        prop_oneof![Just(0.0), 0.0..2.0f64],
        prop_oneof![Just(0.0), Just(-1.0), 0.0..50.0f64],
    )
        .prop_map(|(coefficient, linear)| Drag { coefficient, linear })
}

proptest! {
    /// [`TexelDrag`]'s symmetric sums add what the plain products add.
    #[test]
    fn texel_drag_adds_what_the_reference_adds(
        texels in prop::collection::vec((vec3(), vec3(), vec3(), vec3()), 1..20),
        drag in drag_coefficients(),
    ) {
        let (mut got, mut want) = (TexelDrag::default(), DragSums::default());
        for (r, a, v, u) in &texels {
            got.add(&drag, 1000.0, r, a, v, u);
            reference_texel(&mut want, &drag, 1000.0, r, a, v, u);
        }
        let got = got.sums();
        let (dk, db) = differences(&got, &want);
        prop_assert!(dk <= 1e-12 && db <= 1e-12, "K {dk:e}, b {db:e}");
        prop_assert_eq!(got.k, got.k.transpose());
    }

    /// The object-axes sums of the kernel, about the atlas origin and
    /// turned into the world system about the centre of mass, give what
    /// the plain products give texel by texel in world axes, for a uniform
    /// current; and the per-tile moments give what the kernel gives.
    #[test]
    fn object_axes_sums_give_the_world_system(
        texels in prop::collection::vec((vec3(), vec3()), 1..20),
        angles in prop::array::uniform3(-3.0..3.0f64),
        c in vec3(),
        v in vec3(),
        omega in vec3(),
        u in vec3(),
        drag in drag_coefficients(),
    ) {
        let rot = UnitQuaternion::from_euler_angles(angles[0], angles[1], angles[2])
            .to_rotation_matrix()
            .into_inner();
        // Every texel submerged: α large.
        let p = LocalDrag::new(&drag, 1000.0, 100.0, &Vector3::y(), &rot, &c, &v, &omega, &u);
        let mut acc = DragAcc::default();
        let mut want = DragSums::default();
        let (mut moments, mut hbox) = (DragMoments::default(), HBox::default());
        for (x, a) in &texels {
            // Through f32, as the atlas stores them.
            let x = x.map(|e| f64::from(e as f32));
            let a = a.map(|e| f64::from(e as f32));
            let rc = rot * (x - c);
            let vrel = v + omega.cross(&rc) - u;
            reference_texel(&mut want, &drag, 1000.0, &rc, &(rot * a), &vrel, &u);
            let mut one = DragAcc::default();
            kernel_one(&mut one, &x, &a, &p);
            acc += &one;
            moments.add_texel(&x, &a);
            hbox.add_texel(&x, &a);
        }
        let got = acc.system(&rot, &c, &u);
        let (dk, db) = differences(&got, &want);
        prop_assert!(dk <= 1e-11 && db <= 1e-11, "K {dk:e}, b {db:e}");
        // The closed forms: all the texels' skin friction and `k_q h·w`;
        // where every texel faces the flow that is the kernel's sum.
        if hbox.bounds().facing(&p.w) == super::drag_kernel::Facing::All {
            let mut closed = DragAcc::default();
            if p.lin > 0.0 {
                moments.add_linear(&mut closed, &p);
            }
            moments.add_quadratic(&mut closed, &p);
            let (dk, db) = differences(&closed.system(&rot, &c, &u), &want);
            prop_assert!(dk <= 1e-11 && db <= 1e-11, "closed form: K {dk:e}, b {db:e}");
        }
    }
}

proptest! {
    /// The sea's drag kernel (object axes about the atlas origin, the
    /// fluid's velocity texel by texel), turned into the world system
    /// about the centre of mass, gives what the plain products give, over
    /// more texels than a block holds and fewer (a short last group).
    #[test]
    fn the_sea_drag_kernel_gives_the_world_system(
        texels in prop::collection::vec((vec3(), vec3(), vec3()), 1..150),
        angles in prop::array::uniform3(-3.0..3.0f64),
        c in vec3(),
        v in vec3(),
        omega in vec3(),
        drag in drag_coefficients(),
    ) {
        let rot = UnitQuaternion::from_euler_angles(angles[0], angles[1], angles[2])
            .to_rotation_matrix()
            .into_inner();
        let p = SeaDragParams::new(&drag, 1000.0, &rot, &c, &v, &omega);
        let mut want = DragSums::default();
        let mut local = Vec::new();
        for (k, (x, a, u)) in texels.iter().enumerate() {
            // Every seventh texel without area, as the atlas has some.
            let a = if k % 7 == 3 { Vector3::zeros() } else { *a };
            let rc = rot * (x - c);
            let vrel = v + omega.cross(&rc) - u;
            reference_texel(&mut want, &drag, 1000.0, &rc, &(rot * a), &vrel, u);
            local.push([*x, a, rot.transpose() * u]);
        }
        let got = sea_drag_texels(&p, &local).system(&rot, &c);
        let (dk, db) = differences(&got, &want);
        prop_assert!(dk <= 1e-11 && db <= 1e-11, "K {dk:e}, b {db:e}");
        prop_assert_eq!(got.k, got.k.transpose());
    }
}

/// A tile of texels `(x, A)` in fluid moving at `fluid`, the body at `w`
/// (m/s) and `omega`: its drag system in closed form (`None` where its
/// facing is mixed) and texel by texel, each texel in the fluid's velocity
/// where it is.
fn tile_drag(
    tile: &[(Vector3<f64>, Vector3<f64>)],
    fluid: &LinearFluid,
    w: &Vector3<f64>,
    omega: &Vector3<f64>,
    drag: &Drag,
) -> (Option<DragSums>, DragSums) {
    let p = SeaDragParams::new(drag, 1000.0, &Matrix3::identity(), &Vector3::zeros(), w, omega);
    let (mut moments, mut hbox) = (DragMoments::default(), HBox::default());
    let (mut s1, mut s2) = (Matrix3::zeros(), [Matrix3::zeros(); 3]);
    let mut radius = 0.0f64;
    for (x, a) in tile {
        moments.add_texel(x, a);
        hbox.add_texel(x, a);
        s1 += a * x.transpose();
        for j in 0..3 {
            s2[j] += x * x.transpose() * a[j];
        }
        radius = radius.max((x - fluid.c).norm());
    }
    let mut closed = SeaDragSums::default();
    let added = closed.add_tile(&moments, &hbox.bounds(), &s1, &s2, radius, &p, fluid);
    let texels: Vec<[Vector3<f64>; 3]> = tile
        .iter()
        .map(|(x, a)| [*x, *a, fluid.u + fluid.grad * (x - fluid.c)])
        .collect();
    let (id, zero) = (Matrix3::identity(), Vector3::zeros());
    (
        added.then(|| closed.system(&id, &zero)),
        sea_drag_texels(&p, &texels).system(&id, &zero),
    )
}

proptest! {
    /// A tile all of whose texels face the flow (or all turn from it) in
    /// fluid moving the same over it takes, in closed form from its
    /// moments, what the sea's drag kernel takes texel by texel.
    #[test]
    fn a_tile_in_one_fluid_velocity_takes_its_texels_drag(
        texels in prop::collection::vec((vec3(), vec3(), 0.001..0.1f64), 1..80),
        normal in vec3(),
        u in vec3(),
        omega in prop::array::uniform3(-0.2..0.2f64),
        towards in prop::bool::ANY,
        drag in drag_coefficients(),
    ) {
        let n = normal + Vector3::new(0.0, 0.0, 1e-3);
        let n = n / n.norm();
        // Texels within 0.35 m of the origin facing within about 30° of n,
        // the body moving 3 m/s through the fluid along n or against it.
        let tile: Vec<(Vector3<f64>, Vector3<f64>)> = texels
            .iter()
            .map(|(x, tilt, area)| (0.1 * x, (n + 0.15 * tilt) * *area))
            .collect();
        let w = u + if towards { 3.0 } else { -3.0 } * n;
        let fluid = LinearFluid { u, grad: Matrix3::zeros(), c: Vector3::zeros() };
        let (closed, texels) = tile_drag(&tile, &fluid, &w, &Vector3::from(omega), &drag);
        let closed = closed.expect("all face alike");
        let (dk, db) = differences(&closed, &texels);
        prop_assert!(dk <= 1e-11 && db <= 1e-11, "K {dk:e}, b {db:e}");
    }
}

/// In fluid whose velocity varies over the tile, the closed form takes
/// the variation to first order: its difference from the texels' sums
/// falls as the square of the tile's size (and is far below what leaving
/// the variation out costs).
#[test]
fn a_tile_in_varying_fluid_takes_its_texels_drag_to_second_order() {
    let n = Vector3::new(0.3, 0.9, -0.2).normalize();
    let grad = Matrix3::new(0.8, -0.3, 0.5, 0.2, -0.6, 0.4, -0.7, 0.1, 0.3);
    let drag = Drag {
        coefficient: 0.9,
        linear: 15.0,
    };
    let (w, omega) = (Vector3::new(0.4, 2.5, -0.3), Vector3::new(0.3, -0.2, 0.5));
    let mut last: Option<f64> = None;
    for size in [0.4, 0.2, 0.1, 0.05] {
        // A curved patch of 8 × 8 texels about c, `size` across.
        let c = Vector3::new(0.5, -0.2, 0.3);
        let tangent = n.cross(&Vector3::x()).normalize();
        let bitangent = n.cross(&tangent);
        let tile: Vec<(Vector3<f64>, Vector3<f64>)> = (0..64)
            .map(|k| {
                let (s, t) = (((k % 8) as f64 - 3.5) / 8.0, ((k / 8) as f64 - 3.5) / 8.0);
                let bend = 0.3 * (s * s + t * t);
                let x = c + size * (s * tangent + t * bitangent + bend * n);
                let normal = (n - 0.6 * (s * tangent + t * bitangent)).normalize();
                (x, normal * (size * size / 64.0))
            })
            .collect();
        let fluid = LinearFluid {
            u: Vector3::new(-0.5, 0.2, 0.1),
            grad,
            c,
        };
        let (closed, texels) = tile_drag(&tile, &fluid, &w, &omega, &drag);
        let (dk, db) = differences(&closed.expect("all face the flow"), &texels);
        let uniform = LinearFluid {
            grad: Matrix3::zeros(),
            ..fluid
        };
        let (closed_uniform, _) = tile_drag(&tile, &uniform, &w, &omega, &drag);
        let (uk, ub) = differences(&closed_uniform.expect("all face the flow"), &texels);
        let d = dk.max(db);
        eprintln!(
            "{size} m: {d:.1e} (the velocity at the centre alone: {:.1e})",
            uk.max(ub)
        );
        assert!(d < 0.5 * uk.max(ub), "{size} m: {d:e} against {:e}", uk.max(ub));
        if let Some(prev) = last {
            assert!(
                d < 0.35 * prev,
                "{size} m: {d:e} after {prev:e}: not second order"
            );
        }
        last = Some(d);
    }
}

/// The per-texel kernel on one texel (through a one-texel atlas is
/// awkward, so the same arithmetic on the values).
fn kernel_one(acc: &mut DragAcc, x: &Vector3<f64>, a: &Vector3<f64>, p: &LocalDrag) {
    let h = [
        a.x,
        a.y,
        a.z,
        x.y * a.z - x.z * a.y,
        x.z * a.x - x.x * a.z,
        x.x * a.y - x.y * a.x,
    ];
    let f: f64 = h.iter().zip(&p.w).map(|(h, w)| h * w).sum();
    let mut s = if f > 0.0 { p.kq * f } else { 0.0 };
    let area = a.norm();
    if p.lin > 0.0 && area > 0.0 {
        s += p.lin * area;
        acc.add_rank1(p.lin / area, &h);
    }
    acc.add_iso(s, &[x.x, x.y, x.z]);
}

/// A body of the builtins at `n`², with a solid's mass properties.
fn body(mesh: &soak_bake::Mesh, n: u32) -> (Atlas, MassProperties, TiledAtlas) {
    let atlas = Atlas::bake(mesh, BakeOptions::square(n)).unwrap();
    let mass = MassModel::Solid { density: 500.0 }
        .mass_properties(&atlas)
        .unwrap();
    let tiled = TiledAtlas::new(&atlas);
    (atlas, mass, tiled)
}

/// Sphere, cuboid and boat at poses cut by the waterline, wholly under and
/// wholly above it, tilted, moving every way and spinning, in still water,
/// with a current, under a tilted plane and in an unbounded fluid, with
/// drag coefficients including none of either kind: the per-texel and the
/// tiled sums against the reference, and the drag both evaluations report
/// against the reference's.
/// The difference of two wrenches against the expected one's size, or
/// where it is zero (no motion relative to the fluid) against what one m/s
/// would make through the reference's system `want`.
fn wrench_difference(got: &Wrench, expected: &Wrench, want: &DragSums) -> f64 {
    let six = |w: &Wrench| {
        Vector6::new(
            w.force.x, w.force.y, w.force.z, w.torque.x, w.torque.y, w.torque.z,
        )
    };
    let (g, w) = (six(got), six(expected));
    let scale = max_abs(&w).max(1e-6 * max_abs(&want.k));
    if scale > 0.0 {
        max_abs(&(g - w)) / scale
    } else {
        max_abs(&g)
    }
}

/// On a sampled sea, the per-texel evaluation (the sea kernel's depths and
/// the sea's drag kernel, each texel in the fluid's velocity where it is)
/// gives the reference's system over the same sampled surface, for bodies
/// cut by the swell, moving and spinning.
#[test]
fn sampled_sea_drag_matches_the_reference() {
    let swell = Water::new(Gerstner::new(0.0, GerstnerWave::SWELL.to_vec(), 9.81).unwrap());
    let drag = Drag {
        coefficient: 0.8,
        linear: 20.0,
    };
    let options = HydroOptions {
        drag: Some(drag),
        ..HydroOptions::default()
    };
    let mut worst = 0.0f64;
    for (name, (atlas, mass, _)) in [
        ("sphere", body(&builtin::sphere(0.5, 32, 16), 128)),
        ("boat", body(&builtin::boat(4.0, 1.2, 0.6), 128)),
    ] {
        for (y, angles, v, omega) in [
            (
                0.0,
                (0.2, 0.4, 0.1),
                Vector3::new(0.7, -0.3, 0.2),
                Vector3::new(0.2, 0.5, -0.1),
            ),
            (
                -0.2,
                (-0.3, 1.2, 0.0),
                Vector3::new(-1.5, 0.4, 0.9),
                Vector3::zeros(),
            ),
            (
                0.1,
                (0.0, 0.0, 0.3),
                Vector3::zeros(),
                Vector3::new(-1.0, 0.3, 2.0),
            ),
        ] {
            let pose = Isometry3::from_parts(
                Vector3::new(0.4, y, -0.7).into(),
                UnitQuaternion::from_euler_angles(angles.0, angles.1, angles.2),
            );
            let state = BodyState {
                linear_velocity: v,
                angular_velocity: omega,
                ..BodyState::at_rest(pose)
            };
            let sampled = sampled_water(&atlas, &swell, &state, 1.3, &options)
                .unwrap()
                .expect("the swell is sampled by default");
            let want = reference_sums(&atlas, &sampled, &state, &mass, &drag);
            let (_, explicit) = implicit_drag(&want, &state, &mass, None, options.dt);
            let f = evaluate(&atlas, &sampled, &state, &mass, 0.0, &options).unwrap();
            let d = wrench_difference(&f.drag_explicit, &explicit, &want);
            assert!(d <= 1e-10, "{name} at y = {y}: {d:e}");
            worst = worst.max(d);
        }
    }
    eprintln!("sampled sea drag against the reference: worst wrench {worst:.1e}");
}

#[test]
fn whole_bodies_match_the_reference() {
    let bodies = [
        ("sphere", body(&builtin::sphere(0.5, 32, 16), 128)),
        ("cuboid", body(&builtin::cuboid(1.0, 0.6, 0.4), 96)),
        ("boat", body(&builtin::boat(4.0, 1.2, 0.6), 128)),
    ];
    type NamedWater = (&'static str, fn() -> Water);
    let waters: Vec<NamedWater> = vec![
        ("calm", || Water::calm(0.0)),
        ("current", || {
            Water::new(Plane::horizontal(0.0).with_current(Vector3::new(0.8, 0.0, -0.5)))
        }),
        ("tilted", || {
            Water::new(
                Plane::tilted(Point3::new(0.0, 0.05, 0.0), Vector3::new(0.1, 1.0, -0.05))
                    .unwrap()
                    .with_current(Vector3::new(-0.3, 0.1, 0.4)),
            )
        }),
        ("unbounded", || {
            Water::new(Unbounded {
                current: [0.2, -0.1, 0.3],
            })
        }),
    ];
    let drags = [
        Drag {
            coefficient: 0.8,
            linear: 20.0,
        },
        Drag {
            coefficient: 1.0,
            linear: 0.0,
        },
        Drag {
            coefficient: 0.0,
            linear: 5.0,
        },
    ];
    let motions = [
        (Vector3::zeros(), Vector3::zeros()),
        (Vector3::new(0.7, -0.3, 0.2), Vector3::new(0.2, 0.5, -0.1)),
        (Vector3::new(-1.5, 0.4, 0.9), Vector3::zeros()),
        (Vector3::zeros(), Vector3::new(-1.0, 0.3, 2.0)),
        (Vector3::new(0.0, 2.0, 0.0), Vector3::new(0.0, 0.0, 0.1)),
    ];
    let poses = [
        (0.1, (0.3, 0.2, 0.1)),
        (0.0, (0.0, 0.0, 0.0)),
        (-3.0, (1.0, -0.4, 0.7)),
        (3.0, (0.0, 0.5, 0.0)),
        (-0.2, (0.9, 1.4, -2.0)),
    ];
    let (mut worst_k, mut worst_b, mut worst_wrench) = (0.0f64, 0.0f64, 0.0f64);
    for (name, (atlas, mass, tiled)) in &bodies {
        for (wname, water) in &waters {
            let water = water();
            for (pi, (y, (ax, ay, az))) in poses.iter().enumerate() {
                let pose = Isometry3::from_parts(
                    Vector3::new(0.1, *y, -0.2).into(),
                    UnitQuaternion::from_euler_angles(*ax, *ay, *az),
                );
                for (mi, (v, omega)) in motions.iter().enumerate() {
                    let state = BodyState {
                        linear_velocity: *v,
                        angular_velocity: *omega,
                        ..BodyState::at_rest(pose)
                    };
                    for drag in &drags {
                        let what = format!("{name} {wname} pose {pi} motion {mi} {drag:?}");
                        let want = reference_sums(atlas, &water, &state, mass, drag);
                        let frame = Frame::new(atlas, &water, &state, mass, 0.0, 0.0);
                        let options = HydroOptions {
                            drag: Some(*drag),
                            ..HydroOptions::default()
                        };
                        let per_texel = drag_sums(atlas, &water, &state, &frame, drag, 0.0, 0..atlas.len());
                        let tiled_sums = tiled
                            .sums(atlas, &water, &state, &frame, 0.0, &options, true)
                            .1
                            .unwrap();
                        for (path, got) in [("per texel", &per_texel), ("tiled", &tiled_sums)] {
                            let (dk, db) = differences(got, &want);
                            assert!(dk <= 1e-10 && db <= 1e-10, "{what} {path}: K {dk:e}, b {db:e}");
                            worst_k = worst_k.max(dk);
                            worst_b = worst_b.max(db);
                        }
                        // What the evaluations report: the implicit and the
                        // explicit drag of the reference's system.
                        let (applied, explicit) = implicit_drag(&want, &state, mass, None, options.dt);
                        let f = evaluate(atlas, &water, &state, mass, 0.0, &options).unwrap();
                        let ft = tiled
                            .evaluate(atlas, &water, &state, mass, 0.0, &options)
                            .unwrap();
                        // Where no texel takes drag (the quadratic drag
                        // of a body whose wetted texels all face away from
                        // the flow), the drag is zero: exactly, where the
                        // solve hands back rounding.
                        let (applied, explicit) = if want.k == Matrix6::zeros() && want.b == Vector6::zeros()
                        {
                            let momentum = mass.mass * state.linear_velocity.norm()
                                + mass.inertia.norm() * state.angular_velocity.norm();
                            let noise = applied.force.norm().max(applied.torque.norm());
                            assert!(
                                noise <= 1e-12 * momentum / options.dt,
                                "{what}: the solve's {noise:e}"
                            );
                            (Wrench::default(), Wrench::default())
                        } else {
                            (applied, explicit)
                        };
                        for (path, f) in [("per texel", &f), ("tiled", &ft)] {
                            for (got, expected) in [(&f.drag, &applied), (&f.drag_explicit, &explicit)] {
                                let d = wrench_difference(got, expected, &want);
                                assert!(d <= 1e-10, "{what} {path} wrench: {d:e}");
                                worst_wrench = worst_wrench.max(d);
                            }
                        }
                    }
                }
            }
        }
    }
    println!("worst relative differences: K {worst_k:e}, b {worst_b:e}, wrench {worst_wrench:e}");
}

/// A body wholly above the water has no drag on any path; none at all
/// where both coefficients are zero.
#[test]
fn no_drag_where_nothing_is_wet_or_nothing_drags() {
    let (atlas, mass, tiled) = body(&builtin::sphere(0.5, 32, 16), 64);
    let water = Water::new(Plane::horizontal(0.0).with_current(Vector3::new(0.5, 0.0, 0.0)));
    let moving = |y: f64| BodyState {
        linear_velocity: Vector3::new(0.7, -0.3, 0.2),
        angular_velocity: Vector3::new(0.2, 0.5, -0.1),
        ..BodyState::at_rest(Isometry3::translation(0.0, y, 0.0))
    };
    for (state, drag) in [
        (moving(3.0), Drag::default()),
        (
            moving(0.0),
            Drag {
                coefficient: 0.0,
                linear: 0.0,
            },
        ),
    ] {
        let frame = Frame::new(&atlas, &water, &state, &mass, 0.0, 0.0);
        let options = HydroOptions {
            drag: Some(drag),
            ..HydroOptions::default()
        };
        let per_texel = drag_sums(&atlas, &water, &state, &frame, &drag, 0.0, 0..atlas.len());
        let tiled_sums = tiled
            .sums(&atlas, &water, &state, &frame, 0.0, &options, true)
            .1
            .unwrap();
        for got in [per_texel, tiled_sums] {
            assert_eq!(got.k, Matrix6::zeros());
            assert_eq!(got.b, Vector6::zeros());
        }
    }
}

/// The kernel over a tile whose closed forms were added takes back what
/// they added for texels that do not drag: over a whole body, the closed
/// forms of every texel less the kernel's corrections is the kernel's sum
/// of the submerged, facing texels.
#[test]
fn the_kernel_completes_the_closed_forms() {
    let (atlas, _, _) = body(&builtin::boat(4.0, 1.2, 0.6), 64);
    let rot = UnitQuaternion::from_euler_angles(0.3, -0.2, 0.4)
        .to_rotation_matrix()
        .into_inner();
    let drag = Drag {
        coefficient: 0.9,
        linear: 7.0,
    };
    let p = LocalDrag::new(
        &drag,
        1000.0,
        0.05,
        &Vector3::new(0.1, -1.0, 0.2),
        &rot,
        &Vector3::new(0.01, -0.02, 0.03),
        &Vector3::new(0.4, -0.2, 0.3),
        &Vector3::new(0.3, 0.1, -0.5),
        &Vector3::zeros(),
    );
    let mut want = DragAcc::default();
    add_drag_texels(&mut want, &atlas, 0..atlas.len(), &p, Added::default());
    let mut moments = DragMoments::default();
    for i in 0..atlas.len() {
        let (x, a) = texel(&atlas, i);
        moments.add_texel(&x, &a);
    }
    let mut got = DragAcc::default();
    moments.add_linear(&mut got, &p);
    moments.add_quadratic(&mut got, &p);
    add_drag_texels(
        &mut got,
        &atlas,
        0..atlas.len(),
        &p,
        Added {
            linear: true,
            quadratic: true,
        },
    );
    let size = max_abs(&want.k());
    assert!(max_abs(&(got.k() - want.k())) <= 1e-10 * size);
}
