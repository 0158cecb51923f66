//! Image bytes (PNG, OpenEXR) → decoded luminance → the channels soak lays
//! over an atlas: the initial liquid texture (`soak_wet::LiquidImage`,
//! `Wetting::set_liquid_from_image`), the wetting permeability map and the
//! liquid graph's permeability (`soak_graph::Permeability::from_image`).
//!
//! `LiquidImage::open` reads a path; this target decodes from memory the way
//! it does (`image` → `to_luma32f`), under limits that keep an execution
//! cheap (1024² pixels, 64 MiB).
#![no_main]

use std::io::Cursor;

use libfuzzer_sys::fuzz_target;
use soak_graph::Permeability;
use soak_wet::{Liquid, LiquidImage, Material, Wetting};

fuzz_target!(|data: &[u8]| {
    let atlas = soak_fuzz::small_atlas();
    let Ok(mut reader) = image::ImageReader::new(Cursor::new(data)).with_guessed_format() else {
        return;
    };
    let mut limits = image::Limits::default();
    limits.max_image_width = Some(1024);
    limits.max_image_height = Some(1024);
    limits.max_alloc = Some(64 << 20);
    reader.limits(limits);
    let Ok(decoded) = reader.decode() else {
        return;
    };
    let luma = decoded.to_luma32f();
    let image = LiquidImage {
        width: luma.width(),
        height: luma.height(),
        values: luma.into_raw(),
    };

    // Initial liquid texture.
    let mut wet =
        Wetting::new(atlas, Material::cotton(), Liquid::water()).expect("cotton and water are valid");
    let sat = wet.material().saturation;
    match wet.set_liquid_from_image(atlas, &image, sat) {
        Ok(()) => {
            assert_eq!(wet.liquid().len(), atlas.len());
            assert!(
                wet.liquid()
                    .iter()
                    .all(|h| h.is_finite() && (0.0..=sat).contains(h))
            );
            assert!(wet.total_liquid(atlas).is_finite());
            let tex = soak_wet::liquid_texture(atlas, wet.liquid()).expect("one value per texel");
            assert!(tex.iter().all(|v| v.is_nan() || (v.is_finite() && *v >= 0.0)));
        }
        Err(e) => assert!(!e.to_string().is_empty()),
    }

    // Wetting permeability multiplier, one value per texel.
    let per_texel = atlas.sample_image(&image.values, image.width, image.height);
    assert_eq!(per_texel.len(), atlas.len());
    if let Err(e) = wet.set_permeability_map(atlas, Some(per_texel)) {
        assert!(!e.to_string().is_empty());
    }

    // Liquid-graph permeability κ (m).
    match Permeability::from_image(atlas, &image.values, image.width, image.height, 1e-6) {
        Ok(p) => {
            assert_eq!(p.len(), atlas.len());
            assert!(p.values().iter().all(|k| k.is_finite() && *k >= 0.0));
            assert!(p.conductance(atlas).is_finite());
        }
        Err(e) => assert!(!e.to_string().is_empty()),
    }
});
