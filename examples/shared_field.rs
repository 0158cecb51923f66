//! Two objects sharing a liquid field (thesis Fig. 7.13): a soaked sponge
//! sits on a dry wooden board, a dry block stands 10 cm beside it. Liquid
//! diffuses from the sponge into the board where they touch, spreads along
//! the board, and reaches the block only once the wet patch gets there.
//!
//! Prints each body's liquid over time and writes pseudo-colour liquid
//! textures (blue dry → red saturated) to `out/shared_field/`.
//!
//! `cargo run --release --example shared_field`

use std::path::Path;

use nalgebra::{Isometry3, Point3};
use soak::bake::{Atlas, BakeOptions, builtin};
use soak::hydro::Water;
use soak::wet::prelude::*;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let out = Path::new("out/shared_field");
    std::fs::create_dir_all(out)?;
    // A 1 m × 0.4 m board 4 cm thick, a 20 cm sponge at x = −0.2 m and a
    // 20 cm block at x = +0.1 m: 10 cm between them.
    let board = Atlas::bake(&builtin::cuboid(1.0, 0.04, 0.4), BakeOptions::square(512))?;
    let cube = Atlas::bake(&builtin::cuboid(0.2, 0.2, 0.2), BakeOptions::square(256))?;
    let poses = [
        Isometry3::identity(),
        Isometry3::translation(-0.2, 0.12, 0.0),
        Isometry3::translation(0.1, 0.12, 0.0),
    ];
    let atlases = [&board, &cube, &cube];
    let names = ["board", "sponge", "block"];
    let mut bodies = [
        Wetting::new(&board, Material::wood(), Liquid::water())?,
        Wetting::new(&cube, Material::cotton(), Liquid::water())?,
        Wetting::new(&cube, Material::wood(), Liquid::water())?,
    ];
    bodies[1].fill(&cube, 1.0)?;

    let diffusion = Diffusion::new(1e-4).with_resolution(FieldResolution::VoxelSize(0.01));
    let mut field = SharedField::new(
        Point3::new(-0.5, -0.05, -0.25),
        Point3::new(0.5, 0.25, 0.25),
        diffusion,
    )?;
    // Humid still air, no water to sit in: only diffusion and a little drying.
    let env = Environment {
        relative_humidity: 0.9,
        wind_speed: 0.0,
        ..Environment::default()
    };
    let water = Water::calm(-10.0);
    let dt = 0.5;
    println!(
        "field {:?} voxels of {} m",
        field.grid().dims,
        field.grid().voxel_size
    );
    println!(
        "{:>7} {:>12} {:>12} {:>12} {:>12}",
        "time s", "board m³", "sponge m³", "block m³", "sum m³"
    );
    for step in 0..=1200 {
        if step % 200 == 0 {
            let totals: Vec<f64> = bodies
                .iter()
                .zip(atlases)
                .map(|(w, a)| w.total_liquid(a))
                .collect();
            println!(
                "{:>7.0} {:>12.4e} {:>12.4e} {:>12.4e} {:>12.4e}",
                step as f64 * dt,
                totals[0],
                totals[1],
                totals[2],
                totals.iter().sum::<f64>()
            );
            for ((w, a), name) in bodies.iter().zip(atlases).zip(names) {
                let path = out.join(format!("{name}_{step:05}.png"));
                write_liquid_png(a, w.liquid(), w.material().saturation, &path)?;
            }
        }
        let t = step as f64 * dt;
        for ((w, a), p) in bodies.iter_mut().zip(atlases).zip(&poses) {
            w.step(a, p, &water, &env, t, dt)?;
        }
        let [b, s, c] = &mut bodies[..] else {
            unreachable!()
        };
        field.diffuse(
            &mut [
                FieldMember {
                    wetting: b,
                    atlas: &board,
                    pose: &poses[0],
                },
                FieldMember {
                    wetting: s,
                    atlas: &cube,
                    pose: &poses[1],
                },
                FieldMember {
                    wetting: c,
                    atlas: &cube,
                    pose: &poses[2],
                },
            ],
            dt,
        )?;
    }
    println!("frames in {}", out.display());
    Ok(())
}
