//! Turning diffusion off removes its cost entirely: no field is built and,
//! once warm, a step allocates nothing at all (counted by a global
//! allocator); with diffusion on, the field is built once and steps reuse it.

use std::alloc::{GlobalAlloc, Layout, System};
use std::sync::atomic::{AtomicUsize, Ordering};

use nalgebra::Isometry3;
use soak_bake::{Atlas, BakeOptions, builtin};
use soak_hydro::Water;
use soak_wet::prelude::*;

struct Counting;

static ALLOCATIONS: AtomicUsize = AtomicUsize::new(0);

// SAFETY: forwards to the system allocator, only counting.
#[allow(unsafe_code)]
unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        ALLOCATIONS.fetch_add(1, Ordering::Relaxed);
        // SAFETY: same contract as the caller's.
        unsafe { System.alloc(layout) }
    }
    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        // SAFETY: same contract as the caller's.
        unsafe { System.dealloc(ptr, layout) }
    }
    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        ALLOCATIONS.fetch_add(1, Ordering::Relaxed);
        // SAFETY: same contract as the caller's.
        unsafe { System.realloc(ptr, layout, new_size) }
    }
}

#[global_allocator]
static GLOBAL: Counting = Counting;

#[test]
fn steps_without_diffusion_allocate_nothing() {
    let atlas = Atlas::bake(&builtin::cuboid(1.0, 1.0, 1.0), BakeOptions::square(256)).unwrap();
    let water = Water::calm(0.0);
    let env = Environment::default();
    let pose = Isometry3::translation(0.0, 0.1, 0.0);

    let mut dry = Wetting::new(&atlas, Material::sand(), Liquid::water()).unwrap();
    for k in 0..3 {
        dry.step(&atlas, &pose, &water, &env, k as f64, 0.1).unwrap();
    }
    let before = ALLOCATIONS.load(Ordering::SeqCst);
    for k in 3..53 {
        dry.step(&atlas, &pose, &water, &env, k as f64 * 0.1, 0.1)
            .unwrap();
    }
    let off = ALLOCATIONS.load(Ordering::SeqCst) - before;
    assert_eq!(dry.field_bytes(), 0);

    let mut wet = Wetting::new(&atlas, Material::sand(), Liquid::water())
        .unwrap()
        .with_diffusion(Diffusion::new(1e-3));
    for k in 0..3 {
        wet.step(&atlas, &pose, &water, &env, k as f64, 0.1).unwrap();
    }
    let field = wet.field_bytes();
    let before = ALLOCATIONS.load(Ordering::SeqCst);
    for k in 3..53 {
        wet.step(&atlas, &pose, &water, &env, k as f64 * 0.1, 0.1)
            .unwrap();
    }
    let on = ALLOCATIONS.load(Ordering::SeqCst) - before;
    eprintln!(
        "50 steps: {off} allocations without diffusion; {on} with it (field of {:.1} MB built once)",
        field as f64 / 1e6
    );
    assert_eq!(off, 0);
    assert!(field > 0);
    assert_eq!(wet.field_bytes(), field, "the field is reused, not rebuilt");
}
