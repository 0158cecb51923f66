//! Water entering a body: where its liquid graph comes from ([`GraphSpec`],
//! [`AutoGraphSpec`]) and the permeable regions of its wall ([`HoleSpec`]).

use serde::{Deserialize, Serialize};

/// Where a body's liquid graph comes from.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(untagged)]
pub enum GraphSpec {
    /// A graph file (TOML or JSON), relative to the scene.
    File(String),
    /// Automatic segmentation of the mesh (Shape Diameter Function).
    Auto(AutoGraphSpec),
    /// `{ cavity = true }`: the hollow inside as one compartment
    /// ([`soak_graph::LiquidGraph::cavity`]), for a hull that takes water
    /// only where it is holed or open.
    Cavity(CavitySpec),
}

/// The keyword table `{ cavity = true }`.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CavitySpec {
    /// Must be `true`.
    pub cavity: bool,
}

fn default_clusters() -> usize {
    5
}
fn one() -> f64 {
    1.0
}

/// Automatic graph parameters.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct AutoGraphSpec {
    /// Must be `true`.
    pub auto: bool,
    /// Clusters of the segmentation.
    #[serde(default = "default_clusters")]
    pub clusters: usize,
    /// Fraction of each segment open to liquid, in [0, 1] (≈ 0.9 for stuffing).
    #[serde(default = "one")]
    pub porosity: f64,
}

/// A permeable region: every texel within `radius` of `centre` (an opening
/// when it has no `kappa`).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct HoleSpec {
    /// Centre, m: in the body's local frame, or in the world's with
    /// `world = true` (where the body stands when the hole opens).
    pub centre: [f64; 3],
    /// Whether `centre` is a world point.
    #[serde(default)]
    pub world: bool,
    /// Radius, m.
    pub radius: f64,
    /// Permeability over wall thickness κ = k/L, m; absent: an opening, a
    /// hole through which water flows freely (the orifice law).
    pub kappa: Option<f64>,
    /// Time the region opens (a hole punched during the run), s.
    #[serde(default)]
    pub at: f64,
}
