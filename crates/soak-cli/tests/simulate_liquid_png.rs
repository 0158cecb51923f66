//! `soak simulate --liquid-png-every N`: each wet body's liquid texture is
//! written as a pseudo-colour PNG at the start and every N steps.

use std::path::PathBuf;
use std::process::Command;

#[test]
fn the_wet_crate_writes_its_liquid_texture_every_n_steps() {
    let scene: PathBuf = [
        env!("CARGO_MANIFEST_DIR"),
        "..",
        "..",
        "data",
        "scenes",
        "wet_crate.toml",
    ]
    .iter()
    .collect();
    let out = std::env::temp_dir().join(format!("soak-liquid-png-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&out);
    let run = Command::new(env!("CARGO_BIN_EXE_soak"))
        .arg("simulate")
        .arg(&scene)
        .args(["--duration", "0.5", "--liquid-png-every", "15", "--out"])
        .arg(&out)
        .output()
        .expect("runs soak");
    assert!(run.status.success(), "{}", String::from_utf8_lossy(&run.stderr));
    let stdout = String::from_utf8_lossy(&run.stdout);
    assert!(stdout.contains("soaked into the surface"), "{stdout}");
    // 30 steps: the start, step 15 and step 30.
    let mut files: Vec<String> = std::fs::read_dir(&out)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    files.sort();
    assert_eq!(
        files,
        [
            "crate_liquid_000000.png",
            "crate_liquid_000015.png",
            "crate_liquid_000030.png"
        ]
    );
    let png = image::open(out.join("crate_liquid_000030.png"))
        .unwrap()
        .to_rgb8();
    assert_eq!(png.dimensions(), (128, 128));
    // Dry texels are dark blue [0, 0, 128]; after the plunge some are not.
    let dry = image::Rgb([0u8, 0, 128]);
    assert!(png.pixels().any(|p| *p == dry));
    assert!(png.pixels().any(|p| p[0] > 128), "nothing wet after the plunge");
    let _ = std::fs::remove_dir_all(&out);
}
