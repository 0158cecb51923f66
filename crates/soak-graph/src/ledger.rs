//! The ledger of a flooding: what entered and left the object, in
//! compensated sums, so that `inside = initial + entered − left` can be
//! checked to rounding at every step.

/// A compensated (Neumaier) running sum.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
struct Sum {
    sum: f64,
    carry: f64,
}

impl Sum {
    fn add(&mut self, x: f64) {
        let t = self.sum + x;
        if self.sum.abs() >= x.abs() {
            self.carry += (self.sum - t) + x;
        } else {
            self.carry += (x - t) + self.sum;
        }
        self.sum = t;
    }
    fn value(&self) -> f64 {
        self.sum + self.carry
    }
}

/// What entered and left the object since it was made, m³.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Ledger {
    initial: f64,
    entered: Sum,
    left: Sum,
}

impl Ledger {
    /// Liquid inside at the start, m³.
    pub fn initial(&self) -> f64 {
        self.initial
    }
    /// Liquid that entered since, m³.
    pub fn entered(&self) -> f64 {
        self.entered.value()
    }
    /// Liquid that left since, m³.
    pub fn left(&self) -> f64 {
        self.left.value()
    }
    /// What should be inside: `initial + entered − left`, m³.
    pub fn expected(&self) -> f64 {
        self.initial + self.entered() - self.left()
    }
    /// `|inside − expected| / (initial + entered)`, dimensionless (0 when
    /// nothing was ever inside).
    pub fn relative_error(&self, inside: f64) -> f64 {
        let scale = self.initial + self.entered();
        let err = (inside - self.expected()).abs();
        if scale > 0.0 { err / scale } else { err }
    }

    /// A ledger for `initial` m³ inside and nothing entered or left yet.
    pub(crate) fn new(initial: f64) -> Self {
        Self {
            initial,
            ..Self::default()
        }
    }
    /// Counts `volume` m³ as entered.
    pub(crate) fn enter(&mut self, volume: f64) {
        self.entered.add(volume);
    }
    /// Counts `volume` m³ as left.
    pub(crate) fn leave(&mut self, volume: f64) {
        self.left.add(volume);
    }
    /// The ledger as saved in a [`FloodingState`](crate::FloodingState):
    /// initial, entered (sum, carry), left (sum, carry), m³.
    pub(crate) fn to_parts(self) -> [f64; 5] {
        [
            self.initial,
            self.entered.sum,
            self.entered.carry,
            self.left.sum,
            self.left.carry,
        ]
    }
    /// The ledger saved by [`Ledger::to_parts`].
    pub(crate) fn from_parts([initial, es, ec, ls, lc]: [f64; 5]) -> Self {
        Self {
            initial,
            entered: Sum { sum: es, carry: ec },
            left: Sum { sum: ls, carry: lc },
        }
    }
}
