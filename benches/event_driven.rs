//! Speed of the exact event-driven integrator on the paper's wall (figures in
//! docs/performance.md): `cargo bench --features bench --bench event_driven`. Before each
//! scenario it prints the heap allocations of one run, counted by the allocator below.

use criterion::{criterion_group, criterion_main, Criterion, Throughput};
use pirqa::integrate::event::EventDriven;
use pirqa::integrate::{Integrator, Scenario, Settings};
use pirqa::motion::{Motion, Sine};
use pirqa::{samples, topology};
use std::alloc::{GlobalAlloc, Layout, System};
use std::hint::black_box;
use std::path::Path;
use std::sync::atomic::{AtomicU64, Ordering};

/// The system allocator, counting allocations (a reallocation counts as one).
struct Counting;

static ALLOCATIONS: AtomicU64 = AtomicU64::new(0);

unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        ALLOCATIONS.fetch_add(1, Ordering::Relaxed);
        // SAFETY: the caller's contract is passed on to the system allocator unchanged.
        unsafe { System.alloc(layout) }
    }
    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        // SAFETY: as above.
        unsafe { System.dealloc(ptr, layout) }
    }
    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        ALLOCATIONS.fetch_add(1, Ordering::Relaxed);
        // SAFETY: as above.
        unsafe { System.realloc(ptr, layout, new_size) }
    }
}

#[global_allocator]
static ALLOCATOR: Counting = Counting;

fn run_case(c: &mut Criterion, name: &str, wall: &str, motion: Motion, duration: f64) {
    let (wall, topo) = topology::load(Path::new(wall)).unwrap();
    let settings = Settings::summary_only(duration);
    let sc = Scenario {
        wall: &wall,
        topology: &topo,
        motion: &motion,
        settings: &settings,
    };
    let events = EventDriven::default()
        .run(&sc)
        .unwrap()
        .summary
        .stats
        .events;
    let before = ALLOCATIONS.load(Ordering::Relaxed);
    black_box(EventDriven::default().run(&sc).unwrap());
    let allocations = ALLOCATIONS.load(Ordering::Relaxed) - before;
    eprintln!(
        "{name}: {events} events, {allocations} allocations per run ({:.1} per event)",
        allocations as f64 / events.max(1) as f64
    );
    let mut group = c.benchmark_group(name);
    group.throughput(Throughput::Elements(events));
    group.bench_function("run", |b| {
        b.iter(|| black_box(EventDriven::default().run(black_box(&sc)).unwrap()))
    });
    group.finish();
}

fn benches(c: &mut Criterion) {
    let sine = || {
        Motion::sine(Sine {
            amplitude_m_s2: 4.0,
            frequency_hz: 1.0,
            phase_rad: 0.0,
            duration_s: 20.0,
        })
        .unwrap()
    };
    run_case(
        c,
        "five_block_uniform_sine_400gal_1hz_20s",
        "walls/five-block-uniform.ron",
        sine(),
        20.0,
    );
    run_case(
        c,
        "five_block_variable_sine_400gal_1hz_20s",
        "walls/five-block-variable.ron",
        sine(),
        20.0,
    );
    let record = Motion::Record(samples::broadband_record(60.0, 0.01, 5.0));
    run_case(
        c,
        "five_block_variable_record_60s_100hz",
        "walls/five-block-variable.ron",
        record,
        60.0,
    );
    let quiet = Motion::Record(samples::broadband_record(60.0, 0.01, 2.0));
    run_case(
        c,
        "inca_coursed_stuck_record_60s_100hz",
        "walls/inca-coursed.ron",
        quiet,
        60.0,
    );
}

criterion_group! {
    name = event_driven;
    config = Criterion::default().sample_size(30).measurement_time(std::time::Duration::from_secs(4));
    targets = benches
}
criterion_main!(event_driven);
