//! The bookkeeping of a body's liquid: the cumulative [`Ledger`] and the
//! [`StepReport`] of one step.

use serde::{Deserialize, Serialize};

use crate::diffusion::DiffusionReport;

/// Where a body's liquid came from and went, cumulative, m³.
///
/// `total now − total at creation = absorbed + rained + splashed + painted
/// − evaporated + drift + exchanged` ([`Ledger::net`]), to rounding: the
/// conservation tests check exactly this.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct Ledger {
    /// Absorbed from the water through submerged texels.
    pub absorbed: f64,
    /// Caught from rain.
    pub rained: f64,
    /// Deposited by splashes.
    pub splashed: f64,
    /// Net change from setting the liquid directly (images, fills).
    pub painted: f64,
    /// Evaporated.
    pub evaporated: f64,
    /// Change made by the thesis' diffusion scheme (zero in the
    /// conservative mode).
    pub drift: f64,
    /// Net liquid received from other bodies through a shared field.
    pub exchanged: f64,
}

impl Ledger {
    /// The net change of the body's liquid these entries account for, m³.
    pub fn net(&self) -> f64 {
        self.absorbed + self.rained + self.splashed + self.painted - self.evaporated
            + self.drift
            + self.exchanged
    }
}

/// What one [`Wetting::step`](crate::Wetting::step) did, m³ unless stated.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct StepReport {
    /// Absorbed from the water.
    pub absorbed: f64,
    /// Caught from rain.
    pub rained: f64,
    /// Evaporated.
    pub evaporated: f64,
    /// Texels under water.
    pub submerged_texels: usize,
    /// The diffusion on the body's own field, if it has one.
    pub diffusion: Option<DiffusionReport>,
}
