//! The NaN firewall: nothing non-finite or absurd reaches the engine.

use serde::Serialize;

/// One rejected quantity.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct FirewallEvent {
    /// The driver's step at which it happened.
    pub step: u64,
    /// The soak body's name.
    pub body: String,
    /// What was rejected (`buoyancy force`, `drag torque`, `mass properties`, `body state`, ...).
    pub quantity: &'static str,
    /// Why.
    pub reason: String,
}

/// Counts rejected quantities and keeps the most recent events.
#[derive(Clone, Debug, Default)]
pub struct Firewall {
    count: u64,
    recent: std::collections::VecDeque<FirewallEvent>,
}

/// Events kept by [`Firewall::recent`].
pub const FIREWALL_MEMORY: usize = 256;

impl Firewall {
    /// Records an event and logs it at warn level.
    pub fn reject(&mut self, step: u64, body: &str, quantity: &'static str, reason: String) {
        log::warn!(
            "soak: step {step}: body `{body}`: rejected {quantity}: {reason}; kept its last good value"
        );
        self.count += 1;
        if self.recent.len() == FIREWALL_MEMORY {
            self.recent.pop_front();
        }
        self.recent.push_back(FirewallEvent {
            step,
            body: body.to_string(),
            quantity,
            reason,
        });
    }

    /// How many quantities were rejected since the start.
    pub fn count(&self) -> u64 {
        self.count
    }

    /// The most recent events, oldest first (at most [`FIREWALL_MEMORY`]).
    pub fn recent(&self) -> impl Iterator<Item = &FirewallEvent> {
        self.recent.iter()
    }
}
