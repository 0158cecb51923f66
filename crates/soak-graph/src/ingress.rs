//! Liquid through the wall: the simplified Darcy law (thesis §4.1.2), both
//! ways.
//!
//! A permeable texel `i` at world position `p_i`, depth `d_i` below the
//! outside surface, opens onto its node `n` (see [`crate::TexelNodes`]),
//! whose free surface is at `h_n`. The pressure across the wall, in metres
//! of liquid, is `max(d_i, 0) − max(h_n − p_i.y, 0)`: the outside column
//! over the texel minus the inside one. In one step of `Δt` it passes
//!
//! ```text
//! V_i = (κ_i a_i / μ) ρ g [max(d_i, 0) − max(h_n − p_i.y, 0)] Δt      (m³)
//! ```
//!
//! inwards when positive (the thesis' ingress, which has an empty inside),
//! outwards when negative (beyond the thesis: a holed hull lifted out of the
//! water drains). Per node the texels' volumes are summed, then capped:
//!
//! - outflow by the liquid the node holds and by the volume that lowers its
//!   head to the lowest level where any of its texels still drains;
//! - inflow by the node's free capacity and by the volume that raises its
//!   head to the highest outside surface over its wet texels (so explicit
//!   steps never overshoot the level outside);
//! - inflow a full node cannot take is pushed on, as the sea would push
//!   it, through the discharge search ([`crate::discharge`]) with the
//!   outside surface as the source head: it reaches nodes whose bottoms are
//!   below the sea, each at most once per step, Poiseuille-limited along the
//!   path, capped by their room and by the volume that raises them to the
//!   sea. What still finds no room does not enter.
//!
//! An opening texel (a hole, an open rim's cap; see [`Permeability`]'s
//! *Openings*) passes the orifice flow `C_d a √(2 g |Δh|) Δt` instead, with
//! the same sign and the same caps.
//!
//! An unbounded fluid (no free surface, infinite depth) has no hydrostatic
//! head: the wall passes nothing.

use nalgebra::Isometry3;
use rand_chacha::ChaCha8Rng;
use soak_bake::Atlas;
use soak_hydro::Water;

use crate::discharge::{Levels, Searcher, poiseuille};
use crate::error::FlowError;
use crate::liquid_graph::LiquidGraph;
use crate::permeability::Permeability;
use crate::texel_nodes::TexelNodes;

/// Per-node sums of one step's wall exchange.
#[derive(Clone, Debug, Default)]
pub(crate) struct Exchange {
    /// Requested inflow per node, m³.
    inflow: Vec<f64>,
    /// Requested outflow per node, m³.
    outflow: Vec<f64>,
    /// Highest outside surface over each node's inflowing texels, m.
    sea: Vec<f64>,
    /// Lowest level each node's outflowing texels drain to, m.
    floor: Vec<f64>,
}

/// What the wall passed in one step, m³.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub(crate) struct WallFlow {
    pub entered: f64,
    pub left: f64,
    pub routed: f64,
}

/// Everything the exchange reads.
pub(crate) struct Wall<'a> {
    pub atlas: &'a Atlas,
    pub permeability: &'a Permeability,
    pub texel_nodes: &'a TexelNodes,
}

impl Exchange {
    /// Sums each permeable texel's Darcy volume into its node. Reads only:
    /// on error nothing has changed.
    #[allow(clippy::too_many_arguments)]
    pub(crate) fn gather(
        &mut self,
        wall: &Wall<'_>,
        heads: &[f64],
        pose: &Isometry3<f64>,
        water: &Water,
        t: f64,
        dt: f64,
        viscosity: f64,
        discharge: f64,
    ) -> Result<(), FlowError> {
        let n = heads.len();
        self.inflow.clear();
        self.inflow.resize(n, 0.0);
        self.outflow.clear();
        self.outflow.resize(n, 0.0);
        self.sea.clear();
        self.sea.resize(n, f64::NEG_INFINITY);
        self.floor.clear();
        self.floor.resize(n, f64::INFINITY);
        let k = water.density * water.gravity / viscosity * dt;
        let values = wall.permeability.values();
        let areas = wall.atlas.areas();
        let orifice = discharge * (2.0 * water.gravity).sqrt() * dt;
        let darcy = wall.permeability.permeable().iter().map(|&i| (i, false));
        let open = wall.permeability.openings().iter().map(|&i| (i, true));
        for (i, opening) in darcy.chain(open) {
            let i = i as usize;
            let node = wall.texel_nodes.node(i);
            let p = pose * wall.atlas.position(i);
            let d = water.surface.depth(&p, t);
            if d == f64::INFINITY {
                continue;
            }
            if d.is_nan() {
                return Err(FlowError::Depth {
                    texel: i,
                    position: [p.x, p.y, p.z],
                    depth: d,
                });
            }
            let inside = (heads[node] - p.y).max(0.0);
            let drive = d.max(0.0) - inside;
            let v = if opening {
                areas[i] as f64 * orifice * drive.abs().sqrt() * drive.signum()
            } else {
                values[i] * areas[i] as f64 * k * drive
            };
            if v > 0.0 {
                self.inflow[node] += v;
                self.sea[node] = self.sea[node].max(p.y + d);
            } else if v < 0.0 {
                self.outflow[node] -= v;
                self.floor[node] = self.floor[node].min((p.y + d).max(p.y));
            }
        }
        Ok(())
    }

    /// Applies the gathered volumes with their caps (module docs), updating
    /// `heads` as nodes fill and drain.
    #[allow(clippy::too_many_arguments)]
    pub(crate) fn apply(
        &self,
        graph: &mut LiquidGraph,
        y: &[f64],
        heads: &mut [f64],
        searcher: &mut Searcher,
        density: f64,
        gravity: f64,
        dt: f64,
        viscosity: f64,
        tolerance: f64,
        rng: &mut ChaCha8Rng,
    ) -> WallFlow {
        let mut flow = WallFlow::default();
        for n in 0..graph.node_count() {
            let net = self.inflow[n] - self.outflow[n];
            if net < 0.0 {
                let node = graph.node_mut(n);
                let room = node.section() * (heads[n] - self.floor[n]).max(0.0);
                let out = (-net).min(node.liquid).min(room);
                if out > 0.0 {
                    let before = node.liquid;
                    node.liquid = (before - out).max(0.0);
                    flow.left += before - node.liquid;
                    heads[n] = node.head_at(y[n]);
                }
            } else if net > 0.0 {
                let sea = self.sea[n];
                let node = graph.node_mut(n);
                let room = node.section() * (sea - heads[n]).max(0.0);
                let q = net.min(node.free()).min(room);
                let mut taken = 0.0;
                if q > 0.0 {
                    let before = node.liquid;
                    node.liquid = (before + q).min(node.capacity);
                    taken = node.liquid - before;
                    heads[n] = node.head_at(y[n]);
                }
                flow.entered += taken;
                let rest = net - taken;
                if rest > 0.0 && graph.raw_node(n).is_full() {
                    let routed = route(
                        graph, y, heads, searcher, n, sea, rest, density, gravity, dt, viscosity, tolerance,
                        rng,
                    );
                    flow.entered += routed;
                    flow.routed += routed;
                }
            }
        }
        flow
    }
}

/// Pushes up to `volume` m³ that entered at full node `entry` on to nodes
/// the outside surface at height `sea` can fill; returns what found room.
#[allow(clippy::too_many_arguments)]
fn route(
    graph: &mut LiquidGraph,
    y: &[f64],
    heads: &mut [f64],
    searcher: &mut Searcher,
    entry: usize,
    sea: f64,
    volume: f64,
    density: f64,
    gravity: f64,
    dt: f64,
    viscosity: f64,
    tolerance: f64,
    rng: &mut ChaCha8Rng,
) -> f64 {
    let n = graph.node_count();
    searcher.reset(n);
    let mut rest = volume;
    let mut placed = 0.0;
    for _ in 0..n {
        let levels = Levels { y, heads };
        let Some(d) = searcher.find(graph, &levels, entry, sea, viscosity, tolerance, rng) else {
            break;
        };
        searcher.excluded[d.node] = true;
        let target = graph.raw_node(d.node);
        let dh = sea - heads[d.node];
        let q = rest
            .min(poiseuille(dh, d.resistance, density, gravity, dt))
            .min(target.section() * dh)
            .min(target.free());
        // The entry node is full: move the liquid in through it.
        let before = graph.raw_node(d.node).liquid;
        let target = graph.node_mut(d.node);
        target.liquid = (before + q.max(0.0)).min(target.capacity);
        let moved = target.liquid - before;
        heads[d.node] = target.head_at(y[d.node]);
        placed += moved;
        rest -= moved;
        if rest <= 0.0 {
            break;
        }
    }
    searcher.reset(n);
    placed
}
