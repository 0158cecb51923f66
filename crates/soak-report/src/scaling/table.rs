//! The bench as tables: rows the body counts, columns the variants per
//! water, as aligned text or Markdown.

use std::fmt::Write as _;

use super::{Column, Measurement, ScalingReport};

/// `writeln!` into a `String`, which cannot fail.
macro_rules! w {
    ($out:expr, $($arg:tt)*) => {
        writeln!($out, $($arg)*).expect("writing to a String cannot fail")
    };
}

/// A time in ms with three significant digits, in µs, ms or s.
pub fn format_ms(ms: f64) -> String {
    let (v, unit) = if ms < 1.0 {
        (ms * 1e3, "µs")
    } else if ms < 1e3 {
        (ms, "ms")
    } else {
        (ms / 1e3, "s")
    };
    let digits = if v >= 100.0 {
        0
    } else if v >= 10.0 {
        1
    } else {
        2
    };
    format!("{v:.digits$} {unit}")
}

/// A count with thousands separators.
fn count(n: usize) -> String {
    let s = n.to_string();
    let mut out = String::new();
    for (k, c) in s.chars().enumerate() {
        if k > 0 && (s.len() - k).is_multiple_of(3) {
            out.push(',');
        }
        out.push(c);
    }
    out
}

fn cell(report: &ScalingReport, n: usize, c: &Column) -> String {
    report
        .get(n, c)
        .map_or_else(|| "-".to_string(), |m| format_ms(m.median_ms))
}

/// Per body count: the slowest setup, the most memory and the range of
/// submerged fractions over the generator's columns.
fn setup_of(report: &ScalingReport, n: usize) -> (f64, Option<f64>, Option<(f64, f64)>) {
    let ms: Vec<&Measurement> = report
        .measurements
        .iter()
        .filter(|m| m.case.bodies == n)
        .collect();
    let setup = ms.iter().map(|m| m.setup_ms).fold(0.0, f64::max);
    let rss = ms.iter().filter_map(|m| m.rss_mb).reduce(f64::max);
    let sub = ms
        .iter()
        .filter_map(|m| m.submerged)
        .reduce(|a, b| (a.0.min(b.0), a.1.max(b.1)));
    (setup, rss, sub)
}

/// The setup and memory of the first generator column at the largest
/// body count, per body.
fn memory_note(report: &ScalingReport) -> Option<String> {
    let n = *sizes(report).iter().max()?;
    let m = report
        .measurements
        .iter()
        .find(|m| m.case.bodies == n && m.case.column.water.is_some())?;
    let growth = m.rss_growth_mb?;
    Some(format!(
        "setting up {} bodies ({}) took {} ({} per body) and {growth:.0} MB ({:.0} kB per body)",
        count(n),
        m.case.column.label(),
        format_ms(m.setup_ms),
        format_ms(m.setup_ms / n as f64),
        growth * 1024.0 / n as f64
    ))
}

fn sizes(report: &ScalingReport) -> Vec<usize> {
    let mut v: Vec<usize> = report.measurements.iter().map(|m| m.case.bodies).collect();
    v.dedup();
    v
}

fn header(report: &ScalingReport) -> String {
    let o = &report.options;
    format!(
        "soak bench: step time (median) of a Rapier world of N floating bodies, half boxes and half spheres, \
         {r}² atlases ({tb} and {ts} texels), density 500, 2 m apart, dt = 1/60 s; {settle} steps to settle, \
         then {min}–{max} timed steps (about {budget} s) per case; {threads} threads; {secs:.0} s in all{coarse}",
        r = o.resolution,
        tb = count(report.texels.0),
        ts = count(report.texels.1),
        settle = o.settle_steps,
        min = o.min_steps,
        max = o.max_steps,
        budget = o.budget_s,
        threads = report.threads,
        secs = report.seconds,
        coarse = match o.drag_coarsening {
            Some(k) => format!("; drag over the atlases coarsened by {k} ({k} × {k} texels merged)"),
            None => String::new(),
        } + &match o.sea_sampling {
            Some(soak_hydro::SeaSampling::Plane) => "; the seas read as one plane over each body".to_string(),
            Some(soak_hydro::SeaSampling::Exact) => "; the seas read exactly at every texel".to_string(),
            Some(soak_hydro::SeaSampling::PerWavelength(n)) =>
                format!("; the seas sampled {n} nodes per shortest wave"),
            Some(soak_hydro::SeaSampling::Auto) =>
                "; each body reading the seas as it is against their waves (`auto`)".to_string(),
            None => String::new(),
        },
    )
}

/// The bench as an aligned text table, with the setup cost per body
/// count and the notes below.
pub fn text_table(report: &ScalingReport) -> String {
    let mut out = String::new();
    w!(out, "{}", header(report));
    let labels: Vec<String> = report.columns.iter().map(Column::label).collect();
    let widths: Vec<usize> = labels.iter().map(|l| l.chars().count().max(9)).collect();
    let mut line = format!("{:>6}", "N");
    for (l, wd) in labels.iter().zip(&widths) {
        let _ = write!(line, "  {l:>wd$}");
    }
    let _ = write!(line, "  {:>9}  {:>8}  submerged", "setup", "memory");
    w!(out, "{line}");
    for n in sizes(report) {
        let mut line = format!("{:>6}", count(n));
        for (c, wd) in report.columns.iter().zip(&widths) {
            let _ = write!(line, "  {:>wd$}", cell(report, n, c));
        }
        let (setup, rss, sub) = setup_of(report, n);
        let _ = write!(
            line,
            "  {:>9}  {:>8}  {}",
            format_ms(setup),
            rss.map_or("-".to_string(), |r| format!("{r:.0} MB")),
            sub.map_or("-".to_string(), |(a, b)| format!("{a:.2}–{b:.2}")),
        );
        w!(out, "{line}");
    }
    w!(
        out,
        "(setup: building the world and registering its bodies, the slowest column; memory: resident after setup; \
         submerged: fraction of each body's volume under water at the last step, over the generator's columns)"
    );
    if let Some(m) = memory_note(report) {
        w!(out, "note: {m}");
    }
    for note in &report.notes {
        w!(out, "note: {note}");
    }
    out
}

/// Where the generator's step goes, per body count and column: the mean
/// of each of its phases over the timed steps, and the rest of the mean
/// step (Rapier's own step and what surrounds the generator's).
pub fn phases_table(report: &ScalingReport) -> String {
    let mut out = String::new();
    w!(
        out,
        "soak's step phase by phase (mean over the timed steps): predict (the bodies read from Rapier, their poses \
         predicted; serial), prepare (options, sampled seas; parallel), evaluate (buoyancy and drag; parallel), hand \
         (implicit heave, radiation, firewall; parallel), engine (wrenches handed to Rapier; serial), rest (Rapier)"
    );
    w!(
        out,
        "{:>6}  {:<34}  {:>9}  {:>9}  {:>9}  {:>9}  {:>9}  {:>9}  {:>9}",
        "N",
        "column",
        "step",
        "predict",
        "prepare",
        "evaluate",
        "hand",
        "engine",
        "rest"
    );
    for m in &report.measurements {
        let Some(p) = m.phases else {
            continue;
        };
        let soak = p.predict_ms + p.prepare_ms + p.evaluate_ms + p.hand_ms + p.engine_ms;
        w!(
            out,
            "{:>6}  {:<34}  {:>9}  {:>9}  {:>9}  {:>9}  {:>9}  {:>9}  {:>9}",
            count(m.case.bodies),
            m.case.column.label(),
            format_ms(m.mean_ms),
            format_ms(p.predict_ms),
            format_ms(p.prepare_ms),
            format_ms(p.evaluate_ms),
            format_ms(p.hand_ms),
            format_ms(p.engine_ms),
            format_ms(m.mean_ms - soak),
        );
    }
    out
}

/// The bench as a Markdown table (rows N, columns the variants per water),
/// then setup and notes as a list.
pub fn markdown_table(report: &ScalingReport) -> String {
    let mut out = String::new();
    let mut head = "| N |".to_string();
    let mut rule = "|---:|".to_string();
    for c in &report.columns {
        let _ = write!(head, " {} |", c.label());
        rule.push_str("---:|");
    }
    head.push_str(" setup | memory |");
    rule.push_str("---:|---:|");
    w!(out, "{head}");
    w!(out, "{rule}");
    for n in sizes(report) {
        let mut line = format!("| {} |", count(n));
        for c in &report.columns {
            let _ = write!(line, " {} |", cell(report, n, c));
        }
        let (setup, rss, _) = setup_of(report, n);
        let _ = write!(
            line,
            " {} | {} |",
            format_ms(setup),
            rss.map_or("-".to_string(), |r| format!("{r:.0} MB"))
        );
        w!(out, "{line}");
    }
    w!(out, "");
    w!(out, "{}.", header(report));
    if let Some(m) = memory_note(report) {
        w!(out, "- {m}");
    }
    for note in &report.notes {
        w!(out, "- {note}");
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn times_have_three_digits_and_a_unit() {
        assert_eq!(format_ms(0.00222), "2.22 µs");
        assert_eq!(format_ms(0.16), "160 µs");
        assert_eq!(format_ms(14.4), "14.4 ms");
        assert_eq!(format_ms(147.2), "147 ms");
        assert_eq!(format_ms(2850.0), "2.85 s");
    }

    #[test]
    fn counts_have_separators() {
        assert_eq!(count(1), "1");
        assert_eq!(count(1000), "1,000");
        assert_eq!(count(10000), "10,000");
    }
}
