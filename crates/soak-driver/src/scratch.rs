//! The lists a step of [`Driver::apply`](crate::Driver::apply) fills,
//! kept by the driver from one step to the next.

use soak_hydro::{BodyState, HydroForces, HydroOptions, Water, Wrench};

use crate::engine::EngineBody;
use crate::waves::Pressed;

/// What a body in the step's work list reads: its options for the step,
/// the sea sampled over its footprint (`None`: the driver's water itself)
/// and, with interactive waves, the cells it pressed.
pub(crate) struct Prepared {
    pub(crate) options: HydroOptions,
    pub(crate) sea: Option<Water>,
    pub(crate) pressed: Option<Pressed>,
}

/// The lists a step fills, kept by the driver from one step to the next so
/// that a step allocates none of them once they have grown to the bodies'
/// number (their contents dropped at the end of each step).
pub(crate) struct StepScratch<H> {
    /// The bodies that need texel work: index and predicted state.
    pub(crate) work: Vec<(usize, BodyState)>,
    /// What the engine said of each body in `work`, in the same order.
    pub(crate) engine: Vec<EngineBody>,
    /// What each body in `work` reads, in the same order.
    pub(crate) prepared: Vec<Prepared>,
    /// Each body's evaluation, in `work`'s order.
    pub(crate) results: Vec<Result<HydroForces, String>>,
    /// Each body's place in `work` (`usize::MAX`: not in it).
    pub(crate) slot: Vec<usize>,
    /// What each body hands the engine, by body.
    pub(crate) handed: Vec<Option<Handed<H>>>,
}

impl<H> Default for StepScratch<H> {
    fn default() -> Self {
        Self {
            work: Vec::new(),
            engine: Vec::new(),
            prepared: Vec::new(),
            results: Vec::new(),
            slot: Vec::new(),
            handed: Vec::new(),
        }
    }
}

impl<H> StepScratch<H> {
    /// Drops what the step put in the lists, keeping their room.
    pub(crate) fn clear(&mut self) {
        self.work.clear();
        self.engine.clear();
        self.prepared.clear();
        self.results.clear();
        self.slot.clear();
        self.handed.clear();
    }
}

impl<H> std::fmt::Debug for StepScratch<H> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("StepScratch")
            .field("capacity", &self.work.capacity())
            .finish_non_exhaustive()
    }
}

/// What the step hands the engine for one body (`step::hand`): the wrench for
/// the body `handle` names, and what the firewall rejected on the way (each
/// quantity with the reason), in order.
pub(crate) struct Handed<H> {
    pub(crate) handle: H,
    pub(crate) applied: Wrench,
    pub(crate) rejected: Vec<(&'static str, String)>,
}
