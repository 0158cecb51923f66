//! How long each phase of a step's [`Driver::apply`](crate::Driver::apply)
//! took: where a step's time goes, for a world of many bodies.

use std::time::{Duration, Instant};

/// The wall time of each phase of the last
/// [`Driver::apply`](crate::Driver::apply) (all zero before the first),
/// read with [`Driver::last_step_phases`](crate::Driver::last_step_phases).
/// The engine's own step is not in it.
///
/// Measuring costs six clock reads a step, whatever the number of bodies.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct StepPhases {
    /// Reading each body from the engine and predicting its pose over the
    /// step; the bodies above the highest crest settled (one body at a
    /// time).
    pub predict: Duration,
    /// The water readied for the step (a spectral sea's tile evaluated
    /// once for every body) and each body's options, the sea sampled over
    /// its footprint and the interactive waves it presses (in parallel).
    pub prepare: Duration,
    /// The bodies' buoyancy and drag: their texels' sums, in parallel on
    /// the CPU or in one GPU batch; the water-planes of slamming bodies and
    /// the interactive waves pressed.
    pub evaluate: Duration,
    /// What each body hands the engine: radiation's memory, the added
    /// mass, slamming, the implicit heave and the firewall's checks (in
    /// parallel).
    pub hand: Duration,
    /// The firewall's records and each body's wrench handed to the engine
    /// (one body at a time); the step's lists emptied.
    pub engine: Duration,
}

impl StepPhases {
    /// The five phases together: the whole of the last `apply`.
    pub fn total(&self) -> Duration {
        self.predict + self.prepare + self.evaluate + self.hand + self.engine
    }
}

/// The clock of one `apply`: each phase's end marked in turn.
pub(crate) struct PhaseClock {
    last: Instant,
    phases: [Duration; 5],
    next: usize,
}

impl PhaseClock {
    /// Starts the first phase now.
    pub(crate) fn start() -> Self {
        Self {
            last: Instant::now(),
            phases: [Duration::ZERO; 5],
            next: 0,
        }
    }

    /// Ends the current phase now and starts the next.
    pub(crate) fn mark(&mut self) {
        let now = Instant::now();
        if let Some(p) = self.phases.get_mut(self.next) {
            *p = now - self.last;
        }
        self.last = now;
        self.next += 1;
    }

    /// The phases marked, in order.
    pub(crate) fn phases(&self) -> StepPhases {
        let [predict, prepare, evaluate, hand, engine] = self.phases;
        StepPhases {
            predict,
            prepare,
            evaluate,
            hand,
            engine,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn each_mark_ends_one_phase_in_order() {
        let mut clock = PhaseClock::start();
        std::thread::sleep(Duration::from_millis(2));
        clock.mark();
        clock.mark();
        std::thread::sleep(Duration::from_millis(2));
        clock.mark();
        let p = clock.phases();
        assert!(p.predict >= Duration::from_millis(2));
        assert!(p.evaluate >= Duration::from_millis(2));
        assert_eq!((p.hand, p.engine), (Duration::ZERO, Duration::ZERO));
        assert_eq!(p.total(), p.predict + p.prepare + p.evaluate);
        // Marks beyond the fifth change nothing.
        for _ in 0..4 {
            clock.mark();
        }
        assert_eq!(clock.phases().predict, p.predict);
    }
}
