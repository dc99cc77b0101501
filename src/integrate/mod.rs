//! Integrators: the exact event-driven one ([`event::EventDriven`]) and time-stepping baselines,
//! all behind [`Integrator`]. A run takes a [`Scenario`] (wall, graph, ground motion, settings)
//! and returns a [`Response`].

pub mod baselines;
pub mod event;
pub mod rocking;
// Public for integrators outside the crate (the rapier peer engine): not part of the curated
// surface, so hidden from the documentation.
#[doc(hidden)]
pub mod stepping;

use crate::error::SimulationError;
use crate::motion::Motion;
use crate::response::{EventsTo, HistoryTo, Response};
use crate::topology::Topology;
use crate::wall::Wall;
use std::path::PathBuf;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Arc;

/// What to do once a block falls.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, serde::Serialize)]
#[cfg_attr(feature = "cli", derive(clap::ValueEnum))]
#[serde(rename_all = "lowercase")]
pub enum AfterCollapse {
    /// Stop the run at the first collapse.
    #[default]
    Stop,
    /// Remove the fallen block and its load and go on.
    Continue,
}

/// Settings common to every integrator.
#[derive(Debug, Clone)]
pub struct Settings {
    /// Simulated time (s).
    pub duration_s: f64,
    /// History sampling interval (s); `None` for summary only.
    pub output_dt_s: Option<f64>,
    /// Write the history rows to this CSV file as the run goes instead of keeping them in the
    /// response (memory stays bounded however long the history): `Response::history` is then
    /// `None` and `Response::history_file` says where it went.
    pub history_file: Option<PathBuf>,
    /// Keep the event log.
    pub log_events: bool,
    /// With `log_events`, also write the log to this JSON-lines file as the run goes, under a
    /// partial name (`.events.jsonl.partial` for `events.jsonl`) that the run takes away when
    /// it ends: a run that fails or is killed keeps the events it met up to then.
    pub events_file: Option<PathBuf>,
    /// Keep the log of mode decisions (event-driven only: what each took in and cost).
    pub log_decisions: bool,
    /// With `log_decisions`, also write that log to this JSON-lines file as the run goes, as
    /// `events_file` is written (a partial name until the run ends).
    pub decisions_file: Option<PathBuf>,
    /// What to do after a collapse.
    pub after_collapse: AfterCollapse,
    /// Told the simulated time as the run goes on (a progress bar for long runs).
    pub progress: Option<Progress>,
}

/// Told the simulated time reached (s), once per segment of the ground motion and every
/// [`Progress::EVERY_EVENTS`] events or history rows (event-driven) or per step (time
/// stepping), never past the
/// duration: a run of thousands of blocks takes minutes, and a bar is the only sign it moves.
/// It also carries the caller's request to stop (Ctrl-C): a run asked to stop ends at the time
/// it reached with what it has, the summary saying so (`Summary::interrupted_at_s`).
#[derive(Clone)]
pub struct Progress {
    report: Arc<dyn Fn(f64) + Send + Sync>,
    stop: Option<Arc<dyn Fn() -> bool + Send + Sync>>,
}

impl Progress {
    /// The event-driven integrator also looks at the stop request this often, in events and in
    /// history rows, between segments of the ground motion (a sine is one segment however
    /// long, and a fine history between two far events is most of a run's time).
    pub const EVERY_EVENTS: u64 = 4096;

    /// Reports each time to `report`.
    pub fn new(report: impl Fn(f64) + Send + Sync + 'static) -> Progress {
        Progress {
            report: Arc::new(report),
            stop: None,
        }
    }

    /// The same, also stopping the run once `stop` is set (by a Ctrl-C handler, a notebook's
    /// interrupt, a time limit).
    pub fn with_stop(self, stop: Arc<AtomicBool>) -> Progress {
        self.with_stop_when(move || stop.load(Ordering::Relaxed))
    }

    /// The same, asking `asked` whether to stop (for a caller that must look somewhere itself,
    /// as the Python package looks at Python's signals). The run asks before each pivot of the
    /// uplift check's programs and at each report, so `asked` should be cheap most times.
    pub fn with_stop_when(self, asked: impl Fn() -> bool + Send + Sync + 'static) -> Progress {
        Progress {
            stop: Some(Arc::new(asked)),
            ..self
        }
    }

    /// Reports time t; false when the run is asked to stop.
    pub fn at(&self, t_s: f64) -> bool {
        (self.report)(t_s);
        !self.stop_requested()
    }

    /// The run is asked to stop.
    pub fn stop_requested(&self) -> bool {
        self.stop.as_ref().is_some_and(|asked| asked())
    }
}

impl std::fmt::Debug for Progress {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str("Progress")
    }
}

impl Settings {
    /// Checks the duration and the history's size for a wall of `blocks` blocks (every
    /// integrator calls it before it starts): a duration within the bounds, and a history that
    /// fits in memory (`--output-dt 1e-9` would fill it before the run ends).
    pub fn validate(&self, blocks: usize) -> Result<(), SimulationError> {
        let t = self.duration_s;
        if !(t > 0.0 && t <= crate::bounds::MAX_DURATION_S) {
            return Err(SimulationError::Setting {
                what: "duration".into(),
                value: t,
                unit: " s",
                rule: "it must be positive and at most 1e6 s",
            });
        }
        if let Some(dt) = self.output_dt_s {
            // Rows at output times (events add some), each with u and v of every block: held in
            // memory unless they go to a file.
            let values = (t / dt) * (1.0 + 2.0 * blocks as f64);
            let (most, rule) = if self.history_file.is_some() {
                (
                    crate::bounds::MAX_HISTORY_FILE_VALUES,
                    "it must be positive, and a history written to a file (duration / interval \
                     rows of every block) at most 2e9 numbers, about 50 GB: take a larger \
                     interval, or no history",
                )
            } else {
                (
                    crate::bounds::MAX_HISTORY_VALUES,
                    "it must be positive, and a history kept in memory (duration / interval \
                     rows of every block) at most 5e7 numbers: take a larger interval, write it \
                     to a file (--out does), or keep no history",
                )
            };
            if !(dt > 0.0 && values <= most) {
                return Err(SimulationError::Setting {
                    what: "history interval".into(),
                    value: dt,
                    unit: " s",
                    rule,
                });
            }
        }
        Ok(())
    }

    /// Where the history goes.
    pub fn history_to(&self) -> HistoryTo {
        match (self.output_dt_s, &self.history_file) {
            (None, _) => HistoryTo::Nowhere,
            (Some(_), None) => HistoryTo::Memory,
            (Some(_), Some(path)) => HistoryTo::File(path.clone()),
        }
    }

    /// Where the event log goes.
    pub fn events_to(&self) -> EventsTo {
        match (self.log_events, &self.events_file) {
            (false, _) => EventsTo::Nowhere,
            (true, None) => EventsTo::Memory,
            (true, Some(path)) => EventsTo::File(path.clone()),
        }
    }

    /// Summary only, for `duration_s`.
    pub fn summary_only(duration_s: f64) -> Settings {
        Settings {
            duration_s,
            output_dt_s: None,
            history_file: None,
            log_events: false,
            events_file: None,
            decisions_file: None,
            log_decisions: false,
            after_collapse: AfterCollapse::Stop,
            progress: None,
        }
    }
}

/// One run: a wall, its graph, a ground motion and settings.
#[derive(Debug, Clone, Copy)]
pub struct Scenario<'a> {
    /// The wall.
    pub wall: &'a Wall,
    /// Its support and contact graph.
    pub topology: &'a Topology,
    /// Horizontal ground acceleration.
    pub motion: &'a Motion,
    /// Duration, outputs, collapse policy.
    pub settings: &'a Settings,
}

/// An integrator of the sliding-block wall.
pub trait Integrator {
    /// Name written into `summary.json` (`"event"`, `"paper"`, ...).
    fn method(&self) -> &'static str;
    /// Runs the scenario.
    fn run(&self, scenario: &Scenario) -> Result<Response, SimulationError>;
}
