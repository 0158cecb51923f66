#![doc = include_str!("../README.md")]

pub mod discharge;
pub mod error;
pub mod flooding;
pub mod flow_options;
pub mod graph_file;
pub mod ingress;
pub mod ledger;
pub mod liquid_graph;
pub mod permeability;
pub mod segment;
pub mod texel_nodes;

pub use discharge::Discharge;
pub use error::{Element, FlowError, GraphError, GraphFileError, PermeabilityError, TexelMapError};
pub use flooding::{Flooding, FloodingState, StepReport};
pub use flow_options::FlowOptions;
pub use graph_file::{Format, GraphFile, load_graph, parse_graph};
pub use ledger::Ledger;
pub use liquid_graph::{LiquidGraph, Node, Pipe, SegmentGraphOptions, WATER_VISCOSITY};
pub use permeability::Permeability;
pub use texel_nodes::TexelNodes;

/// The types most users need.
pub mod prelude {
    pub use crate::segment::{SegmentOptions, segment};
    pub use crate::{
        Flooding, FlowOptions, LiquidGraph, Node, Permeability, Pipe, SegmentGraphOptions, TexelNodes,
        load_graph,
    };
}
