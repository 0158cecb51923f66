//! The stability matrix: meshes × relative densities × time steps × scales
//! × waters × effects.
//!
//! Every cell drops one body into one fluid and runs Rapier with the force
//! generator for a while, checking at every step that nothing non-finite
//! reached Rapier, and at the end that the body's energy stayed within what
//! the fluid could give it, that the liquid inside and on it was conserved
//! and stayed within its bounds, and that it floats, sinks or hovers as
//! its density says. The project's `docs/stress.md` explains each check and
//! its bound.
//!
//! ```no_run
//! use soak_report::stress::{Cell, StressOptions, run};
//!
//! let cells = [Cell::from_name("boat/1m/0.5/1/60/sea/+drag").expect("a cell of the matrix")];
//! let outcomes = run(&cells, &StressOptions::default())?;
//! assert!(outcomes[0].pass, "{:?}", outcomes[0].failures);
//! # Ok::<(), soak_report::stress::StressError>(())
//! ```

mod cell;
mod energy;
mod error;
mod fixture;
mod liquid_check;
mod matrix;
mod outcome;
mod settling;
mod table;

use std::collections::HashMap;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::{Arc, Mutex, OnceLock};

use soak_rapier::soak_seakeeping::RadiationModel;

use soak_hydro::BuoyancyMode;

pub use error::StressError;
pub use matrix::{Cell, DENSITIES, Level, RATES, SCALES, Shape, WaterKind, full_matrix, quick_matrix};
pub use outcome::{Expect, Outcome};
pub use table::{markdown_table, text_table};

use cell::run_cell;
use fixture::Fixture;

/// How the cells of a matrix run.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct StressOptions {
    /// Atlas resolution, texels per side (32 in the published matrix).
    pub resolution: u32,
    /// Most steps per cell (150 for the quick matrix, 300 for the full
    /// one); a sea cell runs up to 30 times that, for two wave periods
    /// (ten times where even 30 would not hold them).
    pub max_steps: usize,
    /// Cells run at once, each on a thread of its own.
    pub threads: usize,
    /// Buoyancy mode of every cell.
    pub mode: BuoyancyMode,
}

impl Default for StressOptions {
    /// The full matrix's settings: 32² atlases, at most 300 steps,
    /// Archimedes buoyancy, one thread per core.
    fn default() -> Self {
        Self {
            resolution: 32,
            max_steps: 300,
            threads: std::thread::available_parallelism().map_or(1, |n| n.get()),
            mode: BuoyancyMode::Archimedes,
        }
    }
}

/// Runs `cells`, each mesh baked once per scale, on `options.threads`
/// threads, and returns their outcomes in the order of `cells`.
///
/// # Errors
/// [`StressError::Cell`] naming the first cell (in order) that could not be
/// set up or run, or an error baking a mesh. A cell that runs and fails a
/// check is not an error: its [`Outcome::pass`] is `false`.
pub fn run(cells: &[Cell], options: &StressOptions) -> Result<Vec<Outcome>, StressError> {
    run_with(
        cells,
        options,
        &Control {
            stop: &|| false,
            done: &|_, _| {},
            finished: &|_| {},
        },
    )
}

/// What a caller may do while the matrix runs ([`run_with`]).
pub struct Control<'a> {
    /// Asked before each cell: once it answers `true` (a Ctrl-C handler's
    /// flag, a deadline) no further cell starts.
    pub stop: &'a (dyn Fn() -> bool + Sync),
    /// Told after each cell how many cells are done, of how many.
    pub done: &'a (dyn Fn(usize, usize) + Sync),
    /// Handed each cell's outcome as soon as the cell has run (in the
    /// order the cells finish): `soak stress --journal` writes it down, so
    /// that a run killed at any moment keeps every cell it finished.
    pub finished: &'a (dyn Fn(&Outcome) + Sync),
}

/// [`run`] under `control`: the outcomes of the cells that ran, in the
/// order of `cells`; all of them unless `control.stop` stopped the run, in
/// which case the cells it kept from starting are left out.
///
/// # Errors
/// As [`run`].
pub fn run_with(
    cells: &[Cell],
    options: &StressOptions,
    control: &Control,
) -> Result<Vec<Outcome>, StressError> {
    // Bake each mesh once per scale.
    let mut keys: Vec<(Shape, u64)> = cells.iter().map(|c| (c.mesh, c.scale.to_bits())).collect();
    keys.sort_unstable();
    keys.dedup();
    let mut fixtures = Vec::with_capacity(keys.len());
    for &(mesh, scale) in &keys {
        fixtures.push(Fixture::new(mesh, f64::from_bits(scale), options.resolution)?);
    }
    let fixture_of = |c: &Cell| {
        let k = keys
            .binary_search(&(c.mesh, c.scale.to_bits()))
            .expect("baked above");
        &fixtures[k]
    };

    let bakes = RadiationBakes::default();
    let next = AtomicUsize::new(0);
    let finished = AtomicUsize::new(0);
    let results: Mutex<Vec<Option<Result<Outcome, StressError>>>> =
        Mutex::new((0..cells.len()).map(|_| None).collect());
    std::thread::scope(|s| {
        for _ in 0..options.threads.max(1).min(cells.len()) {
            s.spawn(|| {
                loop {
                    if (control.stop)() {
                        break;
                    }
                    let i = next.fetch_add(1, Ordering::Relaxed);
                    let Some(cell) = cells.get(i) else { break };
                    let r = run_cell(cell, fixture_of(cell), options.max_steps, options.mode, &bakes);
                    if let Ok(outcome) = &r {
                        (control.finished)(outcome);
                    }
                    if let Ok(mut results) = results.lock() {
                        results[i] = Some(r);
                    }
                    (control.done)(finished.fetch_add(1, Ordering::Relaxed) + 1, cells.len());
                }
            });
        }
    });
    let results = results.into_inner().map_err(|_| StressError::Worker)?;
    let mut outcomes = Vec::with_capacity(results.len());
    for (cell, r) in cells.iter().zip(results) {
        match r {
            Some(Ok(o)) => outcomes.push(o),
            Some(Err(e)) => {
                return Err(StressError::Cell {
                    cell: cell.name(),
                    source: Box::new(e),
                });
            }
            None if (control.stop)() => {}
            None => return Err(StressError::Worker),
        }
    }
    Ok(outcomes)
}

/// The radiation of each mesh, scale and relative density the cells ask
/// for, baked once (by the first cell to ask; the others wait for it).
/// `None` where the panel method cannot float the body.
#[derive(Default)]
pub(crate) struct RadiationBakes(Mutex<HashMap<RadiationKey, Arc<RadiationSlot>>>);

/// Mesh, scale bits, relative density bits.
type RadiationKey = (Shape, u64, u64);

/// One key's model, once baked (`None`: the body could not be floated).
type RadiationSlot = OnceLock<Option<Arc<RadiationModel>>>;

impl RadiationBakes {
    /// The model for `key`, baked by `bake` if no cell has asked before.
    pub(crate) fn get(
        &self,
        key: RadiationKey,
        bake: impl FnOnce() -> Option<Arc<RadiationModel>>,
    ) -> Option<Arc<RadiationModel>> {
        let slot = {
            let mut map = self.0.lock().ok()?;
            Arc::clone(map.entry(key).or_default())
        };
        slot.get_or_init(bake).clone()
    }
}

/// The cells of the quick (`quick = true`) or the full matrix whose name
/// contains `only` (all of them without a filter).
///
/// # Errors
/// [`StressError::NoCell`] when no cell matches.
pub fn select(quick: bool, only: Option<&str>) -> Result<Vec<Cell>, StressError> {
    let mut cells = if quick { quick_matrix() } else { full_matrix() };
    if let Some(only) = only {
        cells.retain(|c| c.name().contains(only));
    }
    if cells.is_empty() {
        return Err(StressError::NoCell(only.unwrap_or_default().to_string()));
    }
    Ok(cells)
}
