//! Seakeeping coefficients of any closed mesh: the linear radiation problem
//! of a floating body on deep water.
//!
//! A body oscillating at frequency ω on still water radiates waves; the
//! water answers with a force in phase with the acceleration (added mass
//! `A(ω)`) and one in phase with the velocity (wave damping `B(ω)`).
//! [`Radiation`] solves for both, 6×6, with a constant-strength source
//! distribution over the body's wetted panels and the deep-water
//! free-surface Green function ([`green`]): Rankine parts integrated in
//! closed form over each flat panel, the wave part at the panel
//! centroids, the wave integral evaluated by Delhommeau's angle integral
//! of the complex exponential integral. Its limits at zero and infinite
//! frequency ([`Surface::ZeroFrequency`], [`Surface::InfiniteFrequency`])
//! and the body alone in unbounded water ([`Surface::Unbounded`]) solve
//! the same system with the matching images.
//!
//! In the time domain ([`Sweep`], [`Kernel`], [`Memory`]) the radiation
//! force is Cummins' `−A∞ ẍ − ∫ K(t − τ) ẋ(τ) dτ`, its kernel fitted by a
//! few exponential states.
//!
//! Conventions are soak's: y up, the still water plane at y = 0, SI units.
//!
//! ```
//! use nalgebra::{Isometry3, Point3};
//! use soak_seakeeping::{Radiation, Surface, wetted_panels};
//!
//! # fn main() -> Result<(), soak_seakeeping::SeakeepingError> {
//! // A box barge 4 × 1 × 2 m floating 0.5 m deep (its centre on the surface).
//! let barge = soak_bake::builtin::cuboid(4.0, 1.0, 2.0);
//! let panels = wetted_panels(&barge, &Isometry3::identity(), 0.7)?;
//! let problem = Radiation::new(panels, Point3::origin(), 1025.0, 9.81)?;
//! // Heave at ω = 2 rad/s: K = ω²/g.
//! let c = problem.solve(Surface::Wavenumber(4.0 / 9.81))?;
//! let (a, b) = (c.added_mass[(1, 1)], c.damping[(1, 1)]);
//! assert!(a > 0.0 && b > 0.0);
//! println!("heave: A = {a:.0} kg, B = {b:.0} kg/s");
//! # Ok(())
//! # }
//! ```

mod error;
pub mod green;
mod memory;
mod model;
mod panels;
mod radiation;
pub mod references;
mod special;

pub use self::error::SeakeepingError;
pub use self::green::Panel;
pub use self::memory::{Kernel, KernelStep, Memory, StepFactors, Sweep};
pub use self::model::{
    FloatingBody, Hydrostatics, RadiationModel, RadiationSettings, RadiationState, decay_measure,
};
pub use self::panels::wetted_panels;
pub use self::radiation::{Coefficients, Potentials, Radiation, Surface};
