//! What one cell measured.

use serde::{Deserialize, Serialize};

use super::matrix::{Level, WaterKind};

/// What physics says the body does.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Expect {
    /// Lighter than water: floats with the displaced fraction equal to its
    /// relative density.
    Floats,
    /// Heavier: sinks.
    Sinks,
    /// As dense as water: once under, neither rises nor sinks.
    Neutral,
}

/// What one cell measured, and whether it passed (read back from its JSON
/// as `soak stress --journal` writes it).
#[derive(Clone, Debug, Serialize, Deserialize)]
pub struct Outcome {
    /// The cell's name ([`super::Cell::name`]).
    pub cell: String,
    /// The mesh's label.
    pub mesh: String,
    /// Scale factor of the mesh.
    pub scale: f64,
    /// Relative density ρ_b/ρ_w.
    pub density: f64,
    /// Time step, s.
    pub dt: f64,
    /// The fluid.
    pub water: WaterKind,
    /// The effects.
    pub effects: Level,
    /// Steps taken.
    pub steps: usize,
    /// Simulated time over the body's natural time `√(size/g)`.
    pub natural_times: f64,
    /// Wall-clock time of the cell, ms.
    pub wall_ms: f64,
    /// Body state and applied forces finite at every step.
    pub finite: bool,
    /// Firewall events (rejected forces or states).
    pub firewall: u64,
    /// The body radiated: a `+radiation` cell whose body the panel method
    /// could float, at a step that resolves its motion
    /// (`RadiationModel::resolved_by`).
    pub radiates: bool,
    /// Largest growth of specific energy over the allowance (≤ 1 passes).
    pub energy_ratio: f64,
    /// Largest growth of specific energy, J/kg.
    pub energy_growth: f64,
    /// The growth of specific energy allowed, J/kg.
    pub energy_allowance: f64,
    /// Worst liquid error (ingress and wetting; ≤ 1 passes), `None` without liquid.
    pub liquid_ratio: Option<f64>,
    /// What the worst liquid error was.
    pub liquid_note: String,
    /// Relative density at the end (mass with the liquid inside over the
    /// displaced water's when fully submerged).
    pub density_end: f64,
    /// What physics says the body does.
    pub expect: Expect,
    /// Mean displaced fraction over the last half.
    pub mean_fraction: f64,
    /// The displaced fraction expected.
    pub expected_fraction: f64,
    /// Displaced fraction at the end.
    pub final_fraction: f64,
    /// Final vertical velocity over `√(g·size)`.
    pub final_vy: f64,
    /// Mean vertical velocity over the last half of the run, over `√(g·size)`.
    pub mean_vy: f64,
    /// Whether it floats, sinks or hovers as expected.
    pub settled: bool,
    /// What the settling check measured.
    pub settle_note: String,
    /// Every check passed.
    pub pass: bool,
    /// The failed checks, each with what it measured.
    pub failures: Vec<String>,
}
