//! The parameters of the liquid's motion inside a body: viscosity,
//! redistribution passes, height tolerance and seed, shared by the
//! discharge search and the flooding that drives it.

use serde::{Deserialize, Serialize};

use crate::error::FlowError;
use crate::liquid_graph::WATER_VISCOSITY;

/// Parameters of the liquid's motion.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct FlowOptions {
    /// Dynamic viscosity μ of the liquid, Pa·s (> 0). Default water's, 10⁻³.
    pub viscosity: f64,
    /// Redistribution passes per step (≥ 1), each over `Δt/passes`.
    /// Default 1, as the thesis.
    pub passes: u32,
    /// Height tolerance of the barrier and head comparisons, m (≥ 0).
    /// Default 10⁻⁹.
    pub tolerance: f64,
    /// Seed of the random neighbour and node orders.
    pub seed: u64,
    /// Discharge coefficient `C_d` of openings (holes, open rims) in
    /// `Q = C_d A √(2 g Δh)`, in (0, 1]. Default 0.6, a sharp-edged orifice.
    pub discharge_coefficient: f64,
}

impl Default for FlowOptions {
    fn default() -> Self {
        Self {
            viscosity: WATER_VISCOSITY,
            passes: 1,
            tolerance: 1e-9,
            seed: 0,
            discharge_coefficient: 0.6,
        }
    }
}

impl FlowOptions {
    /// Checks every parameter's range.
    ///
    /// # Errors
    /// The first parameter out of range, by name.
    pub fn check(&self) -> Result<(), FlowError> {
        if !(self.viscosity.is_finite() && self.viscosity > 0.0) {
            return Err(FlowError::Parameter {
                name: "viscosity",
                value: self.viscosity,
                requirement: "must be a finite number > 0 (Pa·s)",
            });
        }
        if self.passes == 0 {
            return Err(FlowError::Parameter {
                name: "passes",
                value: 0.0,
                requirement: "must be ≥ 1",
            });
        }
        if !(self.tolerance.is_finite() && self.tolerance >= 0.0) {
            return Err(FlowError::Parameter {
                name: "tolerance",
                value: self.tolerance,
                requirement: "must be a finite number ≥ 0 (m)",
            });
        }
        if !(self.discharge_coefficient > 0.0 && self.discharge_coefficient <= 1.0) {
            return Err(FlowError::Parameter {
                name: "discharge coefficient",
                value: self.discharge_coefficient,
                requirement: "must be in (0, 1]",
            });
        }
        Ok(())
    }
}
