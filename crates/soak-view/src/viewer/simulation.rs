//! The simulation thread of the live window: the world ([`Live`]), what
//! the window asks of the thread ([`Control`]) and what it reports
//! ([`Stats`]), shared behind locks ([`Shared`]), and the thread itself
//! ([`simulate`]), which steps at the clock's pace while playing.

use std::sync::{Mutex, MutexGuard};
use std::time::{Duration, Instant};

use soak_rapier::{SampleCsv, Simulation};

use super::{MAX_LAG, STARVED, Source, ViewOptions};

/// The world and what it was made from.
pub(super) struct Live {
    pub(super) sim: Simulation,
    pub(super) source: Source,
    /// Bumped by each step, restart and reload: a frame's state is new when
    /// it differs.
    pub(super) generation: u64,
}

/// What the window asks of the simulation thread.
#[derive(Clone, Copy, Debug)]
pub(super) struct Control {
    pub(super) play: bool,
    pub(super) time_scale: f64,
    pub(super) single_steps: u32,
    pub(super) restart: bool,
    pub(super) quit: bool,
    /// When the window thread began to wait for the world, if it does.
    pub(super) wanted_since: Option<Instant>,
    /// The window thread needs the world now (to open, reload): no step
    /// starts until it has had it.
    pub(super) hold: bool,
}

/// What the simulation thread reports.
#[derive(Clone, Debug, Default)]
pub(super) struct Stats {
    /// Mean step, ms, over the recent steps.
    pub(super) step_ms: f64,
    /// Simulated over wall-clock seconds while playing, recently.
    pub(super) speed: f64,
    /// Whether it fell behind the clock (slower than asked).
    pub(super) behind: bool,
    /// The last step's error, if the simulation stopped on one.
    pub(super) error: Option<String>,
    /// Whether it paused at the scene's end.
    pub(super) ended: bool,
}

pub(super) struct Shared {
    pub(super) live: Mutex<Live>,
    pub(super) control: Mutex<Control>,
    pub(super) stats: Mutex<Stats>,
}

impl Shared {
    pub(super) fn new(sim: Simulation, source: Source, options: &ViewOptions) -> Self {
        Self {
            live: Mutex::new(Live {
                sim,
                source,
                generation: 0,
            }),
            control: Mutex::new(Control {
                play: options.play,
                time_scale: options.time_scale,
                single_steps: 0,
                restart: false,
                quit: false,
                wanted_since: None,
                hold: false,
            }),
            stats: Mutex::new(Stats::default()),
        }
    }
}

/// A lock that a panic elsewhere does not poison for good.
pub(super) fn lock<T>(m: &Mutex<T>) -> MutexGuard<'_, T> {
    m.lock().unwrap_or_else(std::sync::PoisonError::into_inner)
}

/// `f` on the world as soon as the step in progress (if any) ends: the
/// simulation thread starts no step meanwhile (the world's lock is not
/// fair, and it would take it back between two steps).
pub(super) fn with_world<R>(shared: &Shared, f: impl FnOnce(&mut Live) -> R) -> R {
    lock(&shared.control).hold = true;
    let r = f(&mut lock(&shared.live));
    lock(&shared.control).hold = false;
    r
}

/// The simulation thread: steps at the clock's pace while playing, and
/// streams the bodies' samples to `csv` if there is one (synced to disk
/// when the window closes).
pub(super) fn simulate(shared: &Shared, mut csv: Option<SampleCsv>) {
    run(shared, &mut csv);
    if let Some(csv) = &mut csv
        && let Err(e) = csv.sync()
    {
        eprintln!("cannot write the CSV {}: {e}", csv.path().display());
    }
}

fn run(shared: &Shared, csv: &mut Option<SampleCsv>) {
    // The clock: simulated time `anchor.1` at wall time `anchor.0`.
    let mut anchor: Option<(Instant, f64)> = None;
    let mut recent: Vec<(Instant, f64, f64)> = Vec::new(); // (wall, sim time, step ms)
    loop {
        let control = *lock(&shared.control);
        if control.quit {
            return;
        }
        if control.restart {
            let mut live = lock(&shared.live);
            let rebuilt = match &live.source {
                Source::Scene(loaded) => {
                    Simulation::from_scene(loaded).map_err(|e| format!("restart failed: {e}"))
                }
                Source::World(_) => Err("a world of your own cannot be built again: no restart".to_string()),
            };
            let mut stats = lock(&shared.stats);
            match rebuilt {
                Ok(sim) => {
                    live.sim = sim;
                    live.generation += 1;
                    stats.error = None;
                    stats.ended = false;
                }
                Err(e) => stats.error = Some(e),
            }
            lock(&shared.control).restart = false;
            anchor = None;
            continue;
        }
        let stepping = control.single_steps > 0;
        if !control.play && !stepping {
            anchor = None;
            std::thread::sleep(Duration::from_millis(4));
            continue;
        }
        // Waiting for the window thread to take a frame's state, or for
        // it to be done with the world.
        if control.hold || control.wanted_since.is_some_and(|t| t.elapsed() > STARVED) {
            std::thread::sleep(Duration::from_millis(1));
            continue;
        }
        let mut live = lock(&shared.live);
        let now = Instant::now();
        let sim_time = live.sim.time();
        if !stepping {
            if sim_time >= live.sim.duration {
                drop(live);
                lock(&shared.control).play = false;
                lock(&shared.stats).ended = true;
                continue;
            }
            let (wall, at) = *anchor.get_or_insert((now, sim_time));
            let due = at + (now - wall).as_secs_f64() * control.time_scale;
            if sim_time > due {
                drop(live);
                let ahead = (sim_time - due) / control.time_scale.max(1e-6);
                std::thread::sleep(Duration::from_secs_f64(ahead.min(0.01)));
                continue;
            }
            let behind = due - sim_time > MAX_LAG * control.time_scale;
            if behind {
                anchor = Some((now, sim_time));
            }
            lock(&shared.stats).behind = behind;
        }
        // A world new to the series (the first, a restart's, a reload's)
        // records from its present state.
        if csv.is_some() && !live.sim.is_recording() {
            live.sim.record(true);
        }
        let start = Instant::now();
        let result = live.sim.step();
        let step_ms = start.elapsed().as_secs_f64() * 1e3;
        live.generation += 1;
        let t = live.sim.time();
        let written = match csv {
            Some(file) => {
                let samples = live.sim.take_samples();
                file.rows(&live.sim, &samples)
                    .map_err(|e| format!("cannot write the CSV {}: {e}", file.path().display()))
            }
            None => Ok(()),
        };
        drop(live);
        if stepping {
            let mut c = lock(&shared.control);
            c.single_steps = c.single_steps.saturating_sub(1);
            anchor = None;
        }
        recent.push((Instant::now(), t, step_ms));
        recent.retain(|(w, _, _)| w.elapsed() < Duration::from_secs(1));
        let mut stats = lock(&shared.stats);
        stats.step_ms = recent.iter().map(|r| r.2).sum::<f64>() / recent.len() as f64;
        if let (Some(first), Some(last)) = (recent.first(), recent.last()) {
            let wall = (last.0 - first.0).as_secs_f64();
            if wall > 0.1 && !stepping {
                stats.speed = (last.1 - first.1) / wall;
            }
        }
        if let Err(e) = result {
            stats.error = Some(format!("the simulation stopped: {e}"));
            drop(stats);
            lock(&shared.control).play = false;
        } else if let Err(e) = written {
            // The series asked for is not being kept: stop rather than
            // run on without it.
            stats.error = Some(e);
            drop(stats);
            lock(&shared.control).play = false;
        }
    }
}
