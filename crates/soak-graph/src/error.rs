//! Typed errors of the liquid graph: building it, reading it from a file,
//! the permeability channel, and advancing the liquid.

use std::path::PathBuf;

/// Which part of a graph an error is about.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Element {
    /// Node `i` (its index in the graph and in the file's `nodes` list).
    Node(usize),
    /// Edge `i` (its index in the graph and in the file's `edges` list).
    Edge(usize),
}

/// A liquid graph is not valid.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum GraphError {
    /// The graph has no node.
    #[error("a liquid graph needs at least one node")]
    Empty,
    /// A node's number is out of range or not finite.
    #[error("node {node} (`{name}`): {field} = {value} {requirement}")]
    NodeValue {
        /// Node index.
        node: usize,
        /// Node name.
        name: String,
        /// The offending field (`capacity`, `liquid`, `height`, `position`).
        field: &'static str,
        /// Its value.
        value: f64,
        /// What it must be.
        requirement: &'static str,
    },
    /// A node holds more liquid than it can.
    #[error("node {node} (`{name}`): liquid {liquid} m³ exceeds its capacity {capacity} m³")]
    OverCapacity {
        /// Node index.
        node: usize,
        /// Node name.
        name: String,
        /// Liquid, m³.
        liquid: f64,
        /// Capacity, m³.
        capacity: f64,
    },
    /// Two nodes share a name.
    #[error("node {node}: name `{name}` is already node {first}'s")]
    DuplicateName {
        /// The later node's index.
        node: usize,
        /// The earlier node's index.
        first: usize,
        /// The shared name.
        name: String,
    },
    /// An edge's number is out of range or not finite.
    #[error("edge {edge} ({a}–{b}): {field} = {value} {requirement}")]
    EdgeValue {
        /// Edge index.
        edge: usize,
        /// One end (node index).
        a: usize,
        /// The other end (node index).
        b: usize,
        /// The offending field (`radius`, `length`, `permeability`).
        field: &'static str,
        /// Its value.
        value: f64,
        /// What it must be.
        requirement: &'static str,
    },
    /// An edge names a node the graph does not have.
    #[error("edge {edge}: node {node} does not exist (the graph has {nodes} nodes)")]
    MissingNode {
        /// Edge index.
        edge: usize,
        /// The node index given.
        node: usize,
        /// Number of nodes.
        nodes: usize,
    },
    /// An edge joins a node to itself.
    #[error("edge {edge} joins node {node} to itself")]
    SelfLoop {
        /// Edge index.
        edge: usize,
        /// The node.
        node: usize,
    },
    /// Two edges join the same pair of nodes.
    #[error("edge {edge} joins nodes {a} and {b}, which edge {first} already joins")]
    DuplicateEdge {
        /// The later edge's index.
        edge: usize,
        /// The earlier edge's index.
        first: usize,
        /// One end.
        a: usize,
        /// The other end.
        b: usize,
    },
    /// A node index passed to a method is out of range.
    #[error("node {node} does not exist (the graph has {nodes} nodes)")]
    NoSuchNode {
        /// The index given.
        node: usize,
        /// Number of nodes.
        nodes: usize,
    },
}

impl GraphError {
    /// The node or edge the error is about, if any.
    pub fn element(&self) -> Option<Element> {
        match self {
            GraphError::NodeValue { node, .. }
            | GraphError::OverCapacity { node, .. }
            | GraphError::DuplicateName { node, .. } => Some(Element::Node(*node)),
            GraphError::EdgeValue { edge, .. }
            | GraphError::MissingNode { edge, .. }
            | GraphError::SelfLoop { edge, .. }
            | GraphError::DuplicateEdge { edge, .. } => Some(Element::Edge(*edge)),
            GraphError::Empty | GraphError::NoSuchNode { .. } => None,
        }
    }
}

/// A graph file could not be read, parsed or turned into a valid graph.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum GraphFileError {
    /// The file could not be read.
    #[error("graph file `{path}`: {source}")]
    Read {
        /// The file.
        path: PathBuf,
        /// The I/O error.
        source: std::io::Error,
    },
    /// The extension is neither `.toml` nor `.json`.
    #[error("graph file `{path}`: unknown format (use a .toml or .json file)")]
    UnknownFormat {
        /// The file.
        path: PathBuf,
    },
    /// The text is not valid TOML/JSON or does not match the schema
    /// (unknown key, wrong type, missing field).
    #[error("graph file `{path}`, line {line}: {message}")]
    Parse {
        /// The file.
        path: PathBuf,
        /// 1-based line.
        line: usize,
        /// The parser's message.
        message: String,
    },
    /// An edge refers to a node name that no node has.
    #[error("graph file `{path}`, line {line}: edge {edge}: no node is called `{name}`")]
    UnknownNode {
        /// The file.
        path: PathBuf,
        /// 1-based line of the edge.
        line: usize,
        /// Edge index.
        edge: usize,
        /// The name given.
        name: String,
    },
    /// The graph the file describes is not valid.
    #[error("graph file `{path}`, line {line}: {source}")]
    Invalid {
        /// The file.
        path: PathBuf,
        /// 1-based line of the offending node or edge (1 if none).
        line: usize,
        /// What is wrong.
        source: GraphError,
    },
}

/// A permeability channel could not be made or changed.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum PermeabilityError {
    /// A value is negative or not finite.
    #[error("texel {texel}: permeability {value} m is not a finite number ≥ 0")]
    Value {
        /// Texel index (or pixel index for an image).
        texel: usize,
        /// The value, m.
        value: f64,
    },
    /// The channel does not have one value per atlas texel.
    #[error("permeability channel has {len} values but the atlas has {texels} texels")]
    Length {
        /// Values given.
        len: usize,
        /// Texels in the atlas.
        texels: usize,
    },
    /// An image has a zero side or the wrong number of pixels.
    #[error("permeability image is {width}×{height} but has {len} pixels")]
    ImageSize {
        /// Width, pixels.
        width: u32,
        /// Height, pixels.
        height: u32,
        /// Pixels given.
        len: usize,
    },
    /// A painted region is not a finite point and radius ≥ 0.
    #[error("painted region centre {centre:?} m, radius {radius} m is not finite and ≥ 0")]
    Region {
        /// Centre, object space, m.
        centre: [f64; 3],
        /// Radius, m.
        radius: f64,
    },
    /// A texel index is out of range.
    #[error("texel {texel} does not exist (the channel has {len})")]
    NoSuchTexel {
        /// The index given.
        texel: usize,
        /// Channel length.
        len: usize,
    },
}

/// The texel → node map does not fit the atlas or the graph.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum TexelMapError {
    /// The map does not have one entry per atlas texel.
    #[error("texel map has {len} entries but the atlas has {texels} texels")]
    Length {
        /// Entries given.
        len: usize,
        /// Texels in the atlas.
        texels: usize,
    },
    /// A texel maps to a node the graph does not have.
    #[error("texel {texel} maps to node {node}, but the graph has {nodes} nodes")]
    Node {
        /// Texel index.
        texel: usize,
        /// Node index.
        node: u32,
        /// Number of nodes.
        nodes: usize,
    },
    /// A texel lies on a triangle the segmentation does not cover.
    #[error(
        "texel {texel} lies on triangle {triangle}, but the segmentation covers {faces} faces \
         (was it made from another mesh?)"
    )]
    Triangle {
        /// Texel index.
        texel: usize,
        /// Triangle index.
        triangle: u32,
        /// Faces in the segmentation.
        faces: usize,
    },
}

/// Advancing the liquid failed; the graph is left as it was before the step.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum FlowError {
    /// A flow parameter is out of range.
    #[error("{name} = {value} {requirement}")]
    Parameter {
        /// Parameter name.
        name: &'static str,
        /// Its value.
        value: f64,
        /// What it must be.
        requirement: &'static str,
    },
    /// The body's pose has a non-finite component.
    #[error("the body pose is not finite: {pose}")]
    Pose {
        /// The pose, printed.
        pose: String,
    },
    /// The water surface returned a non-finite depth.
    #[error("the water depth at texel {texel} (world {position:?} m) is {depth}")]
    Depth {
        /// Texel index.
        texel: usize,
        /// World position, m.
        position: [f64; 3],
        /// The depth returned.
        depth: f64,
    },
    /// The texel map does not fit the graph or the permeability channel.
    #[error(transparent)]
    TexelMap(#[from] TexelMapError),
    /// The atlas does not match the permeability channel or texel map.
    #[error("the atlas has {texels} texels but the {what} has {len}")]
    AtlasMismatch {
        /// Which per-texel array.
        what: &'static str,
        /// Its length.
        len: usize,
        /// Texels in the atlas.
        texels: usize,
    },
    /// A saved state does not fit this flooding.
    #[error("saved state: {0}")]
    State(String),
    /// A graph operation failed.
    #[error(transparent)]
    Graph(#[from] GraphError),
}
