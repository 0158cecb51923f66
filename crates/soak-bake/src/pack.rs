//! Packing charts into the unit square (shelf packing with padding).

use nalgebra::{Point2, Vector2};

/// Padding between charts and around the border, as a fraction of the packed side.
pub const DEFAULT_PADDING: f64 = 0.01;

/// Places charts side by side in the unit square at one common scale, so a
/// metre of surface covers the same number of texels in every chart (shelf
/// packing, with `padding` between charts and around the border).
///
/// `coords[v]` is vertex `v`'s position in its chart's plane (m) and
/// `chart_of[v]` its chart. Returns one UV per vertex, strictly inside
/// `[0, 1]²`, and the common scale (UV units per metre).
pub fn pack_charts(
    coords: &[Point2<f64>],
    chart_of: &[u32],
    n_charts: usize,
    padding: f64,
) -> (Vec<Point2<f64>>, f64) {
    assert_eq!(coords.len(), chart_of.len());
    let mut lo = vec![Point2::new(f64::MAX, f64::MAX); n_charts];
    let mut hi = vec![Point2::new(f64::MIN, f64::MIN); n_charts];
    for (p, &c) in coords.iter().zip(chart_of) {
        lo[c as usize] = lo[c as usize].inf(p);
        hi[c as usize] = hi[c as usize].sup(p);
    }
    let size: Vec<Vector2<f64>> = (0..n_charts)
        .map(|c| {
            if lo[c].x <= hi[c].x {
                hi[c] - lo[c]
            } else {
                Vector2::zeros()
            }
        })
        .collect();
    let area: f64 = size.iter().map(|s| s.x * s.y).sum::<f64>().max(1e-300);
    let pad = padding * area.sqrt();
    let padded_area: f64 = size.iter().map(|s| (s.x + pad) * (s.y + pad)).sum();
    let widest = size.iter().map(|s| s.x).fold(0.0, f64::max) + 2.0 * pad;
    let mut order: Vec<usize> = (0..n_charts).collect();
    order.sort_by(|&a, &b| size[b].y.total_cmp(&size[a].y).then(a.cmp(&b)));

    // Try a few shelf widths and keep the squarest packing.
    let mut best: Option<(f64, Vec<Vector2<f64>>)> = None;
    for k in 0..12 {
        let width = (padded_area.sqrt() * (0.8 + 0.1 * k as f64)).max(widest);
        let mut place = vec![Vector2::zeros(); n_charts];
        let (mut x, mut y, mut shelf) = (pad, pad, 0.0f64);
        let mut used_w = 0.0f64;
        for &c in &order {
            if x + size[c].x + pad > width && x > pad {
                y += shelf + pad;
                x = pad;
                shelf = 0.0;
            }
            place[c] = Vector2::new(x, y);
            x += size[c].x + pad;
            used_w = used_w.max(x);
            shelf = shelf.max(size[c].y);
        }
        let side = used_w.max(y + shelf + pad);
        if best.as_ref().is_none_or(|(s, _)| side < *s) {
            best = Some((side, place));
        }
    }
    let (side, place) = best.expect("at least one packing");
    let scale = 1.0 / side;
    let uvs = coords
        .iter()
        .zip(chart_of)
        .map(|(p, &c)| {
            let q = (p - lo[c as usize] + place[c as usize]) * scale;
            Point2::new(q.x.clamp(0.0, 1.0), q.y.clamp(0.0, 1.0))
        })
        .collect();
    (uvs, scale)
}
