//! Minimum s–t cuts for the graph cut: Boykov–Kolmogorov max-flow, with
//! petgraph's Dinic as a reference solver.
//!
//! Why not petgraph alone: `petgraph::algo::dinics` (0.8.3) clears a
//! visited map and allocates a per-node array for *every* augmenting path
//! (O(V) per path), and an alpha-expansion graph has an augmenting path
//! through almost every face (`source → face → sink`), so one expansion
//! costs O(V²): seconds at 20k faces, times five labels and several sweeps.
//! It also tests residual capacities for exact zero, which floating-point
//! flows do not reliably reach, so it has to run on integers. Boykov and
//! Kolmogorov's algorithm ("An experimental comparison of min-cut/max-flow
//! algorithms for energy minimization in vision", PAMI 2004) reuses its
//! search trees between augmentations and is the solver CGAL uses; on these
//! graphs it is near-linear in practice. [`MaxFlowSolver::Dinics`] keeps
//! petgraph's solver selectable, for cross-checks.
//!
//! The implementation follows Kolmogorov's `maxflow` v3 (trees grown from
//! both terminals, orphan adoption with the timestamp/distance heuristic).
//! Capacities are `f64`; an augmentation subtracts the bottleneck from every
//! arc on the path, so the bottleneck arc becomes exactly zero and the
//! algorithm terminates.

use std::collections::VecDeque;

use petgraph::graph::{DiGraph, NodeIndex};
use petgraph::visit::EdgeRef;
use serde::{Deserialize, Serialize};

/// Which max-flow algorithm computes the cuts.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[non_exhaustive]
pub enum MaxFlowSolver {
    /// Boykov–Kolmogorov (this module): fast on graph-cut graphs.
    #[default]
    BoykovKolmogorov,
    /// `petgraph::algo::dinics` on capacities quantised to
    /// 1/[`DINICS_SCALE`]: a slow reference.
    Dinics,
}

/// Capacities are multiplied by this and rounded to integers for
/// [`MaxFlowSolver::Dinics`].
pub const DINICS_SCALE: f64 = 1048576.0;

const NONE: u32 = u32::MAX;
const TERMINAL: u32 = u32::MAX - 1;
const ORPHAN: u32 = u32::MAX - 2;
const INFINITE_DISTANCE: u32 = u32::MAX;

/// A flow network between a source and a sink, with non-negative
/// capacities, and its minimum cut.
///
/// Arcs are added in pairs (`add_edge(i, j, cap, rev_cap)`); terminal arcs
/// as per-node weights. After [`MaxFlow::solve`], [`MaxFlow::in_source_set`]
/// tells on which side of the minimum cut a node lies: the source side is
/// the set of nodes reachable from the source in the residual graph.
///
/// # Example
/// ```
/// use soak_graph::segment::max_flow::{MaxFlow, MaxFlowSolver};
/// let mut g = MaxFlow::new();
/// let (a, b) = (g.add_node(), g.add_node());
/// g.add_terminal_weights(a, 5.0, 1.0);
/// g.add_terminal_weights(b, 1.0, 5.0);
/// g.add_edge(a, b, 2.0, 0.0);
/// let flow = g.solve(MaxFlowSolver::BoykovKolmogorov);
/// assert_eq!(flow, 4.0);
/// assert!(g.in_source_set(a) && !g.in_source_set(b));
/// ```
#[derive(Clone, Debug, Default)]
pub struct MaxFlow {
    first: Vec<u32>,
    tr_cap: Vec<f64>,
    head: Vec<u32>,
    next: Vec<u32>,
    r_cap: Vec<f64>,
    flow: f64,
    // Solver state.
    parent: Vec<u32>,
    is_sink: Vec<bool>,
    ts: Vec<u32>,
    dist: Vec<u32>,
    active: Vec<bool>,
    queue: VecDeque<u32>,
    orphans: VecDeque<u32>,
    time: u32,
    source_side: Vec<bool>,
}

impl MaxFlow {
    /// An empty network.
    pub fn new() -> Self {
        Self::default()
    }

    /// An empty network with room for `nodes` nodes and `edges` arc pairs.
    pub fn with_capacity(nodes: usize, edges: usize) -> Self {
        Self {
            first: Vec::with_capacity(nodes),
            tr_cap: Vec::with_capacity(nodes),
            head: Vec::with_capacity(2 * edges),
            next: Vec::with_capacity(2 * edges),
            r_cap: Vec::with_capacity(2 * edges),
            ..Self::default()
        }
    }

    /// Adds a node and returns its index.
    pub fn add_node(&mut self) -> usize {
        self.first.push(NONE);
        self.tr_cap.push(0.0);
        self.first.len() - 1
    }

    /// Number of nodes.
    pub fn node_count(&self) -> usize {
        self.first.len()
    }

    /// Number of arc pairs.
    pub fn edge_count(&self) -> usize {
        self.head.len() / 2
    }

    /// Adds capacity `source` on the arc source → `i` and `sink` on `i` →
    /// sink (both ≥ 0). Their common part flows at once and is counted in
    /// the total.
    pub fn add_terminal_weights(&mut self, i: usize, source: f64, sink: f64) {
        let (mut source, mut sink) = (source, sink);
        let delta = self.tr_cap[i];
        if delta > 0.0 {
            source += delta;
        } else {
            sink -= delta;
        }
        self.flow += source.min(sink);
        self.tr_cap[i] = source - sink;
    }

    /// Adds an arc `i → j` of capacity `cap` and `j → i` of `rev_cap` (≥ 0).
    pub fn add_edge(&mut self, i: usize, j: usize, cap: f64, rev_cap: f64) {
        let a = self.head.len() as u32;
        self.head.push(j as u32);
        self.next.push(self.first[i]);
        self.r_cap.push(cap);
        self.first[i] = a;
        self.head.push(i as u32);
        self.next.push(self.first[j]);
        self.r_cap.push(rev_cap);
        self.first[j] = a + 1;
    }

    /// Whether node `i` is on the source side of the minimum cut (reachable
    /// from the source in the residual graph). False before [`MaxFlow::solve`].
    pub fn in_source_set(&self, i: usize) -> bool {
        self.source_side.get(i).copied().unwrap_or(false)
    }

    /// Computes the maximum flow (= minimum cut capacity) and the cut.
    /// Call once per network.
    pub fn solve(&mut self, solver: MaxFlowSolver) -> f64 {
        match solver {
            MaxFlowSolver::BoykovKolmogorov => self.solve_bk(),
            MaxFlowSolver::Dinics => self.solve_dinics(),
        }
    }

    fn solve_dinics(&mut self) -> f64 {
        let n = self.node_count();
        let q = |x: f64| (x * DINICS_SCALE).round() as u64;
        let mut g = DiGraph::<(), u64>::with_capacity(n + 2, n + self.head.len());
        for _ in 0..n + 2 {
            g.add_node(());
        }
        let (s, t) = (NodeIndex::new(n), NodeIndex::new(n + 1));
        for (i, &c) in self.tr_cap.iter().enumerate() {
            if c > 0.0 {
                g.add_edge(s, NodeIndex::new(i), q(c));
            } else if c < 0.0 {
                g.add_edge(NodeIndex::new(i), t, q(-c));
            }
        }
        for a in (0..self.head.len()).step_by(2) {
            let (i, j) = (self.head[a + 1] as usize, self.head[a] as usize);
            if self.r_cap[a] > 0.0 {
                g.add_edge(NodeIndex::new(i), NodeIndex::new(j), q(self.r_cap[a]));
            }
            if self.r_cap[a + 1] > 0.0 {
                g.add_edge(NodeIndex::new(j), NodeIndex::new(i), q(self.r_cap[a + 1]));
            }
        }
        let (flow, flows) = petgraph::algo::dinics(&g, s, t);
        // Residual reachability from the source.
        let mut seen = vec![false; n + 2];
        seen[s.index()] = true;
        let mut stack = vec![s];
        while let Some(v) = stack.pop() {
            for e in g.edges_directed(v, petgraph::Direction::Outgoing) {
                let w = e.target();
                if !seen[w.index()] && flows[e.id().index()] < *e.weight() {
                    seen[w.index()] = true;
                    stack.push(w);
                }
            }
            for e in g.edges_directed(v, petgraph::Direction::Incoming) {
                let w = e.source();
                if !seen[w.index()] && flows[e.id().index()] > 0 {
                    seen[w.index()] = true;
                    stack.push(w);
                }
            }
        }
        seen.truncate(n);
        self.source_side = seen;
        self.flow + flow as f64 / DINICS_SCALE
    }

    fn set_active(&mut self, i: usize) {
        if !self.active[i] {
            self.active[i] = true;
            self.queue.push_back(i as u32);
        }
    }

    fn next_active(&mut self) -> Option<usize> {
        while let Some(i) = self.queue.pop_front() {
            let i = i as usize;
            self.active[i] = false;
            if self.parent[i] != NONE {
                return Some(i);
            }
        }
        None
    }

    fn solve_bk(&mut self) -> f64 {
        let n = self.node_count();
        self.parent = vec![NONE; n];
        self.is_sink = vec![false; n];
        self.ts = vec![0; n];
        self.dist = vec![0; n];
        self.active = vec![false; n];
        self.queue.clear();
        self.orphans.clear();
        self.time = 0;
        for i in 0..n {
            if self.tr_cap[i] != 0.0 {
                self.is_sink[i] = self.tr_cap[i] < 0.0;
                self.parent[i] = TERMINAL;
                self.dist[i] = 1;
                self.set_active(i);
            }
        }

        let mut current: Option<usize> = None;
        loop {
            let mut node = None;
            if let Some(c) = current.take() {
                self.active[c] = false;
                if self.parent[c] != NONE {
                    node = Some(c);
                }
            }
            let i = match node.or_else(|| self.next_active()) {
                Some(i) => i,
                None => break,
            };
            let meet = self.grow(i);
            self.time = self.time.wrapping_add(1);
            if meet != NONE {
                // Keep `i` as the node to grow next; it is marked active so
                // it is not queued twice.
                self.active[i] = true;
                current = Some(i);
                self.augment(meet as usize);
                while let Some(o) = self.orphans.pop_front() {
                    let o = o as usize;
                    if self.is_sink[o] {
                        self.adopt_sink_orphan(o);
                    } else {
                        self.adopt_source_orphan(o);
                    }
                }
            }
        }
        self.source_side = (0..n)
            .map(|i| self.parent[i] != NONE && !self.is_sink[i])
            .collect();
        self.flow
    }

    /// Grows the tree of `i` by one layer; returns an arc from the source
    /// tree to the sink tree if the trees meet, else `NONE`.
    fn grow(&mut self, i: usize) -> u32 {
        let sink_tree = self.is_sink[i];
        let mut a = self.first[i];
        while a != NONE {
            let au = a as usize;
            // Residual capacity in the direction the tree grows.
            let open = if sink_tree {
                self.r_cap[au ^ 1] > 0.0
            } else {
                self.r_cap[au] > 0.0
            };
            if open {
                let j = self.head[au] as usize;
                if self.parent[j] == NONE {
                    self.is_sink[j] = sink_tree;
                    self.parent[j] = a ^ 1;
                    self.ts[j] = self.ts[i];
                    self.dist[j] = self.dist[i] + 1;
                    self.set_active(j);
                } else if self.is_sink[j] != sink_tree {
                    return if sink_tree { a ^ 1 } else { a };
                } else if self.ts[j] <= self.ts[i] && self.dist[j] > self.dist[i] {
                    self.parent[j] = a ^ 1;
                    self.ts[j] = self.ts[i];
                    self.dist[j] = self.dist[i] + 1;
                }
            }
            a = self.next[au];
        }
        NONE
    }

    /// Pushes the bottleneck flow along source → tail(mid) → head(mid) → sink.
    fn augment(&mut self, mid: usize) {
        // Bottleneck.
        let mut b = self.r_cap[mid];
        let mut i = self.head[mid ^ 1] as usize;
        loop {
            let a = self.parent[i];
            if a == TERMINAL {
                break;
            }
            b = b.min(self.r_cap[a as usize ^ 1]);
            i = self.head[a as usize] as usize;
        }
        b = b.min(self.tr_cap[i]);
        let mut i = self.head[mid] as usize;
        loop {
            let a = self.parent[i];
            if a == TERMINAL {
                break;
            }
            b = b.min(self.r_cap[a as usize]);
            i = self.head[a as usize] as usize;
        }
        b = b.min(-self.tr_cap[i]);

        // Augment.
        self.r_cap[mid ^ 1] += b;
        self.r_cap[mid] -= b;
        let mut i = self.head[mid ^ 1] as usize;
        loop {
            let a = self.parent[i];
            if a == TERMINAL {
                break;
            }
            let a = a as usize;
            self.r_cap[a] += b;
            self.r_cap[a ^ 1] -= b;
            if self.r_cap[a ^ 1] == 0.0 {
                self.set_orphan_front(i);
            }
            i = self.head[a] as usize;
        }
        self.tr_cap[i] -= b;
        if self.tr_cap[i] == 0.0 {
            self.set_orphan_front(i);
        }
        let mut i = self.head[mid] as usize;
        loop {
            let a = self.parent[i];
            if a == TERMINAL {
                break;
            }
            let a = a as usize;
            self.r_cap[a ^ 1] += b;
            self.r_cap[a] -= b;
            if self.r_cap[a] == 0.0 {
                self.set_orphan_front(i);
            }
            i = self.head[a] as usize;
        }
        self.tr_cap[i] += b;
        if self.tr_cap[i] == 0.0 {
            self.set_orphan_front(i);
        }
        self.flow += b;
    }

    fn set_orphan_front(&mut self, i: usize) {
        self.parent[i] = ORPHAN;
        self.orphans.push_front(i as u32);
    }

    fn set_orphan_rear(&mut self, i: usize) {
        self.parent[i] = ORPHAN;
        self.orphans.push_back(i as u32);
    }

    /// Distance of `j` to its terminal through parent arcs, or
    /// `INFINITE_DISTANCE` if the path reaches an orphan; marks the path.
    fn origin_distance(&mut self, start: usize) -> u32 {
        let mut j = start;
        let mut d = 0u32;
        loop {
            if self.ts[j] == self.time {
                d += self.dist[j];
                break;
            }
            let a = self.parent[j];
            d += 1;
            if a == TERMINAL {
                self.ts[j] = self.time;
                self.dist[j] = 1;
                break;
            }
            if a == ORPHAN {
                return INFINITE_DISTANCE;
            }
            j = self.head[a as usize] as usize;
        }
        // Mark the path with timestamps and distances.
        let (mut j, mut dd) = (start, d);
        while self.ts[j] != self.time {
            self.ts[j] = self.time;
            self.dist[j] = dd;
            dd -= 1;
            j = self.head[self.parent[j] as usize] as usize;
        }
        d
    }

    fn adopt_source_orphan(&mut self, i: usize) {
        self.adopt(i, false);
    }

    fn adopt_sink_orphan(&mut self, i: usize) {
        self.adopt(i, true);
    }

    /// Finds a new parent for orphan `i` in its tree, or frees it.
    fn adopt(&mut self, i: usize, sink_tree: bool) {
        // Residual capacity from the tree towards `i` along arc pair a0.
        let towards_i = |s: &Self, a0: usize| {
            if sink_tree {
                s.r_cap[a0] > 0.0
            } else {
                s.r_cap[a0 ^ 1] > 0.0
            }
        };
        let (mut best, mut d_min) = (NONE, INFINITE_DISTANCE);
        let mut a0 = self.first[i];
        while a0 != NONE {
            let a0u = a0 as usize;
            if towards_i(self, a0u) {
                let j = self.head[a0u] as usize;
                if self.is_sink[j] == sink_tree && self.parent[j] != NONE {
                    let d = self.origin_distance(j);
                    if d < d_min {
                        best = a0;
                        d_min = d;
                    }
                }
            }
            a0 = self.next[a0u];
        }
        if best != NONE {
            self.parent[i] = best;
            self.ts[i] = self.time;
            self.dist[i] = d_min + 1;
            return;
        }
        self.parent[i] = NONE;
        let mut a0 = self.first[i];
        while a0 != NONE {
            let a0u = a0 as usize;
            let j = self.head[a0u] as usize;
            let a = self.parent[j];
            if self.is_sink[j] == sink_tree && a != NONE {
                if towards_i(self, a0u) {
                    self.set_active(j);
                }
                if a != TERMINAL && a != ORPHAN && self.head[a as usize] as usize == i {
                    self.set_orphan_rear(j);
                }
            }
            a0 = self.next[a0u];
        }
    }
}
