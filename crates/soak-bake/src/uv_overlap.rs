//! Detection of overlapping triangles in the plane (UV bijectivity).

use nalgebra::Point2;

/// Tolerance, in UV units, below which touching triangles are not overlapping.
const TOUCH_EPS: f64 = 1e-10;

/// The first pair `(i, j)` (`i < j`, by position in `tris`) of triangles whose
/// interiors overlap, or `None` if the triangles tile the plane bijectively.
///
/// `tris[k]` are the 2-D corners of triangle `k`. A uniform grid buckets the
/// triangles; each candidate pair is tested once by [`triangles_overlap`].
pub fn find_overlap(tris: &[[Point2<f64>; 3]]) -> Option<(usize, usize)> {
    if tris.len() < 2 {
        return None;
    }
    let (mut lo, mut hi) = (Point2::new(f64::MAX, f64::MAX), Point2::new(f64::MIN, f64::MIN));
    for t in tris {
        for p in t {
            lo = lo.inf(p);
            hi = hi.sup(p);
        }
    }
    let n = ((tris.len() as f64).sqrt().ceil() as usize).clamp(1, 2048);
    let ext = (hi - lo).map(|e| e.max(1e-300));
    let cell = |p: &Point2<f64>| -> (usize, usize) {
        let fx = ((p.x - lo.x) / ext.x * n as f64).floor();
        let fy = ((p.y - lo.y) / ext.y * n as f64).floor();
        (
            (fx.max(0.0) as usize).min(n - 1),
            (fy.max(0.0) as usize).min(n - 1),
        )
    };
    let boxes: Vec<(Point2<f64>, Point2<f64>)> = tris
        .iter()
        .map(|t| (t[0].inf(&t[1]).inf(&t[2]), t[0].sup(&t[1]).sup(&t[2])))
        .collect();
    let mut entries: Vec<(u32, u32)> = Vec::with_capacity(tris.len() * 2);
    for (k, (bl, bh)) in boxes.iter().enumerate() {
        let (x0, y0) = cell(bl);
        let (x1, y1) = cell(bh);
        for y in y0..=y1 {
            for x in x0..=x1 {
                entries.push(((y * n + x) as u32, k as u32));
            }
        }
    }
    entries.sort_unstable();
    let mut best: Option<(usize, usize)> = None;
    let mut start = 0;
    while start < entries.len() {
        let c = entries[start].0;
        let mut end = start;
        while end < entries.len() && entries[end].0 == c {
            end += 1;
        }
        let group = &entries[start..end];
        let (cx, cy) = ((c as usize) % n, (c as usize) / n);
        for (gi, &(_, a)) in group.iter().enumerate() {
            for &(_, b) in &group[gi + 1..] {
                let (a, b) = (a as usize, b as usize);
                let (la, ha) = boxes[a];
                let (lb, hb) = boxes[b];
                if la.x > hb.x + TOUCH_EPS
                    || lb.x > ha.x + TOUCH_EPS
                    || la.y > hb.y + TOUCH_EPS
                    || lb.y > ha.y + TOUCH_EPS
                {
                    continue;
                }
                // Test each pair in one cell only: the one holding the lower
                // corner of the boxes' intersection.
                if cell(&la.sup(&lb)) != (cx, cy) {
                    continue;
                }
                if triangles_overlap(&tris[a], &tris[b]) {
                    let pair = (a.min(b), a.max(b));
                    if best.is_none_or(|q| pair < q) {
                        best = Some(pair);
                    }
                }
            }
        }
        start = end;
    }
    best
}

/// Whether the interiors of two triangles overlap by more than the tolerance,
/// by the separating-axis theorem with a small tolerance (10⁻¹⁰ UV units) so
/// that triangles which only share an edge or a vertex do not count as
/// overlapping.
pub fn triangles_overlap(a: &[Point2<f64>; 3], b: &[Point2<f64>; 3]) -> bool {
    for tri in [a, b] {
        for k in 0..3 {
            let e = tri[(k + 1) % 3] - tri[k];
            let len = e.norm();
            if len == 0.0 {
                continue;
            }
            let axis = nalgebra::Vector2::new(-e.y, e.x) / len;
            let (amin, amax) = project(a, &axis);
            let (bmin, bmax) = project(b, &axis);
            if amax <= bmin + TOUCH_EPS || bmax <= amin + TOUCH_EPS {
                return false;
            }
        }
    }
    true
}

fn project(t: &[Point2<f64>; 3], axis: &nalgebra::Vector2<f64>) -> (f64, f64) {
    let d = [
        t[0].coords.dot(axis),
        t[1].coords.dot(axis),
        t[2].coords.dot(axis),
    ];
    (d[0].min(d[1]).min(d[2]), d[0].max(d[1]).max(d[2]))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn p(x: f64, y: f64) -> Point2<f64> {
        Point2::new(x, y)
    }

    #[test]
    fn shared_edge_and_shared_vertex_do_not_overlap() {
        let a = [p(0.0, 0.0), p(1.0, 0.0), p(0.0, 1.0)];
        let b = [p(1.0, 0.0), p(1.0, 1.0), p(0.0, 1.0)];
        let c = [p(1.0, 1.0), p(2.0, 1.0), p(1.0, 2.0)];
        assert!(!triangles_overlap(&a, &b));
        assert!(!triangles_overlap(&b, &c));
        assert_eq!(find_overlap(&[a, b, c]), None);
    }

    #[test]
    fn crossing_and_contained_triangles_overlap() {
        let a = [p(0.0, 0.0), p(1.0, 0.0), p(0.0, 1.0)];
        let inside = [p(0.1, 0.1), p(0.2, 0.1), p(0.1, 0.2)];
        let crossing = [p(0.4, 0.4), p(1.0, 1.0), p(0.2, 1.0)];
        let far = [p(5.0, 5.0), p(6.0, 5.0), p(5.0, 6.0)];
        assert_eq!(find_overlap(&[far, a, inside]), Some((1, 2)));
        assert_eq!(find_overlap(&[a, far, crossing]), Some((0, 2)));
    }
}
