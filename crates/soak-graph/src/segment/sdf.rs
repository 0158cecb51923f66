//! The Shape Diameter Function (SDF) per face: how thick the solid is under
//! each face, measured by rays cast inwards (Shapira, Shamir & Cohen-Or
//! 2008; CGAL's `Surface_mesh_segmentation` is the reference for defaults).
//!
//! For every face a cone of rays is cast from just inside its centroid
//! around the inward normal, through a BVH of the mesh (parry3d's
//! `TriMesh`). A ray counts only if the first surface it meets is seen from
//! behind (the ray leaves the solid there: hit normal · ray direction > 0).
//! The accepted distances are filtered to those within 1.5 median absolute
//! deviations of the median and averaged with weights by ray angle
//! ([`robust_mean`]). Faces without a value take their neighbours' mean, the
//! values are smoothed by a bilateral filter over face neighbourhoods,
//! normalised linearly to [0, 1] and compressed by [`log_normalize`].
//!
//! Jitter: each face turns the [`RayPattern`] by a random angle about its
//! normal (the pattern is laid out in the face's own frame, from its first
//! edge, so the rays turn with the mesh), moves its ray origin a random
//! sliver inside the surface ([`ORIGIN_OFFSET`]) and nudges every ray
//! ([`DIRECTION_JITTER`]): rays aimed exactly at vertices or edges would
//! otherwise slip through parry's f32 triangle tests.
//!
//! The hard outlier cut is discontinuous: a ray whose distance sits at the
//! 1.5-MAD boundary is in or out depending on a sub-degree tilt. On a
//! tessellated sphere this scatters raw per-face values by about ±2.5 %
//! around the analytic expectation; the bilateral filter brings them within
//! 2 %.
//!
//! Determinism: each face draws its jitter from its own ChaCha stream
//! (`seed`, stream = face index), so the result does not depend on how rayon
//! splits the work; all reductions run in a fixed order.

use std::f64::consts::{PI, TAU};

use nalgebra::{Point3, Vector3};
use parry3d::math::Vector as PVector;
use parry3d::query::{Ray, RayCast};
use parry3d::shape::TriMesh;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use rayon::prelude::*;
use serde::Serialize;
use soak_bake::Mesh;

use super::topology::Topology;
use super::{SegmentError, SegmentOptions};

/// Distances further than this many median absolute deviations from the
/// median are outliers (CGAL's acceptance window).
pub const MAD_WINDOW: f64 = 1.5;

/// Factor of the logarithmic compression `ln(F·x + 1) / ln(F + 1)` (CGAL's 5).
pub const LOG_FACTOR: f64 = 5.0;

/// Ray origins sit this fraction of the bounding-box diagonal inside the
/// surface (times a random factor in [1, 2)), so a ray never hits its own
/// face and never starts exactly on the surface. Distances are measured from
/// the face's plane (the stretch behind the origin is added back).
pub const ORIGIN_OFFSET: f64 = 1e-5;

/// Random perturbation of each ray's point on the sampling disk, in disk
/// radii (the disk of radius 1 maps to the cone's rim).
pub const DIRECTION_JITTER: f64 = 1e-3;

/// One ray of the sampling cone, before the per-face random rotation.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct RaySample {
    /// Point on the unit sampling disk (the disk's rim maps to the cone's rim).
    pub disk: [f64; 2],
    /// Angle between the ray and the cone axis (the inward normal), rad.
    pub angle: f64,
    /// Weight of the ray's distance in the average (dimensionless, ≤ 1).
    pub weight: f64,
}

/// The rays cast from every face: a Vogel (golden-angle) spiral on the unit
/// disk, mapped into a cone.
///
/// Sample `i` of `n` sits at radius `√((i + ½)/n)` and polar angle
/// `i·π(3 − √5)` (uniform density on the disk). The disk is placed at unit
/// distance along the cone axis and scaled by `tan(cone/2)`, so a sample at
/// disk radius `ρ` makes an angle `atan(ρ·tan(cone/2))` with the axis (this is
/// how CGAL maps its disk samples). Each ray's weight is a Gaussian of that
/// angle with σ = cone/3 — our reading of CGAL's angle-weighted average; the
/// rim rays of the default 120° cone weigh `e^{−9/8} ≈ 0.32`.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct RayPattern {
    samples: Vec<RaySample>,
    tan_half: f64,
}

impl RayPattern {
    /// The pattern of `rays` rays in a cone of `cone_degrees` (full angle, degrees).
    pub fn new(rays: usize, cone_degrees: f64) -> Self {
        let half = 0.5 * cone_degrees.to_radians();
        let tan_half = half.tan();
        let sigma = cone_degrees.to_radians() / 3.0;
        let golden = PI * (3.0 - 5f64.sqrt());
        let samples = (0..rays)
            .map(|i| {
                let r = ((i as f64 + 0.5) / rays as f64).sqrt();
                let q = i as f64 * golden;
                let angle = (r * tan_half).atan();
                RaySample {
                    disk: [r * q.cos(), r * q.sin()],
                    angle,
                    weight: (-0.5 * (angle / sigma).powi(2)).exp(),
                }
            })
            .collect();
        Self { samples, tan_half }
    }

    /// The samples, in order.
    pub fn samples(&self) -> &[RaySample] {
        &self.samples
    }

    /// `tan(cone/2)`: the scale from the unit disk to the cone.
    pub fn tan_half_angle(&self) -> f64 {
        self.tan_half
    }
}

/// The weighted mean of the distances within [`MAD_WINDOW`] median absolute
/// deviations of the median (CGAL's outlier rule); `None` without samples.
///
/// `samples` are `(distance, weight)` pairs (distance in any unit, weight
/// ≥ 0). The median and the median absolute deviation of an even count are
/// the means of the two middle values. If every kept weight is zero the
/// median is returned.
///
/// # Example
/// ```
/// use soak_graph::segment::sdf::robust_mean;
/// let d = [(1.0, 1.0), (2.0, 1.0), (3.0, 1.0), (4.0, 1.0), (100.0, 1.0)];
/// assert_eq!(robust_mean(&d), Some(3.0));
/// ```
pub fn robust_mean(samples: &[(f64, f64)]) -> Option<f64> {
    match samples.len() {
        0 => return None,
        1 => return Some(samples[0].0),
        _ => {}
    }
    let median_of = |v: &mut Vec<f64>| {
        v.sort_unstable_by(f64::total_cmp);
        let n = v.len();
        if n % 2 == 1 {
            v[n / 2]
        } else {
            0.5 * (v[n / 2 - 1] + v[n / 2])
        }
    };
    let mut d: Vec<f64> = samples.iter().map(|s| s.0).collect();
    let median = median_of(&mut d);
    let mut dev: Vec<f64> = samples.iter().map(|s| (s.0 - median).abs()).collect();
    let mad = median_of(&mut dev);
    let (mut sum, mut weights) = (0.0, 0.0);
    for &(x, w) in samples {
        if (x - median).abs() <= MAD_WINDOW * mad {
            sum += w * x;
            weights += w;
        }
    }
    Some(if weights > 0.0 { sum / weights } else { median })
}

/// `ln(F·x + 1) / ln(F + 1)` with F = [`LOG_FACTOR`]: maps [0, 1] onto
/// itself, stretching the thin end (CGAL's log normalisation of the SDF).
///
/// # Example
/// ```
/// use soak_graph::segment::sdf::log_normalize;
/// assert!((log_normalize(0.5) - 0.69918).abs() < 5e-6);
/// ```
pub fn log_normalize(x: f64) -> f64 {
    (LOG_FACTOR * x + 1.0).ln() / (LOG_FACTOR + 1.0).ln()
}

/// The SDF of every face, at each stage of its post-processing.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct ShapeDiameter {
    /// The outlier-filtered ray average per face, m; faces where no ray was
    /// accepted hold their neighbours' mean.
    pub raw: Vec<f64>,
    /// `raw` after the bilateral filter, m.
    pub smoothed: Vec<f64>,
    /// `smoothed` normalised linearly to [0, 1], then by [`log_normalize`].
    pub normalized: Vec<f64>,
    /// How many faces had no accepted ray and were filled from neighbours.
    pub filled_faces: usize,
    /// Number of rings of the bilateral filter's neighbourhood.
    pub smoothing_window: usize,
}

/// The SDF of every face of a validated, closed mesh.
///
/// # Errors
/// [`SegmentError::InvalidMesh`] if the mesh is not closed, manifold and
/// outward wound, and the option errors of [`SegmentOptions::check`].
pub fn shape_diameter(mesh: &Mesh, options: &SegmentOptions) -> Result<ShapeDiameter, SegmentError> {
    options.check()?;
    soak_bake::validate_topology(mesh)?;
    let topology = Topology::new(mesh);
    let bvh = build_bvh(mesh, &topology)?;
    Ok(compute(mesh, &topology, &bvh, options))
}

pub(crate) fn compute(
    mesh: &Mesh,
    topology: &Topology,
    bvh: &TriMesh,
    options: &SegmentOptions,
) -> ShapeDiameter {
    let diagonal = mesh.diagonal();
    let pattern = RayPattern::new(options.rays, options.cone_degrees);
    let values: Vec<Option<f64>> = (0..topology.face_count())
        .into_par_iter()
        .map(|f| face_value(mesh, topology, bvh, &pattern, f, diagonal, options.seed))
        .collect();
    let filled_faces = values.iter().filter(|v| v.is_none()).count();
    let raw = fill_missing(values, topology, diagonal);
    let smoothing_window = smoothing_window(topology.face_count());
    let smoothed = bilateral(&raw, topology, smoothing_window);
    let (lo, hi) = smoothed
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), &v| {
            (lo.min(v), hi.max(v))
        });
    let normalized = smoothed
        .iter()
        .map(|&v| {
            let x = if hi > lo { (v - lo) / (hi - lo) } else { 0.5 };
            log_normalize(x)
        })
        .collect();
    ShapeDiameter {
        raw,
        smoothed,
        normalized,
        filled_faces,
        smoothing_window,
    }
}

pub(crate) fn build_bvh(mesh: &Mesh, topology: &Topology) -> Result<TriMesh, SegmentError> {
    let vertices: Vec<PVector> = mesh
        .positions
        .iter()
        .map(|p| PVector::new(p.x as f32, p.y as f32, p.z as f32))
        .collect();
    TriMesh::new(vertices, topology.welded.clone()).map_err(|e| SegmentError::RayCaster {
        mesh: mesh.name.clone(),
        reason: e.to_string(),
    })
}

/// The SDF sample of face `f`, or `None` if no ray was accepted.
fn face_value(
    mesh: &Mesh,
    topology: &Topology,
    bvh: &TriMesh,
    pattern: &RayPattern,
    f: usize,
    diagonal: f64,
    seed: u64,
) -> Option<f64> {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    rng.set_stream(f as u64);
    let axis = -topology.normals[f];
    // A frame from the face's own first edge, so the rays turn with the mesh.
    let [a, b, _] = mesh.triangle_points(f);
    let u = (b - a).normalize();
    let v = axis.cross(&u);
    let psi = rng.random::<f64>() * TAU;
    let (sin_psi, cos_psi) = psi.sin_cos();
    let offset = ORIGIN_OFFSET * diagonal * (1.0 + rng.random::<f64>());
    let origin = topology.centroids[f] + axis * offset;
    let origin = PVector::new(origin.x as f32, origin.y as f32, origin.z as f32);
    let mut hits = Vec::with_capacity(pattern.samples.len());
    for s in &pattern.samples {
        let jx = DIRECTION_JITTER * (2.0 * rng.random::<f64>() - 1.0);
        let jy = DIRECTION_JITTER * (2.0 * rng.random::<f64>() - 1.0);
        let x = cos_psi * s.disk[0] - sin_psi * s.disk[1] + jx;
        let y = sin_psi * s.disk[0] + cos_psi * s.disk[1] + jy;
        let dir = (axis + (u * x + v * y) * pattern.tan_half).normalize();
        let ray = Ray::new(origin, PVector::new(dir.x as f32, dir.y as f32, dir.z as f32));
        if let Some(hit) = bvh.cast_local_ray_and_get_normal(&ray, diagonal as f32, true) {
            let face = hit.subshape as usize;
            if face < topology.normals.len() && topology.normals[face].dot(&dir) > 0.0 {
                // Measured from the surface: add the stretch between the
                // face's plane and the offset origin.
                let from_surface = f64::from(hit.time_of_impact) + offset / dir.dot(&axis);
                hits.push((from_surface, s.weight));
            }
        }
    }
    robust_mean(&hits)
}

/// Faces without a value take the mean of their valued neighbours, round
/// after round (each round reads the previous one). Anything still missing
/// (a component where no ray was accepted) takes the mean of all values, or
/// `diagonal` if there are none.
fn fill_missing(mut values: Vec<Option<f64>>, topology: &Topology, diagonal: f64) -> Vec<f64> {
    loop {
        let missing: Vec<usize> = (0..values.len()).filter(|&f| values[f].is_none()).collect();
        if missing.is_empty() {
            break;
        }
        let updates: Vec<(usize, f64)> = missing
            .iter()
            .filter_map(|&f| {
                let (sum, n) = topology
                    .neighbours(f)
                    .iter()
                    .filter_map(|&g| values[g as usize])
                    .fold((0.0, 0usize), |(s, n), x| (s + x, n + 1));
                (n > 0).then(|| (f, sum / n as f64))
            })
            .collect();
        if updates.is_empty() {
            break;
        }
        for (f, x) in updates {
            values[f] = Some(x);
        }
    }
    let (sum, n) = values
        .iter()
        .flatten()
        .fold((0.0, 0usize), |(s, n), &x| (s + x, n + 1));
    let fallback = if n > 0 { sum / n as f64 } else { diagonal };
    values.into_iter().map(|v| v.unwrap_or(fallback)).collect()
}

/// Rings of the bilateral filter's window: `⌊√(F/2000)⌋ + 1` for F faces
/// (CGAL's rule: the one-ring up to 7999 faces, growing with resolution).
pub fn smoothing_window(faces: usize) -> usize {
    (faces as f64 / 2000.0).sqrt() as usize + 1
}

fn gaussian(x: f64, sigma: f64) -> f64 {
    (-0.5 * (x / sigma).powi(2)).exp()
}

/// CGAL's bilateral filter: each face averages the faces within `window`
/// vertex rings (ring 0 is the face itself; ring k+1 shares a vertex with
/// ring k), weighted by a spatial Gaussian of the ring number (σ = window/2)
/// times a range Gaussian of the value difference (σ = 1.5 × the RMS
/// difference over the window). One pass.
fn bilateral(values: &[f64], topology: &Topology, window: usize) -> Vec<f64> {
    let n = values.len();
    (0..n)
        .into_par_iter()
        .map_init(
            || (vec![0u32; n], Vec::new()),
            |(stamp, hood): &mut (Vec<u32>, Vec<(u32, usize)>), f| {
                let mark = f as u32 + 1;
                hood.clear();
                hood.push((f as u32, 0));
                stamp[f] = mark;
                let mut start = 0;
                for ring in 1..=window {
                    let end = hood.len();
                    for k in start..end {
                        let g = hood[k].0 as usize;
                        for &vtx in &topology.welded[g] {
                            for &h in topology.faces_around(vtx) {
                                if stamp[h as usize] != mark {
                                    stamp[h as usize] = mark;
                                    hood.push((h, ring));
                                }
                            }
                        }
                    }
                    start = end;
                }
                let centre = values[f];
                let var = hood
                    .iter()
                    .map(|&(g, _)| (values[g as usize] - centre).powi(2))
                    .sum::<f64>()
                    / hood.len() as f64;
                let deviation = var.sqrt();
                if deviation <= f64::EPSILON * centre.abs().max(f64::MIN_POSITIVE) {
                    return centre;
                }
                let (mut sum, mut weights) = (0.0, 0.0);
                for &(g, ring) in hood.iter() {
                    let x = values[g as usize];
                    let w =
                        gaussian(ring as f64, window as f64 / 2.0) * gaussian(x - centre, 1.5 * deviation);
                    sum += w * x;
                    weights += w;
                }
                sum / weights
            },
        )
        .collect()
}

/// Whether `point` lies inside the closed mesh: at least two of three rays
/// in fixed, unrelated directions first meet the surface from behind.
pub(crate) fn contains(bvh: &TriMesh, topology: &Topology, point: &Point3<f64>, diagonal: f64) -> bool {
    const DIRECTIONS: [[f64; 3]; 3] = [
        [0.267_261_2, 0.534_522_5, 0.801_783_7],
        [-0.742_781_4, 0.557_086_0, -0.371_390_7],
        [0.408_248_3, -0.816_496_6, -0.408_248_3],
    ];
    let origin = PVector::new(point.x as f32, point.y as f32, point.z as f32);
    let votes = DIRECTIONS
        .iter()
        .filter(|d| {
            let dir = Vector3::from(**d).normalize();
            let ray = Ray::new(origin, PVector::new(dir.x as f32, dir.y as f32, dir.z as f32));
            bvh.cast_local_ray_and_get_normal(&ray, 2.0 * diagonal as f32, true)
                .is_some_and(|hit| {
                    let f = hit.subshape as usize;
                    f < topology.normals.len() && topology.normals[f].dot(&dir) > 0.0
                })
        })
        .count();
    votes >= 2
}
