//! Invariants of the wet optics over the whole parameter space (proptest).

use proptest::prelude::*;
use soak_shade::{
    ArtistCurve, EnergyBudget, Gamma, Liquid, OpticsInput, WetMaterial, absorbed_fraction, blend, evaluate,
    fresnel_f0, gamma_arctan, gamma_log, gamma_power, internal_reflectance, schlick, stern_mean_reflectance,
    wet_albedo,
};

/// Relative refractive index in (1, 2].
fn index() -> impl Strategy<Value = f64> {
    (1e-9f64..=1.0).prop_map(|e| 1.0 + e)
}

/// Any Γ family with a valid parameter, including extreme ones.
fn any_gamma() -> impl Strategy<Value = Gamma> {
    prop_oneof![
        Just(Gamma::Linear),
        (1e-12f64..1e6).prop_map(|k| Gamma::Log { k }),
        (1e-3f64..1e3).prop_map(|exponent| Gamma::Power { exponent }),
        (1e-12f64..1e4).prop_map(|roughness| Gamma::Arctan { roughness }),
        artist_curve().prop_map(|curve| Gamma::Artist { curve }),
    ]
}

/// A random valid artist curve: sorted samples in [0, 1] with exact ends.
fn artist_curve() -> impl Strategy<Value = ArtistCurve> {
    prop::collection::vec(0.0f64..=1.0, 0..40).prop_map(|mut v| {
        v.sort_by(f64::total_cmp);
        let mut s = vec![0.0];
        s.extend(v);
        s.push(1.0);
        ArtistCurve::new(s).unwrap()
    })
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(2000))]

    #[test]
    fn wet_is_never_brighter_than_dry_for_clear_liquid(
        a in 0.0f64..=1.0, n in index(), cos in 0.0f64..=1.0
    ) {
        let r = schlick(cos, fresnel_f0(n));
        let w = wet_albedo(a, 1.0, r, internal_reflectance(n));
        prop_assert!(w <= a, "a = {a}, n = {n}: wet {w}");
        prop_assert!(w >= 0.0);
    }

    #[test]
    fn coloured_liquid_is_darker_still(
        a in 0.0f64..=1.0, s in 0.0f64..=1.0, n in index(), cos in 0.0f64..=1.0
    ) {
        let (r, p) = (schlick(cos, fresnel_f0(n)), internal_reflectance(n));
        prop_assert!(wet_albedo(a, s, r, p) <= wet_albedo(a, 1.0, r, p) + 1e-15);
    }

    #[test]
    fn energy_is_never_created(
        a in 0.0f64..=1.0, s in 0.0f64..=1.0, n in index(), cos in 0.0f64..=1.0
    ) {
        let r = schlick(cos, fresnel_f0(n));
        let p = internal_reflectance(n);
        let reflected = r + wet_albedo(a, s, r, p);
        let absorbed = absorbed_fraction(a, s, r, p);
        prop_assert!(reflected + absorbed <= 1.0 + 1e-12, "{reflected} + {absorbed}");
        for x in [reflected, absorbed] {
            prop_assert!((0.0..=1.0).contains(&x));
        }
        let b = EnergyBudget::new(a, s, r, p);
        prop_assert!((b.total() - 1.0).abs() < 1e-12, "{b:?}");
        for x in [b.specular, b.diffuse, b.surface_absorbed, b.liquid_absorbed] {
            prop_assert!((0.0..=1.0).contains(&x));
        }
    }

    #[test]
    fn no_internal_reflection_leaves_only_the_specular_loss(
        a in 0.0f64..=1.0, r in 0.0f64..=1.0
    ) {
        let w = wet_albedo(a, 1.0, r, 0.0);
        prop_assert!((w - (1.0 - r) * a).abs() <= 1e-15, "{w} vs {}", (1.0 - r) * a);
    }

    #[test]
    fn mean_reflectances_are_fractions_and_grow_with_n(n in index(), dn in 1e-6f64..0.5) {
        let (r, p) = (stern_mean_reflectance(n), internal_reflectance(n));
        prop_assert!((0.0..1.0).contains(&r) && (0.0..1.0).contains(&p));
        prop_assert!(p > r); // total internal reflection
        prop_assert!(stern_mean_reflectance(n + dn) > r);
        prop_assert!(internal_reflectance(n + dn) > p);
    }

    #[test]
    fn gamma_is_monotone_with_exact_ends(
        g in any_gamma(), h1 in 0.0f64..=1.0, h2 in 0.0f64..=1.0
    ) {
        prop_assert_eq!(g.eval(0.0), 0.0);
        prop_assert_eq!(g.eval(1.0), 1.0);
        let (lo, hi) = if h1 <= h2 { (h1, h2) } else { (h2, h1) };
        let (gl, gh) = (g.eval(lo), g.eval(hi));
        prop_assert!(gl <= gh, "{g:?}: Γ({lo}) = {gl} > Γ({hi}) = {gh}");
        prop_assert!((0.0..=1.0).contains(&gl) && (0.0..=1.0).contains(&gh));
    }

    #[test]
    fn gamma_is_monotone_on_a_fine_grid(g in any_gamma()) {
        let mut last = 0.0;
        for i in 0..=1000 {
            let v = g.eval(i as f64 / 1000.0);
            prop_assert!(v >= last, "{g:?} drops at h = {}", i as f64 / 1000.0);
            last = v;
        }
        prop_assert_eq!(last, 1.0);
    }

    #[test]
    fn gamma_tolerates_any_parameter(k in any::<f64>(), h in any::<f64>()) {
        // Unvalidated parameters must not panic nor leave [0, 1].
        for g in [gamma_log(h, k), gamma_power(h, k), gamma_arctan(h, k)] {
            prop_assert!((0.0..=1.0).contains(&g), "Γ = {g} for k = {k}, h = {h}");
        }
    }

    #[test]
    fn blend_is_dry_when_dry_and_wet_when_saturated(
        g in any_gamma(), dry in 0.0f64..=1.0, wet in 0.0f64..=1.0
    ) {
        prop_assert_eq!(blend(dry, wet, g.eval(0.0)), dry);
        prop_assert_eq!(blend(dry, wet, g.eval(1.0)), wet);
    }

    #[test]
    fn material_albedo_ends(
        g in any_gamma(), n in index(), dry in prop::array::uniform3(0.0f64..=1.0),
        s in prop::array::uniform3(0.0f64..=1.0), cos in 0.0f64..=1.0, h in 0.0f64..=1.0
    ) {
        let m = WetMaterial {
            liquid: Liquid { refractive_index: n, transmittance: s, ..Liquid::water() },
            gamma: g,
        };
        prop_assert!(m.validate().is_ok());
        prop_assert_eq!(m.albedo(dry, 0.0, cos), dry);
        prop_assert_eq!(m.albedo(dry, 1.0, cos), m.wet_albedo(dry, cos));
        let mid = m.albedo(dry, h, cos);
        for c in 0..3 {
            prop_assert!(mid[c] <= dry[c] + 1e-15);
        }
        prop_assert!(m.roughness(0.7, h) <= 0.7);
    }

    #[test]
    fn hot_functions_never_panic(
        a in any::<f64>(), s in any::<f64>(), r in any::<f64>(), p in any::<f64>()
    ) {
        let w = wet_albedo(a, s, r, p);
        let b = absorbed_fraction(a, s, r, p);
        prop_assert!((0.0..=1.0).contains(&w) && (0.0..=1.0).contains(&b), "{w} {b}");
        let _ = stern_mean_reflectance(a);
        let _ = internal_reflectance(a);
        let _ = schlick(a, s);
    }

    #[test]
    fn table_rows_never_panic(
        v in prop::array::uniform16(any::<f32>()), kind in any::<u32>()
    ) {
        let input = OpticsInput {
            albedo: [v[0], v[1], v[2], v[3]],
            transmittance: [v[4], v[5], v[6], 0.0],
            refractive_index: v[7],
            n_dot_l: v[8],
            n_dot_v: v[9],
            n_dot_h: v[10],
            v_dot_h: v[11],
            saturation: v[12],
            gamma_kind: kind,
            gamma_param: v[13],
            dry_roughness: v[14],
            film_roughness: v[15],
            porosity: v[0],
            _pad: 0.0,
        };
        let _ = evaluate(&input);
    }
}
