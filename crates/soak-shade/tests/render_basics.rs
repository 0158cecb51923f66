//! The renderer's plumbing on any adapter: readback with padded rows, the
//! debug views, shadows, the subsurface option, and typed errors for bad
//! scenes.
#![cfg(feature = "render")]

mod common;

use std::sync::Arc;

use nalgebra::{Isometry3, Point3, Vector3};
use soak_bake::builtin;
use soak_shade::render::{
    Albedo, Arrow, Camera, DebugView, DirectionalLight, Environment, LiquidImage, RenderError, RenderObject,
    RenderScene, RenderWater, Renderer, RendererOptions, Subsurface, ToneMap,
};
use soak_shade::render::{luminance, mean_linear};
use soak_shade::{Liquid, WetMaterial};

fn renderer(d: &common::Device, w: u32, h: u32) -> Renderer {
    let options = RendererOptions {
        sample_count: 4,
        shadow_map_size: 512,
    };
    Renderer::with_options(&d.0, &d.1, w, h, options).expect("renderer")
}

fn half_wet() -> LiquidImage {
    LiquidImage::from_fn(64, 4, |x, _| image::Luma([if x < 32 { 1.0 } else { 0.0 }]))
}

/// Plate seen from 45° above along −z, orthographic, sun straight above.
fn plate_scene() -> RenderScene {
    let camera = Camera::orthographic(Point3::new(0.0, 4.0, 4.0), Point3::origin(), 1.0);
    let mut scene = RenderScene::new(camera);
    scene.light = DirectionalLight {
        direction: Vector3::y(),
        irradiance: [2.0; 3],
    };
    scene.environment = Environment::uniform([0.15; 3]);
    scene.tone_map = ToneMap::Linear;
    scene.objects.push(
        RenderObject::new(common::plate(4.0), Isometry3::identity())
            .with_albedo(Albedo::Constant([0.5; 3]))
            .with_liquid(half_wet()),
    );
    scene
}

#[test]
fn odd_widths_read_back_unshifted() {
    let Some(d) = common::device() else { return };
    // 77 px: 308 bytes per row, padded to 512 on the GPU.
    let (w, h) = (77, 41);
    let mut r = renderer(&d, w, h);
    let camera = Camera::perspective(Point3::new(0.0, 0.3, 4.0), Point3::new(0.0, 0.3, 0.0), 30.0);
    let mut scene = RenderScene::new(camera);
    scene.dither = false;
    scene.light = DirectionalLight::from_angles(60.0, 90.0, [2.5; 3]); // from +z: symmetric in x
    scene.objects.push(RenderObject::new(
        builtin::sphere(0.5, 64, 32),
        Isometry3::translation(0.0, 0.3, 0.0),
    ));
    let image = r.render(&scene).expect("render");
    common::keep(&image, "odd_width");
    assert_eq!(image.dimensions(), (w, h));
    // The scene is mirror-symmetric in x: so must the image be, row by row.
    let mut diff = 0.0;
    for y in 0..h {
        for x in 0..w / 2 {
            let (a, b) = (image.get_pixel(x, y).0, image.get_pixel(w - 1 - x, y).0);
            diff += (0..3)
                .map(|c| (f64::from(a[c]) - f64::from(b[c])).abs())
                .sum::<f64>();
        }
    }
    let mean = diff / f64::from(3 * h * (w / 2));
    assert!(mean < 2.0, "mean left/right difference {mean} levels");
    // The sphere is in the middle, the sky at the corners.
    let centre = luminance(mean_linear(&image, 34, 18, 43, 24));
    let corner = luminance(mean_linear(&image, 0, 0, 6, 6));
    assert!(centre > 0.05 && corner > 0.05, "centre {centre}, corner {corner}");
    // Resizing keeps working.
    r.resize(64, 48).unwrap();
    assert_eq!(r.render(&scene).unwrap().dimensions(), (64, 48));
}

#[test]
fn debug_views_show_liquid_segments_and_normals() {
    let Some(d) = common::device() else { return };
    let mut r = renderer(&d, 96, 96);
    let mut scene = plate_scene();
    scene.view = DebugView::Liquid;
    let image = r.render(&scene).expect("liquid view");
    common::keep(&image, "debug_liquid");
    // Saturated: the red end of the colour map; dry: the blue end.
    let (wet, dry) = (
        mean_linear(&image, 6, 12, 42, 84),
        mean_linear(&image, 54, 12, 90, 84),
    );
    assert!(wet[0] > wet[2] && dry[2] > dry[0], "wet {wet:?} dry {dry:?}");

    scene.view = DebugView::Normals;
    let image = r.render(&scene).expect("normals view");
    common::keep(&image, "debug_normals");
    let c = mean_linear(&image, 20, 20, 76, 76);
    assert!(
        c[1] > 0.9 && c[0] < 0.3 && c[2] < 0.3,
        "+y normal should be green: {c:?}"
    );

    // The plate's two triangles (split along a diagonal) as segments 1 and
    // 2: each gets its own colour.
    scene.view = DebugView::Segments;
    scene.objects[0] = scene.objects[0].clone().with_segments(vec![1, 2]);
    let image = r.render(&scene).expect("segments view");
    common::keep(&image, "debug_segments");
    let (a, b) = (
        mean_linear(&image, 8, 70, 20, 82),
        mean_linear(&image, 76, 14, 88, 26),
    );
    let distance: f64 = (0..3).map(|k| (a[k] - b[k]).abs()).sum();
    assert!(distance > 0.1, "segments 1 and 2 look alike: {a:?} {b:?}");
}

#[test]
fn shadows_arrows_and_water_draw() {
    let Some(d) = common::device() else { return };
    let mut r = renderer(&d, 128, 96);
    let camera = Camera::perspective(Point3::new(0.0, 3.0, 4.0), Point3::new(0.0, 0.0, 0.0), 40.0);
    let mut scene = RenderScene::new(camera);
    scene.light = DirectionalLight::from_angles(35.0, 0.0, [2.5; 3]); // low, from +x
    let plate =
        RenderObject::new(common::plate(4.0), Isometry3::identity()).with_albedo(Albedo::Constant([0.6; 3]));
    let cube = RenderObject::new(
        builtin::cuboid(0.6, 0.6, 0.6),
        Isometry3::translation(0.0, 0.3, 0.0),
    );
    scene.objects = vec![plate, cube];
    let lit = r.render(&scene).unwrap();
    common::keep(&lit, "shadow");
    // The cube's shadow falls on the plate towards −x of it: left of the
    // cube, at the height of its base.
    let shade = |img: &image::RgbaImage| luminance(mean_linear(img, 36, 46, 50, 50));
    let open = |img: &image::RgbaImage| luminance(mean_linear(img, 80, 46, 94, 50));
    assert!(
        shade(&lit) < 0.7 * open(&lit),
        "shadow {} vs lit {}",
        shade(&lit),
        open(&lit)
    );
    scene.shadows = false;
    let unshadowed = r.render(&scene).unwrap();
    assert!((shade(&unshadowed) / open(&unshadowed) - 1.0).abs() < 0.1);

    // Water over the plate darkens and tints it; arrows draw on top.
    scene.water = Some(RenderWater::plane(0.1));
    scene.arrows = vec![Arrow::weight(
        Point3::new(0.0, 0.3, 0.0),
        Vector3::new(0.0, -1.0, 0.0),
        1.2,
    )];
    let wet = r.render(&scene).unwrap();
    common::keep(&wet, "water_arrows");
    let below = mean_linear(&wet, 80, 50, 88, 56);
    assert!(luminance(below) < luminance(mean_linear(&unshadowed, 80, 50, 88, 56)));
    // The red arrow, drawn over the cube, runs down the middle of the image.
    let arrow = mean_linear(&wet, 63, 46, 65, 56);
    assert!(
        arrow[0] > 2.0 * arrow[1] && arrow[0] > 2.0 * arrow[2],
        "arrow pixel {arrow:?}"
    );
}

#[test]
fn subsurface_keeps_uniform_light_and_softens_a_shadow_edge() {
    let Some(d) = common::device() else { return };
    let mut r = renderer(&d, 128, 128);
    let mut scene = plate_scene();
    let base = r.render(&scene).unwrap();
    // A blur of uniform irradiance changes nothing.
    scene.subsurface = Some(Subsurface::default().scaled(20.0));
    let blurred = r.render(&scene).unwrap();
    common::keep(&blurred, "subsurface_uniform");
    let (a, b) = (
        mean_linear(&base, 8, 16, 56, 112),
        mean_linear(&blurred, 8, 16, 56, 112),
    );
    assert!((luminance(a) / luminance(b) - 1.0).abs() < 0.02, "{a:?} {b:?}");

    // A wall casts a shadow edge across the wet half: the subsurface term
    // spreads light into it (and darkness out of it).
    // (The camera sees x in [−0.5, 0.5]; a 2 m wall at x = 1.6 lit from
    // +x at 47.2° puts the edge at x ≈ −0.25, column 32.)
    let wall = RenderObject::new(
        builtin::cuboid(0.05, 2.0, 6.0),
        Isometry3::translation(1.6, 1.0, 0.0),
    );
    scene.light = DirectionalLight::from_angles(47.2, 0.0, [2.0; 3]);
    scene.objects.push(wall);
    scene.subsurface = None;
    let sharp = r.render(&scene).unwrap();
    scene.subsurface = Some(Subsurface::default().scaled(20.0));
    let soft = r.render(&scene).unwrap();
    common::keep(&sharp, "subsurface_edge_off");
    common::keep(&soft, "subsurface_edge_on");
    let profile = |img: &image::RgbaImage| -> Vec<f64> {
        (0..60)
            .map(|x| luminance(mean_linear(img, x, 60, x + 1, 68)))
            .collect()
    };
    let steepest = |p: &[f64]| p.windows(2).map(|w| (w[1] - w[0]).abs()).fold(0.0, f64::max);
    let (ps, pf) = (profile(&sharp), profile(&soft));
    assert!(
        steepest(&pf) < 0.7 * steepest(&ps),
        "edge gradient {} with subsurface, {} without",
        steepest(&pf),
        steepest(&ps)
    );
}

#[test]
fn cached_uploads_follow_their_arcs() {
    let Some(d) = common::device() else { return };
    let mut r = renderer(&d, 64, 64);
    let camera = Camera::perspective(Point3::new(0.0, 0.5, 4.0), Point3::origin(), 40.0);
    let mut scene = RenderScene::new(camera);
    scene.dither = false;
    let texture = Arc::new(soak_shade::render::speckled(64, 64, [0.6, 0.3, 0.2], 0.3, 4.0, 1));
    scene.objects.push(
        RenderObject::new(builtin::sphere(0.5, 32, 16), Isometry3::identity()).with_albedo(Albedo::Texture {
            image: texture,
            tint: [1.0; 3],
        }),
    );
    let first = r.render(&scene).unwrap();
    assert_eq!(
        first,
        r.render(&scene).unwrap(),
        "the same scene renders the same"
    );
    // Grow the mesh in place: `make_mut` drops the renderer's weak
    // reference, so the new mesh is uploaded.
    Arc::make_mut(&mut scene.objects[0].mesh)
        .positions
        .iter_mut()
        .for_each(|p| *p *= 1.5);
    let grown = r.render(&scene).unwrap();
    let covered = |img: &image::RgbaImage| {
        img.pixels()
            .filter(|p| p.0[0] > p.0[2].saturating_add(20))
            .count()
    };
    assert!(
        covered(&grown) > 2 * covered(&first),
        "{} vs {}",
        covered(&grown),
        covered(&first)
    );
}

#[test]
fn bad_scenes_are_typed_errors() {
    let limit = 8192;
    let ok = plate_scene();
    ok.validate(limit).unwrap();

    let mut s = plate_scene();
    let mut liquid = half_wet();
    liquid.put_pixel(5, 2, image::Luma([f32::NAN]));
    s.objects[0].liquid = Some(Arc::new(liquid));
    let e = s.validate(limit).unwrap_err();
    assert!(matches!(e, RenderError::Texture { object: 0, .. }), "{e}");
    assert!(e.to_string().contains("(5, 2)"), "{e}");

    let mut s = plate_scene();
    s.objects[0].mesh = Arc::new(common::plate(1.0).without_uvs());
    let e = s.validate(limit).unwrap_err();
    assert!(
        matches!(
            e,
            RenderError::MissingUvs {
                texture: "liquid",
                ..
            }
        ),
        "{e}"
    );

    let mut s = plate_scene();
    s.objects[0].segments = Some(Arc::new(vec![1, 2, 3]));
    let e = s.validate(limit).unwrap_err();
    assert!(
        matches!(
            e,
            RenderError::SegmentCount {
                given: 3,
                triangles: 2,
                ..
            }
        ),
        "{e}"
    );

    let mut s = plate_scene();
    s.objects[0].material = WetMaterial {
        liquid: Liquid {
            refractive_index: 0.9,
            ..Liquid::water()
        },
        ..WetMaterial::default()
    };
    let e = s.validate(limit).unwrap_err();
    assert!(matches!(e, RenderError::Material { .. }), "{e}");
    assert!(e.to_string().contains("refractive_index is 0.9"), "{e}");

    let mut s = plate_scene();
    s.objects[0].albedo = Albedo::Constant([0.5, 1.2, 0.5]);
    assert!(matches!(s.validate(limit), Err(RenderError::Material { .. })));

    let mut s = plate_scene();
    s.camera.target = s.camera.eye;
    assert!(matches!(s.validate(limit), Err(RenderError::Scene { .. })));

    let mut s = plate_scene();
    s.objects[0].mesh = Arc::new({
        let mut m = common::plate(1.0);
        m.triangles.push([0, 1, 9]);
        m
    });
    let e = s.validate(limit).unwrap_err();
    assert!(e.to_string().contains("triangle 2 uses vertex 9 of 4"), "{e}");

    let mut s = plate_scene();
    s.objects[0].liquid = Some(Arc::new(LiquidImage::new(9000, 1)));
    assert!(matches!(s.validate(limit), Err(RenderError::Texture { .. })));

    let mut s = plate_scene();
    s.subsurface = Some(Subsurface {
        resolution: 8,
        ..Subsurface::default()
    });
    assert!(matches!(s.validate(limit), Err(RenderError::Scene { .. })));
}

#[test]
fn impossible_sizes_are_typed_errors() {
    let Some(d) = common::device() else { return };
    assert!(matches!(
        Renderer::new(&d.0, &d.1, 0, 10),
        Err(RenderError::ImageSize { width: 0, .. })
    ));
    assert!(matches!(
        Renderer::new(&d.0, &d.1, 1 << 20, 10),
        Err(RenderError::ImageSize { .. })
    ));
    let options = RendererOptions {
        sample_count: 2,
        shadow_map_size: 512,
    };
    assert!(matches!(
        Renderer::with_options(&d.0, &d.1, 8, 8, options),
        Err(RenderError::SampleCount(2))
    ));
}
