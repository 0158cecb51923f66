//! An open container's caps are not a surface: dipped under water, its
//! walls soak liquid up and its caps take none.

use nalgebra::Isometry3;
use soak_bake::{Atlas, BakeOptions, builtin, cap_openings};
use soak_hydro::Water;
use soak_wet::prelude::*;

#[test]
fn the_caps_of_an_open_box_stay_dry_under_water() {
    let atlas = Atlas::bake(
        &cap_openings(&builtin::open_box(1.0, 0.5, 1.0)).unwrap(),
        BakeOptions::square(64),
    )
    .unwrap();
    let mut wet = Wetting::new(&atlas, Material::cotton(), Liquid::water()).unwrap();
    // Wholly under water for a minute.
    let pose = Isometry3::translation(0.0, -1.0, 0.0);
    for k in 0..60 {
        wet.step(
            &atlas,
            &pose,
            &Water::calm(0.0),
            &Environment::default(),
            k as f64,
            1.0,
        )
        .unwrap();
    }
    let (mut walls, mut caps) = (0.0, 0.0);
    for (i, h) in wet.liquid().iter().enumerate() {
        if atlas.is_opening(i) {
            caps += h
        } else {
            walls += h
        }
    }
    assert!(walls > 0.0, "the walls took no liquid");
    assert_eq!(caps, 0.0, "the caps took {caps} m of liquid");
}
