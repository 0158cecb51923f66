//! Lists of texel ranges kept from one evaluation to the next on a thread.
//!
//! A tiled evaluation lists the ranges of texels its kernels are to run
//! over, a few to a few dozen in each chunk of its tiles (the cut tiles'
//! buoyancy, the drag's kernel lists): some ten lists a chunk, made and
//! dropped in a few microseconds. Allocating them each time cost a body
//! with drag on calm water about 3 % of its evaluation (`malloc`,
//! `realloc` and `free` under `perf`); a [`Ranges`] takes a list this
//! thread has dropped before, emptied, and gives it back when dropped, so
//! that after a thread's first evaluations they allocate nothing.

use std::cell::RefCell;
use std::ops::{Deref, DerefMut, Range};

/// Most lists a thread keeps: more than one chunk's worth.
const KEPT: usize = 32;
/// Largest list kept, ranges (a 1024² atlas has 16,384 tiles of 8²): a
/// list longer than this is freed, so that one huge body's lists do not
/// stay with the thread.
const KEPT_CAPACITY: usize = 4096;

thread_local! {
    static KEPT_LISTS: RefCell<Vec<Vec<Range<usize>>>> = const { RefCell::new(Vec::new()) };
}

/// A list of texel ranges, empty when made, its allocation this thread's
/// to reuse once dropped.
#[derive(Debug)]
pub(crate) struct Ranges(Vec<Range<usize>>);

impl Ranges {
    /// An empty list (one the thread kept, when it has one).
    pub(crate) fn new() -> Self {
        let kept = KEPT_LISTS.try_with(|kept| kept.borrow_mut().pop()).ok().flatten();
        Self(kept.unwrap_or_default())
    }
}

impl Default for Ranges {
    fn default() -> Self {
        Self::new()
    }
}

impl Drop for Ranges {
    fn drop(&mut self) {
        let mut list = std::mem::take(&mut self.0);
        if list.capacity() == 0 || list.capacity() > KEPT_CAPACITY {
            return;
        }
        list.clear();
        // A thread being torn down keeps nothing.
        let _ = KEPT_LISTS.try_with(|kept| {
            let mut kept = kept.borrow_mut();
            if kept.len() < KEPT {
                kept.push(list);
            }
        });
    }
}

impl Deref for Ranges {
    type Target = Vec<Range<usize>>;
    fn deref(&self) -> &Self::Target {
        &self.0
    }
}

impl DerefMut for Ranges {
    fn deref_mut(&mut self) -> &mut Self::Target {
        &mut self.0
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_list_dropped_is_handed_out_again_empty() {
        let mut a = Ranges::new();
        a.extend([0..4, 8..12]);
        let pointer = a.as_ptr();
        drop(a);
        let b = Ranges::new();
        assert!(b.is_empty());
        assert_eq!(b.as_ptr(), pointer, "the kept allocation");
        // Two at once: the second is a new one.
        let mut c = Ranges::new();
        c.push(0..1);
        assert_ne!(c.as_ptr(), b.as_ptr());
    }

    #[test]
    fn a_huge_list_is_not_kept() {
        let mut a = Ranges::new();
        a.extend((0..KEPT_CAPACITY + 1).map(|i| i..i + 1));
        let pointer = a.as_ptr();
        drop(a);
        let b = Ranges::new();
        assert!(b.capacity() == 0 || b.as_ptr() != pointer);
    }

    #[test]
    fn a_thread_keeps_a_bounded_number_of_lists() {
        let lists: Vec<Ranges> = (0..2 * KEPT)
            .map(|i| {
                let mut r = Ranges::new();
                r.push(i..i + 1);
                r
            })
            .collect();
        drop(lists);
        assert_eq!(KEPT_LISTS.with(|k| k.borrow().len()), KEPT);
    }
}
