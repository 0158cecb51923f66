//! Floats a mesh read from an OBJ file that has no UV map: soak unwraps
//! it, bakes it and reports its draft. The default mesh is a crate
//! 1 m × 0.6 m × 0.8 m of pine (500 kg/m³), which floats 0.3 m deep.
//!
//! `cargo run --release --example float_obj [-- MESH.obj]`

use rapier3d::prelude::*;
use soak::prelude::*;

/// The crate's draft (m) and submerged fraction after 20 s on calm water.
fn float(path: &str) -> Result<(f64, f64), Box<dyn std::error::Error>> {
    let mesh = load_mesh(path)?;
    let (mesh, _) = soak::bake::unwrap(&mesh, UnwrapOptions::default())?; // a UV map of its own
    let atlas = Atlas::bake(&mesh, BakeOptions::square(128))?;
    let mut world = PhysicsWorld::new();
    let handle = world
        .bodies
        .insert(RigidBodyBuilder::dynamic().translation(Vector::new(0.0, 0.5, 0.0)));
    let mut soak = ForceGenerator::new(Water::calm(0.0));
    let id = soak.register(
        &mut world.bodies,
        &world.colliders,
        handle,
        BodyDesc {
            name: "crate".into(),
            atlas: atlas.into(),
            mass_model: MassModel::Solid { density: 500.0 },
            effects: Effects::buoyancy().with_drag(Drag {
                coefficient: 1.0,
                linear: 200.0,
            }),
        },
    )?;
    for _ in 0..1200 {
        soak.step(&mut world)?;
    }
    let draft = soak.draft(id, &world.bodies).ok_or("the crate is gone")?;
    let fraction = soak.body(id).ok_or("the crate is gone")?.submerged_fraction();
    Ok((draft, fraction))
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let default = concat!(env!("CARGO_MANIFEST_DIR"), "/data/crate_nouv.obj");
    let path = std::env::args().nth(1).unwrap_or_else(|| default.to_string());
    let (draft, fraction) = float(&path)?;
    println!(
        "{path}: draft {draft:.4} m, {:.1} % of its volume under water",
        100.0 * fraction
    );
    Ok(())
}

#[cfg(test)]
mod tests {
    /// A solid of half the water's density floats half immersed: the
    /// 0.6 m-high crate at a draft of 0.3 m, within 1 mm.
    #[test]
    fn the_crate_floats_at_its_analytic_draft() {
        let path = concat!(env!("CARGO_MANIFEST_DIR"), "/data/crate_nouv.obj");
        let (draft, fraction) = super::float(path).unwrap();
        assert!((draft - 0.3).abs() < 1e-3, "draft {draft} m");
        assert!((fraction - 0.5).abs() < 2e-3, "submerged fraction {fraction}");
    }
}
