//! Property tests of the hydrostatics: the tiled path (closed forms for tile
//! groups and tiles wholly under a plane) gives the per-texel sums at any
//! pose, water level and plane tilt, with drag on or off; a body's
//! submerged volume stays within [0, V] (up to the discretisation) and its
//! wetted area within [0, A].

use std::sync::OnceLock;

use nalgebra::{Isometry3, Point3, Translation3, UnitQuaternion, Vector3};
use proptest::prelude::*;
use soak_bake::{Atlas, BakeOptions, builtin};
use soak_hydro::{
    BodyState, BuoyancyMode, Drag, HydroOptions, MassModel, MassProperties, Plane, TiledAtlas, Water,
    evaluate,
};

struct Body {
    atlas: Atlas,
    tiled: TiledAtlas,
    mass: MassProperties,
}

/// A boat and a torus at 256²: many tile groups, seams, open-deck lid.
fn bodies() -> &'static [Body; 2] {
    static BODIES: OnceLock<[Body; 2]> = OnceLock::new();
    BODIES.get_or_init(|| {
        [builtin::boat(4.0, 1.4, 0.8), builtin::torus(1.0, 0.35, 48, 24)].map(|mesh| {
            let atlas = Atlas::bake(&mesh, BakeOptions::square(256)).unwrap();
            let tiled = TiledAtlas::new(&atlas);
            let mass = MassModel::Solid { density: 450.0 }
                .mass_properties(&atlas)
                .unwrap();
            Body { atlas, tiled, mass }
        })
    })
}

#[derive(Debug, Clone)]
struct Case {
    body: usize,
    position: [f64; 3],
    angles: [f64; 3],
    velocity: [f64; 3],
    spin: [f64; 3],
    level: f64,
    tilt: Option<[f64; 2]>,
    drag: bool,
    pressure: bool,
}

fn case() -> impl Strategy<Value = Case> {
    (
        0usize..2,
        prop::array::uniform3(-2.0..2.0f64),
        prop::array::uniform3(-3.2..3.2f64),
        prop::array::uniform3(-3.0..3.0f64),
        prop::array::uniform3(-2.0..2.0f64),
        -2.5..2.5f64,
        prop::option::of(prop::array::uniform2(-0.4..0.4f64)),
        any::<bool>(),
        any::<bool>(),
    )
        .prop_map(
            |(body, position, angles, velocity, spin, level, tilt, drag, pressure)| Case {
                body,
                position,
                angles,
                velocity,
                spin,
                level,
                tilt,
                drag,
                pressure,
            },
        )
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    #[test]
    fn tiled_equals_per_texel(c in case()) {
        let body = &bodies()[c.body];
        let state = BodyState {
            pose: Isometry3::from_parts(
                Translation3::from(Vector3::from(c.position)),
                UnitQuaternion::from_euler_angles(c.angles[0], c.angles[1], c.angles[2]),
            ),
            linear_velocity: Vector3::from(c.velocity),
            angular_velocity: Vector3::from(c.spin),
        };
        let water = match c.tilt {
            None => Water::calm(c.level),
            Some([tx, tz]) => Water::new(
                Plane::tilted(Point3::new(0.0, c.level, 0.0), Vector3::new(tx, 1.0, tz)).unwrap(),
            ),
        };
        let options = HydroOptions {
            buoyancy: if c.pressure { BuoyancyMode::Pressure } else { BuoyancyMode::Archimedes },
            drag: c.drag.then_some(Drag { coefficient: 1.0, linear: 0.2 }),
            ..Default::default()
        };
        let a = evaluate(&body.atlas, &water, &state, &body.mass, 0.0, &options).unwrap();
        let b = body.tiled.evaluate(&body.atlas, &water, &state, &body.mass, 0.0, &options).unwrap();
        let volume = body.atlas.volume();
        prop_assert!((a.submerged_volume - b.submerged_volume).abs() <= 1e-6 * volume);
        prop_assert_eq!(a.submerged_texels, b.submerged_texels);
        prop_assert!((a.wetted_area - b.wetted_area).abs() <= 1e-6 * body.atlas.area());
        let scale = (water.density * water.gravity * volume).max(a.buoyancy.force.norm());
        let diameter = 2.0 * body.atlas.bounding_radius();
        prop_assert!((a.buoyancy.force - b.buoyancy.force).norm() <= 1e-6 * scale,
            "{} vs {}", a.buoyancy.force, b.buoyancy.force);
        prop_assert!((a.buoyancy.torque - b.buoyancy.torque).norm() <= 1e-6 * scale * diameter,
            "{} vs {}", a.buoyancy.torque, b.buoyancy.torque);
        prop_assert!((a.drag.force - b.drag.force).norm() <= 1e-6 * a.drag.force.norm().max(1e-9));
        if a.submerged_volume > 1e-9 * volume {
            prop_assert!((a.center_of_buoyancy - b.center_of_buoyancy).norm() <= 1e-6 * diameter);
        }
        // Bounds: 0 ≤ V_sub ≤ V up to the atlas' discretisation (< 1e-3 V at
        // 256²), 0 ≤ wetted ≤ area.
        prop_assert!(b.submerged_volume >= -1e-3 * volume && b.submerged_volume <= volume * (1.0 + 1e-3),
            "{} of {volume}", b.submerged_volume);
        prop_assert!(b.wetted_area >= 0.0 && b.wetted_area <= body.atlas.area() * (1.0 + 1e-6));
    }
}
