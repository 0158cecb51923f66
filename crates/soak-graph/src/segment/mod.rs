//! Automatic segmentation of a closed mesh into the liquid graph's
//! compartments (thesis §4.1.1), following CGAL's
//! `Surface_mesh_segmentation` defaults without depending on CGAL.
//!
//! 1. **Shape Diameter Function** per face ([`sdf`]): a 120° cone of 25 rays
//!    around the inward normal, cast through a BVH; outlier-filtered,
//!    angle-weighted average; holes filled from neighbours; bilateral
//!    smoothing; normalised to [0, 1] and log-compressed.
//! 2. **Soft clustering** ([`gmm`]): a Gaussian mixture of k components
//!    (default 5) fitted by EM from a seeded k-means++ start; the cost of
//!    label l at a face is `−ln max(P(l | face), 5·10⁻⁶)`.
//! 3. **Hard labels** ([`graph_cut`]): alpha-expansion over face adjacency
//!    with CGAL's dihedral-angle edge weights, each move a minimum cut
//!    ([`max_flow`], Boykov–Kolmogorov).
//! 4. **Segments** are connected components of equal label; each becomes a
//!    [`SegmentNode`] with a least-squares sphere ([`sphere_fit`]) giving its
//!    position, radius and capacity, and segments sharing mesh edges are
//!    joined by an edge carrying the shared boundary length.
//!
//! # Capacities
//!
//! A node's capacity starts as the volume of its sphere, `4/3 π r³`; then
//! all capacities are scaled by one factor so that they sum to the mesh's
//! enclosed volume ([`Mesh::volume`], m³). The spheres set the *shares*,
//! the mesh sets the *total*: a hull that is one segment holds exactly its
//! volume.
//!
//! # Node spheres
//!
//! The sphere is the algebraic least-squares fit ([`sphere_fit::fit_sphere`])
//! to the segment's face centroids, weighted by face area. It is kept when
//! its radius is at most twice the RMS distance of those centroids from
//! their mean (a flat or barely curved patch yields a huge, meaningless
//! sphere) and its centre lies inside the mesh (the liquid sits inside the
//! hull). Otherwise ([`SphereFit::FixedCentre`]) the centre is the
//! area-weighted mean of the points `centroid − n · SDF/2` — half the local
//! thickness in from each face, i.e. inside the part — and the radius the
//! least-squares radius about that centre (the mean distance to the face
//! centroids).
//!
//! # Determinism
//!
//! The same mesh, options and seed give bit-identical results whatever the
//! number of rayon threads: per-face random numbers come from per-face
//! ChaCha streams, parallel loops collect in face order, and every
//! reduction runs sequentially in a fixed order.
//!
//! # Example
//! ```
//! use soak_graph::segment::{segment, SegmentOptions};
//! let mesh = soak_bake::builtin::parse("builtin:dumbbell").unwrap();
//! let seg = segment(&mesh, &SegmentOptions::default()).unwrap();
//! assert_eq!(seg.segments.len(), 3);
//! let total: f64 = seg.segments.iter().map(|s| s.capacity).sum();
//! assert!((total - mesh.volume()).abs() < 1e-9);
//! ```

pub mod gmm;
pub mod graph_cut;
pub mod max_flow;
pub mod sdf;
pub mod sphere_fit;
mod topology;

use std::collections::BTreeMap;
use std::time::{Duration, Instant};

use nalgebra::Point3;
use serde::{Deserialize, Serialize};
use soak_bake::{Mesh, MeshError};

pub use gmm::GaussianMixture;
pub use graph_cut::Labelling;
pub use max_flow::MaxFlowSolver;
pub use sdf::ShapeDiameter;
pub use sphere_fit::Sphere;

use topology::Topology;

/// Parameters of [`segment`]. The defaults are CGAL's.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(default)]
pub struct SegmentOptions {
    /// Number of Gaussian components (SDF clusters), ≥ 1. Default 5.
    pub clusters: usize,
    /// Rays cast per face for the SDF, ≥ 1. Default 25.
    pub rays: usize,
    /// Full opening angle of the ray cone, degrees in (0, 180). Default 120.
    pub cone_degrees: f64,
    /// Smoothness weight λ ≥ 0 of the graph cut (multiplied by 100, see
    /// [`graph_cut::edge_weight`]); 0 keeps the per-face most probable
    /// cluster. Default 0.26.
    pub lambda: f64,
    /// Seed of every random choice (ray jitter, k-means++). Default 0.
    pub seed: u64,
    /// EM stops when the log-likelihood changes by at most this fraction of
    /// its magnitude, ≥ 0. Default 1e-5.
    pub em_tolerance: f64,
    /// Maximum EM iterations, ≥ 1. Default 100.
    pub em_max_iterations: usize,
    /// Max-flow algorithm of the graph cut. Default Boykov–Kolmogorov.
    pub max_flow: MaxFlowSolver,
}

impl Default for SegmentOptions {
    fn default() -> Self {
        Self {
            clusters: 5,
            rays: 25,
            cone_degrees: 120.0,
            lambda: 0.26,
            seed: 0,
            em_tolerance: 1e-5,
            em_max_iterations: 100,
            max_flow: MaxFlowSolver::default(),
        }
    }
}

impl SegmentOptions {
    /// Checks every parameter's range.
    ///
    /// # Errors
    /// The first out-of-range parameter, by name.
    pub fn check(&self) -> Result<(), SegmentError> {
        if self.clusters == 0 {
            return Err(SegmentError::ZeroClusters);
        }
        if self.rays == 0 {
            return Err(SegmentError::ZeroRays);
        }
        if !(self.cone_degrees > 0.0 && self.cone_degrees < 180.0) {
            return Err(SegmentError::ConeAngle {
                degrees: self.cone_degrees,
            });
        }
        if !(self.lambda >= 0.0 && self.lambda.is_finite()) {
            return Err(SegmentError::Lambda { lambda: self.lambda });
        }
        if !(self.em_tolerance >= 0.0 && self.em_tolerance.is_finite()) {
            return Err(SegmentError::EmTolerance {
                tolerance: self.em_tolerance,
            });
        }
        if self.em_max_iterations == 0 {
            return Err(SegmentError::ZeroEmIterations);
        }
        Ok(())
    }
}

/// Why a mesh could not be segmented.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum SegmentError {
    /// The mesh is not closed, manifold and outward wound (or has degenerate
    /// triangles or non-finite positions).
    #[error("cannot segment: {0}")]
    InvalidMesh(#[from] MeshError),
    /// `clusters` is zero.
    #[error("segmentation needs at least one cluster, got clusters = 0")]
    ZeroClusters,
    /// `rays` is zero.
    #[error("the shape diameter function needs at least one ray per face, got rays = 0")]
    ZeroRays,
    /// `cone_degrees` is not inside (0, 180).
    #[error("cone angle {degrees}° is outside (0°, 180°)")]
    ConeAngle {
        /// The given full cone angle, degrees.
        degrees: f64,
    },
    /// `lambda` is negative or not finite.
    #[error("smoothness lambda {lambda} is not a finite number ≥ 0")]
    Lambda {
        /// The given λ.
        lambda: f64,
    },
    /// `em_tolerance` is negative or not finite.
    #[error("EM tolerance {tolerance} is not a finite number ≥ 0")]
    EmTolerance {
        /// The given tolerance.
        tolerance: f64,
    },
    /// `em_max_iterations` is zero.
    #[error("EM needs at least one iteration, got em_max_iterations = 0")]
    ZeroEmIterations,
    /// parry3d refused to build the ray-casting BVH.
    #[error("mesh `{mesh}`: cannot build the ray-casting BVH: {reason}")]
    RayCaster {
        /// The mesh's name.
        mesh: String,
        /// parry3d's message.
        reason: String,
    },
}

/// How a node's sphere was obtained (see the module docs).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
pub enum SphereFit {
    /// Full least-squares sphere through the face centroids.
    LeastSquares,
    /// Centre at the mean of the inner points, least-squares radius.
    FixedCentre,
}

/// One segment: a compartment of the liquid graph.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct SegmentNode {
    /// Node position (the fitted sphere's centre), object space, m.
    pub position: Point3<f64>,
    /// Radius of the fitted sphere, m.
    pub radius: f64,
    /// Capacity, m³: the sphere's share of the mesh's enclosed volume.
    pub capacity: f64,
    /// Number of faces in the segment.
    pub faces: usize,
    /// Surface area of the segment, m².
    pub area: f64,
    /// The cluster label shared by its faces.
    pub label: u32,
    /// Area-weighted mean raw SDF of its faces, m (its typical thickness).
    pub thickness: f64,
    /// How the sphere was fitted.
    pub fit: SphereFit,
}

/// Wall-clock time of each stage of [`segment`].
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct StageTimings {
    /// Validation and adjacency.
    pub topology: Duration,
    /// BVH build, ray casting, filling and smoothing.
    pub sdf: Duration,
    /// Gaussian mixture (k-means++ and EM) and unary costs.
    pub clustering: Duration,
    /// Edge weights and alpha-expansion.
    pub graph_cut: Duration,
    /// Connected components, sphere fits and segment edges.
    pub nodes: Duration,
}

impl StageTimings {
    /// Sum of all stages.
    pub fn total(&self) -> Duration {
        self.topology + self.sdf + self.clustering + self.graph_cut + self.nodes
    }
}

/// The segmentation of a mesh and the liquid-graph skeleton built from it.
#[derive(Clone, Debug, Serialize)]
pub struct Segmentation {
    /// Raw SDF per face (outlier-filtered ray average, holes filled), m.
    pub sdf_raw: Vec<f64>,
    /// Smoothed, normalised and log-compressed SDF per face, in [0, 1].
    pub sdf: Vec<f64>,
    /// The Gaussian mixture over `sdf` (components sorted by mean).
    pub mixture: GaussianMixture,
    /// Cluster label per face after the graph cut (index into
    /// `mixture.components`).
    pub face_labels: Vec<u32>,
    /// Segment index per face (index into `segments`).
    pub face_segment: Vec<u32>,
    /// One node per segment, ordered by their lowest face index.
    pub segments: Vec<SegmentNode>,
    /// Segments sharing mesh edges: `(a, b, boundary length in m)` with
    /// `a < b`, sorted.
    pub edges: Vec<(u32, u32, f64)>,
    /// Graph-cut energies before and after the expansions (dimensionless).
    pub energy: (f64, f64),
    /// Wall-clock time per stage (not serialised).
    #[serde(skip)]
    pub timings: StageTimings,
}

/// Segments a closed mesh into compartments (see the module docs).
///
/// # Errors
/// [`SegmentError::InvalidMesh`] if the mesh is not closed, manifold and
/// outward wound; an option error if a parameter is out of range.
pub fn segment(mesh: &Mesh, options: &SegmentOptions) -> Result<Segmentation, SegmentError> {
    options.check()?;
    let mut timings = StageTimings::default();

    let t = Instant::now();
    soak_bake::validate_topology(mesh)?;
    let topology = Topology::new(mesh);
    timings.topology = t.elapsed();

    let t = Instant::now();
    let bvh = sdf::build_bvh(mesh, &topology)?;
    let diameter = sdf::compute(mesh, &topology, &bvh, options);
    timings.sdf = t.elapsed();

    let t = Instant::now();
    let mixture = GaussianMixture::fit(
        &diameter.normalized,
        options.clusters,
        options.seed,
        options.em_tolerance,
        options.em_max_iterations,
    );
    let k = mixture.components.len();
    let unary = mixture.unary_costs(&diameter.normalized);
    let initial: Vec<u32> = (0..topology.face_count())
        .map(|p| {
            let row = &unary[p * k..(p + 1) * k];
            (0..k).fold(0, |b, j| if row[j] < row[b] { j } else { b }) as u32
        })
        .collect();
    timings.clustering = t.elapsed();

    let t = Instant::now();
    let edges: Vec<(u32, u32, f64)> = topology
        .edges
        .iter()
        .map(|e| {
            let w = graph_cut::edge_weight(e.normal_angle, e.concave, options.lambda);
            (e.faces[0], e.faces[1], w)
        })
        .collect();
    let labelling = graph_cut::alpha_expansion(&unary, k, &edges, initial, options.max_flow);
    timings.graph_cut = t.elapsed();

    let t = Instant::now();
    let (face_segment, count) = components(&topology, &labelling.labels);
    let segments = nodes(
        mesh,
        &topology,
        &bvh,
        &diameter.raw,
        &labelling.labels,
        &face_segment,
        count,
    );
    let mut boundary: BTreeMap<(u32, u32), f64> = BTreeMap::new();
    for e in &topology.edges {
        let (a, b) = (
            face_segment[e.faces[0] as usize],
            face_segment[e.faces[1] as usize],
        );
        if a != b {
            *boundary.entry((a.min(b), a.max(b))).or_insert(0.0) += e.length;
        }
    }
    let edges = boundary.into_iter().map(|((a, b), l)| (a, b, l)).collect();
    timings.nodes = t.elapsed();

    Ok(Segmentation {
        sdf_raw: diameter.raw,
        sdf: diameter.normalized,
        mixture,
        face_labels: labelling.labels,
        face_segment,
        segments,
        edges,
        energy: (labelling.initial_energy, labelling.energy),
        timings,
    })
}

/// Connected components of equal label over face adjacency, numbered in
/// order of their lowest face.
fn components(topology: &Topology, labels: &[u32]) -> (Vec<u32>, usize) {
    let n = labels.len();
    let mut segment = vec![u32::MAX; n];
    let mut count = 0u32;
    let mut stack = Vec::new();
    for start in 0..n {
        if segment[start] != u32::MAX {
            continue;
        }
        segment[start] = count;
        stack.push(start);
        while let Some(f) = stack.pop() {
            for &g in topology.neighbours(f) {
                let g = g as usize;
                if segment[g] == u32::MAX && labels[g] == labels[f] {
                    segment[g] = count;
                    stack.push(g);
                }
            }
        }
        count += 1;
    }
    (segment, count as usize)
}

/// One node per segment (see the module docs for the sphere and the capacity).
fn nodes(
    mesh: &Mesh,
    topology: &Topology,
    bvh: &parry3d::shape::TriMesh,
    sdf_raw: &[f64],
    labels: &[u32],
    face_segment: &[u32],
    count: usize,
) -> Vec<SegmentNode> {
    let diagonal = mesh.diagonal();
    let mut members: Vec<Vec<usize>> = vec![Vec::new(); count];
    for (f, &s) in face_segment.iter().enumerate() {
        members[s as usize].push(f);
    }
    let mut nodes: Vec<SegmentNode> = members
        .iter()
        .map(|faces| {
            let points: Vec<Point3<f64>> = faces.iter().map(|&f| topology.centroids[f]).collect();
            let weights: Vec<f64> = faces.iter().map(|&f| topology.areas[f]).collect();
            let area: f64 = weights.iter().sum();
            let thickness = faces.iter().map(|&f| topology.areas[f] * sdf_raw[f]).sum::<f64>() / area;
            let mean = sphere_fit::weighted_mean(&points, &weights).unwrap_or(points[0]);
            let rms = (points
                .iter()
                .zip(&weights)
                .map(|(p, w)| w * (p - mean).norm_squared())
                .sum::<f64>()
                / area)
                .sqrt();
            let least_squares = sphere_fit::fit_sphere(&points, &weights)
                .filter(|s| s.radius <= 2.0 * rms && sdf::contains(bvh, topology, &s.centre, diagonal));
            let (sphere, fit) = match least_squares {
                Some(s) => (s, SphereFit::LeastSquares),
                None => {
                    let inner: Vec<Point3<f64>> = faces
                        .iter()
                        .map(|&f| topology.centroids[f] - topology.normals[f] * (0.5 * sdf_raw[f]))
                        .collect();
                    let centre = sphere_fit::weighted_mean(&inner, &weights).unwrap_or(mean);
                    let radius = sphere_fit::fit_radius(&centre, &points, &weights);
                    (Sphere { centre, radius }, SphereFit::FixedCentre)
                }
            };
            SegmentNode {
                position: sphere.centre,
                radius: sphere.radius,
                capacity: 4.0 / 3.0 * std::f64::consts::PI * sphere.radius.powi(3),
                faces: faces.len(),
                area,
                label: labels[faces[0]],
                thickness,
                fit,
            }
        })
        .collect();
    let volume = mesh.volume();
    let total: f64 = nodes.iter().map(|n| n.capacity).sum();
    let total_area: f64 = nodes.iter().map(|n| n.area).sum();
    for n in &mut nodes {
        n.capacity = if total > 0.0 {
            volume * n.capacity / total
        } else {
            volume * n.area / total_area
        };
    }
    nodes
}
