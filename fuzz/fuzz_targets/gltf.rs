//! glTF / GLB bytes → `load_gltf_bytes` (no base directory: external
//! buffers are errors) → validate → bake (or unwrap, then bake).
#![no_main]

use std::path::Path;

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let path = Path::new("fuzz.glb");
    match soak_bake::load_gltf_bytes(data, path, None) {
        Ok(mesh) => soak_fuzz::bake_pipeline(&mesh, soak_fuzz::resolution_for(data)),
        Err(e) => assert!(e.to_string().contains("fuzz.glb"), "{e}"),
    }
});
