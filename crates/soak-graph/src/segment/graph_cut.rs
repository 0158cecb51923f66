//! Hard labels from the soft clustering: alpha-expansion graph cuts over
//! face adjacency (Boykov, Veksler & Zabih, "Fast approximate energy
//! minimization via graph cuts", PAMI 2001), with CGAL's dihedral-angle
//! edge weights.
//!
//! The energy of a labelling `f` is
//!
//! ```text
//! E(f) = Σ_faces D_p(f_p) + Σ_edges w_pq · [f_p ≠ f_q]
//! ```
//!
//! with `D_p(l) = −ln max(P(l | p), 5·10⁻⁶)` from the Gaussian mixture and
//! `w_pq` from [`edge_weight`]. Each expansion move "every face may switch
//! to label α" is one minimum cut ([`MaxFlow`]); moves are applied in label
//! order while they lower the energy, and sweeps over all labels repeat
//! until a whole sweep changes nothing (at most [`MAX_SWEEPS`]).

use serde::Serialize;

use super::max_flow::{MaxFlow, MaxFlowSolver};

/// Angle terms are floored at this before the logarithm (CGAL's epsilon).
pub const ANGLE_FLOOR: f64 = 5e-6;

/// Convex edges are this much cheaper to keep uncut than concave ones of
/// the same angle (CGAL's `CGAL_CONVEX_FACTOR`).
pub const CONVEX_FACTOR: f64 = 0.08;

/// λ is multiplied by this (CGAL scales the recommended λ ∈ [0, 1] to [0, 100]).
pub const LAMBDA_SCALE: f64 = 100.0;

/// Upper bound on expansion sweeps over all labels.
pub const MAX_SWEEPS: usize = 32;

/// A move must lower the energy by more than this fraction of it to count.
pub const RELATIVE_IMPROVEMENT: f64 = 1e-10;

/// The cost of cutting the face-adjacency edge between two faces whose
/// normals make `normal_angle` degrees (0 where the surface is flat),
/// `concave` if the surface folds outwards there (a valley):
///
/// ```text
/// a = θ/180          (concave)      a = 0.08 · θ/180   (convex)
/// w = −ln max(a, 5·10⁻⁶) · λ · 100
/// ```
///
/// In terms of the signed dihedral deviation φ (φ = 180° − θ for concave
/// edges and φ = θ − 180° for convex ones) this is `a = 1 − φ/180` and
/// `a = 0.08 (1 + φ/180)`. Sharp valleys are cheap to cut, flat and convex
/// regions expensive; the edge length does not enter (as in CGAL).
///
/// # Example
/// ```
/// use soak_graph::segment::graph_cut::edge_weight;
/// // A flat edge costs −ln(5e-6)·26 ≈ 317; a 90° valley −ln(0.5)·26 ≈ 18.
/// assert!((edge_weight(0.0, true, 0.26) - 317.36).abs() < 0.01);
/// assert!((edge_weight(90.0, true, 0.26) - 18.02).abs() < 0.01);
/// ```
pub fn edge_weight(normal_angle: f64, concave: bool, lambda: f64) -> f64 {
    let mut a = normal_angle / 180.0;
    if !concave {
        a *= CONVEX_FACTOR;
    }
    -(a.max(ANGLE_FLOOR)).ln() * lambda * LAMBDA_SCALE
}

/// The outcome of [`alpha_expansion`].
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Labelling {
    /// Label of every face.
    pub labels: Vec<u32>,
    /// Final energy (dimensionless, natural-log units).
    pub energy: f64,
    /// Energy of the initial labelling.
    pub initial_energy: f64,
    /// Sweeps over all labels.
    pub sweeps: usize,
    /// Expansion moves that lowered the energy.
    pub moves: usize,
}

/// The energy of `labels` (see the module docs). `unary` is row-major,
/// `unary[p·k + l]`; `edges` pair face indices with weights.
pub fn energy(unary: &[f64], k: usize, edges: &[(u32, u32, f64)], labels: &[u32]) -> f64 {
    let data: f64 = labels
        .iter()
        .enumerate()
        .map(|(p, &l)| unary[p * k + l as usize])
        .sum();
    let smooth: f64 = edges
        .iter()
        .filter(|(p, q, _)| labels[*p as usize] != labels[*q as usize])
        .map(|e| e.2)
        .sum();
    data + smooth
}

/// Minimises the energy by alpha-expansion, starting from `initial`
/// (labels < k). `unary[p·k + l]` is the cost of label `l` at face `p`;
/// `edges` are `(p, q, weight)`, weights ≥ 0.
pub fn alpha_expansion(
    unary: &[f64],
    k: usize,
    edges: &[(u32, u32, f64)],
    initial: Vec<u32>,
    solver: MaxFlowSolver,
) -> Labelling {
    let mut labels = initial;
    let initial_energy = energy(unary, k, edges, &labels);
    let mut current = initial_energy;
    let (mut sweeps, mut moves) = (0, 0);
    if k < 2 {
        return Labelling {
            labels,
            energy: current,
            initial_energy,
            sweeps,
            moves,
        };
    }
    while sweeps < MAX_SWEEPS {
        sweeps += 1;
        let mut improved = false;
        for alpha in 0..k as u32 {
            let candidate = expand(unary, k, edges, &labels, alpha, solver);
            let e = energy(unary, k, edges, &candidate);
            if e < current - RELATIVE_IMPROVEMENT * current.abs() {
                labels = candidate;
                current = e;
                improved = true;
                moves += 1;
            }
        }
        if !improved {
            break;
        }
    }
    Labelling {
        labels,
        energy: current,
        initial_energy,
        sweeps,
        moves,
    }
}

/// One expansion move: the optimal labelling where every face keeps its
/// label or switches to `alpha`.
///
/// The graph is Boykov–Veksler–Zabih's: faces already labelled α are fixed
/// and left out; a free face `p` has t-links source → p of capacity D_p(α)
/// (paid if p switches) and p → sink of D_p(f_p) (paid if it keeps its
/// label). An edge to a fixed face adds its weight to the keep cost; an edge
/// between two free faces of the same label is an arc pair of its weight;
/// between different labels an auxiliary node joins both faces (weight
/// each way) and the sink (weight). Faces on the source side of the minimum
/// cut (reachable from the source in the residual graph) keep their label;
/// the rest take α.
fn expand(
    unary: &[f64],
    k: usize,
    edges: &[(u32, u32, f64)],
    labels: &[u32],
    alpha: u32,
    solver: MaxFlowSolver,
) -> Vec<u32> {
    let n = labels.len();
    let mut node = vec![u32::MAX; n];
    let mut g = MaxFlow::with_capacity(n + edges.len() / 4, edges.len() + edges.len() / 4);
    for p in 0..n {
        if labels[p] != alpha {
            let i = g.add_node();
            node[p] = i as u32;
            g.add_terminal_weights(
                i,
                unary[p * k + alpha as usize],
                unary[p * k + labels[p] as usize],
            );
        }
    }
    for &(p, q, w) in edges {
        if w <= 0.0 {
            continue;
        }
        let (p, q) = (p as usize, q as usize);
        let (lp, lq) = (labels[p], labels[q]);
        match (lp == alpha, lq == alpha) {
            (true, true) => {}
            (true, false) => g.add_terminal_weights(node[q] as usize, 0.0, w),
            (false, true) => g.add_terminal_weights(node[p] as usize, 0.0, w),
            (false, false) => {
                let (np, nq) = (node[p] as usize, node[q] as usize);
                if lp == lq {
                    g.add_edge(np, nq, w, w);
                } else {
                    let a = g.add_node();
                    g.add_edge(np, a, w, w);
                    g.add_edge(a, nq, w, w);
                    g.add_terminal_weights(a, 0.0, w);
                }
            }
        }
    }
    g.solve(solver);
    (0..n)
        .map(|p| {
            if labels[p] == alpha || !g.in_source_set(node[p] as usize) {
                alpha
            } else {
                labels[p]
            }
        })
        .collect()
}
