//! `soak simulate --gltf run.glb`: the run as an animated glTF binary whose
//! animation samples are the poses the same run writes to its CSV.

use std::collections::HashMap;
use std::path::PathBuf;
use std::process::Command;

use gltf::animation::util::ReadOutputs;

/// A scene file of `data/scenes`.
fn scene(name: &str) -> PathBuf {
    [env!("CARGO_MANIFEST_DIR"), "..", "..", "data", "scenes", name]
        .iter()
        .collect()
}

#[test]
fn the_gltf_of_a_run_holds_its_recorded_poses() {
    let scene = scene("three_boxes.toml");
    let dir = std::env::temp_dir().join(format!("soak-gltf-{}", std::process::id()));
    let (csv, glb) = (dir.join("run.csv"), dir.join("run.glb"));
    let run = Command::new(env!("CARGO_BIN_EXE_soak"))
        .arg("simulate")
        .arg(&scene)
        .args(["--duration", "2", "--csv"])
        .arg(&csv)
        .arg("--gltf")
        .arg(&glb)
        .output()
        .expect("runs soak");
    assert!(run.status.success(), "{}", String::from_utf8_lossy(&run.stderr));

    // The CSV's poses per body: t, position, rotation [x, y, z, w].
    let text = std::fs::read_to_string(&csv).unwrap();
    let mut poses: HashMap<String, Vec<[f64; 8]>> = HashMap::new();
    for line in text.lines().skip(1) {
        let f: Vec<&str> = line.split(',').collect();
        let v: Vec<f64> = [0, 2, 3, 4, 5, 6, 7, 8]
            .iter()
            .map(|&k| f[k].parse().unwrap())
            .collect();
        poses
            .entry(f[1].to_string())
            .or_default()
            .push(v.try_into().unwrap());
    }

    let (doc, buffers, _) = gltf::import(&glb).expect("a valid glTF binary");
    assert_eq!(doc.nodes().count(), poses.len());
    let animation = doc.animations().next().expect("an animation");
    let mut checked = 0;
    for channel in animation.channels() {
        let node = channel.target().node();
        let want = &poses[node.name().unwrap()];
        let reader = channel.reader(|b| Some(&buffers[b.index()]));
        let times: Vec<f32> = reader.read_inputs().unwrap().collect();
        assert_eq!(times.len(), want.len());
        let got: Vec<Vec<f32>> = match reader.read_outputs().unwrap() {
            ReadOutputs::Translations(t) => t.map(|v| v.to_vec()).collect(),
            ReadOutputs::Rotations(r) => r.into_f32().map(|v| v.to_vec()).collect(),
            _ => panic!("only poses are animated"),
        };
        let columns = if got[0].len() == 3 { 1..4 } else { 4..8 };
        for ((t, g), w) in times.iter().zip(&got).zip(want) {
            assert!((f64::from(*t) - w[0]).abs() < 1e-5, "t {t} vs {}", w[0]);
            for (a, b) in g.iter().zip(&w[columns.clone()]) {
                assert!((f64::from(*a) - b).abs() < 2e-6, "{a} vs {b}");
                checked += 1;
            }
        }
    }
    assert!(checked > 100, "{checked} values checked");
    let _ = std::fs::remove_dir_all(&dir);
}

/// A wet body's vertices carry the liquid soaked into it at the end, as
/// vertex colours between dry grey and saturated blue (the crate of
/// `wet_crate.toml` a second after it is dropped into the swell: its
/// bottom soaked, its top dry).
#[test]
fn the_gltf_of_a_wet_run_colours_its_liquid() {
    let scene = scene("wet_crate.toml");
    let dir = std::env::temp_dir().join(format!("soak-gltf-wet-{}", std::process::id()));
    let glb = dir.join("wet.glb");
    let run = Command::new(env!("CARGO_BIN_EXE_soak"))
        .arg("simulate")
        .arg(&scene)
        .args(["--duration", "1"])
        .arg("--gltf")
        .arg(&glb)
        .arg("--out")
        .arg(&dir)
        .output()
        .expect("runs soak");
    assert!(run.status.success(), "{}", String::from_utf8_lossy(&run.stderr));
    let (doc, buffers, _) = gltf::import(&glb).expect("a valid glTF binary");
    let node = doc
        .nodes()
        .find(|n| n.name() == Some("crate"))
        .expect("the crate");
    let primitive = node.mesh().unwrap().primitives().next().unwrap();
    let reader = primitive.reader(|b| Some(&buffers[b.index()]));
    let colours: Vec<[f32; 4]> = reader
        .read_colors(0)
        .expect("the wet crate has vertex colours")
        .into_rgba_f32()
        .collect();
    let positions: Vec<[f32; 3]> = reader.read_positions().unwrap().collect();
    assert_eq!(colours.len(), positions.len());
    // The fill fraction from the red channel, 0.8 dry to 0.05 saturated.
    let fill: Vec<f32> = colours.iter().map(|c| (0.8 - c[0]) / 0.75).collect();
    assert!(fill.iter().all(|f| (-1e-6..=1.0 + 1e-6).contains(f)), "{fill:?}");
    let (low, high): (Vec<_>, Vec<_>) = positions.iter().zip(&fill).partition(|(p, _)| p[1] < 0.0);
    let mean = |v: &[(&[f32; 3], &f32)]| v.iter().map(|(_, f)| **f).sum::<f32>() / v.len() as f32;
    assert!(
        mean(&low) > mean(&high) + 0.05,
        "the bottom wetter than the top: {} vs {}",
        mean(&low),
        mean(&high)
    );
    let _ = std::fs::remove_dir_all(&dir);
}
