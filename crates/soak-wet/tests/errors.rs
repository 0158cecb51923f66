//! Bad input gets a typed error naming the offending value or texel, never
//! a panic or a NaN in the liquid.

use nalgebra::{Isometry3, Translation3, UnitQuaternion};
use soak_bake::{Atlas, BakeOptions, builtin};
use soak_hydro::Water;
use soak_wet::prelude::*;
use soak_wet::{LiquidImage, Material};

fn atlas() -> Atlas {
    Atlas::bake(&builtin::cuboid(1.0, 1.0, 1.0), BakeOptions::square(32)).unwrap()
}

#[test]
fn parameters_are_checked_and_named() {
    let a = atlas();
    let e = Wetting::new(
        &a,
        Material {
            saturation: -1.0,
            ..Material::sand()
        },
        Liquid::water(),
    )
    .unwrap_err();
    assert!(e.to_string().contains("material.saturation"), "{e}");
    let mut w = Wetting::new(&a, Material::sand(), Liquid::water()).unwrap();
    let water = Water::calm(0.0);
    let env = Environment::default();
    let pose = Isometry3::identity();
    let err = |r: Result<_, WetError>| r.unwrap_err().to_string();
    assert!(err(w.step(&a, &pose, &water, &env, 0.0, -1.0)).contains("-1"));
    assert!(err(w.step(&a, &pose, &water, &env, f64::NAN, 0.1)).contains("NaN"));
    let bad_pose = Isometry3::from_parts(Translation3::new(f64::NAN, 0.0, 0.0), UnitQuaternion::identity());
    assert!(err(w.step(&a, &bad_pose, &water, &env, 0.0, 0.1)).contains("pose"));
    let hot = Environment {
        relative_humidity: 2.0,
        ..env
    };
    assert!(err(w.step(&a, &pose, &water, &hot, 0.0, 0.1)).contains("relative_humidity"));
    let heavy = Water::calm(0.0).with_density(-5.0);
    assert!(err(w.step(&a, &pose, &heavy, &env, 0.0, 0.1)).contains("density"));
    let other = Atlas::bake(&builtin::sphere(0.5, 8, 4), BakeOptions::square(32)).unwrap();
    assert!(err(w.step(&other, &pose, &water, &env, 0.0, 0.1)).contains("texels"));
    w.set_diffusion(Some(Diffusion::new(f64::INFINITY))).unwrap_err();
    w.set_diffusion(Some(
        Diffusion::new(1e-3).with_resolution(FieldResolution::VoxelSize(1e-5)),
    ))
    .unwrap();
    let e = err(w.step(&a, &pose, &water, &env, 0.0, 0.1));
    assert!(e.contains("voxels"), "{e}");
    assert!(w.liquid().iter().all(|h| h.is_finite()));
}

#[test]
fn channels_name_the_texel() {
    let a = atlas();
    let mut w = Wetting::new(&a, Material::sand(), Liquid::water()).unwrap();
    let mut h = vec![0.0; a.len()];
    h[17] = f64::NAN;
    let e = w.set_liquid(&a, h).unwrap_err().to_string();
    assert!(e.contains("texel 17"), "{e}");
    let e = w.set_liquid(&a, vec![0.0; 3]).unwrap_err().to_string();
    assert!(e.contains("3 values"), "{e}");
    let mut map = vec![1.0f32; a.len()];
    map[5] = -1.0;
    let e = w.set_permeability_map(&a, Some(map)).unwrap_err().to_string();
    assert!(e.contains("texel 5"), "{e}");
    let img = LiquidImage {
        width: 4,
        height: 4,
        values: vec![0.5; 15],
    };
    assert!(w.set_liquid_from_image(&a, &img, 1e-3).is_err());
    let img = LiquidImage {
        width: 4,
        height: 4,
        values: vec![0.5; 16],
    };
    w.set_liquid_from_image(&a, &img, 1e-3).unwrap();
    assert!(w.liquid().iter().all(|&h| (h - 5e-4).abs() < 1e-12));
    let e = w
        .splash(
            &a,
            &Isometry3::identity(),
            &Splash {
                center: [0.0; 3],
                radius: 0.0,
                volume: 1.0,
            },
        )
        .unwrap_err()
        .to_string();
    assert!(e.contains("splash.radius"), "{e}");
    let e = w.fill(&a, 1.5).unwrap_err().to_string();
    assert!(e.contains("fill.fraction"), "{e}");
    assert!(
        write_liquid_png(
            &a,
            w.liquid(),
            1e-3,
            std::path::Path::new("/nonexistent/dir/x.png")
        )
        .unwrap_err()
        .to_string()
        .contains("/nonexistent")
    );
    assert!(LiquidImage::open(std::path::Path::new("/nonexistent.png")).is_err());
}

#[test]
fn shared_fields_check_their_box_and_members() {
    let e = SharedField::new(
        nalgebra::Point3::new(0.0, 0.0, 0.0),
        nalgebra::Point3::new(1.0, 1.0, 1.0),
        Diffusion::new(1e-3),
    )
    .unwrap_err()
    .to_string();
    assert!(e.contains("Auto"), "{e}");
    let e = SharedField::new(
        nalgebra::Point3::new(0.0, 0.0, 0.0),
        nalgebra::Point3::new(-1.0, 1.0, 1.0),
        Diffusion::new(1e-3).with_resolution(FieldResolution::VoxelSize(0.1)),
    )
    .unwrap_err();
    assert!(matches!(e, WetError::FieldBox { .. }), "{e}");
    let mut f = SharedField::new(
        nalgebra::Point3::new(0.0, 0.0, 0.0),
        nalgebra::Point3::new(1.0, 1.0, 1.0),
        Diffusion::new(1e-3).with_resolution(FieldResolution::VoxelSize(0.1)),
    )
    .unwrap();
    let a = atlas();
    let mut w = Wetting::new(&a, Material::sand(), Liquid::water()).unwrap();
    let pose = Isometry3::identity();
    assert!(
        f.diffuse(
            &mut [FieldMember {
                wetting: &mut w,
                atlas: &a,
                pose: &pose,
            }],
            f64::NAN,
        )
        .is_err()
    );
    // Texels outside the box are left alone and counted.
    let r = f
        .diffuse(
            &mut [FieldMember {
                wetting: &mut w,
                atlas: &a,
                pose: &pose,
            }],
            0.1,
        )
        .unwrap();
    assert!(r.diffusion.outside > 0 && r.diffusion.outside < a.len());
}

/// Found by fuzzing (the texture target): a 611-byte OpenEXR file whose
/// header declares 65,600 × 71 million pixel tiles made the reader allocate
/// 1.9 GB and take seconds before failing. It is now refused from the header.
#[test]
fn exr_with_a_huge_tile_is_an_error_naming_the_file() {
    let path =
        std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../data/bad/liquid_exr_huge_tile.exr");
    let e = LiquidImage::open(&path).unwrap_err();
    let msg = e.to_string();
    assert!(
        matches!(e, soak_wet::WetError::Image { path: Some(_), .. }),
        "{e:?}"
    );
    assert!(
        msg.contains("liquid_exr_huge_tile.exr") && msg.contains("OpenEXR layer 0: a tile of"),
        "{msg}"
    );
    let bytes = std::fs::read(&path).unwrap();
    assert!(LiquidImage::decode(&bytes, None).is_err());
}

#[test]
fn liquid_image_decodes_png_bytes() {
    let mut png = Vec::new();
    image::GrayImage::from_fn(4, 2, |x, _| image::Luma([(x * 85) as u8]))
        .write_to(&mut std::io::Cursor::new(&mut png), image::ImageFormat::Png)
        .unwrap();
    let img = LiquidImage::decode(&png, None).unwrap();
    assert_eq!((img.width, img.height, img.values.len()), (4, 2, 8));
    assert!((img.values[3] - 1.0).abs() < 1e-6 && img.values[0] == 0.0);
    let e = LiquidImage::decode(b"not an image", Some(std::path::Path::new("x.png"))).unwrap_err();
    assert!(e.to_string().contains("x.png"), "{e}");
}
