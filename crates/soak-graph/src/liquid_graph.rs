//! The liquid graph (thesis §4.1): compartments that hold liquid, joined by
//! pipes.
//!
//! A [`Node`] is a compartment `⟨x_i, c_i, l_i⟩`: an object-space position
//! (m), a capacity (m³) and the liquid it holds (m³). A [`Pipe`] joins two
//! compartments whose spaces connect; it carries a radius and a length (m)
//! for Poiseuille's law and a dimensionless permeability factor.

use nalgebra::{Isometry3, Point3, Vector3};
use petgraph::graph::{EdgeIndex, NodeIndex, UnGraph};
use petgraph::visit::EdgeRef;
use serde::{Deserialize, Serialize};
use soak_hydro::MassProperties;

use crate::error::GraphError;
use crate::segment::Segmentation;

/// Layers of [`LiquidGraph::cavity`].
pub const CAVITY_LAYERS: usize = 4;

/// Dynamic viscosity of fresh water at 20 °C, Pa·s.
pub const WATER_VISCOSITY: f64 = 1.0e-3;

/// A compartment of the liquid graph.
///
/// # Vessels
///
/// The thesis places each node's liquid at a point. To let two nodes at the
/// same height exchange liquid until their levels match (communicating
/// vessels), each node is also a vertical **vessel** of height `H_i` (m)
/// centred on its position: with `y_i` the world height of its position, its
/// bottom is at `y_i − H_i/2`, its top at `y_i + H_i/2` and its free surface
/// (the *head*) at `h_i = y_i + H_i (l_i/c_i − 1/2)`, always along world
/// `y` whatever the body's rotation. Pipes join the vessels' bottoms. The
/// default height is the diameter of the sphere of the node's capacity,
/// `2 (3 c_i / 4π)^(1/3)`; a hand-made graph may give the compartment's real
/// height. With `H_i = 0` every rule below reduces to the thesis' point
/// nodes.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Node {
    /// A name for messages and files (unique within a graph).
    pub name: String,
    /// Position, object space, m.
    pub position: Point3<f64>,
    /// Volume of liquid it holds when full, m³ (≥ 0; 0 for a junction).
    pub capacity: f64,
    /// Volume of liquid it holds, m³ (0 ≤ liquid ≤ capacity).
    pub liquid: f64,
    /// Height of its vessel, m (≥ 0; > 0 when the capacity is), see
    /// *Vessels* above.
    pub height: f64,
}

impl Node {
    /// An empty node of `capacity` (m³) at `position` (m) with the default
    /// vessel height [`Node::sphere_height`].
    pub fn new(name: impl Into<String>, position: Point3<f64>, capacity: f64) -> Self {
        Self {
            name: name.into(),
            position,
            capacity,
            liquid: 0.0,
            height: Self::sphere_height(capacity),
        }
    }

    /// The same node holding `liquid` m³.
    pub fn with_liquid(mut self, liquid: f64) -> Self {
        self.liquid = liquid;
        self
    }

    /// The same node with a vessel `height` m.
    pub fn with_height(mut self, height: f64) -> Self {
        self.height = height;
        self
    }

    /// The diameter of a sphere of volume `capacity` (m³), m: the default
    /// vessel height. 0 for a non-positive or non-finite capacity.
    pub fn sphere_height(capacity: f64) -> f64 {
        if capacity.is_finite() && capacity > 0.0 {
            2.0 * (3.0 * capacity / (4.0 * std::f64::consts::PI)).cbrt()
        } else {
            0.0
        }
    }

    /// Room left, m³.
    #[inline]
    pub fn free(&self) -> f64 {
        (self.capacity - self.liquid).max(0.0)
    }

    /// Whether it can take no more liquid.
    #[inline]
    pub fn is_full(&self) -> bool {
        self.liquid >= self.capacity
    }

    /// Fill fraction `l/c` in [0, 1] (1 for a zero-capacity node).
    #[inline]
    pub fn fill(&self) -> f64 {
        if self.capacity > 0.0 {
            (self.liquid / self.capacity).clamp(0.0, 1.0)
        } else {
            1.0
        }
    }

    /// Horizontal cross-section of its vessel `c/H`, m²: the liquid volume
    /// that raises its head by one metre. 0 for a zero-capacity node.
    #[inline]
    pub fn section(&self) -> f64 {
        if self.capacity > 0.0 && self.height > 0.0 {
            self.capacity / self.height
        } else {
            0.0
        }
    }

    /// Head (free-surface height, m) of the vessel whose centre is at world
    /// height `y` (m).
    #[inline]
    pub fn head_at(&self, y: f64) -> f64 {
        if self.capacity > 0.0 {
            y + self.height * (self.fill() - 0.5)
        } else {
            y
        }
    }

    /// Bottom of the vessel whose centre is at world height `y` (m), m.
    #[inline]
    pub fn bottom_at(&self, y: f64) -> f64 {
        y - 0.5 * self.height
    }

    fn check(&self, i: usize) -> Result<(), GraphError> {
        let err = |field, value, requirement| GraphError::NodeValue {
            node: i,
            name: self.name.clone(),
            field,
            value,
            requirement,
        };
        if let Some(c) = self.position.iter().find(|c| !c.is_finite()) {
            return Err(err("position", *c, "must be finite"));
        }
        if !(self.capacity.is_finite() && self.capacity >= 0.0) {
            return Err(err("capacity", self.capacity, "must be a finite number ≥ 0 (m³)"));
        }
        if !(self.liquid.is_finite() && self.liquid >= 0.0) {
            return Err(err("liquid", self.liquid, "must be a finite number ≥ 0 (m³)"));
        }
        if self.liquid > self.capacity {
            return Err(GraphError::OverCapacity {
                node: i,
                name: self.name.clone(),
                liquid: self.liquid,
                capacity: self.capacity,
            });
        }
        if !(self.height.is_finite() && self.height >= 0.0) {
            return Err(err("height", self.height, "must be a finite number ≥ 0 (m)"));
        }
        if self.capacity > 0.0 && self.height == 0.0 {
            return Err(err("height", self.height, "must be > 0 for a node with capacity"));
        }
        Ok(())
    }
}

/// A pipe joining two compartments.
///
/// Its hydraulic resistance is Poiseuille's, scaled by the permeability
/// factor `p`: `R = 8 μ L / (π r⁴ p)` (Pa·s/m³), so a head difference `Δh`
/// drives `Q = ρ g Δh / R` m³/s through it. Pipes in series add their
/// resistances. `p = 0` or `r = 0` closes the pipe (a watertight bulkhead).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct Pipe {
    /// Permeability factor, dimensionless, ≥ 0 (1 an open pipe; the
    /// thesis' edge permeability `p^g_ik`).
    pub permeability: f64,
    /// Radius, m, ≥ 0.
    pub radius: f64,
    /// Length, m, > 0.
    pub length: f64,
}

impl Pipe {
    /// An open pipe (permeability 1) of `radius` and `length` (m).
    pub fn new(radius: f64, length: f64) -> Self {
        Self {
            permeability: 1.0,
            radius,
            length,
        }
    }

    /// Whether liquid can pass.
    #[inline]
    pub fn is_open(&self) -> bool {
        self.permeability > 0.0 && self.radius > 0.0
    }

    /// Hydraulic resistance `8 μ L / (π r⁴ p)` for viscosity `μ` (Pa·s),
    /// Pa·s/m³; infinite when closed.
    #[inline]
    pub fn resistance(&self, viscosity: f64) -> f64 {
        if !self.is_open() {
            return f64::INFINITY;
        }
        8.0 * viscosity * self.length / (std::f64::consts::PI * self.radius.powi(4) * self.permeability)
    }

    fn check(&self, edge: usize, a: usize, b: usize) -> Result<(), GraphError> {
        let err = |field, value, requirement| GraphError::EdgeValue {
            edge,
            a,
            b,
            field,
            value,
            requirement,
        };
        if !(self.permeability.is_finite() && self.permeability >= 0.0) {
            return Err(err(
                "permeability",
                self.permeability,
                "must be a finite number ≥ 0",
            ));
        }
        if !(self.radius.is_finite() && self.radius >= 0.0) {
            return Err(err("radius", self.radius, "must be a finite number ≥ 0 (m)"));
        }
        if !(self.length.is_finite() && self.length > 0.0) {
            return Err(err("length", self.length, "must be a finite number > 0 (m)"));
        }
        Ok(())
    }
}

/// How [`LiquidGraph::from_segmentation`] turns segments into nodes and pipes.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct SegmentGraphOptions {
    /// Fraction of each segment's capacity open to liquid, in [0, 1]: 1 for
    /// a hollow object, the porosity of a stuffing (≈ 0.9) for a plush toy.
    pub porosity: f64,
    /// Pipe permeability factor, dimensionless, ≥ 0.
    pub permeability: f64,
    /// Pipe radius as a fraction of the radius `ℓ/2π` of a circle as long
    /// as the segments' shared boundary `ℓ`, ≥ 0.
    pub radius_scale: f64,
}

impl Default for SegmentGraphOptions {
    fn default() -> Self {
        Self {
            porosity: 1.0,
            permeability: 1.0,
            radius_scale: 1.0,
        }
    }
}

/// The liquid graph: compartments ([`Node`]) joined by pipes ([`Pipe`]),
/// on a petgraph undirected graph. Node `i` is petgraph's `NodeIndex(i)`.
///
/// # Example
/// ```
/// use nalgebra::Point3;
/// use soak_graph::{LiquidGraph, Node, Pipe};
/// let graph = LiquidGraph::new(
///     vec![
///         Node::new("fore", Point3::new(1.0, 0.3, 0.0), 0.5).with_liquid(0.1),
///         Node::new("aft", Point3::new(-1.0, 0.3, 0.0), 0.5),
///     ],
///     vec![(0, 1, Pipe::new(0.02, 2.0))],
/// )?;
/// assert_eq!(graph.total_liquid(), 0.1);
/// # Ok::<(), soak_graph::GraphError>(())
/// ```
#[derive(Clone, Debug)]
pub struct LiquidGraph {
    graph: UnGraph<Node, Pipe>,
}

impl LiquidGraph {
    /// The graph of a hollow body's inside, for an open mesh's cavity
    /// ([`soak_bake::cap_openings`]) or a hull holed at run time: the
    /// enclosed volume cut into [`CAVITY_LAYERS`] horizontal layers of the
    /// object's `y` (its lowest texel to its highest), bottom first, each a
    /// node named `"inside k"` whose vessel is its layer, at the enclosed
    /// volume's centroid in `x` and `z`, holding its layer's share of the
    /// enclosed volume less `walls` (m³, the room the walls take inside the
    /// surface; 0 for thin walls); consecutive layers are joined by wide
    /// pipes. Liquid settles in the lowest layers, so its weight acts low in
    /// an upright container, as it does in a real one.
    ///
    /// A layer's volume is the enclosed volume between its planes, from the
    /// texels' columns: below a plane `y = c` a closed surface encloses
    /// `Σ_{y_i < c} −A_{y,i} (c − y_i)`.
    ///
    /// # Errors
    /// An atlas that encloses no volume, or `walls` negative, not finite or
    /// not below the enclosed volume.
    pub fn cavity(atlas: &soak_bake::Atlas, walls: f64) -> Result<Self, GraphError> {
        let moments = soak_hydro::volume_moments(atlas);
        let volume = moments.volume;
        let capacity = volume - walls;
        if !(volume > 0.0 && walls.is_finite() && walls >= 0.0 && capacity > 0.0) {
            return Err(GraphError::NodeValue {
                node: 0,
                name: "inside".into(),
                field: "capacity",
                value: capacity,
                requirement: "the enclosed volume less the walls' must be > 0 (m³)",
            });
        }
        let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
        for i in 0..atlas.len() {
            let y = atlas.position(i).y;
            lo = lo.min(y);
            hi = hi.max(y);
        }
        let below = |c: f64| -> f64 {
            let a = atlas.area_vectors();
            (0..atlas.len())
                .map(|i| {
                    let y = atlas.position(i).y;
                    if y < c {
                        -(a.get(i)[1] as f64) * (c - y)
                    } else {
                        0.0
                    }
                })
                .sum()
        };
        let k = CAVITY_LAYERS;
        let h = (hi - lo) / k as f64;
        let c = moments.origin + moments.first / volume;
        let cuts: Vec<f64> = (0..=k)
            .map(|j| if j == k { volume } else { below(lo + j as f64 * h) })
            .collect();
        let nodes = (0..k)
            .map(|j| {
                let share = ((cuts[j + 1] - cuts[j]) / volume).max(0.0);
                let position = Point3::new(c.x, lo + (j as f64 + 0.5) * h, c.z);
                Node::new(format!("inside {j}"), position, share * capacity).with_height(h)
            })
            .collect::<Vec<_>>();
        // Pipes as wide as the layers: the liquid finds its level in a step.
        let radius = (capacity / (hi - lo) / std::f64::consts::PI).sqrt();
        let pipes = (1..k).map(|j| (j - 1, j, Pipe::new(radius, h))).collect();
        Self::new(nodes, pipes)
    }

    /// A graph from its nodes and edges `(a, b, pipe)` (node indices),
    /// validated ([`LiquidGraph::validate`]).
    ///
    /// # Errors
    /// The first invalid node or edge, by index and name.
    pub fn new(nodes: Vec<Node>, edges: Vec<(usize, usize, Pipe)>) -> Result<Self, GraphError> {
        let n = nodes.len();
        let mut graph = UnGraph::with_capacity(n, edges.len());
        for node in nodes {
            graph.add_node(node);
        }
        for (e, &(a, b, _)) in edges.iter().enumerate() {
            for node in [a, b] {
                if node >= n {
                    return Err(GraphError::MissingNode {
                        edge: e,
                        node,
                        nodes: n,
                    });
                }
            }
        }
        for (a, b, pipe) in edges {
            graph.add_edge(NodeIndex::new(a), NodeIndex::new(b), pipe);
        }
        let g = Self { graph };
        g.validate()?;
        Ok(g)
    }

    /// The graph of a mesh's automatic segmentation (thesis §4.1.1): one
    /// node per segment at its sphere's centre with its capacity times
    /// `porosity` and the default vessel height, and a pipe between
    /// segments sharing a boundary of length `ℓ`, of radius
    /// `radius_scale · ℓ/2π` and as long as the distance between the nodes.
    ///
    /// # Errors
    /// An option out of range (reported on node 0 / edge 0), or a node the
    /// segmentation left invalid.
    pub fn from_segmentation(seg: &Segmentation, options: &SegmentGraphOptions) -> Result<Self, GraphError> {
        let bad = |field, value, requirement| GraphError::NodeValue {
            node: 0,
            name: "segmentation options".into(),
            field,
            value,
            requirement,
        };
        if !(options.porosity.is_finite() && (0.0..=1.0).contains(&options.porosity)) {
            return Err(bad("porosity", options.porosity, "must be in [0, 1]"));
        }
        if !(options.permeability.is_finite() && options.permeability >= 0.0) {
            return Err(bad(
                "permeability",
                options.permeability,
                "must be a finite number ≥ 0",
            ));
        }
        if !(options.radius_scale.is_finite() && options.radius_scale >= 0.0) {
            return Err(bad(
                "radius_scale",
                options.radius_scale,
                "must be a finite number ≥ 0",
            ));
        }
        let nodes: Vec<Node> = seg
            .segments
            .iter()
            .enumerate()
            .map(|(i, s)| Node::new(format!("segment {i}"), s.position, s.capacity * options.porosity))
            .collect();
        let edges = seg
            .edges
            .iter()
            .map(|&(a, b, boundary)| {
                let (pa, pb) = (nodes[a as usize].position, nodes[b as usize].position);
                // Nodes at one point (a symmetric part) still get a pipe.
                let length = (pa - pb).norm().max(1e-6);
                let pipe = Pipe {
                    permeability: options.permeability,
                    radius: options.radius_scale * boundary / std::f64::consts::TAU,
                    length,
                };
                (a as usize, b as usize, pipe)
            })
            .collect();
        Self::new(nodes, edges)
    }

    /// Checks every node and edge: finite positions, `0 ≤ liquid ≤
    /// capacity`, heights ≥ 0 (> 0 with capacity), unique names; pipes with
    /// finite radius ≥ 0, length > 0 and permeability ≥ 0, no self-loops,
    /// at most one pipe per pair of nodes.
    ///
    /// # Errors
    /// The first problem found, naming the node or edge.
    pub fn validate(&self) -> Result<(), GraphError> {
        if self.graph.node_count() == 0 {
            return Err(GraphError::Empty);
        }
        let mut names = std::collections::HashMap::new();
        for (i, node) in self.graph.node_weights().enumerate() {
            node.check(i)?;
            if let Some(&first) = names.get(node.name.as_str()) {
                return Err(GraphError::DuplicateName {
                    node: i,
                    first,
                    name: node.name.clone(),
                });
            }
            names.insert(node.name.as_str(), i);
        }
        let mut pairs = std::collections::HashMap::new();
        for e in self.graph.edge_references() {
            let (i, a, b) = (e.id().index(), e.source().index(), e.target().index());
            if a == b {
                return Err(GraphError::SelfLoop { edge: i, node: a });
            }
            if let Some(&first) = pairs.get(&(a.min(b), a.max(b))) {
                return Err(GraphError::DuplicateEdge { edge: i, first, a, b });
            }
            pairs.insert((a.min(b), a.max(b)), i);
            e.weight().check(i, a, b)?;
        }
        Ok(())
    }

    /// The underlying petgraph graph.
    pub fn petgraph(&self) -> &UnGraph<Node, Pipe> {
        &self.graph
    }

    /// Number of nodes.
    pub fn node_count(&self) -> usize {
        self.graph.node_count()
    }

    /// Number of pipes.
    pub fn edge_count(&self) -> usize {
        self.graph.edge_count()
    }

    /// Node `i`, if it exists.
    pub fn node(&self, i: usize) -> Option<&Node> {
        self.graph.node_weight(NodeIndex::new(i))
    }

    /// The nodes, by index.
    pub fn nodes(&self) -> impl ExactSizeIterator<Item = &Node> + '_ {
        self.graph.raw_nodes().iter().map(|n| &n.weight)
    }

    /// The pipes as `(a, b, pipe)`, by index.
    pub fn edges(&self) -> impl ExactSizeIterator<Item = (usize, usize, &Pipe)> + '_ {
        self.graph
            .raw_edges()
            .iter()
            .map(|e| (e.source().index(), e.target().index(), &e.weight))
    }

    /// The index of the node called `name`.
    pub fn find(&self, name: &str) -> Option<usize> {
        self.nodes().position(|n| n.name == name)
    }

    /// The liquid in each node, m³.
    pub fn liquids(&self) -> Vec<f64> {
        self.nodes().map(|n| n.liquid).collect()
    }

    /// Total liquid inside, m³.
    pub fn total_liquid(&self) -> f64 {
        self.nodes().map(|n| n.liquid).sum()
    }

    /// Total capacity, m³.
    pub fn total_capacity(&self) -> f64 {
        self.nodes().map(|n| n.capacity).sum()
    }

    /// Sets the liquid in node `i` (m³), clamped to `[0, capacity]`;
    /// returns the amount actually set.
    ///
    /// # Errors
    /// [`GraphError::NoSuchNode`], or a non-finite value.
    pub fn set_liquid(&mut self, i: usize, liquid: f64) -> Result<f64, GraphError> {
        let nodes = self.graph.node_count();
        let node = self
            .graph
            .node_weight_mut(NodeIndex::new(i))
            .ok_or(GraphError::NoSuchNode { node: i, nodes })?;
        if !liquid.is_finite() {
            return Err(GraphError::NodeValue {
                node: i,
                name: node.name.clone(),
                field: "liquid",
                value: liquid,
                requirement: "must be finite",
            });
        }
        node.liquid = liquid.clamp(0.0, node.capacity);
        Ok(node.liquid)
    }

    /// Empties every node.
    pub fn drain(&mut self) {
        for n in self.graph.node_weights_mut() {
            n.liquid = 0.0;
        }
    }

    /// World height of each node's position under `pose`, m.
    pub fn world_heights(&self, pose: &Isometry3<f64>) -> Vec<f64> {
        self.nodes().map(|n| (pose * n.position).y).collect()
    }

    /// Head (free-surface height, world, m) of each node under `pose`.
    pub fn heads(&self, pose: &Isometry3<f64>) -> Vec<f64> {
        self.nodes().map(|n| n.head_at((pose * n.position).y)).collect()
    }

    /// Mass properties of the liquid inside (thesis §4.1.3), object frame:
    /// a point mass `ρ_f l_i` at each node's position for a liquid of
    /// `density` kg/m³. Zero mass at the origin when empty.
    pub fn mass_properties(&self, density: f64) -> MassProperties {
        let mut mass = 0.0;
        let mut first = Vector3::zeros();
        for n in self.nodes() {
            let m = density * n.liquid;
            mass += m;
            first += n.position.coords * m;
        }
        if !(mass > 0.0 && mass.is_finite()) {
            return MassProperties::zero();
        }
        let c = Point3::from(first / mass);
        let inertia = self
            .nodes()
            .map(|n| soak_hydro::parallel_axis(density * n.liquid, &(n.position - c)))
            .sum();
        MassProperties {
            mass,
            center_of_mass: c,
            inertia,
        }
    }

    pub(crate) fn node_mut(&mut self, i: usize) -> &mut Node {
        &mut self.graph[NodeIndex::new(i)]
    }

    pub(crate) fn raw_node(&self, i: usize) -> &Node {
        &self.graph[NodeIndex::new(i)]
    }

    /// The pipes at node `i` as `(edge, neighbour)`.
    pub(crate) fn incident(&self, i: usize, out: &mut Vec<(EdgeIndex, usize)>) {
        out.clear();
        out.extend(self.graph.edges(NodeIndex::new(i)).map(|e| {
            (
                e.id(),
                if e.source().index() == i {
                    e.target()
                } else {
                    e.source()
                }
                .index(),
            )
        }));
        // petgraph lists edges newest first; a fixed order keeps runs reproducible
        // however the graph was built.
        out.sort_unstable_by_key(|&(e, n)| (n, e.index()));
    }

    pub(crate) fn pipe(&self, e: EdgeIndex) -> &Pipe {
        &self.graph[e]
    }
}
