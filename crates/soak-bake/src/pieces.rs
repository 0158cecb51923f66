//! The pieces of surface among a tile's samples: a tile is a block of the
//! texture, and a block can hold samples of charts of the UV map laid side
//! by side in the texture but apart on the mesh. A tile of samples apart
//! on the mesh has a bounding sphere spanning them all: the tiled
//! evaluations could then seldom settle it wholly under or over the water
//! or read the water over it from one polynomial. So the bake and the
//! coarsening lay one tile per piece.

use nalgebra::Vector3;

/// Samples closer than this many times the largest texel side `√a` of
/// their block are of one piece of surface. Neighbouring samples of one
/// chart are a side apart, diagonal ones √2 (a block cut by a chart's edge,
/// or a texel shared by two triangles, a little more).
pub(crate) const PIECE_LINK: f64 = 2.0;

/// The pieces among the samples at `points` (one block's), chained by
/// single linkage within `link`: the samples' order piece by piece (each
/// piece's samples in their order, the pieces in the order of their first
/// sample), and where each piece ends in it.
pub(crate) fn pieces(points: &[Vector3<f64>], link: f64) -> (Vec<usize>, Vec<usize>) {
    let n = points.len();
    let mut parent: Vec<usize> = (0..n).collect();
    fn root(parent: &mut [usize], mut i: usize) -> usize {
        while parent[i] != i {
            parent[i] = parent[parent[i]];
            i = parent[i];
        }
        i
    }
    let link2 = link * link;
    for i in 0..n {
        for j in i + 1..n {
            if (points[i] - points[j]).norm_squared() <= link2 {
                let (a, b) = (root(&mut parent, i), root(&mut parent, j));
                parent[a.max(b)] = a.min(b);
            }
        }
    }
    // Every root is the least index of its piece.
    let roots: Vec<usize> = (0..n).map(|i| root(&mut parent, i)).collect();
    let mut order = Vec::with_capacity(n);
    let mut ends = Vec::new();
    for piece in (0..n).filter(|&i| roots[i] == i) {
        order.extend((piece..n).filter(|&i| roots[i] == piece));
        ends.push(order.len());
    }
    (order, ends)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Two rows of samples a side apart, the second far from the first:
    /// two pieces, each in its order; a chain of samples each a side from
    /// the next is one piece however long.
    #[test]
    fn samples_apart_are_pieces_and_chains_are_one() {
        let at = |x: f64, y: f64| Vector3::new(x, y, 0.0);
        let points = [
            at(0.0, 0.0),
            at(5.0, 0.0),
            at(1.0, 0.0),
            at(6.0, 0.0),
            at(2.0, 0.0),
        ];
        assert_eq!(pieces(&points, 1.5), (vec![0, 2, 4, 1, 3], vec![3, 5]));
        let chain: Vec<_> = (0..40).map(|i| at(i as f64, 0.0)).collect();
        assert_eq!(pieces(&chain, 1.0).1, vec![40]);
        assert_eq!(pieces(&chain, 0.9).1, (1..=40).collect::<Vec<_>>());
        assert_eq!(pieces(&[], 1.0), (vec![], vec![]));
    }

    /// The box's faces are charts laid side by side in its texture: its
    /// bake lays a block's texels of two faces as two tiles, one after the
    /// other, each within a block of one chart (a tile of the box spanned
    /// two faces, 1.9 m, before), and no sample is lost or moved.
    #[test]
    fn a_bake_lays_a_tile_per_piece() {
        use crate::{Atlas, BakeOptions, builtin};
        let atlas = Atlas::bake(&builtin::cuboid(1.0, 0.6, 0.8), BakeOptions::square(128)).unwrap();
        let position = |i: usize| Vector3::from(atlas.local_positions().get(i).map(f64::from));
        let side = atlas
            .areas()
            .iter()
            .map(|&a| f64::from(a).sqrt())
            .fold(0.0, f64::max);
        let ts = atlas.tile_size();
        let block = |i: usize| {
            let [x, y] = atlas.texels()[i];
            (u32::from(y) / ts, u32::from(x) / ts)
        };
        let (mut split, mut seen, mut next) = (0, std::collections::HashSet::new(), 0);
        let mut last = None;
        for tile in atlas.tiles() {
            assert_eq!(tile.start as usize, next);
            let r = tile.range();
            let b = block(r.start);
            assert!(r.clone().all(|i| block(i) == b));
            if last == Some(b) {
                split += 1;
            } else {
                assert!(seen.insert(b), "block {b:?} in runs apart");
            }
            last = Some(b);
            let centre = r.clone().map(position).sum::<Vector3<f64>>() / r.len() as f64;
            let radius = r
                .clone()
                .map(|i| (position(i) - centre).norm())
                .fold(0.0, f64::max);
            // A block of one chart: 8 × 8 texels of about `side`.
            assert!(radius <= 6.0 * side, "radius {radius} against a side of {side}");
            next = r.end;
        }
        assert_eq!(next, atlas.len());
        assert!(split > 0, "no block of the box's texture holds two faces");
        // The same samples as the texture's row-major order within blocks.
        let mut texels: Vec<_> = atlas.texels().to_vec();
        texels.sort_unstable();
        texels.dedup();
        assert_eq!(texels.len(), atlas.len());
    }
}
