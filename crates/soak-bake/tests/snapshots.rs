//! Rounded atlas summaries of the builtin meshes at 128², pinned.

use soak_bake::{Atlas, BakeOptions, load_mesh};

fn round(v: f64, digits: i32) -> f64 {
    if v == 0.0 {
        return 0.0;
    }
    let scale = 10f64.powi(digits - 1 - v.abs().log10().floor() as i32);
    (v * scale).round() / scale
}

#[derive(serde::Serialize)]
struct Row {
    mesh: &'static str,
    triangles: usize,
    texels: usize,
    centroid_samples: usize,
    tiles: usize,
    area_m2: f64,
    volume_m3: f64,
    closed: bool,
}

#[test]
fn builtin_atlas_summaries_at_128() {
    let rows: Vec<Row> = [
        "builtin:sphere",
        "builtin:box:4x1x1",
        "builtin:cylinder",
        "builtin:capsule",
        "builtin:torus",
        "builtin:boat",
        "builtin:dumbbell",
    ]
    .into_iter()
    .map(|mesh| {
        let s = Atlas::bake(&load_mesh(mesh).unwrap(), BakeOptions::square(128))
            .unwrap()
            .summary();
        Row {
            mesh,
            triangles: s.triangles,
            texels: s.texels,
            centroid_samples: s.centroid_samples,
            tiles: s.tiles,
            area_m2: round(s.area, 6),
            volume_m3: round(s.volume, 6),
            closed: s.closure < 1e-6,
        }
    })
    .collect();
    insta::assert_yaml_snapshot!(rows);
}
