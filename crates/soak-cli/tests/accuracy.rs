//! `soak accuracy --quick`: the accuracy report runs, its numbers say what the
//! method promises, and its files are written.
//!
//! What must hold (quick mode: 32²–256², 11 water levels):
//! - at 256² with moment matching the 64×32 sphere's submerged volume is
//!   within 0.2 % of the body's volume of exact clipping at every level, and
//!   the 256×128 sphere's within 0.2 % of the analytic sphere (the 64×32 mesh
//!   itself is 0.4 % short of the analytic sphere when fully submerged, so it
//!   is compared with its own exact clipping);
//! - the per-triangle game baseline is off by more than 10 % somewhere;
//! - from 128² up, moment matching is at least as good as plain texel centres
//!   for volume, centre of buoyancy and inertia on every mesh. (Below 128² it
//!   is not: on the boat at 32² and 64², with about one sample per triangle,
//!   moment matching's volume error is several times that of the centres.)
//! - the tiled and per-texel paths give the same volumes;
//! - the PNGs and the markdown are written, and the JSON parses.

use std::path::{Path, PathBuf};
use std::process::Command;

use serde_json::Value;

fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("soak-accuracy-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).expect("temp dir");
    dir
}

fn soak(args: &[&str]) -> String {
    let out = Command::new(env!("CARGO_BIN_EXE_soak"))
        .args(args)
        .output()
        .expect("runs soak");
    assert!(
        out.status.success(),
        "soak {args:?} failed:\n{}",
        String::from_utf8_lossy(&out.stderr)
    );
    String::from_utf8(out.stdout).expect("utf-8 output")
}

fn f(v: &Value) -> f64 {
    v.as_f64().unwrap_or_else(|| panic!("{v} is not a number"))
}

fn floats(v: &Value) -> Vec<f64> {
    v.as_array().expect("array").iter().map(f).collect()
}

fn sweep<'a>(report: &'a Value, prefix: &str) -> &'a Value {
    report["sweeps"]
        .as_array()
        .expect("sweeps")
        .iter()
        .find(|s| s["mesh"].as_str().is_some_and(|m| m.starts_with(prefix)))
        .unwrap_or_else(|| panic!("no sweep for {prefix}"))
}

fn volumes(sweep: &Value, resolution: u64, moment_matching: bool) -> Vec<f64> {
    let c = sweep["texel"]
        .as_array()
        .expect("texel curves")
        .iter()
        .find(|c| {
            c["resolution"].as_u64() == Some(resolution)
                && c["moment_matching"].as_bool() == Some(moment_matching)
        })
        .unwrap_or_else(|| panic!("no {resolution}² curve"));
    floats(&c["volume"])
}

fn is_png(path: &Path) -> bool {
    std::fs::read(path).is_ok_and(|b| b.starts_with(b"\x89PNG\r\n\x1a\n"))
}

#[test]
fn quick_report_holds_its_promises() {
    let dir = scratch("json");
    let md = dir.join("accuracy.md");
    let out = dir.join("img");
    let json = soak(&[
        "accuracy",
        "--quick",
        "--json",
        "--out",
        out.to_str().unwrap(),
        "--markdown",
        md.to_str().unwrap(),
    ]);
    let report: Value = serde_json::from_str(&json).expect("the JSON parses");
    assert_eq!(report["quick"], Value::Bool(true));

    // 256², moment matching: within 0.2 % at every level.
    let coarse = sweep(&report, "sphere 64×32");
    let body = f(&coarse["body_volume"]);
    let exact = floats(&coarse["exact"]);
    let texel = volumes(coarse, 256, true);
    assert_eq!(texel.len(), exact.len());
    for (k, (t, e)) in texel.iter().zip(&exact).enumerate() {
        assert!(
            (t - e).abs() < 0.002 * body,
            "64×32 sphere, level {k}: {t} vs exact {e}"
        );
    }
    let fine = sweep(&report, "sphere 256×128");
    let ball = 4.0 / 3.0 * std::f64::consts::PI * 0.125;
    let analytic = floats(&fine["analytic"]);
    for (k, (t, a)) in volumes(fine, 256, true).iter().zip(&analytic).enumerate() {
        assert!(
            (t - a).abs() < 0.002 * ball,
            "256×128 sphere, level {k}: {t} vs analytic {a}"
        );
    }

    // The per-triangle game method is far off somewhere.
    let baseline = floats(&coarse["per_triangle"]);
    let worst = baseline
        .iter()
        .zip(&exact)
        .map(|(b, e)| (b - e).abs() / body)
        .fold(0.0, f64::max);
    assert!(worst > 0.10, "per-triangle baseline's worst error {worst}");

    // Rows: moment matching no worse than texel centres from 128² up; the
    // tiled path agrees with the per-texel one; a GPU column left empty.
    let rows = report["rows"].as_array().expect("rows");
    assert!(rows.len() >= 16, "4 meshes × 4 resolutions");
    for r in rows {
        let name = format!("{} at {}²", r["mesh"], r["resolution"]);
        assert!(r["gpu_ms"].is_null(), "{name}: gpu_ms");
        assert!(
            f(&r["tiled_vs_per_texel"]) < 1e-9,
            "{name}: tiled and per-texel differ"
        );
        for key in ["per_texel_ms", "tiled_ms", "exact_ms", "per_triangle_ms"] {
            assert!(f(&r[key]) > 0.0, "{name}: {key}");
        }
        if r["resolution"].as_u64().unwrap_or(0) >= 128 {
            for what in ["volume_error", "cob_error", "inertia_error"] {
                let (mm, centres) = (f(&r[what]), f(&r[&format!("{what}_centres")]));
                assert!(
                    mm <= centres * (1.0 + 1e-9) + 1e-15,
                    "{name}: {what} {mm} > centres {centres}"
                );
            }
        }
    }
    let speedup = report["tiled_speedup"].as_array().expect("speed-ups");
    assert!(!speedup.is_empty() && speedup.iter().all(|s| f(&s["speedup"]) > 0.0));

    // Files.
    let files: Vec<PathBuf> = report["files"]
        .as_array()
        .expect("files")
        .iter()
        .map(|p| PathBuf::from(p.as_str().expect("path")))
        .collect();
    let pngs: Vec<&PathBuf> = files
        .iter()
        .filter(|p| p.extension().is_some_and(|e| e == "png"))
        .collect();
    assert_eq!(pngs.len(), 2, "{files:?}");
    for p in pngs {
        assert!(p.starts_with(&out) && is_png(p), "{} is not a PNG", p.display());
    }
    let table = std::fs::read_to_string(&md).expect("markdown written");
    assert!(table.contains("| mesh |") && table.contains("| sphere 64×32 | 3968 | 256² |"));
    assert!(
        table.contains("](img/accuracy_sphere.png)"),
        "image links relative to the markdown"
    );
    std::fs::remove_dir_all(dir).ok();
}

#[test]
fn quick_text_report_names_its_files() {
    let dir = scratch("text");
    let text = soak(&["accuracy", "--quick", "--out", dir.to_str().unwrap()]);
    for needle in [
        "sphere 64×32",
        "box 4×1×1",
        "boat",
        "sphere 316×158",
        "tiled speed-up over per-texel at 256²",
        "wrote ",
    ] {
        assert!(text.contains(needle), "`{needle}` missing from:\n{text}");
    }
    assert!(is_png(&dir.join("accuracy_sphere.png")) && is_png(&dir.join("accuracy_cost.png")));
    std::fs::remove_dir_all(dir).ok();
}
