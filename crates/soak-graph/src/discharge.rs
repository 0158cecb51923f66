//! The discharge search (thesis Algorithm 1, *buscarNodoDeDescarga*) and
//! the Poiseuille transfer along the path it finds.
//!
//! The transfer over the path is Poiseuille's `Q = π Δp r⁴ / (8 μ L)` with
//! `Δp = ρ g Δh` and the pipes' resistances `8 μ L / (π r⁴ p)` added in
//! series, for the step `Δt`; it is capped by what the source holds, what
//! the target can take, and the volume that levels the two heads (so no step
//! overshoots: liquid never sloshes back and forth).

use nalgebra::Isometry3;
use petgraph::graph::EdgeIndex;
use rand::SeedableRng;
use rand::seq::SliceRandom;
use rand_chacha::ChaCha8Rng;

use crate::flow_options::FlowOptions;
use crate::liquid_graph::LiquidGraph;

/// A node that can receive and the series resistance of the path to it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Discharge {
    /// The receiving node.
    pub node: usize,
    /// Σ 8 μ L / (π r⁴ p) over the path's pipes, Pa·s/m³.
    pub resistance: f64,
}

#[derive(Clone, Copy, Debug)]
struct Frame {
    start: usize,
    end: usize,
    next: usize,
    resistance: f64,
}

/// Reusable buffers of the search.
#[derive(Clone, Debug, Default)]
pub(crate) struct Searcher {
    visited: Vec<bool>,
    /// Nodes that may not receive (already served this round); they still pass the search on.
    pub(crate) excluded: Vec<bool>,
    stack: Vec<Frame>,
    pool: Vec<(EdgeIndex, usize)>,
    incident: Vec<(EdgeIndex, usize)>,
}

/// World heights and heads the search reads, per node (m).
pub(crate) struct Levels<'a> {
    /// World height of each node's position, m.
    pub y: &'a [f64],
    /// Free-surface height of each node, m.
    pub heads: &'a [f64],
}

impl Searcher {
    pub(crate) fn reset(&mut self, n: usize) {
        self.visited.clear();
        self.visited.resize(n, false);
        self.excluded.clear();
        self.excluded.resize(n, false);
    }

    fn push(&mut self, graph: &LiquidGraph, node: usize, resistance: f64, rng: &mut ChaCha8Rng) {
        graph.incident(node, &mut self.incident);
        self.incident.shuffle(rng);
        let start = self.pool.len();
        self.pool.extend_from_slice(&self.incident);
        self.stack.push(Frame {
            start,
            end: self.pool.len(),
            next: start,
            resistance,
        });
    }

    /// Algorithm 1 from `source` for liquid whose free surface is at world
    /// height `head` (m); see [`find_discharge`]. Iterative, so deep graphs
    /// cannot overflow the call stack.
    #[allow(clippy::too_many_arguments)]
    pub(crate) fn find(
        &mut self,
        graph: &LiquidGraph,
        levels: &Levels<'_>,
        source: usize,
        head: f64,
        viscosity: f64,
        tolerance: f64,
        rng: &mut ChaCha8Rng,
    ) -> Option<Discharge> {
        let n = graph.node_count();
        self.visited.clear();
        self.visited.resize(n, false);
        self.excluded.resize(n, false);
        self.stack.clear();
        self.pool.clear();
        self.visited[source] = true;
        self.push(graph, source, 0.0, rng);
        while let Some(frame) = self.stack.last_mut() {
            if frame.next == frame.end {
                let start = frame.start;
                self.stack.pop();
                self.pool.truncate(start);
                continue;
            }
            let (edge, next) = self.pool[frame.next];
            frame.next += 1;
            let base = frame.resistance;
            if self.visited[next] {
                continue;
            }
            let pipe = graph.pipe(edge);
            if !pipe.is_open() {
                continue;
            }
            self.visited[next] = true;
            let node = graph.raw_node(next);
            // Energy barrier: the liquid cannot rise into this vessel.
            if node.bottom_at(levels.y[next]) > head + tolerance {
                continue;
            }
            let resistance = base + pipe.resistance(viscosity);
            if !self.excluded[next] && !node.is_full() && levels.heads[next] < head - tolerance {
                return Some(Discharge {
                    node: next,
                    resistance,
                });
            }
            self.push(graph, next, resistance, rng);
        }
        None
    }
}

/// Algorithm 1 on its own: the node that `source` would discharge into with
/// the body at `pose` (object → world), searching neighbours in the order a
/// ChaCha8 generator seeded with `seed` shuffles them; `None` when no node
/// can receive (or `source` does not exist).
///
/// # The search
///
/// From a source node (or, inside a [`Flooding`](crate::Flooding), from
/// the sea pushing in through a full node) with free surface at world
/// height `h_s`, a depth-first search walks the open pipes in a seeded
/// random order and returns the first node that can receive liquid:
///
/// - a node already visited is skipped (each node is visited once);
/// - a node whose vessel **bottom** is above `h_s` (+ tolerance) is an
///   **energy barrier**: the liquid cannot climb into it, and the search does
///   not pass through it. Heights are world heights, so the answer changes as
///   the body turns. With zero-height vessels this is the thesis' test
///   `nivel > 0` on node positions;
/// - a node that is not full and whose head is below `h_s` (− tolerance)
///   receives;
/// - any other node (full, or with a higher head) passes the search on:
///   liquid is indistinguishable, so the source discharges straight to the
///   node beyond (thesis Fig. 4.5: A gives to C through a full B).
///
/// # Example
/// ```
/// let path = concat!(env!("CARGO_MANIFEST_DIR"), "/../../data/graphs/fig4_5_cascade.toml");
/// let graph = soak_graph::load_graph(path)?;
/// let options = soak_graph::FlowOptions::default();
/// let found = soak_graph::find_discharge(&graph, &nalgebra::Isometry3::identity(), 0, &options, 7);
/// // A gives straight to C, through the full B.
/// assert_eq!(found.map(|d| d.node), graph.find("C"));
/// # Ok::<(), soak_graph::GraphFileError>(())
/// ```
pub fn find_discharge(
    graph: &LiquidGraph,
    pose: &Isometry3<f64>,
    source: usize,
    options: &FlowOptions,
    seed: u64,
) -> Option<Discharge> {
    let node = graph.node(source)?;
    let y = graph.world_heights(pose);
    let heads = graph.heads(pose);
    let head = node.head_at(y[source]);
    let mut searcher = Searcher::default();
    searcher.reset(graph.node_count());
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let levels = Levels { y: &y, heads: &heads };
    searcher.find(
        graph,
        &levels,
        source,
        head,
        options.viscosity,
        options.tolerance,
        &mut rng,
    )
}

/// Volume (m³) that flows in `dt` (s) down a head difference `dh` (m)
/// through a path of `resistance` (Pa·s/m³) for a liquid of `density`
/// (kg/m³) under `gravity` (m/s²): `ρ g Δh Δt / R` (infinite for R = 0).
#[inline]
pub(crate) fn poiseuille(dh: f64, resistance: f64, density: f64, gravity: f64, dt: f64) -> f64 {
    let q = density * gravity * dh * dt;
    if resistance > 0.0 {
        q / resistance
    } else {
        f64::INFINITY
    }
}

/// Moves `q` m³ from node `s` to node `d`, keeping both within
/// `[0, capacity]`; returns the volume moved.
pub(crate) fn move_liquid(graph: &mut LiquidGraph, s: usize, d: usize, q: f64) -> f64 {
    if q.is_nan() || q <= 0.0 {
        return 0.0;
    }
    let target = graph.node_mut(d);
    let before = target.liquid;
    target.liquid = (before + q).min(target.capacity);
    let moved = target.liquid - before;
    let source = graph.node_mut(s);
    source.liquid = (source.liquid - moved).max(0.0);
    moved
}
