//! The liquid check: the liquid inside a flooding hull and on a wet surface
//! stays within its bounds and balances its ledger, and the wetting
//! diffusion takes the substeps its stability asks for.

use soak_graph::Flooding;
use soak_wet::{StepReport, Wetting};

use super::fixture::Fixture;

/// The worst liquid error of a run over its tolerance (≤ 1 passes), and
/// what it was.
#[derive(Debug, Default)]
pub(crate) struct LiquidCheck {
    /// Worst error over its tolerance.
    pub(crate) worst: f64,
    /// What the worst error was.
    pub(crate) note: String,
}

impl LiquidCheck {
    /// A wetting step at step `k` must plan exactly `expected` substeps
    /// (or one more) and not be limited.
    pub(crate) fn plan(&mut self, k: usize, report: &StepReport, expected: u32) {
        let plan = report.diffusion.map(|d| d.plan).unwrap_or_default();
        if plan.limited || plan.substeps < expected || plan.substeps > expected + 1 {
            self.worst = f64::INFINITY;
            self.note = format!("step {k}: diffusion plan {plan:?}");
        }
    }

    /// Liquid inside: every node within `[0, capacity]`, the ledger
    /// balanced to 1e-9, the total within the hull's `capacity` (m³).
    pub(crate) fn inside(&mut self, flooding: Option<&Flooding>, capacity: f64) {
        if let Some(fl) = flooding {
            let inside = fl.inside();
            let over = fl
                .graph()
                .nodes()
                .map(|n| (-n.liquid).max(n.liquid - n.capacity).max(0.0) / n.capacity.max(f64::MIN_POSITIVE))
                .fold(0.0, f64::max);
            let ledger = fl.ledger().relative_error(inside);
            let ratio = (over / 1e-12)
                .max(ledger / 1e-9)
                .max((inside - capacity).max(0.0) / (1e-12 * capacity));
            if ratio > self.worst {
                self.worst = ratio;
                self.note = format!(
                    "inside {:.3} of capacity, ledger error {ledger:.1e}",
                    inside / capacity
                );
            }
        }
    }

    /// Liquid on the surface: every texel in `[0, saturation]`, the total
    /// within `[0, wet_capacity]` (m³) and balanced by the ledger to 1e-9.
    pub(crate) fn surface(&mut self, wet: &Wetting, f: &Fixture, wet_capacity: f64) {
        let sat = wet.material().saturation;
        let out = wet
            .liquid()
            .iter()
            .map(|&h| (-h).max(h - sat).max(0.0) / sat)
            .fold(0.0, f64::max);
        let total = wet.total_liquid(&f.atlas);
        // A new Wetting is dry: everything on it is in the ledger.
        let balance = (total - wet.ledger().net()).abs() / wet_capacity;
        let ratio =
            (out / 1e-12)
                .max(balance / 1e-9)
                .max(if total.is_finite() { 0.0 } else { f64::INFINITY });
        if ratio > self.worst || (self.note.is_empty() && self.worst == 0.0) {
            self.worst = self.worst.max(ratio);
            self.note = format!(
                "surface {:.3} of saturation, balance error {balance:.1e}",
                total / wet_capacity
            );
        }
    }
}
