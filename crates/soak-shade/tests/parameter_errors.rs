//! Invalid parameters are typed errors that name the parameter and value.

use soak_shade::{
    Gamma, Liquid, ParameterError, WetMaterial, validate_absorption, validate_albedo, validate_saturation,
};

#[test]
fn refractive_index_must_exceed_one() {
    let m = WetMaterial {
        liquid: Liquid {
            refractive_index: 0.9,
            ..Liquid::water()
        },
        ..WetMaterial::default()
    };
    let e = m.validate().unwrap_err();
    assert_eq!(
        e,
        ParameterError::IndexNotAboveOne {
            parameter: "liquid.refractive_index",
            value: 0.9
        }
    );
    assert!(e.to_string().contains("liquid.refractive_index is 0.9"), "{e}");
    let one = Liquid {
        refractive_index: 1.0,
        ..Liquid::water()
    };
    assert!(one.validate().is_err());
}

#[test]
fn nan_is_named() {
    let l = Liquid {
        refractive_index: f64::NAN,
        ..Liquid::water()
    };
    assert!(matches!(
        l.validate(),
        Err(ParameterError::NotFinite {
            parameter: "liquid.refractive_index",
            ..
        })
    ));
    assert!(matches!(
        validate_saturation(f64::NAN),
        Err(ParameterError::NotFinite {
            parameter: "saturation",
            ..
        })
    ));
}

#[test]
fn albedo_and_transmittance_are_fractions() {
    assert_eq!(
        validate_albedo([0.2, 1.5, 0.3]),
        Err(ParameterError::OutsideUnitInterval {
            parameter: "albedo.g",
            value: 1.5
        })
    );
    assert!(validate_albedo([0.0, 1.0, 0.5]).is_ok());
    let l = Liquid {
        transmittance: [1.0, 1.0, -0.1],
        ..Liquid::water()
    };
    let e = l.validate().unwrap_err();
    assert_eq!(e.to_string(), "liquid.transmittance.b is -0.1, outside [0, 1]");
}

#[test]
fn gamma_parameters_are_positive() {
    for (g, name) in [
        (Gamma::Log { k: 0.0 }, "gamma.k"),
        (Gamma::Power { exponent: -1.0 }, "gamma.exponent"),
        (Gamma::Arctan { roughness: 0.0 }, "gamma.roughness"),
    ] {
        match g.validate() {
            Err(ParameterError::NotPositive { parameter, .. }) => assert_eq!(parameter, name),
            other => panic!("{g:?}: {other:?}"),
        }
    }
    assert!(Gamma::default().validate().is_ok());
}

#[test]
fn absorption_inputs() {
    assert!(validate_absorption([0.0, 10.0, 500.0], 1e-3, Some(1e-2)).is_ok());
    assert_eq!(
        validate_absorption([0.0, -1.0, 0.0], 1e-3, None),
        Err(ParameterError::Negative {
            parameter: "absorption.g",
            value: -1.0
        })
    );
    assert!(matches!(
        validate_absorption([0.0; 3], 1e-3, Some(0.0)),
        Err(ParameterError::NotPositive {
            parameter: "reference_thickness",
            ..
        })
    ));
}

#[test]
fn defaults_are_water_and_round_trip_through_serde() {
    let m = WetMaterial::default();
    assert_eq!(m.liquid.refractive_index, 1.333);
    assert_eq!(m.liquid.transmittance, [1.0; 3]);
    let json = serde_json::to_string(&m).unwrap();
    assert_eq!(serde_json::from_str::<WetMaterial>(&json).unwrap(), m);
    // Missing fields take the defaults.
    let partial: WetMaterial = serde_json::from_str(r#"{"liquid":{"refractive_index":1.47}}"#).unwrap();
    assert_eq!(partial.liquid.refractive_index, 1.47);
    assert_eq!(partial.liquid.transmittance, [1.0; 3]);
    assert_eq!(partial.gamma, Gamma::default());
}
