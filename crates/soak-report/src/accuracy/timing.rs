//! Timing: medians of samples long enough to measure, paths timed in turn.

use std::time::Instant;

/// Milliseconds since `start`.
fn ms(start: Instant) -> f64 {
    start.elapsed().as_secs_f64() * 1e3
}

/// How many calls of `f` make one timed sample of about 0.5 ms, so that
/// microsecond calls are measurable.
fn calls_per_sample(f: &mut dyn FnMut()) -> usize {
    let start = Instant::now();
    f();
    ((0.5 / ms(start).max(1e-6)).ceil() as usize).clamp(1, 10_000)
}

/// Time per call of `f` over `calls` calls, ms.
fn sample_ms(calls: usize, f: &mut dyn FnMut()) -> f64 {
    let start = Instant::now();
    for _ in 0..calls {
        f();
    }
    ms(start) / calls as f64
}

fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    v.get(v.len() / 2).copied().unwrap_or(f64::NAN)
}

/// Median time per call of each path, ms, from `runs` samples each, taken
/// in turn so that drift on a shared machine hits every path alike (their
/// ratios are what matters). Each path's result goes through `black_box`.
pub(super) fn per_call_ms<const N: usize>(runs: usize, paths: [&mut dyn FnMut(); N]) -> [f64; N] {
    let mut paths = paths;
    let calls: Vec<usize> = paths.iter_mut().map(|p| calls_per_sample(*p)).collect();
    let mut times: Vec<Vec<f64>> = vec![Vec::with_capacity(runs); N];
    for _ in 0..runs.max(1) {
        for ((p, &n), t) in paths.iter_mut().zip(&calls).zip(&mut times) {
            t.push(sample_ms(n, *p));
        }
    }
    let mut medians = times.into_iter().map(median);
    std::array::from_fn(|_| medians.next().unwrap_or(f64::NAN))
}
