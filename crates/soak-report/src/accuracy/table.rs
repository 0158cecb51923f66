//! The table as aligned text and as markdown.

use std::path::Path;

use super::band::band_cells;
use super::drag_texels::drag_texel_cells;
use super::plane::plane_cells;
use super::sea::sea_cells;

use super::report::{Report, Row};

/// `1.2e-4` below 0.1, `0.25` above; a true zero prints as `0`.
fn sci(v: f64) -> String {
    if v == 0.0 {
        "0".into()
    } else if v.abs() >= 0.1 {
        format!("{v:.2}")
    } else {
        format!("{v:.1e}")
    }
}

/// Milliseconds with three significant digits.
fn msf(v: f64) -> String {
    if v >= 100.0 {
        format!("{v:.0}")
    } else if v >= 10.0 {
        format!("{v:.1}")
    } else if v >= 1.0 {
        format!("{v:.2}")
    } else if v >= 0.01 {
        format!("{v:.3}")
    } else {
        format!("{v:.1e}")
    }
}

fn gpu(v: Option<f64>) -> String {
    v.map_or("—".into(), msf)
}

const HEADERS: [&str; 16] = [
    "mesh",
    "triangles",
    "texture",
    "texels",
    "volume err",
    "(centres)",
    "CoB err",
    "(centres)",
    "inertia err",
    "(centres)",
    "per-texel ms",
    "tiled ms",
    "GPU ms",
    "exact ms",
    "per-tri ms",
    "per-tri vol err",
];

fn cells(r: &Row) -> [String; 16] {
    [
        r.mesh.clone(),
        r.triangles.to_string(),
        format!("{}²", r.resolution),
        r.texels.to_string(),
        sci(r.volume_error),
        sci(r.volume_error_centres),
        sci(r.cob_error),
        sci(r.cob_error_centres),
        sci(r.inertia_error),
        sci(r.inertia_error_centres),
        msf(r.per_texel_ms),
        msf(r.tiled_ms),
        gpu(r.gpu_ms),
        msf(r.exact_ms),
        msf(r.per_triangle_ms),
        sci(r.per_triangle_volume_error),
    ]
}

fn speedup_line(report: &Report) -> String {
    let parts: Vec<String> = report
        .tiled_speedup
        .iter()
        .map(|s| format!("{} ×{:.1}", s.mesh, s.speedup))
        .collect();
    let floors: Vec<String> = report
        .tiled_speedup
        .iter()
        .map(|s| format!("{} ×{:.2}", s.mesh, s.per_texel_over_floor))
        .collect();
    match report.tiled_speedup.first() {
        Some(s) => format!(
            "tiled speed-up over per-texel at {r}²: {}; per-texel time over a streaming read of the same atlas at {r}²: {}",
            parts.join(", "),
            floors.join(", "),
            r = s.resolution,
        ),
        None => String::new(),
    }
}

/// The table as aligned text.
pub fn text_table(report: &Report) -> String {
    let mut all: Vec<[String; 16]> = vec![HEADERS.map(String::from)];
    all.extend(report.rows.iter().map(cells));
    let mut s = String::new();
    s.push_str(&format!(
        "soak accuracy{}: max error over {} water levels against exact clipping; times are medians of {} runs, texel paths on {} threads\n",
        if report.quick { " --quick" } else { "" },
        report.levels,
        report.timing_runs,
        report.threads
    ));
    s.push_str(&aligned(&all, true));
    s.push_str("volume err: |V − V_exact| / V_body; CoB err: |C − C_exact| / bounding-box diagonal (levels ≥ 1 % submerged);\n");
    s.push_str("inertia err: largest |I − I_exact| component / tr I_exact; (centres): texel centres as in the thesis, no moment matching.\n");
    s.push_str(&speedup_line(report));
    s.push('\n');
    if !report.sea.is_empty() {
        s.push_str(&sea_text(report));
    }
    if !report.spectral.is_empty() {
        s.push_str("\non a short JONSWAP sea (Hs 0.5 m, Tp 3 s): sampled read against the exact inversion (worst of six poses)\n");
        s.push_str(&aligned(&sea_cells(&report.spectral), false));
    }
    if !report.band.is_empty() {
        s.push_str("\non the same sea, a band of its waves against every wave (`SeaBand::BodyLengths`, worst of six poses)\n");
        s.push_str(&aligned(&band_cells(&report.band), false));
    }
    if !report.plane.is_empty() {
        s.push_str("\nspectral seas read as one plane over each body against the exact read (`SeaSampling::Plane`, worst of six poses)\n");
        s.push_str(&aligned(&plane_cells(&report.plane), false));
    }
    if !report.drag_texels.is_empty() {
        s.push_str("\ndrag over a coarser bake of the mesh or the atlas coarsened, against the drag over the body's own texels (worst of six moving poses)\n");
        s.push_str(&aligned(&drag_texel_cells(&report.drag_texels), true));
    }
    s.push_str(&format!("{:.1} s in total\n", report.seconds));
    s
}

/// What the sea rows are, before their table.
const SEA_INTRO: &str = "## On a sea\n\n\
The two-wave swell of `data/scenes/buoy_on_waves.toml` (wavelengths 9 m and 4 m), six poses across it: \
the sampled read (`SeaSampling::PerWavelength`: the surface sampled once over the body's footprint, \
bicubic Hermite between the nodes) against the exact inversion of the Gerstner map at every texel \
(`SeaSampling::Exact`). Errors are the worst over the poses, of the volume over the body's volume and \
of the centre of buoyancy and Archimedes' torque (over ρgV) over the bounding diameter; the tiled \
path (`TiledAtlas`) reads the same sampled sea, tiles under the waves in closed form from the \
surface's second-order Taylor polynomial over each. Times are per evaluation with the sampling \
included, beside the same body on calm water (per texel). The drag columns move the body through \
the swell (0.7 m/s, 0.46 rad/s; C_d = 0.8, skin friction 20 N·s/m³): the worst relative difference \
of its drag (force, and torque over the bounding radius) from the exact inversion's, the fluid's \
velocity read from the sampled sea at every texel (`SeaVelocity::PerTexel`) and by the tiled path \
once per tile (`SeaVelocity::PerTile`, the default), and between the two; and the tiled path's \
time with drag, per tile and per texel.\n\n";

/// What the spectral rows are, before their table.
const SPECTRAL_INTRO: &str = "## On a spectral sea\n\n\
The same rows on a short, steep spectral sea: JONSWAP of significant height 0.5 m and peak period \
3 s (its peak wave 14 m long; γ 3.3, spreading 10, seed 1) on its default tile (112 m, 128 cells: \
its shortest wave 1.75 m, shorter than the boat), the same six poses. The reference is the exact \
inversion of the sea's choppy map at every texel (`SeaSampling::Exact`: Newton's method on the \
tile's interpolated fields); the sampled read samples that surface over the body's footprint at the \
given nodes per shortest wavelength (1.75 m), as on the swell.\n\n";

/// What the band rows are, before their table.
const BAND_INTRO: &str = "## A band of the sea's waves\n\n\
The boat and a 10 m barge on the same spectral sea, reading only a band of its waves \
(`SeaBand::BodyLengths(r)`: every wave at least `r` bounding diameters long is read; the sea drops \
its modes shorter than `2^L` times its shortest wave, 1.75 m, for the largest `L` that keeps them, \
and is read on a grid of `128 / 2^L` cells) against the same body reading every wave, both sampled \
at 16 nodes per shortest wavelength read, the same six poses (the barge's spread out to its size). \
Errors are the worst over the poses, of the volume (and so the force) over the body's volume and \
of the centre of buoyancy and Archimedes' torque (over ρgV) over the bounding diameter; the times \
are the tiled path's per evaluation, sampling included.\n\n";

/// What the plane rows are, before their table.
const PLANE_INTRO: &str = "## A sea read as one plane over each body\n\n\
The bench's box and sphere and the boat, on the bench's JONSWAP sea (significant height 2 m, peak \
period 8 s, its shortest wave 12.5 m), on the short sea above (its shortest wave 1.75 m) and on the \
two-wave swell above (its shortest wave 4 m; the box is the crate of `data/scenes/twenty_on_swell.toml`, \
which reads it as planes), each read as one plane over the body (`SeaSampling::Plane`: the plane through the mean over the body's \
horizontal section of the sea's second-order polynomial, from its heights at the section's \
centroid and either way along its principal axes, tilted by their differences, the sea's velocity \
at the centre of the body's bounding sphere as a uniform current; for a body more than an eighth \
of the shortest wave across, with its gradient there too, a current changing linearly over the \
body) against the \
exact read at every texel (`SeaSampling::Exact`). Six poses along each sea, the body's centre 0.1 m \
under the sea there, tilted and turned; the drag's poses the same, moving at 0.7 m/s and turning at \
0.46 rad/s (C_d = 0.8, skin friction 20 N·s/m³). Errors as in the rows above, the drag's as the \
worst relative difference of its force; beside them the sampled read's (16 nodes per \
shortest wave, as the default read samples a body large against the waves) against the same \
reference. The default read (`SeaSampling::Auto`) takes the plane for a body at most an eighth of \
the shortest wave across: on the bench's sea the box and the sphere, not the boat; on the swell \
none of them. Where the relative flow is slow (a body carried along with the water), the \
drag's worst relative error is the largest: a linear current is the velocity's change over \
the body to first order, and the waves shorter than the body bend it further. Times are the tiled path's per evaluation with drag, \
the plane's reads or the patch's sampling included.\n\n";

/// What the drag-texel rows are, before their table.
const DRAG_TEXELS_INTRO: &str = "## Drag over a coarser bake\n\n\
Each body's drag summed over a second bake of its mesh (`DragTexels::bake`, the scene key \
`drag_resolution`), or over its own atlas coarsened (`DragTexels::coarsened`, the scene key \
`drag_coarsening`: each k × k block of texels merged into one, \"atlas by k\"), rather than over its \
own atlas' texels, which keep its buoyancy: the worst relative difference of the drag \
(force, and torque over the bounding radius) from the drag over the body's own texels, over six \
poses at the surface moving at about 0.75 m/s and turning at 0.5 rad/s (C_d = 0.8, skin friction \
20 N·s/m³), on calm water and on the two-wave swell; and the tiled evaluation's time on calm water \
without drag, with the drag over its own texels and with the drag over the bake, the last over the \
first as the ratio. A bake takes at least one texel per triangle (the sphere's 4,096); a coarsened atlas one per \
block.\n\n";

/// Rows as a markdown table, the header first; the first `left` columns
/// left-aligned.
fn markdown_rows<const N: usize>(rows: &[[String; N]], left: usize) -> String {
    let mut s = String::new();
    for (i, r) in rows.iter().enumerate() {
        s.push_str(&format!("| {} |\n", r.join(" | ")));
        if i == 0 {
            s.push_str(&format!(
                "|{}\n",
                (0..N)
                    .map(|c| if c < left { " --- |" } else { " ---: |" })
                    .collect::<String>()
            ));
        }
    }
    s
}

/// The sea rows as aligned text.
fn sea_text(report: &Report) -> String {
    let mut s = String::from(
        "\non the two-wave swell: sampled read against the exact inversion (worst of six poses)\n",
    );
    s.push_str(&aligned(&sea_cells(&report.sea), false));
    s
}

/// Rows as aligned text: the first column left-aligned, the others
/// right-aligned two spaces apart; with `gaps`, an empty line where the
/// first column changes (after the header).
fn aligned<const N: usize>(rows: &[[String; N]], gaps: bool) -> String {
    let widths: Vec<usize> = (0..N)
        .map(|c| rows.iter().map(|r| r[c].chars().count()).max().unwrap_or(0))
        .collect();
    let mut s = String::new();
    let mut last = "";
    for (i, r) in rows.iter().enumerate() {
        if gaps && i > 1 && r[0] != last {
            s.push('\n');
        }
        last = &r[0];
        for (c, cell) in r.iter().enumerate() {
            let pad = " ".repeat(widths[c] - cell.chars().count());
            if c == 0 {
                s.push_str(cell);
                s.push_str(&pad);
            } else {
                s.push_str("  ");
                s.push_str(&pad);
                s.push_str(cell);
            }
        }
        s.push('\n');
    }
    s
}

/// `to` relative to the folder of `from` when it lies inside it.
fn relative(to: &Path, from: &Path) -> String {
    let base = from.parent().unwrap_or(Path::new(""));
    let p = to.strip_prefix(base).unwrap_or(to);
    p.to_string_lossy().replace('\\', "/")
}

/// The table as markdown, for the README; image links relative to `path`.
pub fn markdown(report: &Report, path: &Path) -> String {
    let mut s = String::new();
    s.push_str("<!-- generated by `soak accuracy --markdown`; do not edit by hand -->\n");
    s.push_str("# Accuracy costs time\n\n");
    s.push_str(&format!(
        "Worst error over {} water levels, from dry to fully submerged, against the exact clipping of the \
         same mesh; times per evaluation are medians of {} runs measured in the same run (compare ratios: \
         absolute times drift on shared machines). The texel paths ran on {} threads, exact clipping and \
         the per-triangle method on one.\n\n",
        report.levels, report.timing_runs, report.threads
    ));
    if let Some(a) = &report.adapter {
        s.push_str(&format!("The GPU column ran on {a}.\n\n"));
    }
    s.push_str(
        "- **volume err**: |V − V_exact| / V_body; **CoB err**: |C_B − C_B,exact| / bounding-box diagonal, \
         over the levels with at least 1 % of the body submerged; **inertia err**: largest component of \
         |I − I_exact| / tr I_exact (solid of uniform density).\n\
         - **(centres)**: samples at plain texel centres, as in the thesis; the other columns use moment \
         matching (each triangle's samples nudged so their mean and covariance are the triangle's).\n\
         - **texels**: samples in the atlas, including one centroid sample per triangle too small to cover a \
         texel centre.\n\
         - **per-texel**: `evaluate`; **tiled**: `TiledAtlas::evaluate` (one closed form for the runs of \
         tiles wholly under water, the per-texel kernel on the smaller side of each cut tile; same sums); **GPU**: `gpu::GpuHydro::evaluate` (one body per submission, \
         readback included; `--gpu`); **exact**: `reference::submerged_part`; **per-tri**: the per-triangle \
         game method (AQUAS-style water columns, the baseline of the thesis' Fig. 7.10) and its volume \
         error.\n\n",
    );
    s.push_str(&format!("| {} |\n", HEADERS.join(" | ")));
    s.push_str(&format!(
        "|{}\n",
        HEADERS
            .iter()
            .enumerate()
            .map(|(i, _)| if i == 0 { " --- |" } else { " ---: |" })
            .collect::<String>()
    ));
    for r in &report.rows {
        s.push_str(&format!("| {} |\n", cells(r).join(" | ")));
    }
    s.push('\n');
    s.push_str(&speedup_line(report));
    s.push_str(".\n\n");
    if !report.sea.is_empty() {
        s.push_str(SEA_INTRO);
        s.push_str(&markdown_rows(&sea_cells(&report.sea), 2));
        s.push('\n');
    }
    if !report.spectral.is_empty() {
        s.push_str(SPECTRAL_INTRO);
        s.push_str(&markdown_rows(&sea_cells(&report.spectral), 2));
        s.push('\n');
    }
    if !report.band.is_empty() {
        s.push_str(BAND_INTRO);
        s.push_str(&markdown_rows(&band_cells(&report.band), 4));
        s.push('\n');
    }
    if !report.plane.is_empty() {
        s.push_str(PLANE_INTRO);
        s.push_str(&markdown_rows(&plane_cells(&report.plane), 3));
        s.push('\n');
    }
    if !report.drag_texels.is_empty() {
        s.push_str(DRAG_TEXELS_INTRO);
        s.push_str(&markdown_rows(&drag_texel_cells(&report.drag_texels), 4));
        s.push('\n');
    }
    for f in &report.files {
        let name = f
            .file_stem()
            .map(|n| n.to_string_lossy().into_owned())
            .unwrap_or_default();
        s.push_str(&format!("![{name}]({})\n\n", relative(f, path)));
    }
    s
}
