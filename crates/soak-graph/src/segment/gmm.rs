//! Soft clustering of the normalised SDF: a one-dimensional Gaussian
//! mixture fitted by expectation–maximisation.
//!
//! As in CGAL, the mixture is initialised from a k-means clustering whose
//! centres are seeded by k-means++ ([`KMEANS_RESTARTS`] seeded restarts, the
//! one with the least squared error wins), then refined by EM until the
//! log-likelihood changes by less than a relative tolerance. The components
//! are returned sorted by mean, so label 0 is the thinnest part.
//!
//! Everything runs sequentially in a fixed order: the fit depends only on
//! the data and the seed.

use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use serde::Serialize;

/// Floor of a component's standard deviation, in units of the data (the
/// normalised SDF lives in [0, 1]), so a component cannot collapse onto one
/// value.
pub const MIN_STD_DEV: f64 = 1e-3;

/// Number of k-means++ restarts used to initialise EM.
pub const KMEANS_RESTARTS: usize = 10;

/// Maximum Lloyd iterations of one k-means run.
pub const KMEANS_MAX_ITERATIONS: usize = 100;

/// Probabilities are floored at this before taking the logarithm of the
/// unary cost (CGAL's epsilon).
pub const PROBABILITY_FLOOR: f64 = 5e-6;

/// One Gaussian of the mixture.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct GaussianComponent {
    /// Mean, in units of the data.
    pub mean: f64,
    /// Standard deviation, in units of the data (≥ [`MIN_STD_DEV`]).
    pub std_dev: f64,
    /// Mixing weight in [0, 1]; the weights sum to 1.
    pub weight: f64,
}

/// A fitted one-dimensional Gaussian mixture.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct GaussianMixture {
    /// The components, sorted by mean. There are fewer than requested when
    /// the data has fewer distinct values than components.
    pub components: Vec<GaussianComponent>,
    /// EM iterations run.
    pub iterations: usize,
    /// Whether EM met the tolerance before the iteration limit.
    pub converged: bool,
    /// Final log-likelihood of the data (natural log, dimensionless).
    pub log_likelihood: f64,
}

impl GaussianMixture {
    /// Fits `k` components (fewer if the data has fewer distinct values) to
    /// `data`. EM stops when the log-likelihood changes by at most
    /// `tolerance` relative to its magnitude, or after `max_iterations`.
    ///
    /// # Example
    /// ```
    /// use soak_graph::segment::gmm::GaussianMixture;
    /// let data: Vec<f64> = (0..200).map(|i| if i % 2 == 0 { 0.1 } else { 0.9 } + (i % 7) as f64 * 0.01).collect();
    /// let m = GaussianMixture::fit(&data, 2, 7, 1e-6, 100);
    /// assert_eq!(m.components.len(), 2);
    /// assert!((m.components[0].mean - 0.13).abs() < 0.02);
    /// ```
    pub fn fit(data: &[f64], k: usize, seed: u64, tolerance: f64, max_iterations: usize) -> Self {
        let sorted = Sorted::new(data);
        let mut distinct = sorted.xs.clone();
        distinct.dedup();
        let k = k.min(distinct.len());
        if k == 0 {
            return Self {
                components: Vec::new(),
                iterations: 0,
                converged: true,
                log_likelihood: 0.0,
            };
        }
        let mut rng = ChaCha8Rng::seed_from_u64(seed);
        let mut best: Option<(f64, Vec<f64>)> = None;
        for _ in 0..KMEANS_RESTARTS {
            let (centres, sse) = kmeans(&sorted, k, &mut rng);
            if best.as_ref().is_none_or(|(b, _)| sse < *b) {
                best = Some((sse, centres));
            }
        }
        let centres = best.map(|b| b.1).unwrap_or_default();
        let mut components = initial_components(&sorted, &centres);

        let n = data.len();
        let mut resp = vec![0.0; n * k];
        let mut log_likelihood = f64::NEG_INFINITY;
        let mut iterations = 0;
        let mut converged = false;
        while iterations < max_iterations {
            iterations += 1;
            // E step.
            let terms: Vec<LogTerms> = components.iter().map(LogTerms::new).collect();
            let mut ll = 0.0;
            for (i, &x) in data.iter().enumerate() {
                ll += posteriors_with(&terms, x, &mut resp[i * k..(i + 1) * k]);
            }
            // M step.
            for (j, c) in components.iter_mut().enumerate() {
                let (mut nj, mut sx) = (0.0, 0.0);
                for (i, &x) in data.iter().enumerate() {
                    let r = resp[i * k + j];
                    nj += r;
                    sx += r * x;
                }
                if nj <= 0.0 {
                    c.weight = 0.0;
                    continue;
                }
                let mean = sx / nj;
                let mut sv = 0.0;
                for (i, &x) in data.iter().enumerate() {
                    sv += resp[i * k + j] * (x - mean).powi(2);
                }
                c.mean = mean;
                c.std_dev = (sv / nj).sqrt().max(MIN_STD_DEV);
                c.weight = nj / n as f64;
            }
            let change = (ll - log_likelihood).abs();
            log_likelihood = ll;
            if change <= tolerance * ll.abs().max(1.0) {
                converged = true;
                break;
            }
        }
        components.sort_by(|a, b| a.mean.total_cmp(&b.mean).then(a.std_dev.total_cmp(&b.std_dev)));
        Self {
            components,
            iterations,
            converged,
            log_likelihood,
        }
    }

    /// Posterior probability `P(component j | x)` for every component.
    pub fn posteriors(&self, x: f64) -> Vec<f64> {
        let mut row = vec![0.0; self.components.len()];
        log_posteriors(&self.components, x, &mut row);
        row.iter_mut().for_each(|r| *r = r.exp());
        row
    }

    /// The most probable component of `x`.
    pub fn most_probable(&self, x: f64) -> usize {
        let p = self.posteriors(x);
        (0..p.len()).fold(0, |best, j| if p[j] > p[best] { j } else { best })
    }

    /// Unary costs `−ln max(P(j | x), 5·10⁻⁶)` of every datum and component,
    /// row-major (`cost[i·k + j]`, k = number of components).
    pub fn unary_costs(&self, data: &[f64]) -> Vec<f64> {
        let k = self.components.len();
        let terms: Vec<LogTerms> = self.components.iter().map(LogTerms::new).collect();
        let mut costs = vec![0.0; data.len() * k];
        for (i, &x) in data.iter().enumerate() {
            let row = &mut costs[i * k..(i + 1) * k];
            log_posteriors_with(&terms, x, row);
            for c in row.iter_mut() {
                *c = -(c.exp().max(PROBABILITY_FLOOR)).ln();
            }
        }
        costs
    }
}

/// Writes `ln P(j | x)` into `out` and returns `ln p(x)`.
fn log_posteriors(components: &[GaussianComponent], x: f64, out: &mut [f64]) -> f64 {
    let terms: Vec<LogTerms> = components.iter().map(LogTerms::new).collect();
    log_posteriors_with(&terms, x, out)
}

/// Per-component constants of the log density.
#[derive(Clone, Copy)]
struct LogTerms {
    mean: f64,
    inv_std: f64,
    offset: f64,
}

impl LogTerms {
    fn new(c: &GaussianComponent) -> Self {
        Self {
            mean: c.mean,
            inv_std: 1.0 / c.std_dev,
            offset: c.weight.ln() - c.std_dev.ln() - 0.5 * std::f64::consts::TAU.ln(),
        }
    }
}

/// Writes `P(j | x)` into `out` and returns `ln p(x)`.
fn posteriors_with(terms: &[LogTerms], x: f64, out: &mut [f64]) -> f64 {
    let mut max = f64::NEG_INFINITY;
    for (o, t) in out.iter_mut().zip(terms) {
        let z = (x - t.mean) * t.inv_std;
        *o = t.offset - 0.5 * z * z;
        max = max.max(*o);
    }
    if max == f64::NEG_INFINITY {
        let uniform = 1.0 / terms.len() as f64;
        out.iter_mut().for_each(|o| *o = uniform);
        return f64::NEG_INFINITY;
    }
    let mut sum = 0.0;
    for o in out.iter_mut() {
        *o = (*o - max).exp();
        sum += *o;
    }
    out.iter_mut().for_each(|o| *o /= sum);
    max + sum.ln()
}

fn log_posteriors_with(terms: &[LogTerms], x: f64, out: &mut [f64]) -> f64 {
    let mut max = f64::NEG_INFINITY;
    for (o, t) in out.iter_mut().zip(terms) {
        let z = (x - t.mean) * t.inv_std;
        *o = t.offset - 0.5 * z * z;
        max = max.max(*o);
    }
    if max == f64::NEG_INFINITY {
        let uniform = -(terms.len() as f64).ln();
        out.iter_mut().for_each(|o| *o = uniform);
        return f64::NEG_INFINITY;
    }
    let sum: f64 = out.iter().map(|o| (o - max).exp()).sum();
    let log_total = max + sum.ln();
    out.iter_mut().for_each(|o| *o -= log_total);
    log_total
}

/// The data sorted, with prefix sums of values and squares, so a 1-D
/// k-means cluster (a contiguous run) is summarised in O(1).
struct Sorted {
    xs: Vec<f64>,
    s1: Vec<f64>,
    s2: Vec<f64>,
}

impl Sorted {
    fn new(data: &[f64]) -> Self {
        let mut xs = data.to_vec();
        xs.sort_unstable_by(f64::total_cmp);
        let (mut s1, mut s2) = (vec![0.0], vec![0.0]);
        for &x in &xs {
            s1.push(s1.last().copied().unwrap_or(0.0) + x);
            s2.push(s2.last().copied().unwrap_or(0.0) + x * x);
        }
        Self { xs, s1, s2 }
    }

    /// Index ranges of the clusters of sorted `centres` (split at midpoints).
    fn runs(&self, centres: &[f64]) -> Vec<(usize, usize)> {
        let mut runs = Vec::with_capacity(centres.len());
        let mut start = 0;
        for j in 0..centres.len() {
            let end = if j + 1 < centres.len() {
                let mid = 0.5 * (centres[j] + centres[j + 1]);
                start + self.xs[start..].partition_point(|&x| x <= mid)
            } else {
                self.xs.len()
            };
            runs.push((start, end));
            start = end;
        }
        runs
    }

    /// Sum of squared distances of run `(a, b)` to `c`.
    fn sse(&self, (a, b): (usize, usize), c: f64) -> f64 {
        let m = (b - a) as f64;
        let s1 = self.s1[b] - self.s1[a];
        let s2 = self.s2[b] - self.s2[a];
        (s2 - 2.0 * c * s1 + m * c * c).max(0.0)
    }
}

/// One seeded k-means run: k-means++ seeding then Lloyd iterations (on
/// sorted data, where clusters are runs split at the centres' midpoints).
/// Returns the sorted centres and the sum of squared distances to them.
fn kmeans(data: &Sorted, k: usize, rng: &mut ChaCha8Rng) -> (Vec<f64>, f64) {
    let xs = &data.xs;
    let n = xs.len();
    let mut centres = vec![xs[rng.random_range(0..n)]];
    let mut d2: Vec<f64> = xs.iter().map(|&x| (x - centres[0]).powi(2)).collect();
    while centres.len() < k {
        let total: f64 = d2.iter().sum();
        if total <= 0.0 {
            break;
        }
        let target = rng.random::<f64>() * total;
        let mut acc = 0.0;
        let mut pick = n - 1;
        for (i, &d) in d2.iter().enumerate() {
            acc += d;
            if acc > target && d > 0.0 {
                pick = i;
                break;
            }
        }
        let c = xs[pick];
        centres.push(c);
        for (d, &x) in d2.iter_mut().zip(xs) {
            *d = d.min((x - c).powi(2));
        }
    }
    centres.sort_unstable_by(f64::total_cmp);
    for _ in 0..KMEANS_MAX_ITERATIONS {
        let runs = data.runs(&centres);
        let mut next = centres.clone();
        for (c, &(a, b)) in next.iter_mut().zip(&runs) {
            if b > a {
                *c = (data.s1[b] - data.s1[a]) / (b - a) as f64;
            }
        }
        next.sort_unstable_by(f64::total_cmp);
        if next == centres {
            break;
        }
        centres = next;
    }
    let sse = data
        .runs(&centres)
        .into_iter()
        .zip(&centres)
        .map(|(r, &c)| data.sse(r, c))
        .sum();
    (centres, sse)
}

/// Components from k-means clusters: their mean, spread and share of the data.
fn initial_components(data: &Sorted, centres: &[f64]) -> Vec<GaussianComponent> {
    let runs = data.runs(centres);
    // An empty cluster keeps a small share so EM can still use it.
    let total: f64 = runs.iter().map(|&(a, b)| ((b - a) as f64).max(0.5)).sum();
    runs.into_iter()
        .zip(centres)
        .map(|((a, b), &c)| {
            let m = b - a;
            let mean = if m > 0 {
                (data.s1[b] - data.s1[a]) / m as f64
            } else {
                c
            };
            let var = if m > 0 {
                data.sse((a, b), mean) / m as f64
            } else {
                0.0
            };
            GaussianComponent {
                mean,
                std_dev: var.sqrt().max(MIN_STD_DEV),
                weight: (m as f64).max(0.5) / total,
            }
        })
        .collect()
}
