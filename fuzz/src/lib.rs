//! What must hold after any input, shared by soak's fuzz targets.
//!
//! Every target feeds bytes through a public entry point; a typed error is a
//! fine outcome, a panic (including the assertions here) is a crash.

use std::sync::OnceLock;

use soak_bake::{Atlas, BakeOptions, Mesh, UnwrapOptions, validate, validate_topology};

/// Largest mesh the targets validate and bake: keeps an execution in
/// milliseconds (the loaders themselves see every mesh).
pub const MAX_TRIANGLES: usize = 4_000;
/// Largest vertex count the targets validate and bake.
pub const MAX_VERTICES: usize = 12_000;

/// A bake resolution in 8..=64 derived from the input, so seeds need no
/// header and every resolution gets exercised.
pub fn resolution_for(input: &[u8]) -> u32 {
    8 + (input.len() as u32 % 57)
}

/// Whether `SOAK_FUZZ_STRICT` is set: then an unwrap that returns `Ok` must
/// also give UVs that validate (a stronger claim than "no panic").
pub fn strict() -> bool {
    static STRICT: OnceLock<bool> = OnceLock::new();
    *STRICT.get_or_init(|| std::env::var_os("SOAK_FUZZ_STRICT").is_some())
}

/// Validates `mesh`; bakes it if valid; unwraps it and bakes the result if
/// only its UVs are wrong. Nothing may panic, and a baked atlas must have a
/// finite summary.
pub fn bake_pipeline(mesh: &Mesh, resolution: u32) {
    if mesh.triangles.len() > MAX_TRIANGLES || mesh.positions.len() > MAX_VERTICES {
        return;
    }
    match validate(mesh) {
        Ok(()) => bake(mesh, resolution),
        Err(e) => {
            assert!(!e.to_string().is_empty());
            if validate_topology(mesh).is_err() {
                return;
            }
            match soak_bake::unwrap(mesh, UnwrapOptions::default()) {
                Ok((unwrapped, report)) => {
                    assert_eq!(unwrapped.triangles.len(), mesh.triangles.len());
                    assert!(report.coverage.is_finite(), "unwrap report {report:?}");
                    match validate(&unwrapped) {
                        Ok(()) => bake(&unwrapped, resolution),
                        Err(e) => assert!(!strict(), "unwrap gave invalid UVs: {e}"),
                    }
                }
                Err(e) => assert!(!e.to_string().is_empty()),
            }
        }
    }
}

/// Bakes a mesh that validated: that must succeed, with finite invariants.
pub fn bake(mesh: &Mesh, resolution: u32) {
    let atlas = Atlas::bake(mesh, BakeOptions::square(resolution))
        .unwrap_or_else(|e| panic!("a mesh that validated failed to bake: {e}"));
    check_atlas(&atlas);
}

/// An atlas summary with no NaN or infinity, and at least one sample.
pub fn check_atlas(atlas: &Atlas) {
    let s = atlas.summary();
    assert!(!atlas.is_empty(), "empty atlas {s:?}");
    for (what, v) in [
        ("area", s.area),
        ("volume", s.volume),
        ("closure", s.closure),
        ("bounding_radius", s.bounding_radius),
    ] {
        assert!(v.is_finite(), "atlas summary {what} is {v}: {s:?}");
    }
    assert!(s.area >= 0.0, "{s:?}");
}

/// A small baked box shared by the texture and graph targets
/// (2 × 1 × 1 m at 32², about 700 samples).
pub fn small_atlas() -> &'static Atlas {
    static ATLAS: OnceLock<Atlas> = OnceLock::new();
    ATLAS.get_or_init(|| {
        Atlas::bake(
            &soak_bake::builtin::cuboid(2.0, 1.0, 1.0),
            BakeOptions::square(32),
        )
        .expect("the builtin box bakes")
    })
}
