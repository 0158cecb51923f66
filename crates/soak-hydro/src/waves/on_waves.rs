//! The water a body floats on over interactive waves ([`OnWaves`]).

use super::InteractiveWaves;

/// `base` with the waves on it, less one body's own depression: what
/// [`InteractiveWaves::water_for`] samples.
pub(super) struct OnWaves<'a> {
    pub(super) base: &'a dyn crate::Surface,
    pub(super) waves: &'a InteractiveWaves,
    /// The body's own cells and depths, in increasing cell order.
    pub(super) own: &'a [(usize, f64)],
}

impl OnWaves<'_> {
    fn cell_value(&self, ix: i64, iz: i64) -> f64 {
        let n = self.waves.region.cells as i64;
        if !((0..n).contains(&ix) && (0..n).contains(&iz)) {
            return 0.0;
        }
        let cell = (iz * n + ix) as usize;
        let own = self
            .own
            .binary_search_by_key(&cell, |&(c, _)| c)
            .map_or(0.0, |i| self.own[i].1);
        self.waves.h[cell] + own
    }
}

impl crate::Surface for OnWaves<'_> {
    fn height(&self, x: f64, z: f64, t: f64) -> f64 {
        self.base.height(x, z, t) + self.waves.field(x, z, |i, j| self.cell_value(i, j)).0
    }

    fn velocity(&self, p: &nalgebra::Point3<f64>, t: f64) -> nalgebra::Vector3<f64> {
        self.base.velocity(p, t)
    }

    fn slope(&self, x: f64, z: f64, t: f64, hint: &[f64; 2]) -> [f64; 2] {
        let base = self.base.slope(x, z, t, hint);
        let (_, s) = self.waves.field(x, z, |i, j| self.cell_value(i, j));
        [base[0] + s[0], base[1] + s[1]]
    }

    /// The base's nodes as the base samples them (a spectral sea looks its
    /// tile up once and warm-starts each inversion from the last), the
    /// waves added at each.
    fn sample_nodes(
        &self,
        t: f64,
        origin: [f64; 2],
        spacing: f64,
        nodes: [usize; 2],
        out: &mut [crate::water::SurfaceNode],
    ) {
        self.base.sample_nodes(t, origin, spacing, nodes, out);
        for (k, node) in out.iter_mut().enumerate().take(nodes[0] * nodes[1]) {
            let [x, z] = crate::water::node_at(origin, spacing, nodes, k);
            let (h, s) = self.waves.field(x, z, |i, j| self.cell_value(i, j));
            node.height += h;
            node.slope = [node.slope[0] + s[0], node.slope[1] + s[1]];
            // The waves' twist is not sampled: the patch takes differences.
            node.twist = None;
        }
    }

    /// The base's velocity (the waves' own orbital velocity is not in it),
    /// without the depth a probe would find first.
    fn velocity_under(
        &self,
        p: &nalgebra::Point3<f64>,
        t: f64,
        _height: f64,
        _hint: &[f64; 2],
    ) -> nalgebra::Vector3<f64> {
        self.base.velocity(p, t)
    }
}
