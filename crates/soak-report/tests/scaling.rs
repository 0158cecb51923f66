//! The scaling bench's structure on tiny worlds (1 and 4 bodies, 2 timed
//! steps): every cell measured, finite and positive, the Rapier-alone rows
//! present, the bodies floating. Nothing here depends on how fast the
//! machine is.

use soak_report::scaling::{
    Column, Device, ScalingOptions, Variant, WaterKind, markdown_table, run, text_table,
};

fn tiny() -> ScalingOptions {
    ScalingOptions {
        sizes: vec![1, 4],
        settle_steps: 2,
        min_steps: 2,
        max_steps: 2,
        budget_s: 0.0,
        ..ScalingOptions::quick()
    }
}

#[test]
fn every_cell_is_measured_and_the_bodies_float() {
    let report = run(&tiny(), |_| {}).expect("the bench runs");
    let columns = Column::all(false);
    assert_eq!(report.columns, columns);
    assert_eq!(report.measurements.len(), 2 * columns.len());
    for n in [1, 4] {
        let rapier = report.get(n, &Column::RAPIER).expect("a Rapier-alone row");
        assert!(rapier.submerged.is_none(), "Rapier alone has no water");
        for c in &columns {
            let m = report
                .get(n, c)
                .unwrap_or_else(|| panic!("{n} bodies, {}: missing", c.label()));
            assert_eq!(m.steps, 2);
            for t in [m.median_ms, m.mean_ms, m.min_ms, m.max_ms, m.setup_ms] {
                assert!(t.is_finite() && t > 0.0, "{n} bodies, {}: time {t}", c.label());
            }
            assert!(m.min_ms <= m.median_ms && m.median_ms <= m.max_ms);
            assert_eq!(m.firewall, 0, "{n} bodies, {}: firewall", c.label());
            if c.variant != Variant::RapierAlone {
                let (lo, hi) = m.submerged.expect("the generator's columns report submersion");
                assert!(
                    0.2 < lo && hi < 0.8,
                    "{n} bodies, {}: submerged fractions {lo:.3}–{hi:.3}, not floating",
                    c.label()
                );
            }
        }
    }
    assert!(columns.contains(&Column::soak(
        Variant::BuoyancyDrag,
        WaterKind::Swell,
        Device::Cpu
    )));
    assert_eq!(report.texels.0 > 0, report.texels.1 > 0);

    let text = text_table(&report);
    assert!(text.contains("Rapier alone") && text.contains("swell, buoyancy + drag"));
    let md = markdown_table(&report);
    assert_eq!(md.lines().filter(|l| l.starts_with("| 4 |")).count(), 1, "{md}");
    let json: serde_json::Value = serde_json::to_value(&report).expect("the report serialises");
    assert_eq!(
        json["measurements"].as_array().map(Vec::len),
        Some(2 * columns.len())
    );

    let dir = std::env::temp_dir().join(format!("soak-scaling-{}", std::process::id()));
    let png = soak_report::scaling::write_figure(&report, &dir).expect("the plot is written");
    assert!(std::fs::metadata(&png).map(|m| m.len() > 1000).unwrap_or(false));
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn no_body_counts_is_an_error() {
    let options = ScalingOptions {
        sizes: vec![],
        ..tiny()
    };
    assert!(run(&options, |_| {}).is_err());
}

#[test]
fn the_waters_asked_for_are_the_ones_measured() {
    let options = ScalingOptions {
        sizes: vec![1],
        waters: vec![WaterKind::Jonswap],
        ..tiny()
    };
    let report = run(&options, |_| {}).expect("the bench runs");
    let waters: Vec<_> = report.columns.iter().map(|c| c.water).collect();
    assert_eq!(
        waters,
        [
            None,
            Some(WaterKind::Jonswap),
            Some(WaterKind::Jonswap),
            Some(WaterKind::Jonswap)
        ]
    );
    assert_eq!(report.measurements.len(), 4);
    assert_eq!(WaterKind::from_label("swell"), Some(WaterKind::Swell));
    assert_eq!(WaterKind::from_label("lake"), None);
}

/// Interleaved, every case of a size is built before any is timed and
/// each takes its steps in turn: the same cells, each with its steps.
#[test]
fn interleaved_runs_measure_every_cell() {
    let options = ScalingOptions {
        interleave: true,
        waters: vec![WaterKind::Calm],
        ..tiny()
    };
    let report = run(&options, |_| {}).expect("the bench runs interleaved");
    assert_eq!(report.measurements.len(), 2 * report.columns.len());
    for m in &report.measurements {
        assert_eq!(m.steps, 2, "{m:?}");
        assert!(m.median_ms.is_finite() && m.median_ms > 0.0, "{m:?}");
    }
    assert!(report.notes.iter().any(|n| n.starts_with("interleaved")));
}
