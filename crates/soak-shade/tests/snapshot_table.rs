//! Regression pin: wet albedo over dry albedo × refractive index (clear
//! liquid, light along the normal), rounded to 4 decimals.

use soak_shade::{fresnel_f0, internal_reflectance, schlick, stern_mean_reflectance, wet_albedo};

#[derive(serde::Serialize)]
struct Row {
    n: f64,
    stern_mean_reflectance: f64,
    internal_reflectance: f64,
    r_spec_normal: f64,
    wet: Vec<Cell>,
}

#[derive(serde::Serialize)]
struct Cell {
    dry: f64,
    wet: f64,
}

fn round4(x: f64) -> f64 {
    (x * 1e4).round() / 1e4
}

#[test]
fn wet_albedo_table() {
    let rows: Vec<Row> = [1.2, 1.33, 1.333, 1.5, 1.8]
        .into_iter()
        .map(|n| {
            let r = schlick(1.0, fresnel_f0(n));
            let p = internal_reflectance(n);
            Row {
                n,
                stern_mean_reflectance: round4(stern_mean_reflectance(n)),
                internal_reflectance: round4(p),
                r_spec_normal: round4(r),
                wet: [0.05, 0.1, 0.3, 0.5, 0.8, 1.0]
                    .into_iter()
                    .map(|a| Cell {
                        dry: a,
                        wet: round4(wet_albedo(a, 1.0, r, p)),
                    })
                    .collect(),
            }
        })
        .collect();
    insta::assert_yaml_snapshot!(rows);
}
