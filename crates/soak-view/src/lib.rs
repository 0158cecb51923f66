//! Frames of soak simulations, and a live window on them.
//!
//! [`SceneRenderer`] draws a scene file's [`Simulation`](soak_rapier::Simulation)
//! with soak-shade's wet-surface renderer: `soak render` and `soak demo` use
//! it offscreen. [`run`] (`soak view`) shows a scene file live: simulated in
//! real time on a thread of its own, drawn in a window through winit and
//! wgpu, with an orbit camera, play/pause, single steps, a time scale,
//! restart, the debug views and force arrows, an overlay of the times and
//! the selected body's state, picking with the mouse, and the scene
//! reloaded when its file is saved (a scene that does not load is named in
//! the overlay, with its line, and the running one kept).
//!
//! A world of your own is shown the same way ([`run_world`]): your Rapier
//! world and soak's generator made a
//! [`Simulation`](soak_rapier::Simulation) by
//! [`Simulation::from_parts`](soak_rapier::Simulation::from_parts), with
//! the mesh of each of its bodies.
//!
//! ```no_run
//! use soak_view::{ViewOptions, run};
//!
//! let report = run("data/scenes/sinking_boat.toml".as_ref(), ViewOptions::default())?;
//! println!("{} frames, {:.0} ms each on {}", report.frames, report.frame_ms[0], report.adapter);
//! # Ok::<(), soak_view::ViewError>(())
//! ```

mod error;
mod frames;
mod orbit;
mod overlay;
mod viewer;

pub use error::ViewError;
pub use frames::{FrameOptions, SceneRenderer, View};
pub use viewer::{STARVED, ViewOptions, ViewReport, run, run_world};
