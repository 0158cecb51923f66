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

mod error;
pub mod green;
mod memory;
mod panels;
mod radiation;
mod special;

pub use self::error::SeakeepingError;
pub use self::green::Panel;
pub use self::memory::{Kernel, Memory, Sweep};
pub use self::panels::wetted_panels;
pub use self::radiation::{Coefficients, Potentials, Radiation, Surface};
