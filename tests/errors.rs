//! Errors returned from `main` through `soak::Result` read as messages
//! with their causes, not as the structures behind them.

use soak::bake::{Atlas, BakeOptions, load_mesh};

/// What `main` prints for an error it returns: `Error: {:?}`.
fn printed(e: soak::Error) -> String {
    format!("Error: {e:?}")
}

#[test]
fn a_missing_file_prints_its_path_and_the_reason() {
    let e = load_mesh("no/such/mesh.obj")
        .map_err(soak::Error::from)
        .unwrap_err();
    let text = printed(e);
    assert!(text.contains("no/such/mesh.obj"), "{text}");
    assert!(text.contains("Caused by"), "{text}");
    assert!(!text.contains("Os {"), "{text}");
}

#[test]
fn a_mesh_without_uvs_says_so_and_what_to_do() {
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/data/crate_nouv.obj");
    let mesh = load_mesh(path).unwrap();
    let e = Atlas::bake(&mesh, BakeOptions::square(32))
        .map_err(soak::Error::from)
        .unwrap_err();
    let text = printed(e);
    assert!(text.contains("crate_nouv.obj"), "{text}");
    assert!(!text.contains("MissingUvs"), "{text}");
}
