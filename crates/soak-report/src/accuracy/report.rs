//! What a run measured: the table's rows, the sweeps behind the figures.

use std::path::PathBuf;

use serde::Serialize;

/// One table row: a mesh at a resolution.
#[derive(Clone, Debug, Serialize)]
pub struct Row {
    /// Mesh and pose.
    pub mesh: String,
    /// Triangles in the mesh.
    pub triangles: usize,
    /// Texture side, texels.
    pub resolution: u32,
    /// Samples in the atlas (covered texels plus centroid samples of
    /// triangles too small to cover a texel centre).
    pub texels: usize,
    /// Max over the sweep of |V − V_exact| / V_body, moment matching.
    pub volume_error: f64,
    /// The same at plain texel centres (the thesis).
    pub volume_error_centres: f64,
    /// Max over the sweep of |C_B − C_B,exact| / bounding-box diagonal,
    /// moment matching (levels with ≥ 1 % of the body under water).
    pub cob_error: f64,
    /// The same at plain texel centres.
    pub cob_error_centres: f64,
    /// max_ij |I − I_exact|_ij / tr I_exact of the solid, moment matching.
    pub inertia_error: f64,
    /// The same at plain texel centres.
    pub inertia_error_centres: f64,
    /// Largest |V_tiled − V_per-texel| / V_body over the sweep (the two paths
    /// compute the same sums).
    pub tiled_vs_per_texel: f64,
    /// Median time of one per-texel evaluation (`evaluate`), ms.
    pub per_texel_ms: f64,
    /// Median time of one tiled evaluation (`TiledAtlas::evaluate`), ms.
    pub tiled_ms: f64,
    /// Per-texel time over a plain streaming read of the same atlas
    /// (`soak_hydro::streaming_read`), the two timed in turn.
    pub per_texel_over_floor: f64,
    /// GPU time per evaluation, ms: `None` until the `gpu` feature fills it.
    pub gpu_ms: Option<f64>,
    /// Median time of exact clipping (`reference::submerged_part`), ms.
    pub exact_ms: f64,
    /// Median time of the per-triangle game method, ms.
    pub per_triangle_ms: f64,
    /// Max over the sweep of the per-triangle method's |V − V_exact| / V_body.
    pub per_triangle_volume_error: f64,
}

/// Submerged volume against water level for one atlas.
#[derive(Clone, Debug, Serialize)]
pub struct Curve {
    /// Texture side, texels.
    pub resolution: u32,
    /// Moment-matched samples (true) or plain texel centres.
    pub moment_matching: bool,
    /// Submerged volume at each level, m³ (per-texel path).
    pub volume: Vec<f64>,
    /// Median time of one per-texel evaluation, ms.
    pub per_texel_ms: f64,
    /// Median time of one tiled evaluation, ms.
    pub tiled_ms: f64,
}

/// One mesh swept through the water.
#[derive(Clone, Debug, Serialize)]
pub struct Sweep {
    /// Mesh and pose.
    pub mesh: String,
    /// Triangles in the mesh.
    pub triangles: usize,
    /// The body's volume (exact, of the mesh), m³.
    pub body_volume: f64,
    /// Heights of the water plane, m (the body stays put).
    pub levels: Vec<f64>,
    /// Exact clipping of the mesh, m³.
    pub exact: Vec<f64>,
    /// The per-triangle game method, m³.
    pub per_triangle: Vec<f64>,
    /// Analytic sphere cap, m³ (spheres only).
    pub analytic: Option<Vec<f64>>,
    /// Median time of exact clipping, ms.
    pub exact_ms: f64,
    /// Median time of the per-triangle method, ms.
    pub per_triangle_ms: f64,
    /// Texel curves, per resolution and sampling.
    pub texel: Vec<Curve>,
}

/// Per-texel time over tiled time at one resolution.
#[derive(Clone, Debug, Serialize)]
pub struct Speedup {
    /// Mesh and pose.
    pub mesh: String,
    /// Texture side, texels.
    pub resolution: u32,
    /// per_texel_ms / tiled_ms.
    pub speedup: f64,
    /// Per-texel time over a plain streaming read of the same atlas
    /// (positions, area vectors, areas), the two timed in turn.
    pub per_texel_over_floor: f64,
}

/// Everything `soak accuracy` measured.
#[derive(Clone, Debug, Serialize)]
pub struct Report {
    /// Whether this was a `--quick` run.
    pub quick: bool,
    /// Texture sides, texels.
    pub resolutions: Vec<u32>,
    /// Water levels per sweep.
    pub levels: usize,
    /// Timed runs per path (each run repeats fast calls to ≥ 0.5 ms).
    pub timing_runs: usize,
    /// Worker threads of the texel paths (exact clipping and the
    /// per-triangle method run on one).
    pub threads: usize,
    /// The table.
    pub rows: Vec<Row>,
    /// Tiled speed-up over per-texel at 1024² (or the largest resolution).
    pub tiled_speedup: Vec<Speedup>,
    /// The curves behind the figures.
    pub sweeps: Vec<Sweep>,
    /// The sampled sea against the exact inversion, per sampling setting.
    pub sea: Vec<super::sea::SeaRow>,
    /// The same on a short, steep spectral sea ([`super::short_sea`]):
    /// the sampled read against the exact inversion of its choppy map.
    pub spectral: Vec<super::sea::SeaRow>,
    /// A band of the spectral sea's waves read against every wave, per
    /// cut-off.
    pub band: Vec<super::band::BandRow>,
    /// The spectral seas read as one plane over each body, against their
    /// exact read, per mesh and sea.
    #[serde(default)]
    pub plane: Vec<super::plane::PlaneRow>,
    /// The drag over coarser bakes against the drag over the body's own
    /// texels, per drag resolution.
    pub drag_texels: Vec<super::drag_texels::DragTexelRow>,
    /// Files written.
    pub files: Vec<PathBuf>,
    /// Wall time of the whole run, s.
    pub seconds: f64,
    /// The adapter the GPU column ran on, if it ran.
    pub adapter: Option<String>,
}
