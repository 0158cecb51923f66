//! Ctrl-C for long headless runs: the first one asks the run to stop after
//! the step (or cell, or frame) it is in, so that it writes what it has
//! recorded; a second one ends the process at once.

use std::sync::Once;
use std::sync::atomic::{AtomicBool, Ordering};

/// Set by the first Ctrl-C.
static STOP: AtomicBool = AtomicBool::new(false);
static INSTALL: Once = Once::new();

/// The exit code of a run stopped by Ctrl-C (128 + SIGINT, as shells have it).
pub const EXIT_CODE: u8 = 130;

/// Installs the handler (once; later calls do nothing). Without a handler
/// (one could not be installed) Ctrl-C ends the process as usual.
pub fn install() {
    INSTALL.call_once(|| {
        let installed = ctrlc::set_handler(|| {
            if STOP.swap(true, Ordering::SeqCst) {
                eprintln!("\nstopped at once");
                std::process::exit(i32::from(EXIT_CODE));
            }
            eprintln!("\nCtrl-C: stopping after this step and writing what was recorded (Ctrl-C again to quit at once)");
        });
        if let Err(e) = installed {
            eprintln!("warning: no Ctrl-C handler ({e}): Ctrl-C will end the run without writing its results");
        }
    });
}

/// Whether Ctrl-C has asked the run to stop.
pub fn requested() -> bool {
    STOP.load(Ordering::SeqCst)
}

/// The error a command returns once it has stopped on Ctrl-C and written
/// what it recorded: `main` prints it and exits with [`EXIT_CODE`].
#[derive(Debug)]
pub struct Interrupted {
    /// What the run had done, e.g. "at t = 12.5 s of 60 s (750 steps)".
    pub done: String,
}

impl std::fmt::Display for Interrupted {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "stopped by Ctrl-C {}", self.done)
    }
}

impl std::error::Error for Interrupted {}
