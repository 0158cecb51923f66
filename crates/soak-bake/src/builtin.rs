//! Procedural meshes with bijective UV atlases: the test and demo fixtures.
//!
//! Every generator returns an outward-wound mesh whose UV charts are packed
//! at a common texel density; all are closed but the open containers
//! ([`open_box`], [`bucket`], [`open_boat`]), whose rims
//! [`cap_openings`](crate::cap_openings) closes. They are reachable by name wherever a
//! mesh is accepted, as `builtin:NAME[:PARAM...]` (see [`parse`]).

use std::f64::consts::{FRAC_PI_2, PI, TAU};

use nalgebra::{Point2, Point3};

use crate::error::LoadError;
use crate::mesh::Mesh;
use crate::pack::{DEFAULT_PADDING, pack_charts};

/// Collects charts (3-D vertices with 2-D chart coordinates) and packs them.
#[derive(Default)]
struct Builder {
    positions: Vec<Point3<f64>>,
    coords: Vec<Point2<f64>>,
    chart_of: Vec<u32>,
    triangles: Vec<[u32; 3]>,
    charts: u32,
}

impl Builder {
    fn begin_chart(&mut self) -> (u32, usize) {
        self.charts += 1;
        (self.positions.len() as u32, self.triangles.len())
    }

    fn vertex(&mut self, p: Point3<f64>, c: Point2<f64>) -> u32 {
        self.positions.push(p);
        self.coords.push(c);
        self.chart_of.push(self.charts - 1);
        (self.positions.len() - 1) as u32
    }

    /// Flips the triangles added since `first` if, seen from `inside`, they face inwards.
    fn orient_chart(&mut self, first: usize, inside: Point3<f64>) {
        let mut flux = 0.0;
        for t in &self.triangles[first..] {
            let [a, b, c] = t.map(|v| self.positions[v as usize]);
            flux += (a - inside).dot(&(b - a).cross(&(c - a)));
        }
        if flux < 0.0 {
            for t in &mut self.triangles[first..] {
                t.swap(1, 2);
            }
        }
    }

    fn finish(self, name: String) -> Mesh {
        let (uvs, _) = pack_charts(
            &self.coords,
            &self.chart_of,
            self.charts as usize,
            DEFAULT_PADDING,
        );
        Mesh::new(name, self.positions, Some(uvs), self.triangles)
    }

    /// A surface of revolution about the y axis as one chart. `profile` runs
    /// from top to bottom as `(radius, y)`; a zero radius at an end is a pole.
    /// The seam vertices at φ = 0 and φ = 2π are distinct (same position).
    fn revolution(&mut self, profile: &[(f64, f64)], segments: usize) {
        let (base, first) = self.begin_chart();
        let mut arc = vec![0.0];
        for w in profile.windows(2) {
            let d = ((w[1].0 - w[0].0).powi(2) + (w[1].1 - w[0].1).powi(2)).sqrt();
            arc.push(arc.last().unwrap() + d);
        }
        let rmax = profile.iter().map(|p| p.0).fold(0.0, f64::max);
        let cols = segments + 1;
        for (j, &(r, y)) in profile.iter().enumerate() {
            for i in 0..cols {
                let phi = TAU * (i % segments) as f64 / segments as f64;
                let p = if r == 0.0 {
                    Point3::new(0.0, y, 0.0)
                } else {
                    Point3::new(r * phi.cos(), y, r * phi.sin())
                };
                let c = Point2::new(rmax * TAU * i as f64 / segments as f64, -arc[j]);
                self.vertex(p, c);
            }
        }
        let idx = |i: usize, j: usize| base + (j * cols + i) as u32;
        for j in 0..profile.len() - 1 {
            for i in 0..segments {
                let (a, b, c, d) = (idx(i, j), idx(i + 1, j), idx(i, j + 1), idx(i + 1, j + 1));
                if profile[j].0 != 0.0 {
                    self.triangles.push([a, b, c]);
                }
                if profile[j + 1].0 != 0.0 {
                    self.triangles.push([b, d, c]);
                }
            }
        }
        let ymid = 0.5 * (profile[0].1 + profile[profile.len() - 1].1);
        self.orient_chart(first, Point3::new(0.0, ymid, 0.0));
    }

    /// A planar quad `c` (corners in order around it) as one chart, wound
    /// so its normal points along `out`.
    fn quad(&mut self, c: [Point3<f64>; 4], out: nalgebra::Vector3<f64>) {
        let (_, first) = self.begin_chart();
        let e1 = (c[1] - c[0]).normalize();
        let e2 = out.normalize().cross(&e1);
        let ids = c.map(|p| self.vertex(p, Point2::new((p - c[0]).dot(&e1), (p - c[0]).dot(&e2))));
        self.triangles.push([ids[0], ids[1], ids[2]]);
        self.triangles.push([ids[0], ids[2], ids[3]]);
        let n = (c[1] - c[0]).cross(&(c[2] - c[0]));
        if n.dot(&out) < 0.0 {
            for t in &mut self.triangles[first..] {
                t.swap(1, 2);
            }
        }
    }

    /// A flat disk at height `y` as one fan chart.
    fn disk(&mut self, radius: f64, y: f64, segments: usize, inside: Point3<f64>) {
        let (_, first) = self.begin_chart();
        let centre = self.vertex(Point3::new(0.0, y, 0.0), Point2::origin());
        let rim: Vec<u32> = (0..segments)
            .map(|k| {
                let phi = TAU * k as f64 / segments as f64;
                let (x, z) = (radius * phi.cos(), radius * phi.sin());
                self.vertex(Point3::new(x, y, z), Point2::new(x, z))
            })
            .collect();
        for k in 0..segments {
            self.triangles.push([centre, rim[k], rim[(k + 1) % segments]]);
        }
        self.orient_chart(first, inside);
    }
}

/// UV sphere of `radius` (m) with `segments` around and `rings` from pole to
/// pole, one latitude–longitude chart.
pub fn sphere(radius: f64, segments: usize, rings: usize) -> Mesh {
    let (segments, rings) = (segments.max(3), rings.max(2));
    let profile: Vec<(f64, f64)> = (0..=rings)
        .map(|j| {
            let theta = PI * j as f64 / rings as f64;
            let r = if j == 0 || j == rings {
                0.0
            } else {
                radius * theta.sin()
            };
            (r, radius * theta.cos())
        })
        .collect();
    let mut b = Builder::default();
    b.revolution(&profile, segments);
    b.finish(format!("builtin:sphere:{radius}:{segments}:{rings}"))
}

/// Axis-aligned box centred at the origin with the given full sizes (m),
/// six planar charts of two triangles each.
pub fn cuboid(sx: f64, sy: f64, sz: f64) -> Mesh {
    let (hx, hy, hz) = (sx / 2.0, sy / 2.0, sz / 2.0);
    let mut b = Builder::default();
    // (normal axis, sign): the face's two in-plane axes follow.
    for (axis, sign) in [(0, 1.0), (0, -1.0), (1, 1.0), (1, -1.0), (2, 1.0), (2, -1.0)] {
        let (_, first) = b.begin_chart();
        let (u_ax, v_ax) = ((axis + 1) % 3, (axis + 2) % 3);
        let half = [hx, hy, hz];
        let mut ids = [0u32; 4];
        for (k, (su, sv)) in [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)]
            .into_iter()
            .enumerate()
        {
            let mut p = [0.0; 3];
            p[axis] = sign * half[axis];
            p[u_ax] = su * half[u_ax];
            p[v_ax] = sv * half[v_ax];
            ids[k] = b.vertex(Point3::from(p), Point2::new(p[u_ax], p[v_ax]));
        }
        b.triangles.push([ids[0], ids[1], ids[2]]);
        b.triangles.push([ids[0], ids[2], ids[3]]);
        b.orient_chart(first, Point3::origin());
    }
    b.finish(format!("builtin:box:{sx}x{sy}x{sz}"))
}

/// Open-topped box of outer sizes `sx`×`sy`×`sz` (m), centred at the origin:
/// the cuboid without its top (+y) face, a single surface (no wall
/// thickness), one rim at `y = sy/2`.
pub fn open_box(sx: f64, sy: f64, sz: f64) -> Mesh {
    let mut mesh = cuboid(sx, sy, sz);
    let hy = sy / 2.0;
    mesh.triangles.retain(|t| {
        !t.iter()
            .all(|&v| (mesh.positions[v as usize].y - hy).abs() <= 1e-12 * (1.0 + hy.abs()))
    });
    mesh.name = format!("builtin:open_box:{sx}x{sy}x{sz}");
    mesh
}

/// Open-topped box with walls of thickness `t` (m), modelled as one closed
/// surface — outside, the rim's flat top, inside — as most assets of
/// containers are: outer sizes `sx`×`sy`×`sz`, centred at the origin, the
/// cavity `(sx − 2t)`×`(sy − t)`×`(sz − 2t)` open at `y = sy/2`. Closed: its
/// cavity is found by [`cap_cavities`](crate::cap_cavities).
pub fn thick_open_box(sx: f64, sy: f64, sz: f64, t: f64) -> Mesh {
    use nalgebra::Vector3;
    let (hx, hy, hz) = (sx / 2.0, sy / 2.0, sz / 2.0);
    let (ix, iz, floor) = (hx - t, hz - t, -hy + t);
    let p = Point3::new;
    let mut b = Builder::default();
    // Outside: bottom and four sides.
    b.quad(
        [p(-hx, -hy, -hz), p(hx, -hy, -hz), p(hx, -hy, hz), p(-hx, -hy, hz)],
        -Vector3::y(),
    );
    for (sign, axis) in [(1.0, 0), (-1.0, 0), (1.0, 2), (-1.0, 2)] {
        let (u, w) = if axis == 0 {
            (hx * sign, hz)
        } else {
            (hz * sign, hx)
        };
        let at = |a: f64, y: f64| if axis == 0 { p(u, y, a) } else { p(a, y, u) };
        let out = if axis == 0 {
            Vector3::x() * sign
        } else {
            Vector3::z() * sign
        };
        b.quad([at(-w, -hy), at(w, -hy), at(w, hy), at(-w, hy)], out);
    }
    // The rim's top: a frame between the outer and inner squares.
    let outer = [p(-hx, hy, -hz), p(hx, hy, -hz), p(hx, hy, hz), p(-hx, hy, hz)];
    let inner = [p(-ix, hy, -iz), p(ix, hy, -iz), p(ix, hy, iz), p(-ix, hy, iz)];
    for k in 0..4 {
        let j = (k + 1) % 4;
        b.quad([outer[k], outer[j], inner[j], inner[k]], Vector3::y());
    }
    // Inside: the cavity's four walls and floor, facing into it.
    b.quad(
        [
            p(-ix, floor, -iz),
            p(ix, floor, -iz),
            p(ix, floor, iz),
            p(-ix, floor, iz),
        ],
        Vector3::y(),
    );
    for (sign, axis) in [(1.0, 0), (-1.0, 0), (1.0, 2), (-1.0, 2)] {
        let (u, w) = if axis == 0 {
            (ix * sign, iz)
        } else {
            (iz * sign, ix)
        };
        let at = |a: f64, y: f64| if axis == 0 { p(u, y, a) } else { p(a, y, u) };
        let into = if axis == 0 {
            -Vector3::x() * sign
        } else {
            -Vector3::z() * sign
        };
        b.quad([at(-w, floor), at(w, floor), at(w, hy), at(-w, hy)], into);
    }
    b.finish(format!("builtin:thick_open_box:{sx}x{sy}x{sz}:{t}"))
}

/// Bucket about the y axis: a cylinder of `radius` and `height` (m),
/// centred at the origin, without its top disk: side and bottom, a single
/// surface, one rim at `y = height/2`.
pub fn bucket(radius: f64, height: f64, segments: usize) -> Mesh {
    let segments = segments.max(3);
    let h = height / 2.0;
    let mut b = Builder::default();
    b.revolution(&[(radius, h), (radius, -h)], segments);
    b.disk(radius, -h, segments, Point3::origin());
    b.finish(format!("builtin:bucket:{radius}:{height}:{segments}"))
}

/// Closed cylinder about the y axis, centred at the origin: a side chart and two cap charts.
pub fn cylinder(radius: f64, height: f64, segments: usize) -> Mesh {
    let segments = segments.max(3);
    let h = height / 2.0;
    let mut b = Builder::default();
    b.revolution(&[(radius, h), (radius, -h)], segments);
    b.disk(radius, h, segments, Point3::origin());
    b.disk(radius, -h, segments, Point3::origin());
    b.finish(format!("builtin:cylinder:{radius}:{height}:{segments}"))
}

/// Capsule about the y axis: a cylinder of `height` (between the hemisphere
/// centres) capped by hemispheres of `radius`; one chart.
pub fn capsule(radius: f64, height: f64, segments: usize) -> Mesh {
    let segments = segments.max(4);
    let rings = (segments / 4).max(2);
    let h = height / 2.0;
    let mut profile = Vec::new();
    for j in 0..=rings {
        let theta = FRAC_PI_2 * j as f64 / rings as f64;
        let r = if j == 0 { 0.0 } else { radius * theta.sin() };
        profile.push((r, h + radius * theta.cos()));
    }
    for j in 0..=rings {
        let theta = FRAC_PI_2 + FRAC_PI_2 * j as f64 / rings as f64;
        let r = if j == rings { 0.0 } else { radius * theta.sin() };
        profile.push((r, -h + radius * theta.cos()));
    }
    let mut b = Builder::default();
    b.revolution(&profile, segments);
    b.finish(format!("builtin:capsule:{radius}:{height}:{segments}"))
}

/// Torus about the y axis with major radius `major` and tube radius `minor`
/// (m), one chart with seams in both directions.
pub fn torus(major: f64, minor: f64, segments: usize, sides: usize) -> Mesh {
    let (segments, sides) = (segments.max(4), sides.max(3));
    let mut b = Builder::default();
    // Four charts around the ring keep each chart's aspect near square.
    let chunks = 4;
    for chunk in 0..chunks {
        let (i0, i1) = (chunk * segments / chunks, (chunk + 1) * segments / chunks);
        let (base, first) = b.begin_chart();
        for j in 0..=sides {
            let psi = TAU * (j % sides) as f64 / sides as f64;
            for i in i0..=i1 {
                let phi = TAU * (i % segments) as f64 / segments as f64;
                let rr = major + minor * psi.cos();
                let p = Point3::new(rr * phi.cos(), minor * psi.sin(), rr * phi.sin());
                let c = Point2::new(
                    (major + minor) * TAU * i as f64 / segments as f64,
                    minor * TAU * j as f64 / sides as f64,
                );
                b.vertex(p, c);
            }
        }
        let cols = i1 - i0 + 1;
        let idx = |i: usize, j: usize| base + (j * cols + (i - i0)) as u32;
        for j in 0..sides {
            for i in i0..i1 {
                let (a, bb, c, d) = (idx(i, j), idx(i + 1, j), idx(i, j + 1), idx(i + 1, j + 1));
                b.triangles.push([a, c, bb]);
                b.triangles.push([bb, c, d]);
            }
        }
        // Outward is away from the tube's centre line.
        let [p0, p1, p2] = b.triangles[first].map(|v| b.positions[v as usize]);
        let n = (p1 - p0).cross(&(p2 - p0));
        let centroid = (p0.coords + p1.coords + p2.coords) / 3.0;
        let ring = nalgebra::Vector3::new(centroid.x, 0.0, centroid.z).normalize() * major;
        if n.dot(&(centroid - ring)) < 0.0 {
            for t in &mut b.triangles[first..] {
                t.swap(1, 2);
            }
        }
    }
    b.finish(format!("builtin:torus:{major}:{minor}:{segments}:{sides}"))
}

/// A boat hull of `length` (x), `beam` (z) and `depth` (y, keel at 0, deck at
/// `depth`), closed by a flat deck lid so it is watertight: a hull chart and a
/// deck chart. The bow points to +x and rises slightly; the stern is fuller.
pub fn boat(length: f64, beam: f64, depth: f64) -> Mesh {
    boat_hull(length, beam, depth, true)
}

/// [`boat`] without its deck: a rowing boat's open hull (a single surface),
/// one rim along the gunwale at `y = depth`.
pub fn open_boat(length: f64, beam: f64, depth: f64) -> Mesh {
    let mut mesh = boat_hull(length, beam, depth, false);
    mesh.name = format!("builtin:open_boat:{length}x{beam}x{depth}");
    mesh
}

fn boat_hull(length: f64, beam: f64, depth: f64, deck: bool) -> Mesh {
    let stations = 40;
    let half_sections = 12;
    let half_width = |s: f64| if s >= 0.0 { 1.0 - s * s } else { 1.0 - s.powi(4) };
    let keel = |s: f64| depth * 0.35 * s.max(0.0).powi(3);
    let mut b = Builder::default();
    let inside = Point3::new(0.0, depth * 0.5, 0.0);

    // Hull: rows of stations from stern (s = −1) to bow (s = 1), columns from
    // the port deck edge round the keel to the starboard deck edge.
    let (base, first) = b.begin_chart();
    let cols = 2 * half_sections + 1;
    let girth = depth + beam / 2.0;
    for i in 0..=stations {
        let s = -1.0 + 2.0 * i as f64 / stations as f64;
        let w = beam / 2.0 * half_width(s);
        let k = keel(s);
        for j in 0..cols {
            // Symmetric in j so port and starboard stem vertices weld exactly.
            let theta = PI * (j as f64 - half_sections as f64) / (cols - 1) as f64;
            let z = if i == 0 || i == stations {
                0.0
            } else {
                w * theta.sin()
            };
            let y = if j == 0 || j == cols - 1 {
                depth
            } else {
                k + (depth - k) * (1.0 - theta.cos())
            };
            b.vertex(
                Point3::new(s * length / 2.0, y, z),
                Point2::new(s * length / 2.0, girth * theta / PI),
            );
        }
    }
    let idx = |i: usize, j: usize| base + (i * cols + j) as u32;
    for i in 0..stations {
        for j in 0..cols - 1 {
            let (a, bb, c, d) = (idx(i, j), idx(i + 1, j), idx(i + 1, j + 1), idx(i, j + 1));
            b.triangles.push([a, bb, c]);
            b.triangles.push([a, c, d]);
        }
    }
    b.orient_chart(first, inside);
    if !deck {
        return b.finish(format!("builtin:boat:{length}x{beam}x{depth}"));
    }

    // Deck lid, planar in (x, z).
    let (_, first) = b.begin_chart();
    let mut port = Vec::new();
    let mut starboard = Vec::new();
    for i in 0..=stations {
        let s = -1.0 + 2.0 * i as f64 / stations as f64;
        let x = s * length / 2.0;
        if i == 0 || i == stations {
            let v = b.vertex(Point3::new(x, depth, 0.0), Point2::new(x, 0.0));
            port.push(v);
            starboard.push(v);
        } else {
            let w = beam / 2.0 * half_width(s);
            port.push(b.vertex(Point3::new(x, depth, -w), Point2::new(x, -w)));
            starboard.push(b.vertex(Point3::new(x, depth, w), Point2::new(x, w)));
        }
    }
    for i in 0..stations {
        if i > 0 {
            b.triangles.push([port[i], port[i + 1], starboard[i]]);
        }
        if i + 1 < stations {
            b.triangles.push([starboard[i], port[i + 1], starboard[i + 1]]);
        }
    }
    // The lid faces up (+y).
    let lid_up = {
        let t = b.triangles[first];
        let [p0, p1, p2] = t.map(|v| b.positions[v as usize]);
        (p1 - p0).cross(&(p2 - p0)).y > 0.0
    };
    if !lid_up {
        for t in &mut b.triangles[first..] {
            t.swap(1, 2);
        }
    }
    b.finish(format!("builtin:boat:{length}x{beam}x{depth}"))
}

/// Dumbbell about the y axis: two spheres of `radius` whose centres are
/// `separation` apart, joined by a neck (cylinder) of `neck_radius`; one
/// chart. `neck_radius` must be below `radius` and the spheres must not touch.
pub fn dumbbell(radius: f64, neck_radius: f64, separation: f64, segments: usize) -> Mesh {
    let segments = segments.max(4);
    let rings = (segments / 2).max(4);
    let c = separation / 2.0;
    // Polar angle (from the top) where the top sphere meets the neck.
    let theta_join = PI - (neck_radius / radius).asin();
    let mut profile = Vec::new();
    for j in 0..=rings {
        let theta = theta_join * j as f64 / rings as f64;
        let r = if j == 0 { 0.0 } else { radius * theta.sin() };
        profile.push((r, c + radius * theta.cos()));
    }
    let neck_top = profile.last().expect("rings > 0").1;
    let neck_rows = 6;
    for j in 1..neck_rows {
        let y = neck_top - 2.0 * neck_top * j as f64 / neck_rows as f64;
        profile.push((neck_radius, y));
    }
    for j in 0..=rings {
        let theta = (PI - theta_join) + theta_join * j as f64 / rings as f64;
        let r = if j == rings { 0.0 } else { radius * theta.sin() };
        profile.push((r, -c + radius * theta.cos()));
    }
    let mut b = Builder::default();
    b.revolution(&profile, segments);
    b.finish(format!(
        "builtin:dumbbell:{radius}:{neck_radius}:{separation}:{segments}"
    ))
}

/// The builtin names [`parse`] accepts.
pub const NAMES: &[&str] = &[
    "sphere",
    "box",
    "cylinder",
    "capsule",
    "torus",
    "boat",
    "dumbbell",
    "open_box",
    "bucket",
    "open_boat",
];

/// Builds a mesh from a `builtin:` name.
///
/// | name | parameters (m) | default |
/// |---|---|---|
/// | `builtin:sphere[:R[:SEGMENTS[:RINGS]]]` | radius, segments, rings | `0.5:64:32` |
/// | `builtin:box[:SXxSYxSZ]` or `builtin:box:S` | sizes | `1x1x1` |
/// | `builtin:cylinder[:R[:H[:SEGMENTS]]]` | radius, height | `0.5:1:64` |
/// | `builtin:capsule[:R[:H[:SEGMENTS]]]` | radius, cylinder height | `0.25:0.5:48` |
/// | `builtin:torus[:R[:r[:SEGMENTS[:SIDES]]]]` | major, minor radius | `0.5:0.15:64:32` |
/// | `builtin:boat[:LxBxD]` | length, beam, depth | `4x1.2x0.6` |
/// | `builtin:dumbbell[:R[:r[:SEP[:SEGMENTS]]]]` | sphere radius, neck radius, centre distance | `0.3:0.08:1.2:48` |
/// | `builtin:open_box[:SXxSYxSZ]` (open) | outer sizes | `1x0.5x1` |
/// | `builtin:bucket[:R[:H[:SEGMENTS]]]` (open) | radius, height | `0.3:0.6:64` |
/// | `builtin:open_boat[:LxBxD]` (open) | length, beam, depth | `4x1.2x0.6` |
/// | `builtin:thick_open_box[:SXxSYxSZ[:T]]` (closed, a cavity) | outer sizes, wall thickness | `1x0.5x1:0.05` |
pub fn parse(name: &str) -> Result<Mesh, LoadError> {
    let err = |reason: String| LoadError::Builtin {
        name: name.to_string(),
        reason,
    };
    let rest = name
        .strip_prefix("builtin:")
        .ok_or_else(|| err("a builtin name starts with `builtin:`".into()))?;
    let mut parts = rest.split(':');
    let kind = parts.next().unwrap_or_default();
    let params: Vec<&str> = parts.collect();
    let num = |i: usize, default: f64, what: &str| -> Result<f64, LoadError> {
        match params.get(i) {
            None => Ok(default),
            Some(s) => match s.parse::<f64>() {
                Ok(v) if v.is_finite() && v > 0.0 => Ok(v),
                _ => Err(err(format!("{what} `{s}` is not a positive number"))),
            },
        }
    };
    let count = |i: usize, default: usize, min: usize, what: &str| -> Result<usize, LoadError> {
        match params.get(i) {
            None => Ok(default),
            Some(s) => match s.parse::<usize>() {
                Ok(v) if (min..=4096).contains(&v) => Ok(v),
                _ => Err(err(format!("{what} `{s}` is not a whole number in {min}..=4096"))),
            },
        }
    };
    let sizes = |i: usize, default: [f64; 3]| -> Result<[f64; 3], LoadError> {
        let Some(s) = params.get(i) else {
            return Ok(default);
        };
        let v: Vec<&str> = s.split('x').collect();
        let parse = |t: &str| t.parse::<f64>().ok().filter(|v| v.is_finite() && *v > 0.0);
        match v.as_slice() {
            [a] => parse(a).map(|a| [a, a, a]),
            [a, b, c] => match (parse(a), parse(b), parse(c)) {
                (Some(a), Some(b), Some(c)) => Some([a, b, c]),
                _ => None,
            },
            _ => None,
        }
        .ok_or_else(|| err(format!("size `{s}` is not S or AxBxC with positive numbers")))
    };
    let max_params = match kind {
        "sphere" | "cylinder" | "capsule" | "bucket" => 3,
        "torus" | "dumbbell" => 4,
        "box" | "boat" | "open_box" | "open_boat" => 1,
        "thick_open_box" => 2,
        other => {
            return Err(err(format!(
                "unknown builtin `{other}` (known: {})",
                NAMES.join(", ")
            )));
        }
    };
    if params.len() > max_params {
        return Err(err(format!("`{kind}` takes at most {max_params} parameters")));
    }
    let mut mesh = match kind {
        "sphere" => {
            let segments = count(1, 64, 3, "segments")?;
            sphere(
                num(0, 0.5, "radius")?,
                segments,
                count(2, segments / 2, 2, "rings")?,
            )
        }
        "box" => {
            let [a, b, c] = sizes(0, [1.0; 3])?;
            cuboid(a, b, c)
        }
        "cylinder" => cylinder(
            num(0, 0.5, "radius")?,
            num(1, 1.0, "height")?,
            count(2, 64, 3, "segments")?,
        ),
        "capsule" => capsule(
            num(0, 0.25, "radius")?,
            num(1, 0.5, "height")?,
            count(2, 48, 4, "segments")?,
        ),
        "torus" => {
            let (major, minor) = (num(0, 0.5, "major radius")?, num(1, 0.15, "minor radius")?);
            if minor >= major {
                return Err(err(format!(
                    "minor radius {minor} must be below the major radius {major}"
                )));
            }
            torus(
                major,
                minor,
                count(2, 64, 3, "segments")?,
                count(3, 32, 3, "sides")?,
            )
        }
        "boat" => {
            let [l, b, d] = sizes(0, [4.0, 1.2, 0.6])?;
            boat(l, b, d)
        }
        "open_boat" => {
            let [l, b, d] = sizes(0, [4.0, 1.2, 0.6])?;
            open_boat(l, b, d)
        }
        "open_box" => {
            let [a, b, c] = sizes(0, [1.0, 0.5, 1.0])?;
            open_box(a, b, c)
        }
        "thick_open_box" => {
            let [a, b, c] = sizes(0, [1.0, 0.5, 1.0])?;
            let t = num(1, 0.05, "wall thickness")?;
            if 2.0 * t >= a.min(c) || t >= b {
                return Err(err(format!("walls {t} m thick leave no cavity in {a}x{b}x{c}")));
            }
            thick_open_box(a, b, c, t)
        }
        "bucket" => bucket(
            num(0, 0.3, "radius")?,
            num(1, 0.6, "height")?,
            count(2, 64, 3, "segments")?,
        ),
        "dumbbell" => {
            let (r, neck, sep) = (
                num(0, 0.3, "radius")?,
                num(1, 0.08, "neck radius")?,
                num(2, 1.2, "separation")?,
            );
            if neck >= r || sep <= 2.0 * r {
                return Err(err(format!(
                    "needs neck radius {neck} < radius {r} and separation {sep} > 2 x radius"
                )));
            }
            dumbbell(r, neck, sep, count(3, 48, 4, "segments")?)
        }
        _ => unreachable!("kind checked above"),
    };
    mesh.name = name.to_string();
    Ok(mesh)
}
