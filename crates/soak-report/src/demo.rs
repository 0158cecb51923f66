//! The demo's cases (`soak demo`): the thesis' Chapter 7 cases side by
//! side, and what came after it, each a run of a Rapier world written as
//! plots and CSV into a folder, with a line that sums it up ([`CASES`]).
//!
//! One file on purpose: the cases share the `World` and `Table` helpers
//! here and each is one function that reads top to bottom.

use std::path::Path;

use crate::chart::{Axis, Chart, Figure, Line, Series};
use nalgebra::{Point3, UnitQuaternion, Vector3};
use rapier3d::prelude::*;
use soak_bake::{Atlas, BakeOptions, builtin};
use soak_hydro::{Drag, Gerstner, GerstnerWave, MassModel, Water, volume_moments};
use soak_rapier::{BodyDesc, Effects, ForceGenerator, SoakId, convert};

/// A time series: named columns of equal length.
struct Table {
    names: Vec<&'static str>,
    rows: Vec<Vec<f64>>,
}

impl Table {
    fn new(names: &[&'static str]) -> Self {
        Self {
            names: names.to_vec(),
            rows: Vec::new(),
        }
    }
    fn push(&mut self, row: Vec<f64>) {
        debug_assert_eq!(row.len(), self.names.len());
        self.rows.push(row);
    }
    fn col(&self, name: &str) -> Vec<f64> {
        let k = self.names.iter().position(|n| *n == name).expect("known column");
        self.rows.iter().map(|r| r[k]).collect()
    }
    fn series(&self, label: &str, x: &str, y: &str) -> Series {
        Series::new(label, self.col(x).into_iter().zip(self.col(y)).collect())
    }
    fn write_csv(&self, path: &Path) -> Result<(), DemoError> {
        let mut s = self.names.join(",");
        s.push('\n');
        for r in &self.rows {
            s.push_str(&r.iter().map(|v| format!("{v:.6}")).collect::<Vec<_>>().join(","));
            s.push('\n');
        }
        std::fs::write(path, s).map_err(|source| DemoError::Io {
            path: path.to_path_buf(),
            source,
        })
    }
}

struct World {
    world: PhysicsWorld,
    soak: ForceGenerator,
}

impl World {
    fn new(water: Water, dt: f32) -> Self {
        let mut world = PhysicsWorld::new();
        world.integration_parameters.dt = dt;
        Self {
            world,
            soak: ForceGenerator::new(water),
        }
    }

    fn add(
        &mut self,
        name: &str,
        atlas: Atlas,
        mass: MassModel,
        effects: Effects,
        pose: Pose,
    ) -> Result<(RigidBodyHandle, SoakId), DemoError> {
        let h = self.world.bodies.insert(RigidBodyBuilder::dynamic().pose(pose));
        let id = self.soak.register(
            &mut self.world.bodies,
            &self.world.colliders,
            h,
            BodyDesc {
                name: name.into(),
                atlas: atlas.into(),
                mass_model: mass,
                effects,
            },
        )?;
        Ok((h, id))
    }

    fn step(&mut self) -> Result<(), DemoError> {
        self.soak.step(&mut self.world)?;
        Ok(())
    }

    fn up(&self, h: RigidBodyHandle) -> Vector3<f64> {
        convert::rotation(*self.world.bodies[h].rotation()) * Vector3::y()
    }
}

fn tilt_deg(up: &Vector3<f64>) -> f64 {
    up.y.clamp(-1.0, 1.0).acos().to_degrees()
}

/// Fig. 7.2/7.3: a buoy riding a Gerstner sea.
fn buoy(seconds: f64, out: &Path) -> Result<String, DemoError> {
    let sea = Gerstner::new(
        0.0,
        vec![
            GerstnerWave {
                amplitude: 0.3,
                wavelength: 12.0,
                direction_deg: 0.0,
                steepness: 0.6,
                phase: 0.0,
            },
            GerstnerWave {
                amplitude: 0.08,
                wavelength: 5.0,
                direction_deg: 30.0,
                steepness: 0.5,
                phase: 1.3,
            },
        ],
        9.81,
    )?;
    let mut w = World::new(Water::new(sea), 1.0 / 60.0);
    let mesh = builtin::capsule(0.3, 0.6, 32);
    let atlas = Atlas::bake(&mesh, BakeOptions::square(128))?;
    let drag = Drag {
        coefficient: 0.8,
        linear: 60.0,
    };
    let (h, id) = w.add(
        "buoy",
        atlas,
        MassModel::Solid { density: 150.0 },
        Effects::buoyancy().with_drag(drag),
        Pose::IDENTITY,
    )?;
    // Ballast low in the hull keeps the buoy upright.
    let ballast = soak_hydro::MassProperties::point(75.0, Point3::new(0.0, -0.55, 0.0));
    w.soak
        .set_extra_mass(id, Some(ballast), &mut w.world.bodies, &w.world.colliders)?;
    let mut t = Table::new(&[
        "t_s",
        "buoy_y_m",
        "sea_y_m",
        "tilt_deg",
        "buoyancy_n",
        "weight_n",
        "submerged_m3",
    ]);
    let weight = w.world.bodies[h].mass() as f64 * 9.81;
    let steps = (seconds * 60.0) as usize;
    for _ in 0..steps {
        w.step()?;
        let rb = &w.world.bodies[h];
        let p = convert::vector(rb.translation());
        let f = *w.soak.body(id).expect("registered").forces();
        let sea_y = w.soak.water().surface.height(p.x, p.z, w.soak.time());
        t.push(vec![
            w.soak.time(),
            p.y,
            sea_y,
            tilt_deg(&w.up(h)),
            f.buoyancy.force.y,
            weight,
            f.submerged_volume,
        ]);
    }
    t.write_csv(&out.join("buoy.csv"))?;
    Figure::new(1500, 450)
        .title("Buoy on a Gerstner sea (thesis Fig. 7.2/7.3)")
        .panel(
            Chart::new("Heave")
                .x(Axis::linear("time (s)"))
                .y(Axis::linear("height (m)"))
                .series(
                    t.series("sea surface at the buoy", "t_s", "sea_y_m")
                        .line(Line::Dashed),
                )
                .series(t.series("buoy centre", "t_s", "buoy_y_m")),
        )
        .panel(
            Chart::new("Tilt")
                .x(Axis::linear("time (s)"))
                .y(Axis::linear("tilt from vertical (°)"))
                .series(t.series("tilt", "t_s", "tilt_deg")),
        )
        .panel(
            Chart::new("Forces")
                .x(Axis::linear("time (s)"))
                .y(Axis::linear("force (N)"))
                .series(t.series("buoyancy", "t_s", "buoyancy_n"))
                .series(t.series("weight", "t_s", "weight_n").line(Line::Dashed)),
        )
        .write_png(&out.join("buoy.png"))?;
    let ys = t.col("buoy_y_m");
    let (lo, hi) = ys
        .iter()
        .fold((f64::MAX, f64::MIN), |(a, b), &y| (a.min(y), b.max(y)));
    Ok(format!("buoy: heaves between {lo:.2} and {hi:.2} m"))
}

/// Fig. 7.6: a ball whose centre of mass is above its centre of buoyancy
/// turns over to a new equilibrium instead of returning.
fn top_heavy_ball(seconds: f64, out: &Path) -> Result<String, DemoError> {
    let mut w = World::new(Water::calm(0.0), 1.0 / 60.0);
    let mesh = builtin::sphere(0.5, 48, 24);
    let atlas = Atlas::bake(&mesh, BakeOptions::square(128))?;
    let sigma: Vec<f32> = (0..atlas.len())
        .map(|i| if atlas.position(i).y > 0.25 { 40.0 } else { 4.0 })
        .collect();
    let nudge = UnitQuaternion::from_axis_angle(&Vector3::z_axis(), 3f64.to_radians());
    // Light: it floats with most of it above water, so start it there.
    let pose = Pose::from_parts(Vector::new(0.0, 0.38, 0.0), convert::to_rotation(&nudge));
    let drag = Drag {
        coefficient: 0.5,
        linear: 15.0,
    };
    let (h, id) = w.add(
        "ball",
        atlas,
        MassModel::ShellTexture { areal_density: sigma },
        Effects::buoyancy().with_drag(drag),
        pose,
    )?;
    let mut t = Table::new(&["t_s", "tilt_deg", "centre_y_m", "com_height_m", "cob_height_m"]);
    for _ in 0..(seconds * 60.0) as usize {
        w.step()?;
        let rb = &w.world.bodies[h];
        let f = *w.soak.body(id).expect("registered").forces();
        t.push(vec![
            w.soak.time(),
            tilt_deg(&w.up(h)),
            rb.translation().y as f64,
            rb.center_of_mass().y as f64,
            if f.submerged_volume > 0.0 {
                f.center_of_buoyancy.y
            } else {
                f64::NAN
            },
        ]);
    }
    t.write_csv(&out.join("top_heavy_ball.csv"))?;
    Figure::new(1100, 450)
        .title("A top-heavy ball turns over (thesis Fig. 7.6)")
        .panel(
            Chart::new("Orientation")
                .x(Axis::linear("time (s)"))
                .y(Axis::linear("tilt from start (°)").range(0.0, 190.0))
                .series(t.series("tilt", "t_s", "tilt_deg")),
        )
        .panel(
            Chart::new("Centres")
                .x(Axis::linear("time (s)"))
                .y(Axis::linear("height (m)"))
                .series(t.series("centre of mass", "t_s", "com_height_m"))
                .series(
                    t.series("centre of buoyancy", "t_s", "cob_height_m")
                        .line(Line::Dashed),
                ),
        )
        .write_png(&out.join("top_heavy_ball.png"))?;
    Ok(format!(
        "top-heavy ball: ends tilted {:.0}° from its start",
        t.col("tilt_deg").last().copied().unwrap_or(0.0)
    ))
}

/// Fig. 7.7: the shell density moves over time (people walking in a small
/// boat); mass, centre of mass and inertia follow every step and the ball
/// rolls after its heavy side.
fn moving_mass(seconds: f64, out: &Path) -> Result<String, DemoError> {
    let mut w = World::new(Water::calm(0.0), 1.0 / 60.0);
    let mesh = builtin::sphere(0.5, 48, 24);
    let atlas = Atlas::bake(&mesh, BakeOptions::square(128))?;
    let dirs: Vec<Vector3<f64>> = (0..atlas.len())
        .map(|i| (atlas.position(i) - atlas.origin()).normalize())
        .collect();
    let texture = |phase: f64, growth: f64| -> Vec<f32> {
        // A heavy patch that travels round the ball's equator in its own frame.
        let d = Vector3::new(phase.cos(), 0.0, phase.sin());
        dirs.iter()
            .map(|n| (3.0 + growth * 40.0 * n.dot(&d).max(0.0).powi(6)) as f32)
            .collect()
    };
    let drag = Drag {
        coefficient: 0.5,
        linear: 15.0,
    };
    let (h, id) = w.add(
        "ball",
        atlas.clone(),
        MassModel::ShellTexture {
            areal_density: texture(0.0, 0.0),
        },
        Effects::buoyancy().with_drag(drag),
        Pose::IDENTITY,
    )?;
    let mut t = Table::new(&[
        "t_s",
        "mass_kg",
        "com_offset_m",
        "patch_deg",
        "heavy_side_down_deg",
    ]);
    let period = 20.0;
    for _ in 0..(seconds * 60.0) as usize {
        let time = w.soak.time();
        let phase = std::f64::consts::TAU * time / period;
        let growth = (time / 5.0).min(1.0);
        let model = MassModel::ShellTexture {
            areal_density: texture(phase, growth),
        };
        w.soak
            .set_mass_model(id, model, &mut w.world.bodies, &w.world.colliders)?;
        w.step()?;
        let rb = &w.world.bodies[h];
        let q = convert::rotation(*rb.rotation());
        let com_local = convert::vector(rb.local_center_of_mass());
        // Angle between the heavy side (world) and straight down.
        let heavy = q * Vector3::new(phase.cos(), 0.0, phase.sin());
        let down = heavy.dot(&-Vector3::y()).clamp(-1.0, 1.0).acos().to_degrees();
        t.push(vec![
            time,
            rb.mass() as f64,
            com_local.norm(),
            phase.to_degrees() % 360.0,
            down,
        ]);
    }
    t.write_csv(&out.join("moving_mass.csv"))?;
    Figure::new(1500, 450)
        .title("Mass that moves inside a floating ball (thesis Fig. 7.7)")
        .panel(
            Chart::new("Mass as Rapier has it")
                .x(Axis::linear("time (s)"))
                .y(Axis::linear("mass (kg)"))
                .series(t.series("mass", "t_s", "mass_kg")),
        )
        .panel(
            Chart::new("Centre of mass")
                .x(Axis::linear("time (s)"))
                .y(Axis::linear("offset from the centre (m)"))
                .series(t.series("|c|", "t_s", "com_offset_m")),
        )
        .panel(
            Chart::new("The heavy side seeks the bottom")
                .x(Axis::linear("time (s)"))
                .y(Axis::linear("angle from straight down (°)").range(0.0, 180.0))
                .series(t.series("heavy side", "t_s", "heavy_side_down_deg")),
        )
        .write_png(&out.join("moving_mass.png"))?;
    let late: Vec<f64> = t
        .rows
        .iter()
        .filter(|r| r[0] > seconds * 0.5)
        .map(|r| r[4])
        .collect();
    let mean = late.iter().sum::<f64>() / late.len().max(1) as f64;
    Ok(format!(
        "moving mass: heavy side within {mean:.0}° of straight down on average once loaded"
    ))
}

/// Fig. 7.9: a balloon inflating while it rises through air; its mesh
/// deforms every step and the atlas follows from its barycentrics.
fn balloon(seconds: f64, out: &Path) -> Result<String, DemoError> {
    let mut w = World::new(Water::air(), 1.0 / 60.0);
    let r0 = 1.0;
    let mesh = builtin::sphere(r0, 48, 24);
    let atlas = Atlas::bake(&mesh, BakeOptions::square(128))?;
    let envelope = 3.0; // kg of fabric
    let sigma0 = envelope / atlas.area();
    let helium = 0.17; // kg/m³
    let drag = Drag {
        coefficient: 0.5,
        linear: 0.0,
    };
    let (h, id) = w.add(
        "balloon",
        atlas,
        MassModel::Shell {
            areal_density: sigma0,
        },
        Effects::buoyancy().with_drag(drag),
        Pose::IDENTITY,
    )?;
    let mut t = Table::new(&["t_s", "altitude_m", "radius_m", "volume_m3", "lift_n", "weight_n"]);
    let grow = seconds * 0.6;
    for _ in 0..(seconds * 60.0) as usize {
        let time = w.soak.time();
        let r = r0 * (1.0 + 1.5 * (time / grow).min(1.0));
        let moved: Vec<Point3<f64>> = mesh
            .positions
            .iter()
            .map(|p| Point3::from(p.coords * (r / r0)))
            .collect();
        w.soak
            .deform(id, &moved, &mut w.world.bodies, &w.world.colliders)?;
        // The fabric stretches (constant mass); the gas inside is a uniform solid.
        let area = w.soak.body(id).expect("registered").atlas().area();
        w.soak.set_mass_model(
            id,
            MassModel::Shell {
                areal_density: envelope / area,
            },
            &mut w.world.bodies,
            &w.world.colliders,
        )?;
        let gas = volume_moments(w.soak.body(id).expect("registered").atlas()).solid(helium);
        w.soak
            .set_extra_mass(id, Some(gas), &mut w.world.bodies, &w.world.colliders)?;
        w.step()?;
        let rb = &w.world.bodies[h];
        let f = *w.soak.body(id).expect("registered").forces();
        t.push(vec![
            time,
            rb.translation().y as f64,
            r,
            f.submerged_volume,
            f.buoyancy.force.y,
            rb.mass() as f64 * 9.81,
        ]);
    }
    t.write_csv(&out.join("balloon.csv"))?;
    Figure::new(1500, 450)
        .title("A balloon inflating as it rises through air (thesis Fig. 7.9)")
        .panel(
            Chart::new("Altitude")
                .x(Axis::linear("time (s)"))
                .y(Axis::linear("height (m)"))
                .series(t.series("balloon", "t_s", "altitude_m")),
        )
        .panel(
            Chart::new("Displaced air")
                .x(Axis::linear("time (s)"))
                .y(Axis::linear("volume (m³)"))
                .series(t.series("volume", "t_s", "volume_m3")),
        )
        .panel(
            Chart::new("Forces")
                .x(Axis::linear("time (s)"))
                .y(Axis::linear("force (N)"))
                .series(t.series("buoyancy", "t_s", "lift_n"))
                .series(
                    t.series("weight (fabric + helium)", "t_s", "weight_n")
                        .line(Line::Dashed),
                ),
        )
        .write_png(&out.join("balloon.png"))?;
    Ok(format!(
        "balloon: rose to {:.1} m while its volume grew {:.0}×",
        t.col("altitude_m").last().copied().unwrap_or(0.0),
        (2.5f64).powi(3)
    ))
}

/// Fig. 7.4/7.5: a boat holed at the bow (starboard) and one holed at the
/// stern on both sides take on water compartment by compartment and sink,
/// bow first and stern first.
fn sinking_boats(seconds: f64, out: &Path) -> Result<String, DemoError> {
    use soak_graph::{Flooding, FlowOptions, Format, Permeability, parse_graph};
    use soak_rapier::hull::{highest_above_water, pitch_degrees};
    let graph_text = include_str!("../graphs/boat.toml");
    let mesh = builtin::boat(4.0, 1.2, 0.6);
    let atlas = Atlas::bake(&mesh, BakeOptions::square(128))?;
    let mut world = World::new(Water::calm(0.0), 1.0 / 30.0);
    let damage: [(&str, Vec<Point3<f64>>, f64, f32); 2] = [
        ("bow", vec![Point3::new(1.5, 0.15, 0.125)], 0.15, -3.0),
        (
            "stern",
            vec![Point3::new(-1.6, 0.1, 0.2), Point3::new(-1.6, 0.1, -0.2)],
            0.12,
            3.0,
        ),
    ];
    let drag = Drag {
        coefficient: 1.0,
        linear: 50.0,
    };
    let mut boats = Vec::new();
    let mut handles = Vec::new();
    for (name, _, _, z) in &damage {
        let pose = Pose::from_translation(Vector::new(0.0, -0.15, *z));
        let graph = parse_graph(graph_text, Format::Toml, Path::new("boat.toml"))?;
        let flooding = Flooding::for_atlas(
            &atlas,
            graph,
            Permeability::watertight(&atlas),
            FlowOptions::default(),
        )?;
        let (h, id) = world.add(
            name,
            atlas.clone(),
            MassModel::Shell { areal_density: 40.0 },
            Effects::buoyancy().with_drag(drag).with_flooding(flooding),
            pose,
        )?;
        boats.push(id);
        handles.push(h);
    }
    let punch = 5.0;
    let mut punched = false;
    let mut sunk: [Option<f64>; 2] = [None, None];
    let mut t = Table::new(&[
        "t_s",
        "bow_water_m3",
        "stern_water_m3",
        "bow_mass_kg",
        "stern_mass_kg",
        "bow_pitch_deg",
        "stern_pitch_deg",
    ]);
    let steps = (seconds * 30.0) as usize;
    for _ in 0..steps {
        let time = world.soak.time();
        if !punched && time >= punch {
            for (&id, (_, centres, radius, _)) in boats.iter().zip(&damage) {
                for c in centres {
                    world.soak.punch(id, *c, *radius, 1e-6)?;
                }
            }
            punched = true;
        }
        world.step()?;
        let mut row = vec![world.soak.time()];
        let pitch: Vec<f64> = handles
            .iter()
            .map(|h| pitch_degrees(world.world.bodies[*h].position()))
            .collect();
        for &id in &boats {
            row.push(world.soak.flooding(id).map_or(0.0, |f| f.inside()));
        }
        for h in &handles {
            row.push(world.world.bodies[*h].mass() as f64);
        }
        row.extend(&pitch);
        for (k, h) in handles.iter().enumerate() {
            // Sunk: the whole hull under water (as the `sinking_boat`
            // example has it).
            let top = highest_above_water(
                &atlas,
                world.world.bodies[*h].position(),
                world.soak.water(),
                world.soak.time(),
            );
            if sunk[k].is_none() && top < 0.0 {
                sunk[k] = Some(world.soak.time() - punch);
            }
        }
        t.push(row);
    }
    t.write_csv(&out.join("sinking_boats.csv"))?;
    Figure::new(1500, 450)
        .title("Holed boats take on water and sink (thesis Fig. 7.4, bow; Fig. 7.5, stern)")
        .panel(
            Chart::new("Water inside")
                .x(Axis::linear("time (s)"))
                .y(Axis::linear("volume (m³)"))
                .series(t.series("bow hole", "t_s", "bow_water_m3"))
                .series(t.series("stern holes", "t_s", "stern_water_m3")),
        )
        .panel(
            Chart::new("Mass as Rapier has it")
                .x(Axis::linear("time (s)"))
                .y(Axis::linear("mass (kg)"))
                .series(t.series("bow hole", "t_s", "bow_mass_kg"))
                .series(t.series("stern holes", "t_s", "stern_mass_kg")),
        )
        .panel(
            Chart::new("Trim (bow up > 0)")
                .x(Axis::linear("time (s)"))
                .y(Axis::linear("pitch (°)"))
                .series(t.series("bow hole", "t_s", "bow_pitch_deg"))
                .series(t.series("stern holes", "t_s", "stern_pitch_deg")),
        )
        .write_png(&out.join("sinking_boats.png"))?;
    let when = |s: Option<f64>| {
        s.map_or("still afloat".to_string(), |t| {
            format!("sank {t:.0} s after the damage")
        })
    };
    Ok(format!(
        "sinking boats: bow-holed {}, stern-holed {}",
        when(sunk[0]),
        when(sunk[1])
    ))
}

/// A boat passing a moored buoy on calm water, with the waves bodies make
/// and without: the boat's wake reaches the buoy and rocks it; without the
/// waves the buoy never knows the boat went by.
fn passing_boat(seconds: f64, out: &Path) -> Result<String, DemoError> {
    let mut t = Table::new(&[
        "t_s",
        "tilt_on_deg",
        "tilt_off_deg",
        "heave_on_m",
        "heave_off_m",
        "boat_x_on_m",
    ]);
    let steps = (seconds * 60.0) as usize;
    let mut runs = Vec::new();
    for waves in [true, false] {
        let mut w = World::new(Water::calm(0.0), 1.0 / 60.0);
        if waves {
            w.soak = std::mem::replace(&mut w.soak, ForceGenerator::new(Water::calm(0.0)))
                .with_waves(soak_rapier::WaveCoupling::default())?;
        }
        let boat = Atlas::bake(&builtin::boat(6.0, 2.0, 1.0), BakeOptions::square(128))?;
        let (bh, _) = w.add(
            "boat",
            boat,
            MassModel::Solid { density: 300.0 },
            Effects::buoyancy(),
            Pose::from_translation(Vector::new(-15.0, -0.3, 4.0)),
        )?;
        w.world.bodies[bh].set_linvel(Vector::new(3.0, 0.0, 0.0), true);
        // A disc buoy (r = 0.5 m, 0.3 m tall, 400 kg/m³): wide enough to
        // float upright on its own.
        let buoy = Atlas::bake(&builtin::cylinder(0.5, 0.3, 64), BakeOptions::square(128))?;
        let (h, _) = w.add(
            "buoy",
            buoy,
            MassModel::Solid { density: 400.0 },
            Effects::buoyancy().with_drag(Drag {
                coefficient: 0.8,
                linear: 20.0,
            }),
            Pose::from_translation(Vector::new(0.0, -0.03, 0.0)),
        )?;
        // Moored: a rope of 9 m from the middle of its bottom to an anchor
        // 8.2 m down (slack at rest: the buoy can rise 0.8 m or drift 3.8 m
        // before it pulls).
        let anchor = w
            .world
            .bodies
            .insert(RigidBodyBuilder::fixed().translation(Vector::new(0.0, -8.2, 0.0)));
        let rope = RopeJointBuilder::new(9.0).local_anchor2(Vector::new(0.0, -0.15, 0.0));
        w.world.impulse_joints.insert(anchor, h, rope, true);
        let mut rows = Vec::with_capacity(steps);
        for _ in 0..steps {
            w.step()?;
            let rb = &w.world.bodies[h];
            let boat = &w.world.bodies[bh];
            rows.push([
                w.soak.time(),
                tilt_deg(&w.up(h)),
                rb.translation().y as f64,
                boat.translation().x as f64,
            ]);
        }
        runs.push(rows);
    }
    for (on, off) in runs[0].iter().zip(&runs[1]) {
        t.push(vec![on[0], on[1], off[1], on[2], off[2], on[3]]);
    }
    t.write_csv(&out.join("passing_boat.csv"))?;
    Figure::new(1100, 450)
        .title("A boat passes a moored buoy 4 m off at 3 m/s (abeam at 5 s): its wake rocks the buoy")
        .panel(
            Chart::new("Buoy tilt")
                .x(Axis::linear("time (s)"))
                .y(Axis::linear("tilt from vertical (°)"))
                .series(t.series("with the waves bodies make", "t_s", "tilt_on_deg"))
                .series(t.series("without", "t_s", "tilt_off_deg").line(Line::Dashed)),
        )
        .panel(
            Chart::new("Buoy heave")
                .x(Axis::linear("time (s)"))
                .y(Axis::linear("centre height (m)"))
                .series(t.series("with the waves bodies make", "t_s", "heave_on_m"))
                .series(t.series("without", "t_s", "heave_off_m").line(Line::Dashed)),
        )
        .write_png(&out.join("passing_boat.png"))?;
    let peak = |c: &str| t.col(c).into_iter().fold(0.0, f64::max);
    Ok(format!(
        "passing boat: the buoy tilts up to {:.2}° with the waves bodies make, {:.2}° without",
        peak("tilt_on_deg"),
        peak("tilt_off_deg")
    ))
}

/// A demo case: runs for the given seconds, writes its plots and CSV into
/// the folder, and returns a line that sums it up.
pub type Case = fn(f64, &Path) -> Result<String, DemoError>;

/// The cases `soak demo` runs, in order: name, case and full duration (s).
pub const CASES: [(&str, Case, f64); 6] = [
    ("buoy", buoy, 40.0),
    ("top_heavy_ball", top_heavy_ball, 30.0),
    ("moving_mass", moving_mass, 60.0),
    ("balloon", balloon, 30.0),
    ("sinking_boats", sinking_boats, 150.0),
    ("passing_boat", passing_boat, 16.0),
];

/// A demo case that could not run.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum DemoError {
    /// A body could not be registered or a step failed.
    #[error(transparent)]
    Soak(#[from] soak_rapier::SoakError),
    /// A mesh could not be baked.
    #[error(transparent)]
    Bake(#[from] soak_bake::BakeError),
    /// The boat's liquid graph could not be read.
    #[error(transparent)]
    Graph(#[from] soak_graph::GraphFileError),
    /// A liquid graph could not be laid in its hull.
    #[error(transparent)]
    Flow(#[from] soak_graph::FlowError),
    /// A water surface was refused.
    #[error(transparent)]
    Water(#[from] soak_hydro::WaterError),
    /// A plot could not be drawn or written.
    #[error(transparent)]
    Chart(#[from] crate::chart::ChartError),
    /// A file could not be written.
    #[error("cannot write `{path}`: {source}")]
    Io {
        /// The file.
        path: std::path::PathBuf,
        /// The I/O error.
        source: std::io::Error,
    },
}
