//! `par_map`: the parallel loop under every pass of this crate.
//!
//! A pass here is short: tens of microseconds for a tiled evaluation,
//! a few hundred for a per-texel one at 1024². Rayon's scopes make the
//! calling thread, when it is not one of the pool's, sleep until the last
//! job has run and be woken again; on a loaded two-core machine that
//! round trip alone takes about as long as a tiled evaluation's work. So
//! the helpers here are rayon jobs the caller does not wait for unless
//! they have started: the caller claims chunks like any helper, and when
//! none is left it closes the loop; a helper that starts after that finds
//! it closed and returns without touching the caller's data, and a helper
//! still at work is waited for by spinning a little (its chunk is short)
//! before parking.
//!
//! Measured against rayon's own `(0..n).into_par_iter().map(f).collect()`
//! (two threads, each variant built and run in turn three times, the
//! sphere at 1024² and 128² and a world of 100 floating spheres): the
//! per-texel pass and the world step take the same time either way, and a
//! tiled evaluation at 1024² (about 6 µs) takes 5.3–5.6 µs here against
//! 6.5 µs with rayon when the caller runs inside rayon's pool (as rapier
//! runs its step) and 11–23 µs when it does not (a game loop calling
//! `evaluate`). So the loop stays.
//!
//! The lifetime of the caller's task is erased for the helpers (they are
//! `'static` rayon jobs); the tests below exercise the hand-over under
//! Miri too: `MIRIFLAGS="-Zmiri-tree-borrows -Zmiri-permissive-provenance
//! -Zmiri-ignore-leaks -Zmiri-many-seeds=0..6" cargo +nightly miri test -p
//! soak-hydro --lib parallel` passes (under Stacked Borrows Miri stops
//! earlier, inside crossbeam-epoch, which rayon uses).

use std::any::Any;
use std::panic::{AssertUnwindSafe, catch_unwind, resume_unwind};
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::{Arc, Mutex, OnceLock};

/// The state bit set once the caller has closed the loop.
const CLOSED: usize = 1;
/// The state's count of helpers inside the loop, in units of this.
const INSIDE: usize = 2;
/// How long a caller waiting for a helper's last chunk spins before it
/// parks: longer than a chunk takes, shorter than a time slice.
const SPIN: std::time::Duration = std::time::Duration::from_micros(50);

/// The loop's task, `Fn(usize)`, with its lifetime erased: a pointer only
/// dereferenced by a helper inside the loop (see [`Shared::enter`]).
struct Task(*const (dyn Fn(usize) + Sync + 'static));

// SAFETY: the pointee is `Sync` (shared calls from any thread are sound),
// and the pointer is dereferenced only while the caller keeps the pointee
// alive (see `Shared::enter` and `Close::drop`).
#[allow(unsafe_code)]
unsafe impl Send for Task {}
// SAFETY: as for `Send`: the pointer itself is never written after creation.
#[allow(unsafe_code)]
unsafe impl Sync for Task {}

/// What the caller shares with its helpers, kept alive by each of them.
struct Shared {
    /// The next index to claim.
    next: AtomicUsize,
    /// Indices `0..n`.
    n: usize,
    /// [`CLOSED`] | [`INSIDE`] × helpers inside the loop.
    state: AtomicUsize,
    /// The thread to unpark when the last helper leaves a closed loop.
    caller: std::thread::Thread,
    task: Task,
    /// The first panic of a helper's task, resumed on the caller's thread.
    panic: Mutex<Option<Box<dyn Any + Send>>>,
}

impl Shared {
    /// Claims indices and runs the task on them until none is left.
    fn run(&self, task: &(dyn Fn(usize) + Sync)) {
        loop {
            let i = self.next.fetch_add(1, Ordering::Relaxed);
            if i >= self.n {
                break;
            }
            task(i);
        }
    }

    /// A helper's whole job: enter the loop unless it is closed, run, leave.
    fn help(&self) {
        if !self.enter() {
            return;
        }
        // SAFETY: entered while the loop was open, so the caller is still
        // in `par_map`, which does not return (nor unwind past the task)
        // before this helper has left (`Close::drop` waits for it).
        #[allow(unsafe_code)]
        let task = unsafe { &*self.task.0 };
        if let Err(payload) = catch_unwind(AssertUnwindSafe(|| self.run(task))) {
            // Stop the others claiming, keep the first panic for the caller.
            self.next.store(self.n, Ordering::Relaxed);
            let mut first = self.panic.lock().unwrap_or_else(|e| e.into_inner());
            first.get_or_insert(payload);
        }
        // Release: the results this helper wrote happen before the caller
        // sees it gone.
        let before = self.state.fetch_sub(INSIDE, Ordering::Release);
        if before == CLOSED | INSIDE {
            self.caller.unpark();
        }
    }

    /// Counts a helper in, unless the caller has closed the loop.
    fn enter(&self) -> bool {
        let mut state = self.state.load(Ordering::Acquire);
        loop {
            if state & CLOSED != 0 {
                return false;
            }
            match self.state.compare_exchange_weak(
                state,
                state + INSIDE,
                Ordering::Acquire,
                Ordering::Acquire,
            ) {
                Ok(_) => return true,
                Err(now) => state = now,
            }
        }
    }
}

/// Closes the loop and waits for the helpers inside it, also when the
/// caller's own task panics: the task must outlive every use of it.
struct Close<'a>(&'a Shared);

impl Drop for Close<'_> {
    fn drop(&mut self) {
        let shared = self.0;
        // No helper enters after this.
        shared.state.fetch_or(CLOSED, Ordering::AcqRel);
        let mut spun: Option<std::time::Instant> = None;
        while shared.state.load(Ordering::Acquire) != CLOSED {
            if spun.get_or_insert_with(std::time::Instant::now).elapsed() < SPIN {
                std::hint::spin_loop();
            } else {
                // The last helper out unparks; a stale unpark only makes
                // this loop check once more.
                std::thread::park();
            }
        }
    }
}

/// `[f(0), …, f(n − 1)]`, computed on rayon's pool with the calling thread
/// taking part: every thread claims the next index from one counter until
/// none is left. The result does not depend on which thread computed which
/// item. A call with work for one thread only (a short pass, or a pool of
/// one) runs on the calling thread alone, at the cost of a few atomic
/// operations and one job handed to rayon per other thread.
///
/// A panic in `f` reaches the caller, after every thread has left `f`.
pub(crate) fn par_map<T, F>(n: usize, f: F) -> Vec<T>
where
    T: Send + Sync,
    F: Fn(usize) -> T + Sync,
{
    let helpers = rayon::current_num_threads().min(n).saturating_sub(1);
    if helpers == 0 {
        return (0..n).map(f).collect();
    }
    let slots: Vec<OnceLock<T>> = (0..n).map(|_| OnceLock::new()).collect();
    // Each index is claimed once, so its slot is empty.
    let task = |i: usize| {
        let _ = slots[i].set(f(i));
    };
    let task: &(dyn Fn(usize) + Sync) = &task;
    // SAFETY: only the lifetime changes (same pointer, same vtable); the
    // pointer is dereferenced by helpers inside the loop only, and `Close`
    // keeps `task` alive until every helper inside has left.
    #[allow(unsafe_code)]
    let erased = unsafe {
        std::mem::transmute::<*const (dyn Fn(usize) + Sync + '_), *const (dyn Fn(usize) + Sync + 'static)>(
            task,
        )
    };
    let shared = Arc::new(Shared {
        next: AtomicUsize::new(0),
        n,
        state: AtomicUsize::new(0),
        caller: std::thread::current(),
        task: Task(erased),
        panic: Mutex::new(None),
    });
    for _ in 0..helpers {
        let shared = Arc::clone(&shared);
        rayon::spawn(move || shared.help());
    }
    {
        let _close = Close(&shared);
        shared.run(task);
    }
    if let Some(payload) = shared.panic.lock().unwrap_or_else(|e| e.into_inner()).take() {
        resume_unwind(payload);
    }
    // Every index was claimed by a thread that ran it to the end (no panic),
    // and every such thread has left: every slot is set.
    slots.into_iter().filter_map(OnceLock::into_inner).collect()
}

/// [`par_map`] folded into `acc` in index order, `add(acc, f(0))`,
/// `add(acc, f(1))`, …, `add(acc, f(n − 1))`: the same result on any
/// number of threads. A single item (a body whose tiles make one chunk) is
/// computed and folded on the calling thread, with no list. The
/// accumulator is added to in place (a body's sums are a few hundred
/// bytes, which a fold by value would move out and back for each item).
pub(crate) fn par_fold<T, A, F, G>(n: usize, f: F, acc: &mut A, mut add: G)
where
    T: Send + Sync,
    F: Fn(usize) -> T + Sync,
    G: FnMut(&mut A, T),
{
    if n == 1 {
        add(acc, f(0));
        return;
    }
    for item in par_map(n, f) {
        add(acc, item);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_index_once_in_order() {
        for n in [0, 1, 2, 3, 17, 1000] {
            let out = par_map(n, |i| i * i);
            assert_eq!(out, (0..n).map(|i| i * i).collect::<Vec<_>>());
        }
    }

    #[test]
    fn a_fold_adds_in_index_order() {
        for n in [0, 1, 2, 5, 100] {
            let mut folded = Vec::new();
            par_fold(n, |i| i, &mut folded, |v, i| v.push(i));
            assert_eq!(folded, (0..n).collect::<Vec<_>>());
        }
    }

    #[test]
    fn nested_calls_finish() {
        let out = par_map(8, |i| par_map(50, |j| i * j).into_iter().sum::<usize>());
        assert_eq!(
            out,
            (0..8).map(|i| i * (0..50).sum::<usize>()).collect::<Vec<_>>()
        );
    }

    #[test]
    fn from_inside_the_pool_and_from_many_threads() {
        let inside = rayon::ThreadPoolBuilder::new()
            .num_threads(3)
            .build()
            .unwrap()
            .install(|| par_map(100, |i| i + 1));
        assert_eq!(inside, (1..=100).collect::<Vec<_>>());
        std::thread::scope(|s| {
            for t in 0..4 {
                s.spawn(move || {
                    for _ in 0..if cfg!(miri) { 3 } else { 200 } {
                        assert_eq!(par_map(7, |i| i + t), (t..t + 7).collect::<Vec<_>>());
                    }
                });
            }
        });
    }

    #[test]
    fn a_panic_reaches_the_caller_after_the_helpers_leave() {
        for bad in [0, 5, 63] {
            let result = catch_unwind(|| {
                par_map(64, |i| {
                    if i == bad {
                        panic!("chunk {i}");
                    }
                    i
                })
            });
            let payload = result.expect_err("the panic is resumed");
            assert_eq!(
                payload.downcast_ref::<String>().map(String::as_str),
                Some(format!("chunk {bad}").as_str())
            );
        }
    }
}
