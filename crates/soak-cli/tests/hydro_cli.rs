//! `soak hydro` with no pose options floats the body with its centre of
//! mass at the water level, and says what it used; a body clear of the
//! water gets no buoyancy errors.

use std::process::Command;

fn hydro(args: &[&str]) -> std::process::Output {
    Command::new(env!("CARGO_BIN_EXE_soak"))
        .arg("hydro")
        .args(args)
        .output()
        .expect("run soak hydro")
}

#[test]
fn without_a_position_the_centre_of_mass_is_at_the_water_level() {
    let out = hydro(&["builtin:boat", "-r", "64", "--json", "--water-level", "0.5"]);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let r: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(r["mass_model"], "solid, 500 kg/m³");
    assert_eq!(r["position_given"], false);
    // The boat's centre of mass (object frame) plus the origin's position
    // is at the water level.
    let com_y = r["exact"]["center_of_mass"][1].as_f64().unwrap();
    let y = r["position"][1].as_f64().unwrap();
    assert!(
        (y + com_y - 0.5).abs() < 1e-3,
        "origin at {y}, centre of mass {com_y}"
    );
    // Part of it under water, part above: the comparison means something.
    let (sub, vol) = (
        r["exact"]["submerged_volume"].as_f64().unwrap(),
        r["exact"]["volume"].as_f64().unwrap(),
    );
    assert!(
        sub > 0.2 * vol && sub < 0.8 * vol,
        "{sub} of {vol} m³ under water"
    );
}

#[test]
fn a_body_clear_of_the_water_is_said_to_be_so() {
    let out = hydro(&["builtin:box", "-r", "32", "--position", "0,5,0"]);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(text.contains("nothing is under water"), "{text}");
    assert!(!text.contains("buoyancy centre"), "{text}");
    assert!(text.contains("solid, 500 kg/m³"), "{text}");
}

#[test]
fn a_missing_file_prints_its_cause_once() {
    let out = hydro(&["no/such/mesh.obj"]);
    assert!(!out.status.success());
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(stderr.contains("cannot read `no/such/mesh.obj`"), "{stderr}");
    assert_eq!(stderr.matches("No such file or directory").count(), 1, "{stderr}");
}
