//! Water inside an object, step by step: the liquid graph, its wall, and a
//! ledger that proves nothing is created or lost.

use nalgebra::Isometry3;
use rand::SeedableRng;
use rand::seq::SliceRandom;
use rand_chacha::ChaCha8Rng;
use serde::{Deserialize, Serialize};
use soak_bake::Atlas;
use soak_hydro::{MassProperties, Water};

use crate::discharge::{Levels, Searcher, move_liquid, poiseuille};
use crate::error::{FlowError, GraphError, TexelMapError};
use crate::flow_options::FlowOptions;
use crate::ingress::{Exchange, Wall};
use crate::ledger::Ledger;
use crate::liquid_graph::LiquidGraph;
use crate::permeability::Permeability;
use crate::texel_nodes::TexelNodes;

/// What one step did, m³.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize)]
pub struct StepReport {
    /// Liquid that came in through the wall.
    pub entered: f64,
    /// Liquid that went out through the wall.
    pub left: f64,
    /// Of `entered`, what a full node pushed on to other nodes.
    pub routed: f64,
    /// Liquid moved between nodes.
    pub moved: f64,
    /// Number of node-to-node transfers.
    pub transfers: usize,
    /// Liquid inside after the step.
    pub inside: f64,
}

impl StepReport {
    /// Whether the step changed the liquid anywhere.
    pub fn changed(&self) -> bool {
        self.entered > 0.0 || self.left > 0.0 || self.moved > 0.0
    }
}

#[derive(Clone, Debug)]
struct WallState {
    permeability: Permeability,
    texel_nodes: TexelNodes,
}

/// A liquid graph in motion inside a body, with its permeable wall.
///
/// Each [`Flooding::step`]:
/// 1. takes the world height of every node from the body's pose, and their
///    heads (see the vessels of [`Node`](crate::Node));
/// 2. exchanges liquid through the permeable texels of the wall (Darcy in
///    and out, see [`Permeability`], capped by capacity; what a full node
///    cannot take is pushed on to the nodes the sea can fill);
/// 3. redistributes it inside (for every node with liquid, in a seeded
///    random order, Algorithm 1 finds a discharge node, see
///    [`find_discharge`](crate::find_discharge), and Poiseuille's law sets
///    the volume), `passes` times with `Δt/passes`.
///
/// The [`Ledger`] accumulates what entered and what left (compensated sums,
/// f64); at every step `inside = initial + entered − left` to rounding,
/// whatever the caps did, and no node ever holds less than 0 or more than
/// its capacity.
///
/// The same seed, graph, atlas and inputs give bit-identical runs.
///
/// # Example
/// ```
/// use nalgebra::{Isometry3, Point3};
/// use soak_bake::{Atlas, BakeOptions, builtin};
/// use soak_graph::{Flooding, FlowOptions, LiquidGraph, Node, Permeability};
/// use soak_hydro::Water;
///
/// let atlas = Atlas::bake(&builtin::cuboid(1.0, 1.0, 1.0), BakeOptions::square(64))?;
/// let graph = LiquidGraph::new(vec![Node::new("inside", Point3::origin(), 1.0)], vec![])?;
/// let mut permeability = Permeability::watertight(&atlas);
/// // A hole 0.2 m across in the bottom face.
/// permeability.paint(&atlas, Point3::new(0.0, -0.5, 0.0), 0.1, 1e-6)?;
/// let mut flooding = Flooding::for_atlas(&atlas, graph, permeability, FlowOptions::default())?;
/// let water = Water::calm(0.0);
/// let pose = Isometry3::identity(); // half under water
/// for step in 0..900 {
///     flooding.step(&atlas, &pose, &water, step as f64 / 30.0, 1.0 / 30.0)?;
/// }
/// // It fills up to the waterline: half its volume.
/// assert!((flooding.inside() - 0.5).abs() < 0.01);
/// assert!(flooding.ledger().relative_error(flooding.inside()) < 1e-12);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
#[derive(Clone, Debug)]
pub struct Flooding {
    graph: LiquidGraph,
    wall: Option<WallState>,
    options: FlowOptions,
    rng: ChaCha8Rng,
    ledger: Ledger,
    y: Vec<f64>,
    heads: Vec<f64>,
    exchange: Exchange,
    searcher: Searcher,
    order: Vec<usize>,
}

/// The evolving state of a [`Flooding`]: the liquid in every node, the
/// wall's permeability (holes punched at run time), the ledger and the
/// random stream of the discharge search — everything a saved simulation
/// needs to resume bit for bit.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct FloodingState {
    /// Liquid per node, m³.
    pub liquid: Vec<f64>,
    /// The wall's permeability channel, if the graph has a wall.
    pub permeability: Option<Permeability>,
    /// Ledger: initial, entered (sum, carry), left (sum, carry), m³.
    pub ledger: [f64; 5],
    /// The random stream of the neighbour order.
    pub rng: ChaCha8Rng,
}

impl Flooding {
    /// The evolving state, for saving.
    pub fn state(&self) -> FloodingState {
        FloodingState {
            liquid: self.graph.liquids(),
            permeability: self.wall.as_ref().map(|w| w.permeability.clone()),
            ledger: self.ledger.to_parts(),
            rng: self.rng.clone(),
        }
    }

    /// Restores a state saved from a flooding of the same graph and wall.
    ///
    /// # Errors
    /// A state for another graph (node count) or another atlas (texels).
    pub fn restore(&mut self, state: &FloodingState) -> Result<(), FlowError> {
        if state.liquid.len() != self.graph.node_count() {
            return Err(FlowError::State(format!(
                "state has {} nodes, the graph {}",
                state.liquid.len(),
                self.graph.node_count()
            )));
        }
        match (&mut self.wall, &state.permeability) {
            (Some(w), Some(p)) if p.len() == w.permeability.len() => w.permeability = p.clone(),
            (None, None) => {}
            _ => {
                return Err(FlowError::State(
                    "state's wall does not match the flooding's".into(),
                ));
            }
        }
        for (i, &l) in state.liquid.iter().enumerate() {
            self.graph.set_liquid(i, l).map_err(FlowError::Graph)?;
        }
        self.ledger = Ledger::from_parts(state.ledger);
        self.rng = state.rng.clone();
        Ok(())
    }

    /// A graph with a watertight wall: its liquid only moves inside.
    ///
    /// # Errors
    /// Options out of range.
    pub fn sealed(graph: LiquidGraph, options: FlowOptions) -> Result<Self, FlowError> {
        options.check()?;
        let n = graph.node_count();
        Ok(Self {
            ledger: Ledger::new(graph.total_liquid()),
            graph,
            wall: None,
            rng: ChaCha8Rng::seed_from_u64(options.seed),
            options,
            y: vec![0.0; n],
            heads: vec![0.0; n],
            exchange: Exchange::default(),
            searcher: Searcher::default(),
            order: (0..n).collect(),
        })
    }

    /// A graph behind a wall with the given permeability channel and texel
    /// → node map (both one entry per texel of the atlas that
    /// [`Flooding::step`] will get).
    ///
    /// # Errors
    /// Options out of range; a map and channel of different lengths; a map
    /// naming a node the graph does not have.
    pub fn new(
        graph: LiquidGraph,
        permeability: Permeability,
        texel_nodes: TexelNodes,
        options: FlowOptions,
    ) -> Result<Self, FlowError> {
        if texel_nodes.len() != permeability.len() {
            return Err(FlowError::TexelMap(TexelMapError::Length {
                len: texel_nodes.len(),
                texels: permeability.len(),
            }));
        }
        let n = graph.node_count();
        if let Some(texel) = texel_nodes.nodes().iter().position(|&k| k as usize >= n) {
            return Err(FlowError::TexelMap(TexelMapError::Node {
                texel,
                node: texel_nodes.nodes()[texel],
                nodes: n,
            }));
        }
        let mut f = Self::sealed(graph, options)?;
        f.wall = Some(WallState {
            permeability,
            texel_nodes,
        });
        Ok(f)
    }

    /// An open container's water: the cavity of `atlas` (an open mesh's,
    /// [`soak_bake::cap_openings`]) as one compartment
    /// ([`LiquidGraph::cavity`], `walls` m³ of its room taken by the walls),
    /// behind a watertight wall whose caps are openings
    /// ([`Permeability::open_mesh`]): water comes in over the rims when
    /// they go under and pours out when the container tips. The caps drain
    /// into the lowest layer (what comes over a rim falls to the bottom);
    /// every other texel (a hole opened later) into its nearest layer.
    ///
    /// # Errors
    /// As [`LiquidGraph::cavity`] and [`Flooding::new`].
    pub fn open_container(atlas: &Atlas, walls: f64, options: FlowOptions) -> Result<Self, FlowError> {
        let graph = LiquidGraph::cavity(atlas, walls).map_err(FlowError::Graph)?;
        let mut nodes = TexelNodes::nearest(atlas, &graph).nodes().to_vec();
        for i in atlas.opening_samples() {
            nodes[i as usize] = 0;
        }
        let map = TexelNodes::from_nodes(atlas, &graph, nodes).map_err(FlowError::TexelMap)?;
        Self::new(graph, Permeability::open_mesh(atlas), map, options)
    }

    /// [`Flooding::new`] with each texel of `atlas` draining into its nearest node.
    ///
    /// # Errors
    /// As [`Flooding::new`]; a channel made for another atlas.
    pub fn for_atlas(
        atlas: &Atlas,
        graph: LiquidGraph,
        permeability: Permeability,
        options: FlowOptions,
    ) -> Result<Self, FlowError> {
        if permeability.len() != atlas.len() {
            return Err(FlowError::AtlasMismatch {
                what: "permeability channel",
                len: permeability.len(),
                texels: atlas.len(),
            });
        }
        let map = TexelNodes::nearest(atlas, &graph);
        Self::new(graph, permeability, map, options)
    }

    /// The graph and its liquid.
    pub fn graph(&self) -> &LiquidGraph {
        &self.graph
    }

    /// The wall's permeability channel (`None` when sealed).
    pub fn permeability(&self) -> Option<&Permeability> {
        self.wall.as_ref().map(|w| &w.permeability)
    }

    /// The wall's permeability channel, to punch a hole at run time
    /// ([`Permeability::paint`]); `None` when sealed.
    pub fn permeability_mut(&mut self) -> Option<&mut Permeability> {
        self.wall.as_mut().map(|w| &mut w.permeability)
    }

    /// The texel → node map (`None` when sealed).
    pub fn texel_nodes(&self) -> Option<&TexelNodes> {
        self.wall.as_ref().map(|w| &w.texel_nodes)
    }

    /// The flow parameters.
    pub fn options(&self) -> &FlowOptions {
        &self.options
    }

    /// What entered and left so far.
    pub fn ledger(&self) -> &Ledger {
        &self.ledger
    }

    /// Liquid inside, m³.
    pub fn inside(&self) -> f64 {
        self.graph.total_liquid()
    }

    /// `|inside − (initial + entered − left)| / (initial + entered)`.
    pub fn conservation_error(&self) -> f64 {
        self.ledger.relative_error(self.inside())
    }

    /// Mass properties of the liquid inside for a liquid of `density`
    /// (kg/m³), object frame: point masses at the nodes.
    pub fn mass_properties(&self, density: f64) -> MassProperties {
        self.graph.mass_properties(density)
    }

    /// Pours up to `volume` m³ into node `node` (a bucket, a wave over the
    /// gunwale); returns what fitted. Counted as entered.
    ///
    /// # Errors
    /// An unknown node or a volume that is negative or not finite.
    pub fn pour(&mut self, node: usize, volume: f64) -> Result<f64, GraphError> {
        let nodes = self.graph.node_count();
        if node >= nodes {
            return Err(GraphError::NoSuchNode { node, nodes });
        }
        let n = self.graph.node_mut(node);
        if !(volume.is_finite() && volume >= 0.0) {
            return Err(GraphError::NodeValue {
                node,
                name: n.name.clone(),
                field: "poured volume",
                value: volume,
                requirement: "must be a finite number ≥ 0 (m³)",
            });
        }
        let before = n.liquid;
        n.liquid = (before + volume).min(n.capacity);
        let taken = n.liquid - before;
        self.ledger.enter(taken);
        Ok(taken)
    }

    fn check_step(pose: &Isometry3<f64>, water: &Water, t: f64, dt: f64) -> Result<(), FlowError> {
        if !(dt.is_finite() && dt >= 0.0) {
            return Err(FlowError::Parameter {
                name: "dt",
                value: dt,
                requirement: "must be a finite number ≥ 0 (s)",
            });
        }
        if !t.is_finite() {
            return Err(FlowError::Parameter {
                name: "t",
                value: t,
                requirement: "must be finite (s)",
            });
        }
        if !(water.density.is_finite() && water.density > 0.0) {
            return Err(FlowError::Parameter {
                name: "water density",
                value: water.density,
                requirement: "must be a finite number > 0 (kg/m³)",
            });
        }
        if !(water.gravity.is_finite() && water.gravity >= 0.0) {
            return Err(FlowError::Parameter {
                name: "gravity",
                value: water.gravity,
                requirement: "must be a finite number ≥ 0 (m/s²)",
            });
        }
        let finite = pose.translation.vector.iter().all(|c| c.is_finite())
            && pose.rotation.coords.iter().all(|c| c.is_finite());
        if !finite {
            return Err(FlowError::Pose {
                pose: format!("{pose:?}"),
            });
        }
        Ok(())
    }

    fn levels(&mut self, pose: &Isometry3<f64>) {
        self.y.clear();
        self.heads.clear();
        for n in self.graph.nodes() {
            let y = (pose * n.position).y;
            self.y.push(y);
            self.heads.push(n.head_at(y));
        }
    }

    /// One step of `dt` seconds at time `t` (s): wall exchange, then
    /// redistribution, with the body at `pose` (object → world) in `water`
    /// (its density and gravity drive both). `atlas` is the body's, the one
    /// the permeability channel was made for (unused when sealed).
    ///
    /// # Errors
    /// Out-of-range `dt`, water or pose, a channel or map that does not fit
    /// the atlas, a non-finite depth; the liquid is then unchanged.
    pub fn step(
        &mut self,
        atlas: &Atlas,
        pose: &Isometry3<f64>,
        water: &Water,
        t: f64,
        dt: f64,
    ) -> Result<StepReport, FlowError> {
        Self::check_step(pose, water, t, dt)?;
        self.levels(pose);
        let mut report = StepReport::default();
        if let Some(wall) = &self.wall {
            if wall.permeability.len() != atlas.len() {
                return Err(FlowError::AtlasMismatch {
                    what: "permeability channel",
                    len: wall.permeability.len(),
                    texels: atlas.len(),
                });
            }
            if wall.texel_nodes.len() != atlas.len() {
                return Err(FlowError::AtlasMismatch {
                    what: "texel map",
                    len: wall.texel_nodes.len(),
                    texels: atlas.len(),
                });
            }
            let view = Wall {
                atlas,
                permeability: &wall.permeability,
                texel_nodes: &wall.texel_nodes,
            };
            self.exchange.gather(
                &view,
                &self.heads,
                pose,
                water,
                t,
                dt,
                self.options.viscosity,
                self.options.discharge_coefficient,
            )?;
            let flow = self.exchange.apply(
                &mut self.graph,
                &self.y,
                &mut self.heads,
                &mut self.searcher,
                water.density,
                water.gravity,
                dt,
                self.options.viscosity,
                self.options.tolerance,
                &mut self.rng,
            );
            self.ledger.enter(flow.entered);
            self.ledger.leave(flow.left);
            report.entered = flow.entered;
            report.left = flow.left;
            report.routed = flow.routed;
        }
        self.redistribute_passes(water, dt, &mut report);
        report.inside = self.inside();
        Ok(report)
    }

    /// Redistribution only (no wall exchange): one step of `dt` seconds with
    /// the body at `pose` in `water` (density and gravity).
    ///
    /// # Errors
    /// Out-of-range `dt`, water or pose; the liquid is then unchanged.
    pub fn redistribute(
        &mut self,
        pose: &Isometry3<f64>,
        water: &Water,
        dt: f64,
    ) -> Result<StepReport, FlowError> {
        Self::check_step(pose, water, 0.0, dt)?;
        self.levels(pose);
        let mut report = StepReport::default();
        self.redistribute_passes(water, dt, &mut report);
        report.inside = self.inside();
        Ok(report)
    }

    fn redistribute_passes(&mut self, water: &Water, dt: f64, report: &mut StepReport) {
        let passes = self.options.passes.max(1);
        let h = dt / passes as f64;
        for _ in 0..passes {
            self.pass(water.density, water.gravity, h, report);
        }
    }

    /// One pass of Algorithm 1 over every node holding liquid.
    fn pass(&mut self, density: f64, gravity: f64, dt: f64, report: &mut StepReport) {
        let n = self.graph.node_count();
        self.order.clear();
        self.order.extend(0..n);
        self.order.shuffle(&mut self.rng);
        self.searcher.reset(n);
        for k in 0..n {
            let s = self.order[k];
            let source = self.graph.raw_node(s);
            if source.liquid <= 0.0 {
                continue;
            }
            let head = self.heads[s];
            let levels = Levels {
                y: &self.y,
                heads: &self.heads,
            };
            let Some(found) = self.searcher.find(
                &self.graph,
                &levels,
                s,
                head,
                self.options.viscosity,
                self.options.tolerance,
                &mut self.rng,
            ) else {
                continue;
            };
            let d = found.node;
            let (src, dst) = (self.graph.raw_node(s), self.graph.raw_node(d));
            let dh = head - self.heads[d];
            // Heads level after q = Δh / (H_s/c_s + H_d/c_d); both capacities are > 0 here.
            let level = dh / (src.height / src.capacity + dst.height / dst.capacity);
            let q = poiseuille(dh, found.resistance, density, gravity, dt)
                .min(level)
                .min(src.liquid)
                .min(dst.free());
            let moved = move_liquid(&mut self.graph, s, d, q);
            if moved > 0.0 {
                report.moved += moved;
                report.transfers += 1;
                self.heads[s] = self.graph.raw_node(s).head_at(self.y[s]);
                self.heads[d] = self.graph.raw_node(d).head_at(self.y[d]);
            }
        }
    }
}
