//! Every shader the renderer compiles parses and validates with naga for
//! the WebGPU baseline (no capabilities), without a GPU; so does the
//! parity kernel.
#![cfg(feature = "render")]

use naga::valid::{Capabilities, ValidationFlags, Validator};
use soak_shade::render::{optics_kernel_source, shader_sources};

fn validate(name: &str, source: &str) {
    let module = match naga::front::wgsl::parse_str(source) {
        Ok(m) => m,
        Err(e) => panic!("{name} does not parse:\n{}", e.emit_to_string(source)),
    };
    if let Err(e) = Validator::new(ValidationFlags::all(), Capabilities::empty()).validate(&module) {
        panic!("{name} does not validate:\n{}", e.emit_to_string(source));
    }
}

#[test]
fn renderer_shaders_validate() {
    let sources = shader_sources();
    assert_eq!(sources.len(), 7);
    for (name, source) in &sources {
        validate(name, source);
    }
}

#[test]
fn parity_kernel_validates() {
    validate("optics parity", &optics_kernel_source());
}
