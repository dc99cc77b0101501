//! Speed of the exact event-driven integrator on the paper's wall (figures in
//! docs/performance.md): `cargo bench --features bench --bench event_driven`.

use criterion::{criterion_group, criterion_main, Criterion, Throughput};
use pirqa::integrate::event::EventDriven;
use pirqa::integrate::{Integrator, Scenario, Settings};
use pirqa::motion::{Motion, Sine};
use pirqa::{samples, topology};
use std::hint::black_box;
use std::path::Path;

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
