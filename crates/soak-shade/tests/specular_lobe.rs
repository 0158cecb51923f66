//! The liquid film's specular lobe, the wet roughness, and Lagarde's
//! shortcut as a comparison.

use soak_shade::{
    MIN_ALPHA, WetMaterial, alpha_from_roughness, film_specular, fresnel_f0, ggx_distribution,
    internal_reflectance, lagarde_wet_diffuse, lagarde_wet_gloss, schlick, smith_visibility, wet_albedo,
    wet_roughness,
};
use std::f64::consts::PI;

#[test]
fn ggx_is_normalised() {
    // ∫ D(h) (n·h) dω_h = 1 over the hemisphere, for every roughness.
    for alpha in [0.05, 0.1, 0.3, 0.7, 1.0] {
        let n = 200_000;
        let mut sum = 0.0;
        for i in 0..n {
            // u = cos²θ gives dω cosθ = π du·… : ∫ D cosθ sinθ dθ dφ = π ∫₀¹ D(√u) du
            let u = (i as f64 + 0.5) / n as f64;
            sum += ggx_distribution(u.sqrt(), alpha);
        }
        let integral = PI * sum / n as f64;
        assert!((integral - 1.0).abs() < 1e-4, "α = {alpha}: ∫D cos = {integral}");
    }
}

#[test]
fn visibility_is_one_quarter_at_normal_for_smooth_film() {
    // V = G/(4 n·l n·v) → 1/4 when G → 1 at normal incidence.
    let v = smith_visibility(1.0, 1.0, MIN_ALPHA);
    assert!((v - 0.25).abs() < 1e-12, "{v}");
    assert_eq!(smith_visibility(0.0, 0.0, 0.3), 0.0);
}

#[test]
fn film_lobe_peaks_in_the_mirror_direction_and_vanishes_below_horizon() {
    let f0 = fresnel_f0(1.333);
    let alpha = alpha_from_roughness(0.1);
    let peak = film_specular(0.8, 0.8, 1.0, 0.8, alpha, f0);
    let off = film_specular(0.8, 0.8, 0.98, 0.8, alpha, f0);
    assert!(peak > 10.0 * off, "{peak} vs {off}");
    assert_eq!(film_specular(-0.1, 0.8, 1.0, 0.8, alpha, f0), 0.0);
    assert_eq!(film_specular(0.8, 0.0, 1.0, 0.8, alpha, f0), 0.0);
    // Fresnel: grazing views reflect more.
    assert!(film_specular(0.2, 0.2, 1.0, 0.2, alpha, f0) > film_specular(0.9, 0.9, 1.0, 0.9, alpha, f0));
}

#[test]
fn wetting_only_smooths() {
    assert_eq!(wet_roughness(0.7, 0.1, 0.0), 0.7);
    assert_eq!(wet_roughness(0.7, 0.1, 1.0), 0.1);
    assert!((wet_roughness(0.7, 0.1, 0.5) - 0.4).abs() < 1e-15);
    // A surface already smoother than the film stays as it is.
    assert_eq!(wet_roughness(0.05, 0.1, 1.0), 0.05);
    let m = WetMaterial::default();
    assert_eq!(m.film_specular(0.8, 0.8, 1.0, 0.8, 0.0), 0.0); // no film yet
    assert!(m.film_specular(0.8, 0.8, 1.0, 0.8, 1.0) > 0.0);
}

#[test]
fn lagarde_is_a_constant_factor_lekner_dorf_is_not() {
    // Fully wet, fully porous: Lagarde keeps 20 % of any albedo.
    for a in [0.1, 0.5, 0.8] {
        assert!((lagarde_wet_diffuse(a, 1.0, 1.0) - 0.2 * a).abs() < 1e-15);
        assert_eq!(lagarde_wet_diffuse(a, 1.0, 0.0), a);
    }
    // Lekner–Dorf darkens dark albedos relatively more than light ones.
    let (r, p) = (schlick(1.0, fresnel_f0(1.333)), internal_reflectance(1.333));
    let ratio = |a: f64| wet_albedo(a, 1.0, r, p) / a;
    assert!(ratio(0.1) < ratio(0.5) && ratio(0.5) < ratio(0.8));
    // Gloss is raised, more for porous materials.
    assert_eq!(lagarde_wet_gloss(0.3, 1.0, 0.0), 0.3);
    assert!((lagarde_wet_gloss(0.3, 1.0, 1.0) - (0.4 + 0.6 * 0.3)).abs() < 1e-15);
    assert!(lagarde_wet_gloss(0.3, 1.0, 1.0) > lagarde_wet_gloss(0.3, 0.2, 1.0));
}
