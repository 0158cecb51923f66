//! `soak_report::accuracy::compute(true, ..)`: the quick accuracy report runs,
//! its numbers say what the method promises, and its files are written.
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
//! - the PNGs and the markdown are made, the tables name every mesh.

use std::path::{Path, PathBuf};

use soak_report::accuracy::{Report, Sweep, compute, markdown, text_table};

fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("soak-report-accuracy-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).expect("temp dir");
    dir
}

fn sweep<'a>(report: &'a Report, prefix: &str) -> &'a Sweep {
    report
        .sweeps
        .iter()
        .find(|s| s.mesh.starts_with(prefix))
        .unwrap_or_else(|| panic!("no sweep for {prefix}"))
}

fn volumes(sweep: &Sweep, resolution: u32, moment_matching: bool) -> &[f64] {
    &sweep
        .texel
        .iter()
        .find(|c| c.resolution == resolution && c.moment_matching == moment_matching)
        .unwrap_or_else(|| panic!("no {resolution}² curve"))
        .volume
}

fn is_png(path: &Path) -> bool {
    std::fs::read(path).is_ok_and(|b| b.starts_with(b"\x89PNG\r\n\x1a\n"))
}

#[test]
fn quick_report_holds_its_promises() {
    let dir = scratch("quick");
    let out = dir.join("img");
    let report = compute(true, &out, None).expect("the quick report runs");
    assert!(report.quick);

    // 256², moment matching: within 0.2 % at every level.
    let coarse = sweep(&report, "sphere 64×32");
    let body = coarse.body_volume;
    let exact = &coarse.exact;
    let texel = volumes(coarse, 256, true);
    assert_eq!(texel.len(), exact.len());
    for (k, (t, e)) in texel.iter().zip(exact).enumerate() {
        assert!(
            (t - e).abs() < 0.002 * body,
            "64×32 sphere, level {k}: {t} vs exact {e}"
        );
    }
    let fine = sweep(&report, "sphere 256×128");
    let ball = 4.0 / 3.0 * std::f64::consts::PI * 0.125;
    let analytic = fine.analytic.as_deref().expect("a sphere has an analytic curve");
    for (k, (t, a)) in volumes(fine, 256, true).iter().zip(analytic).enumerate() {
        assert!(
            (t - a).abs() < 0.002 * ball,
            "256×128 sphere, level {k}: {t} vs analytic {a}"
        );
    }

    // The per-triangle game method is far off somewhere.
    let worst = coarse
        .per_triangle
        .iter()
        .zip(exact)
        .map(|(b, e)| (b - e).abs() / body)
        .fold(0.0, f64::max);
    assert!(worst > 0.10, "per-triangle baseline's worst error {worst}");

    // Rows: moment matching no worse than texel centres from 128² up; the
    // tiled path agrees with the per-texel one; a GPU column left empty.
    assert!(report.rows.len() >= 16, "4 meshes × 4 resolutions");
    for r in &report.rows {
        let name = format!("{} at {}²", r.mesh, r.resolution);
        assert!(r.gpu_ms.is_none(), "{name}: gpu_ms");
        assert!(r.tiled_vs_per_texel < 1e-9, "{name}: tiled and per-texel differ");
        for (key, ms) in [
            ("per_texel_ms", r.per_texel_ms),
            ("tiled_ms", r.tiled_ms),
            ("exact_ms", r.exact_ms),
            ("per_triangle_ms", r.per_triangle_ms),
        ] {
            assert!(ms > 0.0, "{name}: {key}");
        }
        if r.resolution >= 128 {
            for (what, mm, centres) in [
                ("volume_error", r.volume_error, r.volume_error_centres),
                ("cob_error", r.cob_error, r.cob_error_centres),
                ("inertia_error", r.inertia_error, r.inertia_error_centres),
            ] {
                assert!(
                    mm <= centres * (1.0 + 1e-9) + 1e-15,
                    "{name}: {what} {mm} > centres {centres}"
                );
            }
        }
    }
    assert!(!report.tiled_speedup.is_empty() && report.tiled_speedup.iter().all(|s| s.speedup > 0.0));

    // Files: the two figures, in `out`.
    let pngs: Vec<&PathBuf> = report
        .files
        .iter()
        .filter(|p| p.extension().is_some_and(|e| e == "png"))
        .collect();
    assert_eq!(pngs.len(), 2, "{:?}", report.files);
    for p in pngs {
        assert!(p.starts_with(&out) && is_png(p), "{} is not a PNG", p.display());
    }
    assert!(is_png(&out.join("accuracy_sphere.png")) && is_png(&out.join("accuracy_cost.png")));

    // The markdown table, image links relative to the markdown.
    let table = markdown(&report, &dir.join("accuracy.md"));
    assert!(table.contains("| mesh |") && table.contains("| sphere 64×32 | 3968 | 256² |"));
    assert!(
        table.contains("](img/accuracy_sphere.png)"),
        "image links relative to the markdown"
    );

    // The drag-texel rows: every mesh at every drag bake below the atlas
    // and its atlas coarsened to each such side, the drag over them within
    // a tenth of the body's own for the sphere and the box (the boat's
    // 32² sets are coarser), the drag texels fewer than the body's.
    assert_eq!(
        report.drag_texels.len(),
        18,
        "3 meshes × 3 drag bakes below 256², and their atlas coarsened to the same sides"
    );
    for r in &report.drag_texels {
        let name = format!("{} {}² {:?}", r.mesh, r.drag_resolution, r.coarsening);
        assert!(r.calm_error.is_finite() && r.sea_error.is_finite(), "{name}");
        if !r.mesh.starts_with("boat") {
            assert!(r.calm_error < 0.1 && r.sea_error < 0.1, "{name}: {r:?}");
        }
        assert!(r.drag_texels > 0 && r.drag_texels < 40_000, "{name}: {r:?}");
        assert!(r.still_ms > 0.0 && r.own_ms > 0.0 && r.coarse_ms > 0.0, "{name}");
    }
    assert!(
        table.contains("## Drag over a coarser bake")
            && table.contains("| sphere 64×32 | 256² | 64² | 3968 |")
    );

    // The spectral rows: every mesh at 4, 8, 16 and 32 nodes per
    // shortest wavelength; at the default 16 the sampled read of the short
    // JONSWAP sea is within 1e-5 of the exact inversion's volume and
    // centre of buoyancy, and within 2 % of its drag, on the per-texel and
    // the tiled paths alike, and 16 nodes are better than 4.
    assert_eq!(report.spectral.len(), 12, "3 meshes × 4 settings");
    for mesh in ["sphere 64×32", "box 1×0.6×0.8", "boat 4×1.2×0.6"] {
        let at = |per: f64| {
            report
                .spectral
                .iter()
                .find(|r| r.mesh == mesh && r.per_wavelength == per)
                .unwrap_or_else(|| panic!("{mesh} at {per} per wavelength"))
        };
        let (coarse, default) = (at(4.0), at(16.0));
        for e in [
            default.volume_error,
            default.cob_error,
            default.tiled_errors[0],
            default.tiled_errors[1],
        ] {
            assert!(e.is_finite() && e < 1e-5, "{mesh}: {default:?}");
        }
        assert!(
            default.drag_errors[0] < 2e-2 && default.drag_errors[1] < 2e-2,
            "{mesh}: {default:?}"
        );
        assert!(
            default.volume_error < coarse.volume_error,
            "{mesh}: {default:?} against {coarse:?}"
        );
    }
    assert!(table.contains("## On a spectral sea"));

    // The plane rows: on the bench's JONSWAP sea the box and the sphere
    // read as one plane over their own section are within 1e-4 of their
    // volume and 10 % of their drag of the exact read; on every sea and
    // mesh the plane holds less of the surface than the sampled read (its
    // torque and drag errors are larger; its volume, the sea's mean over
    // the section, may not be: the sphere's on JONSWAP is within the
    // sampled read's). On the two-wave swell, whose shortest wave is
    // four metres, every mesh is more than an eighth of it across, and
    // its plane carries a current changing linearly over it: the box (the
    // twenty-body scene's crate) and the sphere within a quarter of their
    // drag where they move with the water (a uniform current there is off
    // by more than their drag itself).
    assert_eq!(report.plane.len(), 9, "3 seas × 3 meshes");
    for r in &report.plane {
        let errors = [r.volume_error, r.cob_error, r.torque_error, r.drag_error];
        assert!(errors.iter().all(|e| e.is_finite() && *e >= 0.0), "{r:?}");
        assert!(
            r.torque_error > r.sampled_errors[2] && r.drag_error > r.sampled_errors[3],
            "{r:?}"
        );
        if r.sea.contains("Hs 2 m") && !r.mesh.starts_with("boat") {
            assert!(r.volume_error < 1e-4 && r.drag_error < 0.1, "{r:?}");
        }
        if r.sea.contains("swell") && !r.mesh.starts_with("boat") {
            assert!(r.volume_error < 1e-3 && r.drag_error < 0.25, "{r:?}");
        }
    }
    assert!(table.contains("## A sea read as one plane over each body"));

    // The text table names every table mesh and the speed-up.
    let text = text_table(&report);
    for needle in [
        "sphere 64×32",
        "box 4×1×1",
        "boat",
        "sphere 316×158",
        "tiled speed-up over per-texel at 256²",
    ] {
        assert!(text.contains(needle), "`{needle}` missing from:\n{text}");
    }
    std::fs::remove_dir_all(dir).ok();
}
