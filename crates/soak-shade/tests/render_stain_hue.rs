//! A coloured liquid stains a beige plate: the stain's hue moves towards the
//! liquid's colour (and the stain is darker), under the default look
//! (sun at 50°, sky, tone mapping), for a blue ink and a red wine.
#![cfg(feature = "render")]

mod common;

use nalgebra::{Isometry3, Point3};
use soak_shade::render::{Albedo, Camera, LiquidImage, RenderObject, RenderScene, Renderer, RendererOptions};
use soak_shade::render::{hue_degrees, hue_distance, luminance, mean_linear};
use soak_shade::{Liquid, WetMaterial};

const SIZE: u32 = 128;

#[test]
fn stain_hue_moves_towards_the_liquid() {
    let Some((device, queue, _)) = common::device() else {
        return;
    };
    let options = RendererOptions {
        sample_count: 4,
        shadow_map_size: 512,
    };
    let mut renderer = Renderer::with_options(&device, &queue, SIZE, SIZE, options).expect("renderer");
    let beige = [0.62, 0.55, 0.42];
    // A round stain in the middle of the plate.
    let stain = LiquidImage::from_fn(64, 64, |x, y| {
        let (dx, dy) = (x as f32 - 31.5, y as f32 - 31.5);
        image::Luma([if dx * dx + dy * dy < 14.0 * 14.0 { 1.0 } else { 0.0 }])
    });
    for (name, colour) in [("blue ink", [0.05, 0.20, 0.60]), ("red wine", [0.50, 0.03, 0.08])] {
        let liquid = Liquid::from_colour(1.34, colour, 1e-2, 2e-3);
        let camera = Camera::perspective(Point3::new(0.0, 3.0, 1.6), Point3::origin(), 40.0);
        let mut scene = RenderScene::new(camera);
        scene.objects.push(
            RenderObject::new(common::plate(2.0), Isometry3::identity())
                .with_albedo(Albedo::Constant(beige))
                .with_liquid(stain.clone())
                .with_material(WetMaterial {
                    liquid,
                    ..WetMaterial::default()
                }),
        );
        let image = renderer.render(&scene).expect("render");
        let centre = mean_linear(&image, 56, 56, 72, 72);
        // Dry plate: a band near the bottom edge of the image, outside the stain.
        let dry = mean_linear(&image, 20, 104, 108, 112);
        let liquid_hue = hue_degrees(liquid.transmittance).expect("coloured");
        let (hs, hd) = (
            hue_degrees(centre).expect("stain hue"),
            hue_degrees(dry).expect("dry hue"),
        );
        eprintln!(
            "{name}: liquid hue {liquid_hue:.1}°, dry {hd:.1}° ({:.1}° away), stain {hs:.1}° ({:.1}° away)",
            hue_distance(hd, liquid_hue),
            hue_distance(hs, liquid_hue)
        );
        assert!(
            hue_distance(hs, liquid_hue) + 10.0 < hue_distance(hd, liquid_hue),
            "{name}: the stain's hue {hs}° is not closer to the liquid's {liquid_hue}° than the dry {hd}°"
        );
        assert!(
            luminance(centre) < luminance(dry),
            "{name}: the stain is not darker"
        );
    }
}
