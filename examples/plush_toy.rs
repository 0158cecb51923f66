//! A plush toy dropped into water soaks up water through its fabric and
//! floats lower and lower as it grows heavy (thesis Fig. 7.8). Its liquid
//! graph is built automatically: the mesh is segmented by its Shape
//! Diameter Function (body, head, limbs), one node per segment.
//!
//! ```text
//! cargo run --release --example plush_toy
//! cargo run --release --example plush_toy -- --clusters 4 --seconds 120 --obj plush.obj
//! ```
//!
//! The toy is a smooth union of spheres (body, head, two arms, two legs)
//! made by displacing a UV sphere, so it keeps the sphere's bijective UV
//! map. Stuffing and fabric weigh 50 kg/m³ dry; 90 % of each segment's
//! volume is open to water (`porosity`); the fabric's permeability is
//! κ = 5·10⁻⁹ m everywhere.

use std::io::Write;

use nalgebra::{Point3, Vector3};
use rapier3d::prelude::*;
use soak::bake::{Atlas, BakeOptions, Mesh, builtin};
use soak::graph::segment::{SegmentOptions, segment};
use soak::graph::{Flooding, FlowOptions, LiquidGraph, Permeability, SegmentGraphOptions, TexelNodes};
use soak::hydro::{Drag, MassModel, Water};
use soak::rapier::hull::highest_above_water;
use soak::rapier::{BodyDesc, Effects, ForceGenerator};

/// A teddy-like toy, star-shaped about its body centre: the smooth union
/// (p-norm of radial functions) of a body sphere and offset spheres whose
/// far sides the origin sees (`D² ≤ R_body² + R²`), so the displaced UV
/// sphere stays a valid closed mesh. About 0.6 m tall.
pub fn plush(segments: usize) -> Mesh {
    let body = 0.2;
    // (direction, centre distance D, radius R)
    let parts: [(Vector3<f64>, f64, f64); 5] = [
        (Vector3::new(0.0, 1.0, 0.0), 0.24, 0.14),
        (Vector3::new(0.94, 0.34, 0.0), 0.21, 0.075),
        (Vector3::new(-0.94, 0.34, 0.0), 0.21, 0.075),
        (Vector3::new(0.5, -0.8, 0.33), 0.215, 0.085),
        (Vector3::new(-0.5, -0.8, 0.33), 0.215, 0.085),
    ];
    let radial = move |d: Vector3<f64>| -> f64 {
        let p = 10.0;
        let mut sum = body.powf(p);
        for (u, dist, r) in &parts {
            let c = d.dot(&u.normalize());
            let s2 = 1.0 - c * c;
            let disc = r * r - dist * dist * s2;
            if c > 0.0 && disc > 0.0 {
                sum += (dist * c + disc.sqrt()).powf(p);
            }
        }
        sum.powf(1.0 / p)
    };
    let mut mesh = builtin::sphere(1.0, segments, segments / 2).map_positions(|q| {
        let d = q.coords.normalize();
        Point3::from(d * radial(d))
    });
    mesh.name = format!("plush:{segments}");
    mesh
}

fn write_obj(mesh: &Mesh, path: &str) -> std::io::Result<()> {
    let mut f = std::io::BufWriter::new(std::fs::File::create(path)?);
    writeln!(f, "# {}", mesh.name)?;
    for p in &mesh.positions {
        writeln!(f, "v {} {} {}", p.x, p.y, p.z)?;
    }
    if let Some(uvs) = &mesh.uvs {
        for t in uvs {
            writeln!(f, "vt {} {}", t.x, t.y)?;
        }
    }
    for t in &mesh.triangles {
        let [a, b, c] = t.map(|i| i + 1);
        writeln!(f, "f {a}/{a} {b}/{b} {c}/{c}")?;
    }
    Ok(())
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let (mut clusters, mut seconds, mut obj) = (5usize, 180.0f64, None::<String>);
    let mut it = std::env::args().skip(1);
    while let Some(a) = it.next() {
        match a.as_str() {
            "--clusters" => clusters = it.next().ok_or("--clusters N")?.parse()?,
            "--seconds" => seconds = it.next().ok_or("--seconds S")?.parse()?,
            "--obj" => obj = Some(it.next().ok_or("--obj FILE")?),
            other => return Err(format!("unknown argument `{other}`").into()),
        }
    }
    let mesh = plush(96);
    if let Some(path) = &obj {
        write_obj(&mesh, path)?;
        println!("wrote {path}");
    }
    let seg = segment(
        &mesh,
        &SegmentOptions {
            clusters,
            ..SegmentOptions::default()
        },
    )?;
    let graph = LiquidGraph::from_segmentation(
        &seg,
        &SegmentGraphOptions {
            porosity: 0.9,
            ..SegmentGraphOptions::default()
        },
    )?;
    println!(
        "{}: {} triangles, volume {:.4} m³; segmented in {:.0} ms into {} nodes:",
        mesh.name,
        mesh.triangles.len(),
        mesh.volume(),
        seg.timings.total().as_secs_f64() * 1e3,
        graph.node_count()
    );
    for (i, n) in graph.nodes().enumerate() {
        println!(
            "  node {i}: at ({:+.3}, {:+.3}, {:+.3}) m, capacity {:.5} m³ ({} faces)",
            n.position.x, n.position.y, n.position.z, n.capacity, seg.segments[i].faces
        );
    }
    for (a, b, p) in graph.edges() {
        println!(
            "  pipe {a}–{b}: radius {:.3} m, length {:.3} m",
            p.radius, p.length
        );
    }

    let atlas = Atlas::bake(&mesh, BakeOptions::square(128))?;
    let map = TexelNodes::from_segmentation(&atlas, &seg)?;
    let permeability = Permeability::uniform(&atlas, 5e-9)?;
    let flooding = Flooding::new(graph, permeability, map, FlowOptions::default())?;

    let mut world = PhysicsWorld::new();
    world.integration_parameters.dt = 1.0 / 30.0;
    let handle = world
        .bodies
        .insert(RigidBodyBuilder::dynamic().translation(Vector::new(0.0, 0.5, 0.0)));
    let mut soak = ForceGenerator::new(Water::calm(0.0));
    let id = soak.register(
        &mut world.bodies,
        &world.colliders,
        handle,
        BodyDesc {
            name: "plush".into(),
            atlas: atlas.clone().into(),
            mass_model: MassModel::Solid { density: 50.0 },
            effects: Effects::buoyancy()
                .with_drag(Drag {
                    coefficient: 1.0,
                    linear: 20.0,
                })
                .with_flooding(flooding),
        },
    )?;
    let dry = soak.body(id).map_or(0.0, |b| b.mass_properties().mass);
    println!("dropped from 0.5 m, dry mass {dry:.2} kg");
    println!(
        "{:>6}  {:>9}  {:>8}  {:>9}  {:>6}  segments (% full)",
        "t (s)", "water l", "mass kg", "top above", "tilt°"
    );
    let steps = (seconds * 30.0) as usize;
    for step in 0..=steps {
        if step % 300 == 0 {
            let t = soak.time();
            let pose = *world.bodies[handle].position();
            let f = soak.flooding(id).ok_or("no flooding")?;
            println!(
                "{t:>6.0}  {:>9.3}  {:>8.2}  {:>9.3}  {:>6.1}  {}",
                1e3 * f.inside(),
                soak.body(id).map_or(0.0, |b| b.mass_properties().mass),
                highest_above_water(&atlas, &pose, soak.water(), t),
                f64::from((pose.rotation * Vector::Y).y)
                    .clamp(-1.0, 1.0)
                    .acos()
                    .to_degrees(),
                f.graph()
                    .nodes()
                    .map(|n| format!("{:>3.0}", 100.0 * n.fill()))
                    .collect::<Vec<_>>()
                    .join(" ")
            );
        }
        soak.step(&mut world)?;
    }
    let f = soak.flooding(id).ok_or("no flooding")?;
    println!(
        "soaked up {:.2} l, conservation error {:.1e}",
        1e3 * f.inside(),
        f.conservation_error()
    );
    Ok(())
}
