//! Lists of texel ranges kept from one evaluation to the next on a thread.
//!
//! A tiled evaluation lists the ranges of texels its kernels are to run
//! over, a few to a few dozen in each chunk of its tiles (the cut tiles'
//! buoyancy, the drag's kernel lists): some ten lists a chunk, made and
//! dropped in a few microseconds. Allocating them each time cost a body
//! with drag on calm water about 3 % of its evaluation (`malloc`,
//! `realloc` and `free` under `perf`); a [`Ranges`] takes a list this
//! thread has dropped before, emptied, and gives it back when dropped, so
//! that after a thread's first evaluations they allocate nothing. It takes
//! one on its first range only: most of a chunk's lists stay empty (a
//! floating body's drag fills two or three of its eight), and an empty
//! list is made and dropped without reaching the thread's store.

use std::cell::RefCell;
use std::ops::{Deref, Range};

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
    /// An empty list, holding no allocation until its first range.
    pub(crate) const fn new() -> Self {
        Self(Vec::new())
    }

    /// Adds `range` at the end; the first range takes a list the thread
    /// kept, when it has one.
    #[inline]
    pub(crate) fn push(&mut self, range: Range<usize>) {
        if self.0.capacity() == 0 {
            if let Some(kept) = KEPT_LISTS.try_with(|kept| kept.borrow_mut().pop()).ok().flatten() {
                self.0 = kept;
            }
        }
        self.0.push(range);
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
    type Target = [Range<usize>];
    fn deref(&self) -> &Self::Target {
        &self.0
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn kept() -> usize {
        KEPT_LISTS.with(|k| k.borrow().len())
    }

    #[test]
    fn a_list_dropped_is_handed_out_again_empty() {
        let mut a = Ranges::new();
        a.push(0..4);
        a.push(8..12);
        let pointer = a.as_ptr();
        drop(a);
        let mut b = Ranges::new();
        assert!(b.is_empty());
        b.push(16..20);
        assert_eq!(b.as_ptr(), pointer, "the kept allocation");
        assert_eq!((b.len(), b[0].clone()), (1, 16..20), "emptied when kept");
        // Two at once: the second is a new one.
        let mut c = Ranges::new();
        c.push(0..1);
        assert_ne!(c.as_ptr(), b.as_ptr());
    }

    #[test]
    fn an_empty_list_leaves_the_store_alone() {
        let mut a = Ranges::new();
        a.push(0..1);
        drop(a);
        let before = kept();
        assert!(before >= 1);
        let lists: Vec<Ranges> = (0..8).map(|_| Ranges::new()).collect();
        assert_eq!(kept(), before, "made without taking");
        assert!(lists.iter().all(|l| l.0.capacity() == 0), "no allocation");
        drop(lists);
        assert_eq!(kept(), before, "dropped without giving");
    }

    #[test]
    fn a_huge_list_is_not_kept() {
        let mut a = Ranges::new();
        for i in 0..=KEPT_CAPACITY {
            a.push(i..i + 1);
        }
        let before = kept();
        drop(a);
        assert_eq!(kept(), before, "freed, not kept");
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
        assert_eq!(kept(), KEPT);
    }
}
