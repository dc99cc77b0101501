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
use crate::response::Response;
use crate::topology::Topology;
use crate::wall::Wall;

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
    /// Keep the event log.
    pub log_events: bool,
    /// Keep the log of mode decisions (event-driven only: what each took in and cost).
    pub log_decisions: bool,
    /// What to do after a collapse.
    pub after_collapse: AfterCollapse,
    /// Told the simulated time as the run goes on (a progress bar for long runs).
    pub progress: Option<Progress>,
}

/// Told the simulated time reached (s), once per segment of the ground motion (event-driven)
/// or per step (time stepping), never past the duration: a run of thousands of blocks takes
/// minutes, and a bar is the only sign it moves.
#[derive(Clone)]
pub struct Progress(pub std::sync::Arc<dyn Fn(f64) + Send + Sync>);

impl Progress {
    /// Reports time t.
    pub fn at(&self, t_s: f64) {
        (self.0)(t_s)
    }
}

impl std::fmt::Debug for Progress {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str("Progress")
    }
}

impl Settings {
    /// Summary only, for `duration_s`.
    pub fn summary_only(duration_s: f64) -> Settings {
        Settings {
            duration_s,
            output_dt_s: None,
            log_events: false,
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
