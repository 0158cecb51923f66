//! Image bytes (PNG, OpenEXR) → decoded luminance → the channels soak lays
//! over an atlas: the initial liquid texture (`soak_wet::LiquidImage`,
//! `Wetting::set_liquid_from_image`), the wetting permeability map and the
//! liquid graph's permeability (`soak_graph::Permeability::from_image`).
//!
//! Bytes go through `LiquidImage::decode` (what `LiquidImage::open` does with
//! a file's bytes); images over 1024² are skipped before decoding to keep an
//! execution cheap.
#![no_main]

use std::io::Cursor;
use std::path::Path;

use libfuzzer_sys::fuzz_target;
use soak_graph::Permeability;
use soak_wet::{Liquid, LiquidImage, Material, Wetting};

fuzz_target!(|data: &[u8]| {
    let atlas = soak_fuzz::small_atlas();
    // Keep an execution cheap: skip images over 1024² before decoding them.
    let Ok(reader) = image::ImageReader::new(Cursor::new(data)).with_guessed_format() else {
        return;
    };
    if reader.into_dimensions().is_ok_and(|(w, h)| w > 1024 || h > 1024) {
        return;
    }
    let image = match LiquidImage::decode(data, Some(Path::new("fuzz.png"))) {
        Ok(image) => image,
        Err(e) => {
            assert!(e.to_string().contains("fuzz.png"), "{e}");
            return;
        }
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
