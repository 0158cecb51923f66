//! Open containers in Rapier worlds, against hydrostatics computed
//! independently: an empty open box floats at the draft of the air in it;
//! pushed under it fills and, with walls denser than water, sinks; a bucket
//! tipped over fills and floats full at the freeboard of its filled shape;
//! an open boat carries a load at the freeboard the exact clipping of its
//! hull predicts, and swamps when heeled past the angle where its gunwale
//! meets the water.

use nalgebra::{Isometry3, Point3, UnitQuaternion, Vector3};
use rapier3d::prelude::*;
use soak_bake::{Atlas, BakeOptions, Mesh, builtin, cap_openings};
use soak_graph::{Flooding, FlowOptions};
use soak_hydro::reference::{ClipPlane, submerged_part};
use soak_hydro::{Drag, MassModel, MassProperties, Water};
use soak_rapier::{BodyDesc, Effects, ForceGenerator, SoakId};

const DT: f32 = 1.0 / 60.0;
const RHO: f64 = 1000.0;

struct World {
    world: PhysicsWorld,
    soak: ForceGenerator,
    handle: RigidBodyHandle,
    id: SoakId,
}

impl World {
    fn step(&mut self) {
        self.soak.step(&mut self.world).unwrap();
    }
    fn pose(&self) -> Isometry3<f64> {
        let p = self.world.bodies[self.handle].position();
        let (t, r) = (p.translation, p.rotation);
        Isometry3::from_parts(
            Vector3::new(t.x as f64, t.y as f64, t.z as f64).into(),
            UnitQuaternion::from_quaternion(nalgebra::Quaternion::new(
                r.w as f64, r.x as f64, r.y as f64, r.z as f64,
            )),
        )
    }
    fn inside(&self) -> f64 {
        self.soak.flooding(self.id).unwrap().inside()
    }
    fn capacity(&self) -> f64 {
        self.soak
            .flooding(self.id)
            .unwrap()
            .graph()
            .nodes()
            .map(|n| n.capacity)
            .sum()
    }
    /// Tilt of the body's y axis from the vertical, degrees.
    fn tilt(&self) -> f64 {
        (self.pose().rotation * Vector3::y())
            .angle(&Vector3::y())
            .to_degrees()
    }
}

fn open(mesh: &Mesh, n: u32) -> Atlas {
    Atlas::bake(&cap_openings(mesh).unwrap(), BakeOptions::square(n)).unwrap()
}

fn world(atlas: &Atlas, density: f64, thickness: f64, body: RigidBodyBuilder) -> World {
    let mut world = PhysicsWorld::new();
    world.integration_parameters.dt = DT;
    let handle = world.bodies.insert(body);
    let flooding =
        Flooding::open_container(atlas, atlas.wall_area() * thickness, FlowOptions::default()).unwrap();
    let mut soak = ForceGenerator::new(Water::calm(0.0));
    let id = soak
        .register(
            &mut world.bodies,
            &world.colliders,
            handle,
            BodyDesc {
                name: "container".into(),
                atlas: atlas.clone().into(),
                mass_model: MassModel::Walls { density, thickness },
                effects: Effects::buoyancy()
                    .with_drag(Drag {
                        coefficient: 1.0,
                        linear: 30.0,
                    })
                    .with_flooding(flooding),
            },
        )
        .unwrap();
    World {
        world,
        soak,
        handle,
        id,
    }
}

#[test]
fn an_empty_open_box_floats_upright_on_the_air_in_it() {
    // 1 m × 0.5 m × 1 m, walls 5 cm of density 600: 3 m² of walls, 90 kg,
    // so it floats 90 kg / (1000 kg/m³ × 1 m²) = 0.09 m deep.
    let atlas = open(&builtin::open_box(1.0, 0.5, 1.0), 128);
    let mut w = world(
        &atlas,
        600.0,
        0.05,
        RigidBodyBuilder::dynamic().translation(Vector::new(0.0, 0.3, 0.0)),
    );
    let mass = w.soak.body(w.id).unwrap().mass_properties().mass;
    assert!((mass - 90.0).abs() < 0.1, "{mass} kg");
    for _ in 0..1800 {
        w.step();
    }
    let draft = 0.25 - w.pose().translation.y;
    println!(
        "open box: draft {draft:.4} m (0.09 analytic), tilt {:.3}°",
        w.tilt()
    );
    assert!((draft - 0.09).abs() < 0.09 * 0.02, "draft {draft} m");
    assert!(w.tilt() < 0.5, "tilted {}°", w.tilt());
    assert_eq!(w.inside(), 0.0, "no water came over the rim");
}

#[test]
fn pushed_under_an_open_box_fills_and_sinks_when_its_walls_are_dense() {
    // Aluminium walls 5 mm thick (2700 kg/m³): 40.5 kg, floating 4 cm deep
    // while empty; held with its rim 10 cm under for a second, it fills
    // (through the cap, at the orifice rate: in well under a second) and,
    // let go, sinks.
    let atlas = open(&builtin::open_box(1.0, 0.5, 1.0), 128);
    let mut w = world(
        &atlas,
        2700.0,
        0.005,
        RigidBodyBuilder::dynamic().translation(Vector::new(0.0, -0.35, 0.0)),
    );
    let held = *w.world.bodies[w.handle].position();
    for _ in 0..60 {
        w.step();
        let b = &mut w.world.bodies[w.handle];
        b.set_position(held, true);
        b.set_linvel(Vector::ZERO, true);
        b.set_angvel(Vector::ZERO, true);
    }
    let filled = w.inside() / w.capacity();
    println!("open box held under: {:.1} % full after 1 s", 100.0 * filled);
    assert!(filled > 0.99, "only {:.1} % full", 100.0 * filled);
    for _ in 0..300 {
        w.step();
    }
    assert!(
        w.pose().translation.y < -2.0,
        "still at y = {}",
        w.pose().translation.y
    );
    assert!(w.soak.flooding(w.id).unwrap().conservation_error() < 1e-12);
}

#[test]
fn a_bucket_heeled_under_fills_and_floats_at_the_draft_of_what_it_holds() {
    // r = 0.3 m, h = 0.6 m, walls 2 cm of density 600 (lighter than water).
    let (r, h, t, rho_w) = (0.3f64, 0.6f64, 0.02f64, 600.0);
    let mesh = cap_openings(&builtin::bucket(r, h, 64)).unwrap();
    let atlas = Atlas::bake(&mesh, BakeOptions::square(512)).unwrap();
    let walls = atlas.wall_area() * t;
    let section = std::f64::consts::PI * r * r;
    let closed = section * h;
    let capacity = closed - walls;
    // Held heeled 60° with its mouth's lower edge under water for 5 s, it
    // fills to the level outside; let go, it rights itself and floats with
    // the water it holds.
    let mut w = world(
        &atlas,
        rho_w,
        t,
        RigidBodyBuilder::dynamic()
            .translation(Vector::new(0.0, -0.15, 0.0))
            .rotation(Vector::new(0.0, 0.0, 60f32.to_radians())),
    );
    let held = *w.world.bodies[w.handle].position();
    for _ in 0..300 {
        w.step();
        let b = &mut w.world.bodies[w.handle];
        b.set_position(held, true);
        b.set_linvel(Vector::ZERO, true);
        b.set_angvel(Vector::ZERO, true);
    }
    let taken = w.inside();
    for _ in 0..(60 * 60) {
        w.step();
    }
    let l = w.inside();
    // The hydrostatics of the bucket holding `l` m³ (its walls, and the
    // water at its compartments' nodes: soak's liquid graph), from the exact
    // clipping of its closed shape: the heel and height at which it
    // displaces its weight with the centre of buoyancy under the centre of
    // mass.
    let walls_mass = MassModel::Walls {
        density: rho_w,
        thickness: t,
    }
    .mass_properties(&atlas)
    .unwrap();
    let node = w
        .soak
        .flooding(w.id)
        .unwrap()
        .graph()
        .nodes()
        .next()
        .unwrap()
        .position;
    let body = walls_mass.combine(&MassProperties::point(RHO * l, node));
    let expected = upright_or_lolled(&mesh, body.mass / RHO, body.center_of_mass);
    let tilt = |p: &Isometry3<f64>| (p.rotation * Vector3::y()).angle(&Vector3::y()).to_degrees();
    println!(
        "bucket: took {taken:.4} m³ ({:.1} % of {capacity:.4}), kept {l:.4}; tilt {:.2}° at y {:.4} m \
         (exact hydrostatics of the bucket and its water: {:.2}° at y {:.4} m)",
        100.0 * taken / capacity,
        w.tilt(),
        w.pose().translation.y,
        tilt(&expected),
        expected.translation.y
    );
    assert!(taken > 0.5 * capacity, "took only {taken} m³");
    assert!(l > 0.25 * capacity, "kept only {l} m³");
    assert!((w.tilt() - tilt(&expected)).abs() < 0.5, "tilt {}°", w.tilt());
    assert!((w.pose().translation.y - expected.translation.y).abs() < 2e-3);
}

/// Where a body of the closed shape `mesh` (axially symmetric about y)
/// floats displacing `volume` m³ with its centre of mass at `com` (body
/// frame): upright if that is stable, else at the heel where the centre of
/// buoyancy comes under the centre of mass. Exact clipping, bisection.
fn upright_or_lolled(mesh: &Mesh, volume: f64, com: Point3<f64>) -> Isometry3<f64> {
    let lever = |heel: f64| {
        let pose = afloat(mesh, heel, 0.0, volume);
        let b = submerged_part(mesh, &pose, &ClipPlane::horizontal(0.0)).centroid;
        b.z - (pose * com).z
    };
    let small = 0.01;
    let (mut lo, mut hi) = (small, 1.5f64);
    if lever(lo).signum() == lever(hi).signum() {
        return afloat(mesh, 0.0, 0.0, volume);
    }
    for _ in 0..50 {
        let mid = 0.5 * (lo + hi);
        if lever(mid).signum() == lever(lo).signum() {
            lo = mid
        } else {
            hi = mid
        }
    }
    afloat(mesh, 0.5 * (lo + hi), 0.0, volume)
}

/// The pose at which the closed shape of `mesh`, heeled `heel` and
/// pitched `pitch` radians (about its long axis x, then about z), displaces
/// `volume` m³: exact clipping of the mesh, bisection on the height.
fn afloat(mesh: &Mesh, heel: f64, pitch: f64, volume: f64) -> Isometry3<f64> {
    let rotation = UnitQuaternion::from_axis_angle(&Vector3::z_axis(), pitch)
        * UnitQuaternion::from_axis_angle(&Vector3::x_axis(), heel);
    let pose = |y: f64| Isometry3::from_parts(Vector3::new(0.0, y, 0.0).into(), rotation);
    let (mut lo, mut hi) = (-2.0, 2.0);
    for _ in 0..80 {
        let mid = 0.5 * (lo + hi);
        let v = submerged_part(mesh, &pose(mid), &ClipPlane::horizontal(0.0)).volume;
        if v > volume { lo = mid } else { hi = mid }
    }
    pose(0.5 * (lo + hi))
}

/// Upright equilibrium in heave and trim: the pitch at which the centre of
/// buoyancy is under the centre of mass `com` (body frame), displacement
/// `volume` m³.
fn trimmed(mesh: &Mesh, volume: f64, com: Point3<f64>) -> Isometry3<f64> {
    let lever = |pitch: f64| {
        let pose = afloat(mesh, 0.0, pitch, volume);
        let b = submerged_part(mesh, &pose, &ClipPlane::horizontal(0.0)).centroid;
        b.x - (pose * com).x
    };
    let (mut lo, mut hi) = (-0.3f64, 0.3f64);
    let rising = lever(hi) > lever(lo);
    for _ in 0..50 {
        let mid = 0.5 * (lo + hi);
        if (lever(mid) > 0.0) == rising {
            hi = mid
        } else {
            lo = mid
        }
    }
    afloat(mesh, 0.0, 0.5 * (lo + hi), volume)
}

/// The gunwale's lowest point above the water at `pose`, m.
fn rim_clearance(mesh: &Mesh, pose: &Isometry3<f64>) -> f64 {
    mesh.openings[0]
        .rim
        .iter()
        .map(|&v| (pose * mesh.positions[v as usize]).y)
        .fold(f64::INFINITY, f64::min)
}

#[test]
fn an_open_boat_carries_a_load_at_its_freeboard_and_swamps_past_its_heel_limit() {
    let mesh = cap_openings(&builtin::open_boat(4.0, 1.2, 0.6)).unwrap();
    let atlas = Atlas::bake(&mesh, BakeOptions::square(256)).unwrap();
    let (rho_w, t, load) = (500.0, 0.02, 400.0);
    let walls = MassModel::Walls {
        density: rho_w,
        thickness: t,
    }
    .mass_properties(&atlas)
    .unwrap();
    let total = walls.mass + load;
    // The load rides at the boat's centre, on its floor.
    let cargo = MassProperties::point(load, Point3::new(0.0, 0.05, 0.0));
    let com = walls.combine(&cargo).center_of_mass;
    // Upright: the freeboard (the gunwale's lowest point) at the heave and
    // trim the exact clipping of the hull gives.
    let upright = trimmed(&mesh, total / RHO, com);
    let freeboard = rim_clearance(&mesh, &upright);
    // The heel (trim held level) at which the gunwale meets the water,
    // displacement kept.
    let (mut lo, mut hi) = (0.0f64, 1.2f64);
    for _ in 0..50 {
        let mid = 0.5 * (lo + hi);
        if rim_clearance(&mesh, &afloat(&mesh, mid, 0.0, total / RHO)) > 0.0 {
            lo = mid
        } else {
            hi = mid
        }
    }
    let limit = 0.5 * (lo + hi);
    println!(
        "open boat: {:.1} kg with its load, freeboard {freeboard:.4} m, gunwale under at {:.2}°",
        total,
        limit.to_degrees()
    );

    let run = |heel: f64, seconds: f64| -> (World, f64) {
        // Started where the hydrostatics put it, so it does not bob.
        let start = if heel == 0.0 {
            upright
        } else {
            afloat(&mesh, heel, 0.0, total / RHO)
        };
        let mut body = RigidBodyBuilder::dynamic()
            .translation(Vector::new(0.0, start.translation.y as f32, 0.0))
            .rotation(Vector::new(heel as f32, 0.0, 0.0));
        if heel != 0.0 {
            body = body.lock_rotations();
        }
        let mut w = world(&atlas, rho_w, t, body);
        w.soak
            .set_ballast(w.id, Some(cargo), &mut w.world.bodies, &w.world.colliders)
            .unwrap();
        let mut lowest = f64::INFINITY;
        for _ in 0..(60.0 * seconds) as usize {
            w.step();
            lowest = lowest.min(rim_clearance(&mesh, &w.pose()));
        }
        (w, lowest)
    };
    let (w, _) = run(0.0, 30.0);
    let measured = rim_clearance(&mesh, &w.pose());
    println!("  upright: freeboard {measured:.4} m, dry: {}", w.inside() == 0.0);
    assert!(
        (measured - freeboard).abs() < 0.03 * freeboard,
        "freeboard {measured} m, exact {freeboard} m"
    );
    assert_eq!(w.inside(), 0.0);
    // Held 3° short of the limit it stays dry; 3° past it, it swamps.
    let margin = 3f64.to_radians();
    let (short, _) = run(limit - margin, 20.0);
    let (past, _) = run(limit + margin, 20.0);
    println!(
        "  heeled {:.1}°: {:.3} m³ inside; {:.1}°: {:.3} m³ of {:.3}",
        (limit - margin).to_degrees(),
        short.inside(),
        (limit + margin).to_degrees(),
        past.inside(),
        past.capacity()
    );
    assert_eq!(short.inside(), 0.0);
    assert!(
        past.inside() > 0.5 * past.capacity(),
        "only {} m³ came in",
        past.inside()
    );
}

#[test]
fn scenes_say_open_walls_and_liquid_and_wrong_values_are_named() {
    use soak_rapier::{LoadedScene, Simulation};
    let scene = |body: &str| {
        format!(
            "dt = 0.02\nduration = 1.0\n[water]\nkind = \"plane\"\nlevel = 0.0\n[[bodies]]\nname = \"bucket\"\n\
             mesh = \"builtin:bucket\"\nresolution = 64\n{body}"
        )
    };
    let ok = scene(
        "open = true\nmass = { model = \"walls\", density = 600.0, thickness = 0.02 }\nliquid = 0.05\n",
    );
    let s = LoadedScene::from_str(&ok, "bucket.toml".as_ref()).unwrap();
    let sim = Simulation::from_scene(&s).unwrap();
    let id = sim.bodies[0].id.unwrap();
    let flooding = sim.soak.flooding(id).unwrap();
    assert!((flooding.inside() - 0.05).abs() < 1e-12);
    assert_eq!(flooding.graph().node_count(), soak_graph::CAVITY_LAYERS);
    // The walls' mass plus the water's reaches Rapier.
    let mass = sim.soak.body(id).unwrap().mass_properties().mass;
    let walls = 600.0 * 0.02 * sim.soak.body(id).unwrap().atlas().wall_area();
    assert!((mass - walls - 50.0).abs() < 1e-6 * mass, "{mass} kg");
    for (body, key) in [
        (
            "open = true\nmass = { model = \"walls\", density = 600.0, thickness = 0.02 }\nliquid = 1.0\n",
            "liquid",
        ),
        (
            "mass = { model = \"shell\", areal_density = 10.0 }\nliquid = 0.01\n",
            "liquid",
        ),
        (
            "open = true\nmass = { model = \"walls\", density = 600.0, thickness = -0.02 }\n",
            "mass.thickness",
        ),
        (
            "open = true\nmass = { model = \"solid\", density = 600.0 }\n",
            "mesh",
        ),
        ("mass = { model = \"shell\", areal_density = 10.0 }\n", "mesh"),
    ] {
        let text = scene(body);
        let e = LoadedScene::from_str(&text, "bucket.toml".as_ref())
            .and_then(|s| Simulation::from_scene(&s).map(|_| ()))
            .unwrap_err()
            .to_string();
        assert!(e.contains("bucket.toml") && e.contains(key), "{key}: {e}");
    }
}

/// The thick-walled crate (one closed surface: outside, rim, inside) as a
/// scene body with `open = true`, its walls a solid of `density`.
fn thick_crate(density: f64, y: f64) -> soak_rapier::Simulation {
    let text = format!(
        "dt = 0.0166667\nduration = 30.0\n[water]\nkind = \"plane\"\nlevel = 0.0\n[[bodies]]\nname = \"crate\"\n\
         mesh = \"builtin:thick_open_box:1x0.5x1:0.05\"\nopen = true\nresolution = 128\n\
         mass = {{ model = \"solid\", density = {density} }}\nposition = [0.0, {y}, 0.0]\n\
         drag = {{ coefficient = 1.0, linear = 30.0 }}\n"
    );
    let s = soak_rapier::LoadedScene::from_str(&text, "crate.toml".as_ref()).unwrap();
    soak_rapier::Simulation::from_scene(&s).unwrap()
}

#[test]
fn a_thick_walled_crate_floats_on_the_air_in_its_cavity_and_sinks_once_filled() {
    // Walls: the 1 × 0.5 × 1 m box less its 0.9 × 0.45 × 0.9 m cavity,
    // 0.1355 m³; of density 600, 81.3 kg: afloat on the cavity's air it is
    // 81.3 kg / (1000 kg/m³ × 1 m²) = 0.0813 m deep.
    let walls = 0.5 - 0.9 * 0.45 * 0.9;
    let mut sim = thick_crate(600.0, 0.3);
    let id = sim.bodies[0].id.unwrap();
    let mass = sim.soak.body(id).unwrap().mass_properties().mass;
    assert!((mass - 600.0 * walls).abs() < 1e-3 * mass, "{mass} kg");
    for _ in 0..1800 {
        sim.step().unwrap();
    }
    let r = &sim.report()[0];
    let draft = 0.25 - r.position[1];
    let expected = 600.0 * walls / 1000.0;
    let tilt = r.rotation[0].abs().max(r.rotation[2].abs());
    println!(
        "thick-walled crate: draft {draft:.4} m ({expected:.4} from its walls' weight), tilt {tilt:.3}°"
    );
    assert!((draft - expected).abs() < 0.02 * expected, "draft {draft} m");
    assert!(tilt < 0.5);
    assert_eq!(sim.soak.flooding(id).unwrap().inside(), 0.0);
    // Of aluminium (2700: 366 kg) it floats 0.37 m deep while dry; held
    // with its rim 10 cm under, it fills and, let go, sinks.
    let mut sim = thick_crate(2700.0, -0.35);
    let handle = sim.bodies[0].handle;
    let held = *sim.world.bodies[handle].position();
    for _ in 0..120 {
        sim.step().unwrap();
        let b = &mut sim.world.bodies[handle];
        b.set_position(held, true);
        b.set_linvel(Vector::ZERO, true);
        b.set_angvel(Vector::ZERO, true);
    }
    let f = sim.soak.flooding(id).unwrap();
    let capacity: f64 = f.graph().nodes().map(|n| n.capacity).sum();
    assert!((capacity - 0.9 * 0.45 * 0.9).abs() < 1e-3, "cavity {capacity} m³");
    assert!(f.inside() > 0.99 * capacity, "{} of {capacity} m³", f.inside());
    for _ in 0..300 {
        sim.step().unwrap();
    }
    assert!(sim.report()[0].position[1] < -2.0);
}
