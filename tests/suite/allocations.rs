//! Heap allocations of the exact integrator, counted per thread by this test binary's
//! allocator: a decision's working memory is kept from one event to the next, so a periodic
//! response allocates nothing once its cycle has been met (issue 37).

use crate::engine::{exact, load, sine};
use pirqa::integrate::Settings;
use std::alloc::{GlobalAlloc, Layout, System};
use std::cell::Cell;
use std::hint::black_box;

/// The system allocator, counting the allocations of each thread (a reallocation counts as one).
struct Counting;

thread_local! {
    static ALLOCATIONS: Cell<u64> = const { Cell::new(0) };
}

fn counted() {
    // A thread being torn down has no counter left; its allocations are no test's.
    let _ = ALLOCATIONS.try_with(|n| n.set(n.get() + 1));
}

unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        counted();
        // SAFETY: the caller's contract is passed on to the system allocator unchanged.
        unsafe { System.alloc(layout) }
    }
    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        // SAFETY: as above.
        unsafe { System.dealloc(ptr, layout) }
    }
    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        counted();
        // SAFETY: as above.
        unsafe { System.realloc(ptr, layout, new_size) }
    }
}

#[global_allocator]
static ALLOCATOR: Counting = Counting;

/// Allocations this thread makes while running `f`.
fn allocations_of(f: impl FnOnce()) -> u64 {
    let before = ALLOCATIONS.with(Cell::get);
    f();
    ALLOCATIONS.with(Cell::get) - before
}

#[test]
fn a_periodic_response_allocates_nothing_once_its_cycle_is_met() {
    // The paper's walls settle into a cycle of the 1 Hz sine within a few seconds (the variable
    // wall: 245 events in 20 s, every decision after the first cycles met before).
    for path in [
        "walls/five-block-variable.ron",
        "walls/five-block-uniform.ron",
    ] {
        let wall = load(path);
        let motion = sine(4.0, 1.0, 0.0, 40.0);
        let run = |duration_s: f64| {
            let settings = Settings::summary_only(duration_s);
            let mut events = 0;
            let n = allocations_of(|| {
                events = black_box(exact(&wall, &motion, &settings))
                    .summary
                    .stats
                    .events
            });
            (n, events)
        };
        let ((short, short_events), (long, long_events)) = (run(20.0), run(40.0));
        assert!(
            long_events > short_events + 50,
            "{path}: {short_events}, {long_events}"
        );
        assert!(short > 0, "{path}: the allocator counts");
        assert_eq!(
            long - short,
            0,
            "{path}: {} more events, {} more allocations",
            long_events - short_events,
            long - short
        );
    }
}
