//! A flat plate, lit along its normal, half saturated with liquid: the wet
//! half's mean luminance is lower than the dry half's by the ratio the CPU
//! optics predict, within 5 %, on any adapter.
//!
//! The setup keeps the prediction clean: sun straight above (n·l = 1), a
//! uniform environment (irradiance π·L on the plate, reflected radiance L),
//! an orthographic camera at 45° (the same view direction at every pixel,
//! far from the sun's mirror direction), linear tone mapping. Predicted
//! radiances, per channel:
//!
//! - dry: `a (E_sun + E_env)/π`;
//! - wet: `(W(R_spec(1)) E_sun + W(R̄) E_env)/π + f_film E_sun + F(n·v) L`,
//!   the Lekner–Dorf albedos under the sun and under diffuse light, the
//!   film lobe and the film's mirror reflection of the environment.
#![cfg(feature = "render")]

mod common;

use nalgebra::{Isometry3, Point3, Vector3};
use soak_shade::render::{
    Albedo, Camera, DirectionalLight, Environment, LiquidImage, RenderObject, RenderScene, Renderer,
    RendererOptions, ToneMap,
};
use soak_shade::render::{luminance, mean_linear};
use soak_shade::{ArtistCurve, Gamma, Liquid, WetMaterial, schlick};

const SIZE: u32 = 128;
const SUN: f64 = 2.0;
const ENV: f64 = 0.15;

struct Case {
    name: &'static str,
    albedo: [f64; 3],
    material: WetMaterial,
    saturation: f32,
}

fn predicted(case: &Case) -> ([f64; 3], [f64; 3]) {
    let pi = std::f64::consts::PI;
    let e_env = pi * ENV;
    let m = &case.material;
    let h = f64::from(case.saturation);
    let g = m.gamma.eval(h);
    let a = case.albedo;
    let w_sun = m.wet_albedo(a, 1.0);
    let w_env = m.wet_albedo_diffuse_light(a);
    let (nv, nh) = (
        std::f64::consts::FRAC_1_SQRT_2,
        (std::f64::consts::PI / 8.0).cos(),
    );
    // Γ-weighted film lobe, per unit Γ.
    let lobe = if g > 0.0 {
        m.film_specular(1.0, nv, nh, nh, h) / g
    } else {
        0.0
    };
    let mirror = schlick(nv, m.liquid.f0()) * ENV;
    let dry: [f64; 3] = std::array::from_fn(|c| a[c] * (SUN + e_env) / pi);
    let wet_full: [f64; 3] =
        std::array::from_fn(|c| (w_sun[c] * SUN + w_env[c] * e_env) / pi + lobe * SUN + mirror);
    let wet = std::array::from_fn(|c| (1.0 - g) * dry[c] + g * wet_full[c]);
    (dry, wet)
}

fn scene(case: &Case) -> RenderScene {
    // Orthographic, 45° above the plate, looking along −z.
    let camera = Camera::orthographic(Point3::new(0.0, 4.0, 4.0), Point3::origin(), 1.0);
    let mut scene = RenderScene::new(camera);
    scene.light = DirectionalLight {
        direction: Vector3::y(),
        irradiance: [SUN; 3],
    };
    scene.environment = Environment::uniform([ENV; 3]);
    scene.tone_map = ToneMap::Linear;
    // Left half (u < ½, world −x) wet.
    let liquid = LiquidImage::from_fn(64, 4, |x, _| {
        image::Luma([if x < 32 { case.saturation } else { 0.0 }])
    });
    scene.objects.push(
        RenderObject::new(common::plate(4.0), Isometry3::identity())
            .with_albedo(Albedo::Constant(case.albedo))
            .with_liquid(liquid)
            .with_material(case.material.clone()),
    );
    scene
}

#[test]
fn wet_half_is_darker_by_the_predicted_ratio() {
    let Some((device, queue, _)) = common::device() else {
        return;
    };
    let options = RendererOptions {
        sample_count: 4,
        shadow_map_size: 512,
    };
    let mut renderer = Renderer::with_options(&device, &queue, SIZE, SIZE, options).expect("renderer");
    let coffee = Liquid::from_colour(1.34, [0.45, 0.20, 0.06], 1e-2, 2e-3);
    let cases = [
        Case {
            name: "grey 0.5, clear water, saturated",
            albedo: [0.5; 3],
            material: WetMaterial::default(),
            saturation: 1.0,
        },
        Case {
            name: "dark terracotta, clear water, saturated",
            albedo: [0.30, 0.15, 0.09],
            material: WetMaterial::default(),
            saturation: 1.0,
        },
        Case {
            name: "sand, coffee, h = 0.6, artist Γ",
            albedo: [0.72, 0.60, 0.42],
            material: WetMaterial {
                liquid: coffee,
                gamma: Gamma::Artist {
                    curve: ArtistCurve::new(vec![0.0, 0.5, 0.8, 1.0]).unwrap(),
                },
            },
            saturation: 0.6,
        },
    ];
    for case in &cases {
        let image = renderer.render(&scene(case)).expect("render");
        let (dry_p, wet_p) = predicted(case);
        // Halves, away from the wet/dry boundary in the middle and the edges.
        let wet = mean_linear(&image, 8, 16, 56, 112);
        let dry = mean_linear(&image, 72, 16, 120, 112);
        let ratio = luminance(wet) / luminance(dry);
        let expected = luminance(wet_p) / luminance(dry_p);
        eprintln!(
            "{}: wet/dry luminance {ratio:.4}, predicted {expected:.4} ({:+.2} %); dry {:.4} vs {:.4}",
            case.name,
            100.0 * (ratio / expected - 1.0),
            luminance(dry),
            luminance(dry_p),
        );
        assert!(ratio < 1.0, "{}: the wet half is not darker", case.name);
        assert!(
            (ratio / expected - 1.0).abs() < 0.05,
            "{}: ratio {ratio} against {expected}",
            case.name
        );
        // The absolute level is right too (no stray factor on both halves).
        assert!(
            (luminance(dry) / luminance(dry_p) - 1.0).abs() < 0.05,
            "{}: dry luminance {} against {}",
            case.name,
            luminance(dry),
            luminance(dry_p)
        );
    }
}
