//! Runs of the exact integrator for the integration tests, and the ground motions they share.

use pirqa::integrate::event::EventDriven;
use pirqa::integrate::{Integrator, Scenario, Settings};
use pirqa::motion::{Motion, Record, Sine};
use pirqa::response::{EventKind, EventRecord, Response};
use pirqa::{Topology, Wall};

/// The first `seconds` of El Centro 1940 (the shipped PEER record), scaled to a PGA of
/// `pga_m_s2` over the whole record.
pub fn el_centro_first_s(seconds: usize, pga_m_s2: f64) -> Motion {
    let record = pirqa::motion::read_record(
        std::path::Path::new("records/elcentro1940_IELC180_peer_dt0p01_g.AT2"),
        None,
        &pirqa::motion::ReadOptions::default(),
    )
    .unwrap();
    let n = seconds * 100 + 1;
    let first = Record::new("El Centro", 0.01, record.accel_m_s2()[..n].to_vec()).unwrap();
    Motion::Record(first.scaled(pga_m_s2 / record.pga_m_s2()).unwrap())
}

/// `wall` under `motion` with the exact integrator and `settings`, its graph built from it.
pub fn exact(wall: &Wall, motion: &Motion, settings: &Settings) -> Response {
    exact_on(wall, &Topology::new(wall).unwrap(), motion, settings)
}

/// The same on a given graph (one whose friction was changed joint by joint).
pub fn exact_on(
    wall: &Wall,
    topology: &Topology,
    motion: &Motion,
    settings: &Settings,
) -> Response {
    let sc = Scenario {
        wall,
        topology,
        motion,
        settings,
    };
    EventDriven::default().run(&sc).unwrap()
}

/// `duration` s of `wall` under `motion`, events logged, the history sampled every `output_dt`
/// s if given.
pub fn run(wall: &Wall, motion: &Motion, duration: f64, output_dt: Option<f64>) -> Response {
    let settings = Settings {
        output_dt_s: output_dt,
        log_events: true,
        ..Settings::summary_only(duration)
    };
    exact(wall, motion, &settings)
}

/// A sine of `amp` m/s2 at `freq` Hz starting at phase `phase_deg`, lasting `duration` s.
pub fn sine(amp: f64, freq: f64, phase_deg: f64, duration: f64) -> Motion {
    Motion::sine(Sine {
        amplitude_m_s2: amp,
        frequency_hz: freq,
        phase_rad: phase_deg.to_radians(),
        duration_s: duration,
    })
    .unwrap()
}

/// `n` samples every `dt` s of `amp` sin(2 pi `freq` t + `phase_rad`), as a record named `name`
/// (a sine a record's piecewise-linear segments follow, with or beside a vertical component).
pub fn sampled_sine(
    name: &str,
    amp: f64,
    freq: f64,
    phase_rad: f64,
    dt: f64,
    n: usize,
) -> pirqa::motion::Record {
    let samples = (0..n)
        .map(|k| amp * (std::f64::consts::TAU * freq * k as f64 * dt + phase_rad).sin())
        .collect();
    pirqa::motion::Record::new(name, dt, samples).unwrap()
}

/// A constant ground acceleration `a` (m/s2) for `duration` s, as a record sampled at 100 Hz.
pub fn constant(a: f64, duration: f64) -> Motion {
    let dt = 0.01;
    let n = (duration / dt).round() as usize + 2;
    Motion::Record(Record::new("constant", dt, vec![a; n]).unwrap())
}

/// A wall file, relative to the project's root.
pub fn load(path: &str) -> Wall {
    Wall::load(std::path::Path::new(path)).unwrap()
}

/// The impacts a run logged, in order.
pub fn impacts(r: &Response) -> Vec<&EventRecord> {
    r.events
        .iter()
        .filter(|e| e.kind == EventKind::Impact)
        .collect()
}
