//! An open mesh's caps displace water but weigh nothing: its walls carry the
//! mass (the shell of the real surface, or walls of a density and a
//! thickness), and a solid of it is refused.

use soak_bake::{Atlas, BakeOptions, builtin, cap_openings};
use soak_hydro::{HydroError, MassModel};

#[test]
fn an_open_box_weighs_its_walls_only() {
    let atlas = Atlas::bake(
        &cap_openings(&builtin::open_box(1.2, 0.5, 0.8)).unwrap(),
        BakeOptions::square(256),
    )
    .unwrap();
    // Bottom 1.2 × 0.8, two sides 1.2 × 0.5, two ends 0.8 × 0.5: 2.96 m².
    let walls = 0.96 + 1.2 + 0.8;
    let m = MassModel::Walls {
        density: 700.0,
        thickness: 0.02,
    }
    .mass_properties(&atlas)
    .unwrap();
    assert!((m.mass - 14.0 * walls).abs() < 1e-3 * m.mass, "{}", m.mass);
    // The centre of mass of the open walls, from their faces' areas and centres.
    let cy = (0.96 * -0.25 + 2.0 * 0.0) / walls;
    assert!(
        (m.center_of_mass.y - cy).abs() < 1e-4,
        "{} vs {cy}",
        m.center_of_mass.y
    );
    assert!(m.center_of_mass.x.abs() < 1e-5 && m.center_of_mass.z.abs() < 1e-5);
    let shell = MassModel::Shell { areal_density: 14.0 }
        .mass_properties(&atlas)
        .unwrap();
    assert!((shell.mass - m.mass).abs() < 1e-9 * m.mass);
    assert_eq!(
        MassModel::Solid { density: 500.0 }
            .mass_properties(&atlas)
            .unwrap_err(),
        HydroError::OpenSolid
    );
    assert_eq!(
        MassModel::Walls {
            density: 700.0,
            thickness: -0.01
        }
        .mass_properties(&atlas)
        .unwrap_err(),
        HydroError::Thickness { value: -0.01 }
    );
    // The displaced volume is the closed box's: the air inside floats it.
    assert!((atlas.volume() - 0.48).abs() < 1e-6);
}
