//! Progress of long headless runs: on a terminal a bar with the simulated
//! time and an estimate of the time left; elsewhere (a log, CI) a line every
//! ten seconds of wall time, or every `SOAK_PROGRESS_SECONDS`.

use std::io::IsTerminal;
use std::sync::OnceLock;
use std::time::{Duration, Instant};

/// How often a run that does not write to a terminal prints its progress:
/// `SOAK_PROGRESS_SECONDS` (a number of seconds, e.g. `0.5`), or 10 s.
fn line_every() -> Duration {
    static EVERY: OnceLock<Duration> = OnceLock::new();
    *EVERY.get_or_init(|| {
        std::env::var("SOAK_PROGRESS_SECONDS")
            .ok()
            .and_then(|s| s.parse::<f64>().ok())
            .filter(|s| s.is_finite() && *s >= 0.0)
            .map_or(Duration::from_secs(10), Duration::from_secs_f64)
    })
}

/// One run's progress: `done` of `total` units (steps, cells, frames).
pub struct Progress {
    label: String,
    unit: &'static str,
    total: u64,
    start: Instant,
    last_line: Instant,
    bar: Option<indicatif::ProgressBar>,
}

impl Progress {
    /// Progress of `total` `unit`s (plural, e.g. "steps") labelled `label`.
    pub fn new(label: impl Into<String>, unit: &'static str, total: u64) -> Self {
        let label = label.into();
        let bar = std::io::stderr().is_terminal().then(|| {
            let bar = indicatif::ProgressBar::new(total);
            bar.set_style(
                indicatif::ProgressStyle::with_template("{prefix} {wide_bar} {msg}").expect("valid template"),
            );
            bar.set_prefix(label.clone());
            bar
        });
        let now = Instant::now();
        Self {
            label,
            unit,
            total,
            start: now,
            last_line: now,
            bar,
        }
    }

    /// `done` units are done; `what` says where the run stands (e.g. the
    /// simulated time), shown beside the estimate of the time left.
    pub fn set(&mut self, done: u64, what: impl FnOnce() -> String) {
        let now = Instant::now();
        if let Some(bar) = &self.bar {
            // A bar redraws a few times a second at most, whatever is set.
            if done.is_multiple_of(16) || done == self.total {
                bar.set_position(done);
                bar.set_message(format!("{}, {}", what(), self.left(done, now)));
            }
        } else if now.duration_since(self.last_line) >= line_every() {
            self.last_line = now;
            eprintln!("{}: {}, {}", self.label, what(), self.left(done, now));
        }
    }

    /// "about N s left" from the rate so far.
    fn left(&self, done: u64, now: Instant) -> String {
        let elapsed = now.duration_since(self.start).as_secs_f64();
        // A run without an end (`duration = "forever"`): its pace.
        if self.total == u64::MAX {
            return format!(
                "{done} {} in {}, until stopped",
                self.unit,
                seconds(elapsed.round())
            );
        }
        format!(
            "{done}/{} {}, {}",
            self.total,
            self.unit,
            time_left(elapsed, done, self.total)
        )
    }

    /// Clears the bar.
    pub fn finish(self) {
        if let Some(bar) = self.bar {
            bar.finish_and_clear();
        }
    }
}

/// A number of seconds as a person reads it: `60`, `2.5`, `1e300`.
pub fn seconds(s: f64) -> String {
    if s.abs() >= 1e7 {
        format!("{s:e}")
    } else {
        format!("{s}")
    }
}

/// The estimate of the time left after `done` of `total` units in
/// `elapsed` seconds: seconds, minutes, hours or days, or far beyond.
pub fn time_left(elapsed: f64, done: u64, total: u64) -> String {
    if done == 0 || elapsed <= 0.0 {
        return "time left unknown yet".to_string();
    }
    let left = elapsed / done as f64 * total.saturating_sub(done) as f64;
    match left {
        l if l < 120.0 => format!("about {l:.0} s left"),
        l if l < 7200.0 => format!("about {:.0} min left", l / 60.0),
        l if l < 172_800.0 => format!("about {:.1} h left", l / 3600.0),
        l if l < 3.15e9 => format!("about {:.0} days left", l / 86_400.0),
        l => format!("about {:.1e} years left", l / 3.156e7),
    }
}

#[cfg(test)]
mod tests {
    use super::time_left;

    #[test]
    fn the_time_left_reads_in_units_that_fit() {
        assert_eq!(time_left(0.0, 0, 10), "time left unknown yet");
        assert_eq!(time_left(10.0, 10, 20), "about 10 s left");
        assert_eq!(time_left(10.0, 1, 61), "about 10 min left");
        assert_eq!(time_left(36.0, 1, 1001), "about 10.0 h left");
        assert_eq!(time_left(1.0, 100, 100), "about 0 s left");
        // A run of 1e300 s at 60 Hz: as many steps as a u64 holds.
        assert_eq!(time_left(1.0, 1000, u64::MAX), "about 5.8e8 years left");
    }

    #[test]
    fn seconds_read_as_written() {
        assert_eq!(super::seconds(60.0), "60");
        assert_eq!(super::seconds(2.5), "2.5");
        assert_eq!(super::seconds(1e300), "1e300");
    }
}
