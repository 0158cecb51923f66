//! The matrix as tables: one line per cell, or Markdown rows per mesh,
//! water and effects.

use std::fmt::Write as _;

use super::matrix::{Level, WaterKind};
use super::outcome::{Expect, Outcome};

/// `writeln!` into a `String`, which cannot fail.
macro_rules! w {
    ($out:expr, $($arg:tt)*) => {
        writeln!($out, $($arg)*).expect("writing to a String cannot fail")
    };
}

fn mark(ok: bool) -> &'static str {
    if ok { "ok" } else { "FAIL" }
}

/// The matrix as a text table, one line per cell: `resolution`² atlases, at
/// most `max_steps` steps per cell, `seconds` of wall-clock time.
pub fn text_table(outcomes: &[Outcome], resolution: u32, max_steps: usize, seconds: f64) -> String {
    let mut out = String::new();
    w!(
        out,
        "soak stress: {} cells, {resolution}² atlases, at most {max_steps} steps per cell, {seconds:.1} s",
        outcomes.len()
    );
    w!(
        out,
        "{:<44} {:>5} {:>6} {:>9} {:>3} {:>8} {:>9} {:>8} {:>6} {:>6}  verdict",
        "cell (mesh/scale/density/dt/water/effects)",
        "steps",
        "τ",
        "finite",
        "fw",
        "energy",
        "liquid",
        "expect",
        "frac",
        "want"
    );
    for o in outcomes {
        w!(
            out,
            "{:<44} {:>5} {:>6.1} {:>9} {:>3} {:>8.3} {:>9} {:>8} {:>6.3} {:>6.3}  {}",
            o.cell,
            o.steps,
            o.natural_times,
            mark(o.finite),
            o.firewall,
            o.energy_ratio,
            o.liquid_ratio.map_or("-".to_string(), |r| format!("{r:.2e}")),
            format!("{:?}", o.expect).to_lowercase(),
            if o.expect == Expect::Sinks {
                o.final_fraction
            } else {
                o.mean_fraction
            },
            o.expected_fraction,
            if o.pass {
                "pass".to_string()
            } else {
                format!("FAIL: {}", o.failures.join("; "))
            }
        );
    }
    let passed = outcomes.iter().filter(|o| o.pass).count();
    w!(out, "{passed} passed, {} failed", outcomes.len() - passed);
    out
}

/// The matrix as Markdown: one row per mesh, water and effects, summing
/// its cells, then the failing cells (as in docs/stress.md); `quick` says
/// whether the run was the quick matrix.
pub fn markdown_table(
    outcomes: &[Outcome],
    quick: bool,
    resolution: u32,
    max_steps: usize,
    seconds: f64,
) -> String {
    let mut out = String::new();
    w!(
        out,
        "`soak stress{}`: {} cells, {resolution}² atlases, at most {max_steps} steps per cell, {seconds:.0} s.\n",
        if quick { " --quick" } else { "" },
        outcomes.len()
    );
    w!(
        out,
        "One row per mesh, water and effects; each row sums its cells over relative density, scale and time step. \
         *energy* is the worst growth of specific energy over its allowance (≤ 1 passes), *liquid* the worst liquid error \
         over its tolerance (≤ 1 passes), *floats / sinks / neutral* count the cells of each expected outcome that \
         behaved so.\n"
    );
    w!(
        out,
        "| mesh | water | effects | cells | finite | firewall | energy | liquid | floats | sinks | neutral | passed |"
    );
    w!(out, "|---|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|");
    let mut groups: Vec<(&str, WaterKind, Level)> = outcomes
        .iter()
        .map(|o| (o.mesh.as_str(), o.water, o.effects))
        .collect();
    groups.dedup();
    for (mesh, water, level) in groups {
        let g: Vec<&Outcome> = outcomes
            .iter()
            .filter(|o| o.mesh == mesh && o.water == water && o.effects == level)
            .collect();
        let count = |e: Expect| {
            let all = g.iter().filter(|o| o.expect == e).count();
            let ok = g.iter().filter(|o| o.expect == e && o.settled).count();
            if all == 0 {
                "-".to_string()
            } else {
                format!("{ok}/{all}")
            }
        };
        let energy = g.iter().map(|o| o.energy_ratio).fold(f64::NEG_INFINITY, f64::max);
        let liquid = g
            .iter()
            .filter_map(|o| o.liquid_ratio)
            .fold(None, |a: Option<f64>, r| Some(a.map_or(r, |a| a.max(r))));
        w!(
            out,
            "| {mesh} | {} | {} | {} | {}/{} | {} | {energy:.2} | {} | {} | {} | {} | {}/{} |",
            water.label(),
            level.label(),
            g.len(),
            g.iter().filter(|o| o.finite).count(),
            g.len(),
            g.iter().map(|o| o.firewall).sum::<u64>(),
            liquid.map_or("-".to_string(), |r| format!("{r:.1e}")),
            count(Expect::Floats),
            count(Expect::Sinks),
            count(Expect::Neutral),
            g.iter().filter(|o| o.pass).count(),
            g.len(),
        );
    }
    let failing: Vec<&Outcome> = outcomes.iter().filter(|o| !o.pass).collect();
    out.push('\n');
    if failing.is_empty() {
        w!(out, "Every cell passed.");
    } else {
        w!(out, "Failing cells ({}):\n", failing.len());
        for o in failing {
            w!(out, "- `{}`: {}", o.cell, o.failures.join("; "));
        }
    }
    out
}
