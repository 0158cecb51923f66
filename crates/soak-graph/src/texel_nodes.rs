//! Which node each texel's liquid enters (thesis §4.1.2: "according to the
//! texel's closeness to the graph's nodes"), computed once per atlas and
//! graph.

use rayon::prelude::*;
use soak_bake::Atlas;

use crate::error::TexelMapError;
use crate::liquid_graph::LiquidGraph;
use crate::segment::Segmentation;

/// The node (index) each atlas texel drains into.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct TexelNodes {
    nodes: Vec<u32>,
}

impl TexelNodes {
    /// Each texel to its nearest node (object-space distance; ties to the
    /// lower index).
    pub fn nearest(atlas: &Atlas, graph: &LiquidGraph) -> Self {
        let positions: Vec<_> = graph.nodes().map(|n| n.position).collect();
        let nodes = (0..atlas.len())
            .into_par_iter()
            .map(|i| {
                let p = atlas.position(i);
                let mut best = (f64::INFINITY, 0u32);
                for (k, q) in positions.iter().enumerate() {
                    let d = (p - q).norm_squared();
                    if d < best.0 {
                        best = (d, k as u32);
                    }
                }
                best.1
            })
            .collect();
        Self { nodes }
    }

    /// Each texel to the node of its triangle's segment: for a graph made by
    /// [`LiquidGraph::from_segmentation`] from the same mesh the atlas was
    /// baked from. Better than [`TexelNodes::nearest`] on thin parts, where
    /// the nearest node may be across a wall.
    ///
    /// # Errors
    /// A texel on a triangle the segmentation does not have.
    pub fn from_segmentation(atlas: &Atlas, seg: &Segmentation) -> Result<Self, TexelMapError> {
        let faces = seg.face_segment.len();
        let nodes = atlas
            .triangle_ids()
            .iter()
            .enumerate()
            .map(|(texel, &t)| {
                seg.face_segment
                    .get(t as usize)
                    .copied()
                    .ok_or(TexelMapError::Triangle {
                        texel,
                        triangle: t,
                        faces,
                    })
            })
            .collect::<Result<_, _>>()?;
        Ok(Self { nodes })
    }

    /// A given map, one node index per texel.
    ///
    /// # Errors
    /// A wrong length or a node the graph does not have.
    pub fn from_nodes(atlas: &Atlas, graph: &LiquidGraph, nodes: Vec<u32>) -> Result<Self, TexelMapError> {
        let map = Self { nodes };
        map.fits(atlas, graph)?;
        Ok(map)
    }

    /// Checks the map has one entry per texel of `atlas` and names nodes of `graph`.
    ///
    /// # Errors
    /// [`TexelMapError::Length`] or [`TexelMapError::Node`].
    pub fn fits(&self, atlas: &Atlas, graph: &LiquidGraph) -> Result<(), TexelMapError> {
        if self.nodes.len() != atlas.len() {
            return Err(TexelMapError::Length {
                len: self.nodes.len(),
                texels: atlas.len(),
            });
        }
        let n = graph.node_count();
        if let Some(texel) = self.nodes.iter().position(|&k| k as usize >= n) {
            return Err(TexelMapError::Node {
                texel,
                node: self.nodes[texel],
                nodes: n,
            });
        }
        Ok(())
    }

    /// Node index per texel.
    pub fn nodes(&self) -> &[u32] {
        &self.nodes
    }

    /// Node of texel `i`.
    #[inline]
    pub fn node(&self, i: usize) -> usize {
        self.nodes[i] as usize
    }

    /// Number of texels.
    pub fn len(&self) -> usize {
        self.nodes.len()
    }

    /// Whether the map is empty.
    pub fn is_empty(&self) -> bool {
        self.nodes.is_empty()
    }
}
