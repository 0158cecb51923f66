//! Three-component vectors stored as three arrays, one per coordinate.

use serde::{Deserialize, Serialize};

/// A sequence of three-component `f32` vectors stored column-wise: all the
/// x coordinates, then all the y, then all the z, each in an array of its
/// own (a structure of arrays).
///
/// This is how an [`crate::Atlas`] holds its positions and area vectors: a
/// pass over the texels reads each coordinate as a contiguous run of
/// floats, which a processor loads straight into its vector registers,
/// where an array of `[f32; 3]` must first be shuffled apart lane by lane.
///
/// # Example
/// ```
/// use soak_bake::Columns;
///
/// let v: Columns = [[1.0, 2.0, 3.0], [4.0, 5.0, 6.0]].into_iter().collect();
/// assert_eq!(v.len(), 2);
/// assert_eq!(v.get(1), [4.0, 5.0, 6.0]);
/// assert_eq!(v.y(), &[2.0, 5.0]);
/// assert_eq!(v.iter().collect::<Vec<_>>(), vec![[1.0, 2.0, 3.0], [4.0, 5.0, 6.0]]);
/// ```
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct Columns {
    x: Vec<f32>,
    y: Vec<f32>,
    z: Vec<f32>,
}

impl Columns {
    /// An empty sequence with room for `n` vectors.
    pub fn with_capacity(n: usize) -> Self {
        Self {
            x: Vec::with_capacity(n),
            y: Vec::with_capacity(n),
            z: Vec::with_capacity(n),
        }
    }

    /// Number of vectors.
    #[inline]
    pub fn len(&self) -> usize {
        self.x.len()
    }

    /// Whether there is no vector.
    #[inline]
    pub fn is_empty(&self) -> bool {
        self.x.is_empty()
    }

    /// Vector `i`.
    ///
    /// # Panics
    /// If `i >= self.len()`, like indexing a slice.
    #[inline]
    pub fn get(&self, i: usize) -> [f32; 3] {
        [self.x[i], self.y[i], self.z[i]]
    }

    /// Appends a vector.
    #[inline]
    pub fn push(&mut self, v: [f32; 3]) {
        self.x.push(v[0]);
        self.y.push(v[1]);
        self.z.push(v[2]);
    }

    /// The x coordinates.
    #[inline]
    pub fn x(&self) -> &[f32] {
        &self.x
    }

    /// The y coordinates.
    #[inline]
    pub fn y(&self) -> &[f32] {
        &self.y
    }

    /// The z coordinates.
    #[inline]
    pub fn z(&self) -> &[f32] {
        &self.z
    }

    /// The three coordinate arrays `[x, y, z]`, each restricted to `range`.
    ///
    /// # Panics
    /// If `range` is out of bounds, like slicing.
    #[inline]
    pub fn columns(&self, range: std::ops::Range<usize>) -> [&[f32]; 3] {
        [&self.x[range.clone()], &self.y[range.clone()], &self.z[range]]
    }

    /// The three coordinate arrays, mutable.
    #[inline]
    pub(crate) fn columns_mut(&mut self) -> [&mut [f32]; 3] {
        [&mut self.x, &mut self.y, &mut self.z]
    }

    /// The vectors in order.
    pub fn iter(&self) -> impl ExactSizeIterator<Item = [f32; 3]> + Clone + '_ {
        (0..self.len()).map(|i| self.get(i))
    }

    /// The vectors as an array of `[f32; 3]` (a copy), for an API that
    /// wants them interleaved.
    pub fn to_vec(&self) -> Vec<[f32; 3]> {
        self.iter().collect()
    }
}

impl FromIterator<[f32; 3]> for Columns {
    fn from_iter<I: IntoIterator<Item = [f32; 3]>>(iter: I) -> Self {
        let iter = iter.into_iter();
        let mut v = Self::with_capacity(iter.size_hint().0);
        for x in iter {
            v.push(x);
        }
        v
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn columns_round_trip_interleaved_vectors() {
        let vs: Vec<[f32; 3]> = (0..10).map(|i| [i as f32, -(i as f32), 0.5 * i as f32]).collect();
        let c: Columns = vs.iter().copied().collect();
        assert_eq!(c.len(), 10);
        assert_eq!(c.to_vec(), vs);
        assert_eq!(
            c.columns(2..4),
            [&[2.0, 3.0][..], &[-2.0, -3.0][..], &[1.0, 1.5][..]]
        );
        for (i, v) in vs.iter().enumerate() {
            assert_eq!(c.get(i), *v);
        }
        assert!(Columns::default().is_empty());
    }
}
