//! `soak sea` end to end: a scene's spectral sea recovers the spectrum it
//! asks for (significant height and peak over 16 seeds, the binned
//! variance), and a scene without a spectral sea is refused by name. (Its
//! still, which needs a GPU adapter, is tested with the renders.)

use std::path::PathBuf;
use std::process::{Command, Output};

fn scene() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../data/scenes/spectral_sea.toml")
}

fn sea(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_soak"))
        .arg("sea")
        .args(args)
        .output()
        .expect("runs soak")
}

#[test]
fn the_realised_sea_recovers_its_target() {
    let out = sea(&[scene().to_str().unwrap(), "--json"]);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let r: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    let f = |v: &serde_json::Value| v.as_f64().unwrap();
    let target = f(&r["target"]["significant_height"]);
    assert_eq!(target, 1.0);
    // Over 16 seeds: Hs within 3 %, the peak within one bin.
    let averaged = &r["averaged"];
    assert_eq!(averaged["seeds"], 16);
    let hs = f(&averaged["significant_height"]);
    assert!((hs / target - 1.0).abs() < 0.03, "Hs {hs}");
    let off = f(&averaged["peak_off_by_bins"]);
    assert!(off.abs() <= 1.0, "peak {off} bins off");
    // The scene's own seed: its modes' variance is its nodes' (Parseval).
    let modes = f(&r["realised"]["significant_height"]);
    let nodes = f(&r["realised"]["significant_height_nodes"]);
    assert!(
        (modes / nodes - 1.0).abs() < 0.01,
        "{modes} over the modes, {nodes} over the nodes"
    );
    // The binned spectrum, averaged, holds the target's variance.
    let bin = f(&r["bin"]);
    let bins = r["bins"].as_array().unwrap();
    let sum = |key: &str| bins.iter().map(|b| f(&b[key])).sum::<f64>() * bin;
    let (mean, wanted) = (sum("mean"), sum("target"));
    assert!(
        (mean / wanted - 1.0).abs() < 0.06,
        "binned variance {mean} against {wanted}"
    );
    assert!((wanted / (target * target / 16.0) - 1.0).abs() < 0.02, "{wanted}");
}

#[test]
fn a_scene_without_a_spectral_sea_is_refused_by_name() {
    let wet = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../data/scenes/wet_crate.toml");
    let out = sea(&[wet.to_str().unwrap()]);
    assert!(!out.status.success());
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(
        stderr.contains("not a spectral sea") && stderr.contains("wet_crate.toml"),
        "{stderr}"
    );
    let out = sea(&[scene().to_str().unwrap(), "--seeds", "0"]);
    assert!(!out.status.success());
    assert!(String::from_utf8_lossy(&out.stderr).contains("--seeds"));
}
