//! What each digit of accuracy costs in time.
//!
//! Reproduces and extends the thesis' Fig. 7.10 (submerged volume of a sphere
//! r = 0.5 m against water level, texture sizes 32²…1024², against the
//! analytic cap and the per-triangle game method) and Table 7.1 (time per
//! evaluation): for several meshes and every resolution, the worst error over
//! a sweep of water levels of
//! - the submerged volume (fraction of the body's volume),
//! - the centre of buoyancy (fraction of the bounding-box diagonal),
//! - the solid inertia tensor (largest component error over the trace),
//!
//! all against the exact references of `soak_hydro::reference` (clipping the
//! same mesh), for texel sampling with moment matching (the default) and at
//! plain texel centres (the thesis), beside the median time per evaluation of
//! each path: per-texel sums, tiled sums, exact clipping, the per-triangle
//! game baseline; GPU is a column filled with the `gpu` feature. The sea
//! rows put the sampled read of a Gerstner sea against the exact inversion
//! at every texel, per sampling setting; the drag-texel rows put the drag
//! over a coarser bake of each mesh against the drag over its own texels.
//!
//! ```no_run
//! use soak_report::accuracy::{compute, markdown, text_table};
//!
//! let report = compute(true, "out/accuracy".as_ref(), None)?;
//! print!("{}", text_table(&report));
//! std::fs::write("accuracy.md", markdown(&report, "accuracy.md".as_ref()))?;
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

mod band;
mod cases;
mod drag_texels;
mod error;
mod figures;
mod measure;
mod plane;
mod report;
mod sea;
mod table;
mod timing;

pub use band::BandRow;
pub use drag_texels::DragTexelRow;
pub use error::AccuracyError;
pub use figures::{cost_figure, sphere_figure, write_figures};
pub use measure::compute;
pub use plane::PlaneRow;
pub use report::{Curve, Report, Row, Speedup, Sweep};
pub use sea::{SeaRow, short_sea, swell};
pub use table::{markdown, text_table};
