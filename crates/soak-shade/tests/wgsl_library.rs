//! The WGSL library must parse and validate for the WebGPU baseline (no
//! capabilities: no f64, no extensions), define every function the CPU
//! reference has, and lay out its structs exactly as the Rust mirrors.

use naga::valid::{Capabilities, ValidationFlags, Validator};
use soak_shade::{ArtistCurveGpu, OpticsInput, OpticsOutput, WET_OPTICS_WGSL};
use std::mem::{offset_of, size_of};

fn validate(source: &str) -> naga::Module {
    let module = match naga::front::wgsl::parse_str(source) {
        Ok(m) => m,
        Err(e) => panic!("WGSL does not parse:\n{}", e.emit_to_string(source)),
    };
    if let Err(e) = Validator::new(ValidationFlags::all(), Capabilities::empty()).validate(&module) {
        panic!("WGSL does not validate:\n{}", e.emit_to_string(source));
    }
    module
}

#[test]
fn library_validates_for_the_webgpu_baseline() {
    let module = validate(WET_OPTICS_WGSL);
    assert!(module.entry_points.is_empty(), "the library has no entry point");
    assert!(module.global_variables.is_empty(), "the library has no bindings");
}

#[test]
fn library_defines_every_function() {
    let module = validate(WET_OPTICS_WGSL);
    let names: Vec<&str> = module
        .functions
        .iter()
        .filter_map(|(_, f)| f.name.as_deref())
        .collect();
    for f in [
        "stern_mean_reflectance",
        "internal_reflectance",
        "fresnel_f0",
        "schlick",
        "wet_albedo",
        "absorbed_fraction",
        "beer_lambert",
        "gamma_linear",
        "gamma_log",
        "gamma_power",
        "gamma_arctan",
        "gamma_artist",
        "gamma_eval",
        "blend",
        "alpha_from_roughness",
        "ggx_distribution",
        "smith_visibility",
        "film_specular",
        "wet_roughness",
        "lagarde_factor",
        "lagarde_wet_diffuse",
        "lagarde_wet_gloss",
        "evaluate_optics",
    ] {
        assert!(names.contains(&f), "WGSL lacks `{f}`; has {names:?}");
    }
}

/// `(member name, offset)` of a WGSL struct, and its size.
fn wgsl_struct(module: &naga::Module, name: &str) -> (Vec<(String, u32)>, u32) {
    for (_, ty) in module.types.iter() {
        if ty.name.as_deref() == Some(name) {
            if let naga::TypeInner::Struct { members, span } = &ty.inner {
                let m = members
                    .iter()
                    .map(|m| (m.name.clone().unwrap_or_default(), m.offset))
                    .collect();
                return (m, *span);
            }
        }
    }
    panic!("WGSL has no struct {name}");
}

macro_rules! rust_layout {
    ($ty:ty { $($field:ident),* $(,)? }) => {
        (
            vec![$((stringify!($field).to_string(), offset_of!($ty, $field) as u32)),*],
            size_of::<$ty>() as u32,
        )
    };
}

#[test]
fn structs_mirror_the_rust_layouts() {
    let module = validate(WET_OPTICS_WGSL);
    let input = rust_layout!(OpticsInput {
        albedo,
        transmittance,
        refractive_index,
        n_dot_l,
        n_dot_v,
        n_dot_h,
        v_dot_h,
        saturation,
        gamma_kind,
        gamma_param,
        dry_roughness,
        film_roughness,
        porosity,
        _pad,
    });
    assert_eq!(wgsl_struct(&module, "OpticsInput"), input);
    let output = rust_layout!(OpticsOutput {
        wet_albedo,
        absorbed,
        blended,
        lagarde_albedo,
        stern,
        internal,
        r_spec,
        gamma,
        film_specular,
        wet_roughness,
        lagarde_gloss,
        _pad,
    });
    assert_eq!(wgsl_struct(&module, "OpticsOutput"), output);
    // ArtistCurveGpu: samples [f32; 64] is array<vec4<f32>, 16>; the padding
    // is one [u32; 3] in Rust and three u32 in WGSL.
    let (members, size) = wgsl_struct(&module, "ArtistCurveGpu");
    assert_eq!(size as usize, size_of::<ArtistCurveGpu>());
    assert_eq!(
        members[0],
        ("samples".into(), offset_of!(ArtistCurveGpu, samples) as u32)
    );
    assert_eq!(members[1], ("len".into(), offset_of!(ArtistCurveGpu, len) as u32));
    assert_eq!(members[2].1 as usize, offset_of!(ArtistCurveGpu, _pad));
}

#[test]
fn parity_kernel_from_the_docs_validates() {
    let kernel = r#"
@group(0) @binding(0) var<storage, read> inputs: array<OpticsInput>;
@group(0) @binding(1) var<storage, read_write> outputs: array<OpticsOutput>;
@group(0) @binding(2) var<uniform> curve: ArtistCurveGpu;
@group(0) @binding(3) var<storage, read_write> artist: array<f32>;

@compute @workgroup_size(64)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    if (id.x < arrayLength(&inputs)) {
        outputs[id.x] = evaluate_optics(inputs[id.x]);
        artist[id.x] = gamma_artist(inputs[id.x].saturation, curve);
    }
}
"#;
    let module = validate(&format!("{WET_OPTICS_WGSL}\n{kernel}"));
    assert_eq!(module.entry_points.len(), 1);
}
