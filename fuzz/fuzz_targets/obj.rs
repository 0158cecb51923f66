//! OBJ bytes → `load_obj_bytes` → validate → bake (or unwrap, then bake).
#![no_main]

use std::path::Path;

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let path = Path::new("fuzz.obj");
    match soak_bake::load_obj_bytes(data, path) {
        Ok(mesh) => soak_fuzz::bake_pipeline(&mesh, soak_fuzz::resolution_for(data)),
        Err(e) => assert!(e.to_string().contains("fuzz.obj"), "{e}"),
    }
});
