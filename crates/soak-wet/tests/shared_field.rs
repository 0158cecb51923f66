//! A shared field passes liquid from a wet cube to a dry cube it touches,
//! and not to one 10 cm away; total liquid over all members is conserved.

use nalgebra::Isometry3;
use soak_bake::{Atlas, BakeOptions, builtin};
use soak_wet::prelude::*;

#[test]
fn a_wet_cube_wets_the_cube_it_touches_and_not_the_one_ten_cm_away() {
    let atlas = Atlas::bake(&builtin::cuboid(0.2, 0.2, 0.2), BakeOptions::square(128)).unwrap();
    // Wet cube on [-0.2, 0] in x, one touching it on [0, 0.2], one on
    // [-0.5, -0.3]: 10 cm away.
    let poses = [
        Isometry3::translation(-0.1, 0.0, 0.0),
        Isometry3::translation(0.1, 0.0, 0.0),
        Isometry3::translation(-0.4, 0.0, 0.0),
    ];
    let mut wet: Vec<Wetting> = (0..3)
        .map(|_| Wetting::new(&atlas, Material::cotton(), Liquid::water()).unwrap())
        .collect();
    wet[0].fill(&atlas, 1.0).unwrap();
    let diffusion = Diffusion::new(2e-4).with_resolution(FieldResolution::VoxelSize(0.02));
    let bodies: Vec<(&Atlas, &Isometry3<f64>)> = poses.iter().map(|p| (&atlas, p)).collect();
    let mut field = SharedField::around(&bodies, 0.05, diffusion).unwrap();
    let start: f64 = wet.iter().map(|w| w.total_liquid(&atlas)).sum();
    let mut rebinned = 0;
    for _ in 0..40 {
        let [a, b, c] = &mut wet[..] else { unreachable!() };
        let r = field
            .diffuse(
                &mut [
                    FieldMember {
                        wetting: a,
                        atlas: &atlas,
                        pose: &poses[0],
                    },
                    FieldMember {
                        wetting: b,
                        atlas: &atlas,
                        pose: &poses[1],
                    },
                    FieldMember {
                        wetting: c,
                        atlas: &atlas,
                        pose: &poses[2],
                    },
                ],
                0.25,
            )
            .unwrap();
        rebinned += usize::from(r.rebinned);

        assert!(r.gained.iter().sum::<f64>().abs() < 1e-15);
    }
    let totals: Vec<f64> = wet.iter().map(|w| w.total_liquid(&atlas)).collect();
    let end: f64 = totals.iter().sum();
    eprintln!(
        "after 10 s: wet {:.4e} m³, touching {:.4e} m³ ({:.1} % of the start), 10 cm away {:.1e} m³",
        totals[0],
        totals[1],
        100.0 * totals[1] / start,
        totals[2]
    );
    assert_eq!(rebinned, 1, "static bodies are binned once");
    assert!(totals[1] > 0.01 * start, "liquid crossed into the touching cube");
    assert_eq!(totals[2], 0.0, "nothing reached the cube 10 cm away");
    assert!(wet[2].liquid().iter().all(|&h| h == 0.0));
    assert!((end - start).abs() / start < 1e-12);
    // The touching cube's wet side is the one facing the wet cube.
    let sat = wet[1].material().saturation;
    let facing: f64 = (0..atlas.len())
        .filter(|&i| atlas.position(i).x < -0.099)
        .map(|i| wet[1].liquid()[i])
        .sum::<f64>();
    let far: f64 = (0..atlas.len())
        .filter(|&i| atlas.position(i).x > 0.099)
        .map(|i| wet[1].liquid()[i])
        .sum::<f64>();
    assert!(facing > 10.0 * far, "{facing} vs {far} (sat {sat})");
    assert!((wet[1].ledger().exchanged - totals[1]).abs() < 1e-15);
}

#[test]
fn a_wet_sheet_lying_on_a_dry_one_wets_it_even_where_they_share_every_voxel() {
    // Two thin sheets 4 mm apart in one layer of 5 cm voxels, same
    // footprint: every voxel holds both, so only the exchange between the
    // two bodies' cells of a voxel can move liquid.
    let atlas = Atlas::bake(&builtin::cuboid(0.5, 0.002, 0.5), BakeOptions::square(128)).unwrap();
    let poses = [
        Isometry3::translation(0.0, 0.0, 0.0),
        Isometry3::translation(0.0, 0.004, 0.0),
    ];
    let mut a = Wetting::new(&atlas, Material::cotton(), Liquid::water()).unwrap();
    let mut b = Wetting::new(&atlas, Material::cotton(), Liquid::water()).unwrap();
    a.fill(&atlas, 1.0).unwrap();
    let start = a.total_liquid(&atlas);
    let diffusion = Diffusion::new(1e-4).with_resolution(FieldResolution::VoxelSize(0.05));
    let mut field = SharedField::around(&[(&atlas, &poses[0]), (&atlas, &poses[1])], 0.0, diffusion).unwrap();
    assert_eq!(field.grid().dims[1], 1);
    for _ in 0..20 {
        field
            .diffuse(
                &mut [
                    FieldMember {
                        wetting: &mut a,
                        atlas: &atlas,
                        pose: &poses[0],
                    },
                    FieldMember {
                        wetting: &mut b,
                        atlas: &atlas,
                        pose: &poses[1],
                    },
                ],
                1.0,
            )
            .unwrap();
    }
    let (ta, tb) = (a.total_liquid(&atlas), b.total_liquid(&atlas));
    eprintln!(
        "sheets after 20 s: {:.1} % moved to the dry sheet",
        100.0 * tb / start
    );
    assert!(tb > 0.2 * start && tb <= 0.5 * start + 1e-12);
    assert!(((ta + tb) - start).abs() / start < 1e-12);
}
