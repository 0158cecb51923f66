//! Frames of soak simulations, and a live window on them.
//!
//! [`SceneRenderer`] draws a scene file's [`Simulation`](soak_rapier::Simulation)
//! with soak-shade's wet-surface renderer: `soak render` and `soak demo` use
//! it offscreen.

mod error;
mod frames;

pub use error::ViewError;
pub use frames::{FrameOptions, SceneRenderer, View};
