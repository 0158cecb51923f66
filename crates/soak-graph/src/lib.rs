#![doc = include_str!("../README.md")]

// The files are private: what users reach is re-exported below, so the
// layout can change without changing the API.
mod discharge;
mod error;
mod flooding;
mod flow_options;
mod graph_file;
mod ingress;
mod ledger;
mod liquid_graph;
mod permeability;
mod texel_nodes;

// Public on purpose: segmentation is a pipeline of its own (shape diameter,
// Gaussian mixture, graph cut, max flow, sphere fit) whose stages are usable
// and tested one by one, and whose many names (options, constants, stage
// results) would crowd the crate root.
pub mod segment;

pub use self::discharge::{Discharge, find_discharge};
pub use self::error::{Element, FlowError, GraphError, GraphFileError, PermeabilityError, TexelMapError};
pub use self::flooding::{Flooding, FloodingState, StepReport};
pub use self::flow_options::FlowOptions;
pub use self::graph_file::{
    EdgeSpec, Format, GraphFile, NodeRef, NodeSpec, load_graph, parse_graph, to_json, to_toml, unnamed,
};
pub use self::ledger::Ledger;
pub use self::liquid_graph::{CAVITY_LAYERS, LiquidGraph, Node, Pipe, SegmentGraphOptions, WATER_VISCOSITY};
pub use self::permeability::Permeability;
pub use self::texel_nodes::TexelNodes;

/// The types most users need.
pub mod prelude {
    pub use crate::segment::{SegmentOptions, segment};
    pub use crate::{
        Flooding, FlowOptions, LiquidGraph, Node, Permeability, Pipe, SegmentGraphOptions, TexelNodes,
        load_graph,
    };
}
