//! Artist Γ curves: validation, image rows, serde, and the GPU copy.

use soak_shade::{ARTIST_CURVE_GPU_SAMPLES, ArtistCurve, CurveError, Gamma};

#[test]
fn rejects_what_is_not_a_gamma_curve() {
    assert_eq!(ArtistCurve::new(vec![0.0]), Err(CurveError::TooShort { len: 1 }));
    assert_eq!(
        ArtistCurve::new(vec![0.0, 0.6, 0.5, 1.0]),
        Err(CurveError::Decreasing {
            index: 2,
            value: 0.5,
            previous: 0.6
        })
    );
    assert_eq!(
        ArtistCurve::new(vec![0.1, 1.0]),
        Err(CurveError::Ends {
            first: 0.1,
            last: 1.0
        })
    );
    assert!(matches!(
        ArtistCurve::new(vec![0.0, f64::NAN, 1.0]),
        Err(CurveError::NotFinite { index: 1, .. })
    ));
    let msg = ArtistCurve::new(vec![0.0, 0.6, 0.5, 1.0])
        .unwrap_err()
        .to_string();
    assert!(
        msg.contains("sample 2 is 0.5") && msg.contains("sample 1 (0.6)"),
        "{msg}"
    );
}

#[test]
fn normalized_pins_the_ends() {
    let c = ArtistCurve::normalized(vec![12.0, 100.0, 240.0]).unwrap();
    assert_eq!(c.samples()[0], 0.0);
    assert_eq!(c.samples()[2], 1.0);
    assert!((c.samples()[1] - 88.0 / 228.0).abs() < 1e-15);
    assert_eq!(
        ArtistCurve::normalized(vec![0.5, 0.5]),
        Err(CurveError::Flat { value: 0.5 })
    );
}

#[test]
fn interpolates_linearly_between_samples() {
    let c = ArtistCurve::new(vec![0.0, 0.5, 0.6, 1.0]).unwrap();
    assert_eq!(c.eval(0.0), 0.0);
    assert_eq!(c.eval(1.0), 1.0);
    assert!((c.eval(1.0 / 3.0) - 0.5).abs() < 1e-15);
    assert!((c.eval(0.5) - 0.55).abs() < 1e-15);
    assert_eq!(c.eval(-3.0), 0.0);
    assert_eq!(c.eval(7.0), 1.0);
    assert_eq!(c.eval(f64::NAN), 0.0);
}

#[test]
fn loads_from_an_image_row() {
    // Row 0 a ramp, row 1 not monotone.
    let mut img = image::GrayImage::new(256, 2);
    for x in 0..256u32 {
        img.put_pixel(x, 0, image::Luma([x as u8]));
        img.put_pixel(x, 1, image::Luma([(255 - x) as u8]));
    }
    let dynamic = image::DynamicImage::ImageLuma8(img);
    let ramp = ArtistCurve::from_image_row(&dynamic, 0).unwrap();
    assert_eq!(ramp.samples().len(), 256);
    for h in [0.1, 0.37, 0.9] {
        assert!((ramp.eval(h) - h).abs() < 1e-12);
    }
    assert!(matches!(
        ArtistCurve::from_image_row(&dynamic, 1),
        Err(CurveError::Decreasing { index: 1, .. })
    ));
    assert_eq!(
        ArtistCurve::from_image_row(&dynamic, 2),
        Err(CurveError::RowOutOfBounds { row: 2, height: 2 })
    );
    // RGB images read the red channel.
    let rgb = image::DynamicImage::ImageRgb8(image::RgbImage::from_fn(4, 1, |x, _| {
        image::Rgb([[0, 100, 200, 255][x as usize], 7, 7])
    }));
    let c = ArtistCurve::from_image_row(&rgb, 0).unwrap();
    assert!((c.samples()[1] - 100.0 / 255.0).abs() < 1e-6);
}

#[test]
fn serde_round_trip_validates() {
    let g = Gamma::Artist {
        curve: ArtistCurve::new(vec![0.0, 0.8, 1.0]).unwrap(),
    };
    let json = serde_json::to_string(&g).unwrap();
    assert_eq!(json, r#"{"kind":"artist","curve":[0.0,0.8,1.0]}"#);
    assert_eq!(serde_json::from_str::<Gamma>(&json).unwrap(), g);
    let bad = r#"{"kind":"artist","curve":[0.0,0.9,0.8,1.0]}"#;
    let err = serde_json::from_str::<Gamma>(bad).unwrap_err().to_string();
    assert!(err.contains("non-decreasing"), "{err}");
}

#[test]
fn gpu_copy_evaluates_like_the_cpu() {
    let short = ArtistCurve::new(vec![0.0, 0.1, 0.15, 0.7, 0.95, 1.0]).unwrap();
    let long = ArtistCurve::new(
        (0..=200)
            .map(|i| {
                let h = i as f64 / 200.0;
                h * h * (3.0 - 2.0 * h) // smoothstep
            })
            .collect::<Vec<_>>(),
    )
    .unwrap();
    for (curve, tol) in [(&short, 1e-6), (&long, 5e-4)] {
        let gpu = curve.to_gpu();
        assert!(gpu.len as usize <= ARTIST_CURVE_GPU_SAMPLES);
        for i in 0..=1000 {
            let h = i as f64 / 1000.0;
            let (c, g) = (curve.eval(h), f64::from(gpu.eval(h as f32)));
            assert!((c - g).abs() < tol, "h = {h}: cpu {c}, gpu copy {g}");
        }
        assert_eq!(gpu.eval(0.0), 0.0);
        assert_eq!(gpu.eval(1.0), 1.0);
    }
}
